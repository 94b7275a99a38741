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
  # The distinct code paths: QEMU binding; rig with logging and fallback; rig with neither.
  for spec in "${FIRMWARE_BUILDS[0]}" "${FIRMWARE_BUILDS[2]}" "${FIRMWARE_BUILDS[5]}"; do
    set -- $spec
    (cd firmware && cargo clippy --locked --release --target "$2" --features "$3" \
        --target-dir "$FIRMWARE_TARGET_DIR" -- -D warnings)
  done
else
  echo "Debian fallback: no clippy for the cross toolchain; skipped"
fi

step "firmware builds (QEMU machines; the rig with and without defmt and the 8x8 fallback)"
for spec in "${FIRMWARE_BUILDS[@]}"; do
  set -- $spec
  elf=$(build_firmware "$1" "$2" "$3")
  printf '%-18s %s\n' "$1" "$(size "$elf" | tail -n 1)"
done
M4="$FIRMWARE_TARGET_DIR/elf/qemu-m4f.elf"
M0="$FIRMWARE_TARGET_DIR/elf/qemu-m0.elf"

step "firmware under QEMU"
MS_FIRMWARE_M4="$M4" MS_FIRMWARE_M0="$M0" \
  $HOST_CARGO test --locked -p meterstick-tests --test qemu -- --ignored

echo
echo "all tests passed in $(( $(date +%s) - start )) s"
