#!/usr/bin/env bash
# Firmware figures: flash/RAM of every build (with and without defmt, with and without the 8x8
# fallback, with and without the host link; the Picos' .uf2 sizes), and Cortex-M instructions per
# scene step on the emulated Cortex-M4F, Cortex-M0 and Cortex-M33F,
# counted deterministically (QEMU -icount shift=0, SysTick, calibrated against a loop of known
# length). Writes out/firmware/report.md and prints it. Installs what it needs first.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
. scripts/lib.sh
$HOST_CARGO build --locked --release -p meterstick-host-sim >&2
mkdir -p out/firmware
declare -A ELF
for spec in "${FIRMWARE_BUILDS[@]}"; do
  set -- $spec
  ELF[$1]=$(build_firmware "$1" "$2" "$3")
done
{
  echo "# Firmware figures"
  echo
  echo "| build | features | flash (text+data, B) | static RAM (data+bss, B) | .uf2 (B) |"
  echo "|---|---|---|---|---|"
  for spec in "${FIRMWARE_BUILDS[@]}"; do
    b=${spec%% *}
    read -r text data bss _ < <(size "${ELF[$b]}" | tail -n 1)
    feats=$(printf '%s\n' "${FIRMWARE_BUILDS[@]}" | awk -v b="$b" '$1 == b { print $3 }')
    uf2="$FIRMWARE_TARGET_DIR/uf2/$b.uf2"
    if [ -f "$uf2" ]; then uf2=$(stat -c %s "$uf2"); else uf2=""; fi
    echo "| $b | $feats | $((text + data)) | $((data + bss)) | $uf2 |"
  done
  echo
  echo "Instructions per step (slow scene v = 0.1 m/s and fast v = 5 m/s, x1 = -0.35 m, f32 6x6 with the 8x8"
  echo "fallback, through the rig loop; every other scene of one body at its defaults, f32, in the reduced layout,"
  echo "through the core's scene interface (SceneView: the scene's step and the view's checksum of it); on the M4F"
  echo "and M33F also block-on-block, the 3-block stack and disc-on-board at their defaults, f32, through the same"
  echo "interface, and the stack through the stack rig (stack-rig-held: 0.2 s at the default"
  echo "overhang; stack-rig-fell: overhang 1.02), and the tablecloth at mu = 2 (tablecloth-mu2) with its steps the rule"
  echo "flagged as possibly having several motions timed apart (tablecloth-mu2-flagged: the worst flagged multibody step);"
  echo "the puck, the billiard ball, the curling stone and the meter stick in 3D at their defaults, f32, through the"
  echo "same interface (the qemu-*-spatial builds);"
  echo "in a run where the rule decided some steps' load, the steps whose load the contacts decide (<scene>-determinate)"
  echo "and those whose load the rule decides (<scene>-decided: e.g. the slow rod at rest on two sticking fingers,"
  echo "docs/formulation.md, \"The load: the least norm\") apart;"
  echo "QEMU -icount shift=0, SysTick ticks converted with the calibration loop;"
  echo "stack peak: the deepest the stack grew in the scene, painted and read back, firmware/src/stack_peak.rs):"
  echo
  echo "| core (QEMU machine) | scene | steps | instructions/step (mean) | worst step (instructions) | stack peak (B) |"
  echo "|---|---|---|---|---|---|"
  # The spatial builds run the scenes of one body too: only their own scenes are printed (those the
  # machine's main build did not time).
  for m in "qemu-m4f mps2-an386 Cortex-M4F" "qemu-m0 microbit Cortex-M0" "qemu-m33 mps2-an505 Cortex-M33F" \
    "qemu-m4f-spatial mps2-an386 Cortex-M4F qemu-m4f" "qemu-m33-spatial mps2-an505 Cortex-M33F qemu-m33"; do
    set -- $m
    # host-sim reads the firmware's timing lines and converts them (JSON, `host-sim qemu --json`).
    target/release/host-sim qemu --icount --json --machine "$2" "${ELF[$1]}" > "out/firmware/$1-icount.json"
    python3 - "out/firmware/$1-icount.json" "$3 ($2)" "${4:+out/firmware/$4-icount.json}" <<'PY'
import json, sys
timing = json.load(open(sys.argv[1]))["timing"]
timed = {s["scene"] for s in json.load(open(sys.argv[3]))["timing"]["scenes"]} if sys.argv[3] else set()
for s in timing["scenes"]:
    if s["scene"] in timed:
        continue
    peak = s["stack_peak_bytes"]
    peak = "-" if peak is None else f"{peak:,}"
    print(f"| {sys.argv[2]} | {s['scene']} | {s['steps']} | {s['mean_instructions']:,.0f} | {s['worst_instructions']:,.0f} | {peak} |")
PY
  done
  echo
  echo "Stack: the deepest each run grew (painted and read back, firmware/src/stack_peak.rs, timed or not) against"
  echo "the RAM the stack may grow into (the stack top less the static data); headroom = room - peak:"
  echo
  echo "| core (QEMU machine) | run | stack peak (B) | room (B) | headroom (B) |"
  echo "|---|---|---|---|---|"
  for m in "qemu-m4f mps2-an386 Cortex-M4F" "qemu-m0 microbit Cortex-M0" "qemu-m33 mps2-an505 Cortex-M33F"; do
    set -- $m
    python3 - "out/firmware/$1-icount.json" "$3 ($2)" <<'PY'
import json, sys
timing = json.load(open(sys.argv[1]))["timing"]
room = timing["stack_room_bytes"]
for p in timing["stack_peaks"]:
    cells = (f"{room:,}", f"{room - p['peak_bytes']:,}") if room is not None else ("-", "-")
    print(f"| {sys.argv[2]} | {p['scene']} | {p['peak_bytes']:,} | {cells[0]} | {cells[1]} |")
PY
  done
  echo
  echo "Steps by the path that answered their LCP (docs/formulation.md, \"Solving a step\"; a step is counted"
  echo "under the last path it needed), with each path's mean and worst step (instructions, slow scene):"
  echo
  echo "| core | free | warm | candidate | lemke |"
  echo "|---|---|---|---|---|"
  for m in "qemu-m4f Cortex-M4F" "qemu-m0 Cortex-M0" "qemu-m33 Cortex-M33F"; do
    set -- $m
    python3 - "out/firmware/$1-icount.json" "$2" <<'PY'
import json, sys
timing = json.load(open(sys.argv[1]))["timing"]
slow = next(s for s in timing["scenes"] if s["scene"] == "slow")
paths = {p["path"]: p for p in slow["paths"]}
cells = []
for name in ("free", "warm", "candidate", "lemke"):
    p = paths[name]
    cells.append(f"{p['steps']:,} steps, {p['mean_instructions']:,.0f} / {p['worst_instructions']:,.0f}" if p["steps"] else "0")
print(f"| {sys.argv[2]} | " + " | ".join(cells) + " |")
PY
  done
  echo
  echo "The scenes of several bodies' steps by the path that answered their LCP (docs/formulation.md, \"Solving a"
  echo "multibody step (the core)\"; each step under the path that answered it, the rule's search included), each"
  echo "path's steps, mean / worst instructions, and the step that failed (every path tried, StepError; failing-*:"
  echo "runs that end so, firmware/src/qemu.rs), timed as a worst case:"
  echo
  echo "| core | run | free | warm | candidate | lemke | failed |"
  echo "|---|---|---|---|---|---|---|"
  for m in "qemu-m4f Cortex-M4F" "qemu-m33 Cortex-M33F"; do
    set -- $m
    python3 - "out/firmware/$1-icount.json" "$2" <<'PY'
import json, sys
timing = json.load(open(sys.argv[1]))["timing"]
for s in timing["scenes"]:
    paths = {p["path"]: p for p in s["paths"]}
    if "failed" not in paths:
        continue
    cells = []
    for name in ("free", "warm", "candidate", "lemke", "failed"):
        p = paths[name]
        cells.append(f"{p['steps']:,}: {p['mean_instructions']:,.0f} / {p['worst_instructions']:,.0f}" if p["steps"] else "0")
    print(f"| {sys.argv[2]} | {s['scene']} | " + " | ".join(cells) + " |")
PY
  done
} | tee out/firmware/report.md
