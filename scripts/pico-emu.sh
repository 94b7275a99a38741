#!/usr/bin/env bash
# The Pico without a board (#23): the Pico firmware's .uf2, as a teacher flashes it, on an
# emulated RP2040 (rp2040js, tests/pico/), checked against the host core running the same rig
# (tests/tests/pico_emu.rs): STEP pulses tick by tick, DIR, the lights at the scene's switch
# events, the fault light, the tick period; it prints the cycles each step takes on the
# 125 MHz Cortex-M0+ against the 1 ms period; the meter stick in three dimensions' .uf2 the same
# way for its first steps (it does not keep up with 1 ms there). Then the host link over the emulated UART0,
# bridged to TCP: the QEMU link test's checks (tests/tests/link_checks/).
#
# Usage: bash scripts/pico-emu.sh [--no-setup] [TEST-NAME-FILTER...]
#   --no-setup   skip scripts/setup.sh (scripts/test.sh has run it)
#   MS_PICO_UF2       a .uf2 to run instead of the build tagged `emu` (scripts/lib.sh)
#   MS_PICO_LINK_UF2  the same for the host link's tests, instead of the build tagged `emu-link`
#   MS_PICO_3D_UF2    the same for the meter stick in three dimensions, instead of `emu-3d`
# Only builds whose arithmetic does not call the RP2040's boot ROM run on the emulator
# (rp2040js has none): `builtins-float`.
set -euo pipefail
cd "$(dirname "$0")/.."
setup=1
if [ "${1:-}" = --no-setup ]; then setup=0; shift; fi
[ "$setup" = 0 ] || bash scripts/setup.sh
. scripts/lib.sh

if ! command -v node >/dev/null 2>&1 || [ ! -f tests/pico/node_modules/rp2040js/package.json ]; then
  echo "pico-emu: node or tests/pico/node_modules is missing: run scripts/setup.sh" >&2
  exit 1
fi
# The .uf2 of the build tagged $1 (exactly one), built; sets UF2.
build_tagged_uf2() {
  builds_tagged "$1"
  [ ${#TAGGED[@]} = 1 ] || { echo "pico-emu: ${#TAGGED[@]} builds are tagged $1, expected one" >&2; return 1; }
  local spec
  read -r -a spec <<<"${TAGGED[0]}"
  build_firmware "${spec[0]}" "${spec[1]}" "${spec[2]}" >/dev/null
  UF2="$FIRMWARE_TARGET_DIR/uf2/${spec[0]}.uf2"
}
if [ -z "${MS_PICO_UF2:-}" ]; then build_tagged_uf2 emu; MS_PICO_UF2=$UF2; fi
if [ -z "${MS_PICO_LINK_UF2:-}" ]; then build_tagged_uf2 emu-link; MS_PICO_LINK_UF2=$UF2; fi
if [ -z "${MS_PICO_3D_UF2:-}" ]; then build_tagged_uf2 emu-3d; MS_PICO_3D_UF2=$UF2; fi
for f in "$MS_PICO_UF2" "$MS_PICO_LINK_UF2" "$MS_PICO_3D_UF2"; do
  [ -s "$f" ] || { echo "pico-emu: no .uf2 at $f" >&2; exit 1; }
done
version=$(node -p 'require("./tests/pico/node_modules/rp2040js/package.json").version')
echo "pico-emu: ${MS_PICO_UF2#"$ROOT"/}, ${MS_PICO_LINK_UF2#"$ROOT"/} and ${MS_PICO_3D_UF2#"$ROOT"/} on rp2040js $version"
MS_PICO_UF2="$MS_PICO_UF2" MS_PICO_LINK_UF2="$MS_PICO_LINK_UF2" MS_PICO_3D_UF2="$MS_PICO_3D_UF2" $HOST_CARGO test --locked -p meterstick-tests --test pico_emu -- \
  --ignored --test-threads=1 --nocapture "$@"
echo "pico-emu: the harness's JSON per run is in target/pico-emu/"
