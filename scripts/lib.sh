# Shared helpers, sourced by the other scripts (after scripts/setup.sh has run).
# shellcheck shell=bash
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
# `set -e` reaches into command substitutions (`x=$(helper)`), where bash otherwise turns it off:
# a helper whose middle step fails then fails the caller instead of printing a stale path.
shopt -s inherit_errexit
# shellcheck disable=SC1091
. "$ROOT/target/meterstick-toolchain.env"

# Host cargo: rustup's when present, else Debian's.
if command -v cargo >/dev/null 2>&1; then HOST_CARGO=cargo; else HOST_CARGO=/usr/bin/cargo; fi

# cargo for a Cortex-M target: rustup's, or Debian's building `core` from source.
# Usage: cross_cargo <cargo args...>   (the caller passes --target)
cross_cargo() {
  if [ "$MS_CROSS_MODE" = debian ]; then
    RUSTC=/usr/bin/rustc RUSTDOC=/usr/bin/rustdoc RUSTC_BOOTSTRAP=1 \
      /usr/bin/cargo "$@" -Z build-std=core
  else
    cargo "$@"
  fi
}

# Target directory for cross builds of the host workspace's crates (core): kept apart from
# the host build, and per mode, so neither invalidates the other.
CROSS_TARGET_DIR="$ROOT/target/cross-$MS_CROSS_MODE"
FIRMWARE_TARGET_DIR="$ROOT/firmware/target/$MS_CROSS_MODE"

# The Picos' .uf2 converter (tools/uf2: elf2flash-core, with the boot ROMs' checks), built by
# scripts/setup.sh.
UF2_TOOL="$ROOT/target/tools/release/meterstick-uf2"

# Builds one firmware variant and copies the ELF to firmware/target/<mode>/elf/<name>.elf
# (variants of one target share cargo's output path); prints that path. A Pico build (features
# board-pico2 or board-pico) also gets its .uf2, firmware/target/<mode>/uf2/<name>.uf2.
# Usage: build_firmware <name> <target> <features-or-empty>
build_firmware() {
  local name=$1 target=$2 features=$3 args=() chip=""
  [ -n "$features" ] && args+=(--features "$features")
  # Called as `elf=$(build_firmware ...)`, where `set -e` does not apply inside: every step
  # returns on failure (a failed link must not leave the previous build's ELF under this name).
  rm -f "$FIRMWARE_TARGET_DIR/elf/$name.elf" "$FIRMWARE_TARGET_DIR/uf2/$name.uf2"
  (cd "$ROOT/firmware" && cross_cargo build --release --locked --no-default-features --target "$target" \
      --target-dir "$FIRMWARE_TARGET_DIR" "${args[@]}" >&2) || { echo "build_firmware $name: the build failed" >&2; return 1; }
  mkdir -p "$FIRMWARE_TARGET_DIR/elf" || return 1
  cp "$FIRMWARE_TARGET_DIR/$target/release/meterstick-firmware" "$FIRMWARE_TARGET_DIR/elf/$name.elf" || return 1
  case ",$features," in
    *,board-pico2,*) chip=rp2350 ;;
    *,board-pico,*) chip=rp2040 ;;
  esac
  if [ -n "$chip" ]; then
    mkdir -p "$FIRMWARE_TARGET_DIR/uf2" || return 1
    "$UF2_TOOL" "$chip" "$FIRMWARE_TARGET_DIR/elf/$name.elf" "$FIRMWARE_TARGET_DIR/uf2/$name.uf2" >&2 || return 1
  fi
  echo "$FIRMWARE_TARGET_DIR/elf/$name.elf"
}

# Every firmware build: "<name> <target> <features> <tags>". qemu-*: the QEMU board binding (run in
# the tests); rig-*: the demo rig on the STM32F411 Black Pill, with and without defmt logging
# (`log`) and the 8x8 fallback (the 6x6-only builds link no 8x8 code); *-link: with the host link
# (`meterstick-link`: QEMU's UART, the Black Pill's USB CDC), the QEMU ones run by the end-to-end
# test; *-uart: the Black Pill's link on USART2; rig-m4f-stack*: the Black Pill running the rig of
# the 3-block stack (`rig-stack`), with and without `log`, the host link on USB and on USART2. qemu-m33: the Cortex-M33F (the Pico 2's core) on
# QEMU's mps2-an505. pico2-*: the rig on a Raspberry Pi Pico 2 (RP2350), pico-*: on a Pico
# (RP2040), each with a .uf2; as the Black Pill's, with and without `log` and `fallback`, and with
# the host link on UART0 (the Picos' link builds run the meter stick and, selected by the host, the
# 3-block stack: firmware/src/realtime_stack.rs); pico-nolog-builtins and pico-link-builtins: the Pico's arithmetic from
# compiler_builtins instead of its boot ROM (docs/hardware.md), which the emulated RP2040 runs
# (scripts/pico-emu.sh); pico2-stick-3d and pico-stick-3d-builtins: the rig of the meter stick in
# three dimensions (`rig-stick-3d`, firmware/src/realtime_stick_3d.rs), the Pico's run on the
# emulated RP2040 for its cycles a step.
# Tags (comma-separated; scripts select builds by tag, never by position, `builds_tagged`):
#   clippy  - linted in scripts/test.sh (the distinct code paths);
#   nopanic - linked with the panic handler that references an undefined symbol (firmware/src/
#             main.rs): that it links proves no panic path; test.sh also checks the ELF;
#   uf2     - a Pico build: build_firmware writes its .uf2, test.sh checks it is there;
#   emu     - the one Pico build run on the emulated RP2040 by scripts/pico-emu.sh (rp2040js has
#             no boot ROM: the build's float arithmetic must not call it, `builtins-float`);
#   emu-link - the one Pico build with the host link run there, its UART0 bridged to TCP;
#   emu-3d  - the one Pico build of the meter stick in three dimensions run there.
FIRMWARE_BUILDS=(
  "qemu-m4f thumbv7em-none-eabihf qemu-mps2-an386,qemu-multibody,fallback clippy,nopanic"
  "qemu-m4f-spatial thumbv7em-none-eabihf qemu-mps2-an386,qemu-spatial,fallback clippy,nopanic"
  "qemu-m4f-algebra thumbv7em-none-eabihf qemu-mps2-an386,qemu-algebra clippy"
  "qemu-m0 thumbv6m-none-eabi qemu-microbit,fallback nopanic"
  "rig-m4f thumbv7em-none-eabihf board-blackpill,log,fallback clippy"
  "rig-m4f-nolog thumbv7em-none-eabihf board-blackpill,fallback nopanic"
  "rig-m4f-6x6 thumbv7em-none-eabihf board-blackpill,log -"
  "rig-m4f-6x6-nolog thumbv7em-none-eabihf board-blackpill clippy,nopanic"
  "qemu-m4f-link thumbv7em-none-eabihf qemu-mps2-an386,qemu-multibody,fallback,link clippy,nopanic"
  "qemu-m0-link thumbv6m-none-eabi qemu-microbit,fallback,link nopanic"
  "rig-m4f-link thumbv7em-none-eabihf board-blackpill,log,fallback,link clippy"
  "rig-m4f-6x6-nolog-uart thumbv7em-none-eabihf board-blackpill,uart-link clippy,nopanic"
  "rig-m4f-stack thumbv7em-none-eabihf board-blackpill,rig-stack,log,fallback clippy"
  "rig-m4f-stack-nolog thumbv7em-none-eabihf board-blackpill,rig-stack,fallback clippy,nopanic"
  "rig-m4f-stack-link thumbv7em-none-eabihf board-blackpill,rig-stack,log,fallback,link clippy"
  "rig-m4f-stack-nolog-uart thumbv7em-none-eabihf board-blackpill,rig-stack,fallback,uart-link clippy,nopanic"
  "qemu-m33 thumbv8m.main-none-eabihf qemu-mps2-an505,qemu-multibody,fallback clippy,nopanic"
  "qemu-m33-spatial thumbv8m.main-none-eabihf qemu-mps2-an505,qemu-spatial,fallback nopanic"
  "pico2 thumbv8m.main-none-eabihf board-pico2,log,fallback clippy,uf2"
  "pico2-nolog thumbv8m.main-none-eabihf board-pico2,fallback nopanic,uf2"
  "pico2-6x6-nolog thumbv8m.main-none-eabihf board-pico2 nopanic,uf2"
  "pico2-link thumbv8m.main-none-eabihf board-pico2,fallback,link clippy,nopanic,uf2"
  "pico2-stick-3d thumbv8m.main-none-eabihf board-pico2,rig-stick-3d,fallback clippy,nopanic,uf2"
  "pico thumbv6m-none-eabi board-pico,log,fallback clippy,uf2"
  "pico-nolog thumbv6m-none-eabi board-pico,fallback uf2"
  "pico-6x6-nolog thumbv6m-none-eabi board-pico uf2"
  "pico-link thumbv6m-none-eabi board-pico,fallback,link clippy,uf2"
  "pico-nolog-builtins thumbv6m-none-eabi board-pico,fallback,builtins-float clippy,uf2,emu"
  "pico-link-builtins thumbv6m-none-eabi board-pico,fallback,link,builtins-float uf2,emu-link"
  "pico-stick-3d-builtins thumbv6m-none-eabi board-pico,rig-stick-3d,fallback,builtins-float clippy,uf2,emu-3d"
)

# Sets TAGGED to the specs ("<name> <target> <features> <tags>") of the builds tagged $1 (no
# subshell, so that nothing here can fail unseen); a tag no build has is an error (a typo).
builds_tagged() {
  local spec
  TAGGED=()
  for spec in "${FIRMWARE_BUILDS[@]}"; do
    case ",${spec##* }," in *",$1,"*) TAGGED+=("$spec") ;; esac
  done
  [ ${#TAGGED[@]} -gt 0 ] || { echo "builds_tagged: no firmware build is tagged '$1'" >&2; return 1; }
}

# The core for the browser: meterstick-web built for wasm32-unknown-unknown (release, without
# debug info, in a target directory of its own so that the host builds are not invalidated), once
# per number of contacts (cargo features k2, k1, k3), once for the scenes of several bodies
# (feature mb), twice for the scenes in three dimensions of one body (feature sp: f32; sp64: f64)
# and twice for the stack in three dimensions (st, st64), copied to web/page/pkg/: meterstick_web.wasm
# (the two-contact scenes, which the page loads first), meterstick_web_k1.wasm, meterstick_web_k3.wasm,
# meterstick_web_mb.wasm, meterstick_web_sp.wasm, meterstick_web_sp64.wasm, meterstick_web_st.wasm and
# meterstick_web_st64.wasm, and the scenes'
# headings, introductions and modules, intros.json (generated, git-ignored). Prints the first module's path.
WEB_TARGET_DIR="$ROOT/target/web/$MS_CROSS_MODE"
WEB_WASM="$ROOT/web/page/pkg/meterstick_web.wasm"
WEB_MODULES=("$WEB_WASM" "${WEB_WASM%.wasm}_k1.wasm" "${WEB_WASM%.wasm}_k3.wasm" "${WEB_WASM%.wasm}_mb.wasm"
  "${WEB_WASM%.wasm}_sp.wasm" "${WEB_WASM%.wasm}_sp64.wasm" "${WEB_WASM%.wasm}_st.wasm" "${WEB_WASM%.wasm}_st64.wasm")
build_web() {
  local args=(build --locked --release -p meterstick-web --lib --target wasm32-unknown-unknown
    --target-dir "$WEB_TARGET_DIR" --config profile.release.debug=0 --config profile.release.strip=true
    --no-default-features --config 'profile.release.opt-level="s"')
  if [ "$MS_CROSS_MODE" = debian ] && command -v wasm-ld-22 >/dev/null 2>&1; then
    args+=(--config 'target.wasm32-unknown-unknown.linker="wasm-ld-22"')
  fi
  # Called as `wasm=$(build_web)`: every step returns on failure (a failed build must not leave
  # a previous module in place for the page's test).
  rm -f "${WEB_MODULES[@]}"
  mkdir -p "$(dirname "$WEB_WASM")" || return 1
  # Every module at opt-level "s": the page allows itself 350 kB a module (docs/page.md), and at
  # opt-level 3 the two-contact module is 419,515 B, the three-contact one 391,449 B; the scenes of
  # several bodies also in the core's `compact` shape (one copy of the multibody solve: 355,746 B
  # without it). The same arithmetic: optimisation levels and the copies keep IEEE results, and
  # the page's test checks the checksums bit for bit against the host, which has every copy.
  local k out feature
  for k in 2 1 3 mb sp sp64 st st64; do
    case $k in
      2) out=$WEB_WASM feature=k2 ;;
      mb) out="${WEB_WASM%.wasm}_mb.wasm" feature=mb,compact ;;
      sp) out="${WEB_WASM%.wasm}_sp.wasm" feature=sp ;;
      sp64) out="${WEB_WASM%.wasm}_sp64.wasm" feature=sp,sp64 ;;
      st) out="${WEB_WASM%.wasm}_st.wasm" feature=st ;;
      st64) out="${WEB_WASM%.wasm}_st64.wasm" feature=st,st64 ;;
      *) out="${WEB_WASM%.wasm}_k$k.wasm" feature="k$k" ;;
    esac
    (cd "$ROOT" && cross_cargo "${args[@]}" --features "$feature" >&2) || { echo "build_web: the build failed" >&2; return 1; }
    cp "$WEB_TARGET_DIR/wasm32-unknown-unknown/release/meterstick_web.wasm" "$out" || return 1
  done
  # Each scene's heading and introduction (the catalogue's INTRODUCTIONS), which the modules do
  # not carry (their size budget): pkg/intros.json, written on the host.
  (cd "$ROOT" && $HOST_CARGO run --locked -q -p meterstick-web --example intros) >"$(dirname "$WEB_WASM")/intros.json" \
    || { echo "build_web: intros.json failed" >&2; return 1; }
  echo "$WEB_WASM"
}
