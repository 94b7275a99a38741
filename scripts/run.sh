#!/usr/bin/env bash
# The main job: run the firmware on both emulated Cortex-M cores and show what it printed.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
. scripts/lib.sh
$HOST_CARGO build --locked --release -p meterstick-host-sim
M4=$(build_firmware qemu-m4f thumbv7em-none-eabihf qemu-mps2-an386)
M0=$(build_firmware qemu-m0 thumbv6m-none-eabi qemu-microbit)
echo "== Cortex-M4F (QEMU mps2-an386)"
target/release/host-sim qemu --machine mps2-an386 "$M4"
echo "== Cortex-M0 (QEMU microbit)"
target/release/host-sim qemu --machine microbit "$M0"
