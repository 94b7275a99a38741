#!/usr/bin/env bash
# The main job: the paper's scenes in the core (f32, 6x6, as the firmware runs them) beside the
# independent f64 reference, with CSVs, summary.json and plots in out/run/; then the firmware
# itself on both emulated Cortex-M cores. Installs what it needs first.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
. scripts/lib.sh
$HOST_CARGO build --locked --release -p meterstick-host-sim
echo "== the paper's scenes: core f32 6x6 (as the firmware) beside the independent f64 reference"
target/release/host-sim run --out out/run
M4=$(build_firmware qemu-m4f thumbv7em-none-eabihf qemu-mps2-an386,qemu-multibody,fallback)
M0=$(build_firmware qemu-m0 thumbv6m-none-eabi qemu-microbit,fallback)
echo
echo "== firmware on Cortex-M4F (QEMU mps2-an386)"
target/release/host-sim qemu --machine mps2-an386 "$M4" | grep -v ' event '
echo
echo "== firmware on Cortex-M0 (QEMU microbit)"
target/release/host-sim qemu --machine microbit "$M0" | grep -v ' event '
