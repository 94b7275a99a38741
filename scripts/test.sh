#!/usr/bin/env bash
# Every test: host tests, lints, cross builds for both Cortex-M targets, firmware under QEMU.
# Installs what it needs first (scripts/setup.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
start=$(date +%s)
bash scripts/setup.sh
. scripts/lib.sh

step() { printf '\n== %s\n' "$*"; }

step "format"
if $HOST_CARGO fmt --version >/dev/null 2>&1; then $HOST_CARGO fmt --all -- --check; else echo "rustfmt not installed: skipped"; fi

step "clippy (host workspace, all targets)"
$HOST_CARGO clippy --locked --workspace --all-targets -- -D warnings

step "host tests"
$HOST_CARGO test --locked --workspace

step "core for Cortex-M (with and without defmt)"
for t in thumbv7em-none-eabihf thumbv6m-none-eabi; do
  for f in "" defmt; do
    echo "core: $t ${f:-no features}"
    cross_cargo build --locked -p meterstick-core --target "$t" --release \
      --target-dir "$CROSS_TARGET_DIR" ${f:+--features "$f"}
  done
done

step "firmware clippy"
if [ "$MS_CROSS_MODE" = rustup ]; then
  (cd firmware && cargo clippy --locked --release --target thumbv7em-none-eabihf --features qemu-mps2-an386 \
      --target-dir "$FIRMWARE_TARGET_DIR" -- -D warnings)
else
  echo "Debian fallback: no clippy for the cross toolchain; skipped"
fi

step "firmware builds"
M4=$(build_firmware qemu-m4f thumbv7em-none-eabihf qemu-mps2-an386)
M0=$(build_firmware qemu-m0 thumbv6m-none-eabi qemu-microbit)
RIG=$(build_firmware rig-m4f thumbv7em-none-eabihf "")
for elf in "$M4" "$M0" "$RIG"; do size "$elf" | tail -n 1; done

step "firmware under QEMU"
MS_FIRMWARE_M4="$M4" MS_FIRMWARE_M0="$M0" \
  $HOST_CARGO test --locked -p meterstick-tests --test qemu -- --ignored

echo
echo "all tests passed in $(( $(date +%s) - start )) s"
