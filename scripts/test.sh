#!/usr/bin/env bash
# Every test: host tests, lints, the page in headless Chromium, cross builds for the three Cortex-M
# targets (M4F, M0/M0+, M33F) and the boards (Black Pill, Pico 2 and Pico with their .uf2),
# firmware under QEMU, the Pico's .uf2 on an emulated RP2040.
# Installs what it needs first (scripts/setup.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
start=$(date +%s)
bash scripts/setup.sh
. scripts/lib.sh

step() { printf '\n== %s\n' "$*"; }

step "build glue: a failing build stops its caller"
# scripts/lib.sh's helpers are called as `x=$(helper)`; a failed build must stop the caller, not
# hand it a stale artefact. Here the build command itself is made to fail.
for helper in "build_web" "build_firmware qemu-m4f thumbv7em-none-eabihf qemu-mps2-an386,qemu-multibody,fallback"; do
  status=0
  bash -c 'set -euo pipefail; . scripts/lib.sh; cross_cargo() { return 3; }; out=$('"$helper"'); echo "reached: $out"' \
    >target/glue.out 2>target/glue.err || status=$?
  if [ "$status" = 0 ] || grep -q reached target/glue.out || ! grep -q "the build failed" target/glue.err; then
    echo "${helper%% *}: a failed build did not stop its caller (status $status):" >&2
    cat target/glue.out target/glue.err >&2
    exit 1
  fi
  echo "${helper%% *}: a failed build stops its caller (status $status)"
done

step "format"
if $HOST_CARGO fmt --version >/dev/null 2>&1; then $HOST_CARGO fmt --all -- --check; else echo "rustfmt not installed: skipped"; fi

step "clippy (host workspace, all targets)"
$HOST_CARGO clippy --locked --workspace --all-targets -- -D warnings

step "docs: rustdoc of every host crate and of tools/uf2, warnings denied (broken or private links, bad HTML)"
RUSTDOCFLAGS="-D warnings" $HOST_CARGO doc --locked --workspace --no-deps --quiet
(cd tools/uf2 && RUSTDOCFLAGS="-D warnings" $HOST_CARGO doc --locked --no-deps --quiet --target-dir "$ROOT/target/tools")
# The README's first scene is core/examples/first_scene.rs between its README markers, line for
# line; the example runs (its asserts are the README's claims).
if ! grep -q '^```rust$' README.md || ! grep -q '^// README begin$' core/examples/first_scene.rs; then
  echo "README.md has no rust block, or core/examples/first_scene.rs no '// README begin' line" >&2
  exit 1
fi
if ! diff -u <(awk '/^```rust$/ { on = 1; next } on && /^```$/ { exit } on' README.md) \
  <(awk '/^\/\/ README end$/ { exit } on; /^\/\/ README begin$/ { on = 1 }' core/examples/first_scene.rs); then
  echo "README.md's first rust block differs from core/examples/first_scene.rs (between its README markers)" >&2
  exit 1
fi
$HOST_CARGO run --locked --quiet -p meterstick-core --example first_scene

step "the declared MSRV: the library crates, every feature, with the toolchain of rust-version"
if [ -n "${MS_MSRV_TOOLCHAIN:-}" ]; then
  cargo "+$MS_MSRV_TOOLCHAIN" check --locked --all-features --target-dir "$ROOT/target/msrv" \
    -p meterstick-core -p meterstick-link -p meterstick-rig -p meterstick-reference
else
  echo "no MSRV toolchain (the Debian fallback, or rustup could not install it): skipped"
fi

step "host tests"
$HOST_CARGO test --locked --workspace
# The core alone, without `host-tuned` (host-sim turns it on for the whole workspace run): the
# shape the microcontrollers and the page run, built and tested on the host too.
$HOST_CARGO test --locked -p meterstick-core

step "the page: the core for the browser (wasm32), the page in headless Chromium"
wasm=$(build_web)
for module in "${WEB_MODULES[@]}"; do printf '%s: %s bytes\n' "${module#"$ROOT"/}" "$(stat -c %s "$module")"; done
$HOST_CARGO test --locked -p meterstick-tests --test browser -- --ignored --nocapture

step "the Picos' .uf2 converter (tools/uf2)"
(cd tools/uf2 && $HOST_CARGO test --locked --target-dir "$ROOT/target/tools" --quiet)
if $HOST_CARGO clippy --version >/dev/null 2>&1; then
  (cd tools/uf2 && $HOST_CARGO clippy --locked --all-targets --target-dir "$ROOT/target/tools" -- -D warnings)
fi

step "core and rig for Cortex-M (with and without defmt)"
for t in thumbv7em-none-eabihf thumbv6m-none-eabi thumbv8m.main-none-eabihf; do
  for f in "" defmt; do
    for p in meterstick-core meterstick-rig; do
      echo "$p: $t ${f:-no features}"
      cross_cargo build --locked -p "$p" --target "$t" --release \
        --target-dir "$CROSS_TARGET_DIR" ${f:+--features "$f"}
    done
  done
done

step "firmware clippy"
if [ "$MS_CROSS_MODE" = rustup ]; then
  # The distinct code paths (the builds tagged `clippy` in scripts/lib.sh).
  builds_tagged clippy
  for spec in "${TAGGED[@]}"; do
    set -- $spec
    (cd firmware && cargo clippy --locked --release --no-default-features --target "$2" --features "$3" \
        --target-dir "$FIRMWARE_TARGET_DIR" -- -D warnings)
  done
else
  echo "Debian fallback: no clippy for the cross toolchain; skipped"
fi

step "firmware builds (QEMU machines; the rigs with and without defmt, the 8x8 fallback, the host link; the Picos' .uf2)"
for spec in "${FIRMWARE_BUILDS[@]}"; do
  set -- $spec
  elf=$(build_firmware "$1" "$2" "$3")
  printf '%-24s %s\n' "$1" "$(size "$elf" | tail -n 1)"
done
builds_tagged uf2
for spec in "${TAGGED[@]}"; do
  name=${spec%% *}
  uf2="$FIRMWARE_TARGET_DIR/uf2/$name.uf2"
  [ -s "$uf2" ] || { echo "$name: no .uf2" >&2; exit 1; }
  printf '%-24s %s bytes\n' "$name.uf2" "$(stat -c %s "$uf2")"
done
M4="$FIRMWARE_TARGET_DIR/elf/qemu-m4f.elf"
M0="$FIRMWARE_TARGET_DIR/elf/qemu-m0.elf"
M33="$FIRMWARE_TARGET_DIR/elf/qemu-m33.elf"

step "no panic path (link-time check: these builds' panic handler references an undefined symbol)"
# A build with a panic path left would have failed to link above; that they linked is the proof.
# Here, a second look at the final ELFs: no panic function of core is in them at all.
builds_tagged nopanic
for spec in "${TAGGED[@]}"; do
  name=${spec%% *}
  elf="$FIRMWARE_TARGET_DIR/elf/$name.elf"
  if nm "$elf" | grep -qiE 'panicking|rust_begin_unwind'; then
    echo "$name: a panic handler is linked in: a panic path survived" >&2
    exit 1
  fi
  echo "$name: no panic path"
done

step "firmware under QEMU (and the host link end to end)"
MS_FIRMWARE_M4="$M4" MS_FIRMWARE_M0="$M0" MS_FIRMWARE_M33="$M33" \
MS_FIRMWARE_M4_SPATIAL="$FIRMWARE_TARGET_DIR/elf/qemu-m4f-spatial.elf" \
MS_FIRMWARE_M33_SPATIAL="$FIRMWARE_TARGET_DIR/elf/qemu-m33-spatial.elf" \
  $HOST_CARGO test --locked -p meterstick-tests --test qemu -- --ignored
MS_FIRMWARE_M4_LINK="$FIRMWARE_TARGET_DIR/elf/qemu-m4f-link.elf" \
MS_FIRMWARE_M0_LINK="$FIRMWARE_TARGET_DIR/elf/qemu-m0-link.elf" \
  $HOST_CARGO test --locked -p meterstick-tests --test qemu_link -- --ignored

step "the Pico on an emulated RP2040 (rp2040js): its .uf2 against the host core, the link over UART0 (scripts/pico-emu.sh)"
# The .uf2 files built above (the builds tagged emu and emu-link in scripts/lib.sh).
builds_tagged emu
emu_uf2="$FIRMWARE_TARGET_DIR/uf2/${TAGGED[0]%% *}.uf2"
builds_tagged emu-link
emu_link_uf2="$FIRMWARE_TARGET_DIR/uf2/${TAGGED[0]%% *}.uf2"
builds_tagged emu-3d
emu_3d_uf2="$FIRMWARE_TARGET_DIR/uf2/${TAGGED[0]%% *}.uf2"
MS_PICO_UF2="$emu_uf2" MS_PICO_LINK_UF2="$emu_link_uf2" MS_PICO_3D_UF2="$emu_3d_uf2" bash scripts/pico-emu.sh --no-setup

echo
echo "all tests passed in $(( $(date +%s) - start )) s"
