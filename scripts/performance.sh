#!/usr/bin/env bash
# Regenerates docs/performance.md from the tools' own outputs, stamped with the commit and the
# machine (CPU model, cores, rustc):
#   - scripts/firmware-report.sh: flash/RAM of every firmware build (out/firmware/report.md) and
#     Cortex-M instructions per step under QEMU -icount (out/firmware/*-icount.json, read as JSON);
#   - the rapier bench (`cargo bench -p meterstick-tests --features rapier --bench rapier`): the
#     meter stick and the 3-block stack in rapier2d and in the core, one process
#     (out/bench/rapier.md, quoted as written);
#   - the rapier3d bench (`cargo bench -p meterstick-tests --features rapier3d --bench rapier3d`):
#     the puck on an incline, the billiard ball and the curling stone in rapier3d and in the core,
#     their anisotropy
#     (out/bench/rapier3d.md, quoted as written);
#   - the Pico's rig of the meter stick in three dimensions (the build tagged `emu-3d`) on the
#     emulated RP2040 (tests/pico/harness.mjs): its cycles a step over its first 300 steps
#     (out/firmware/pico-stick-3d-emu.json, read as JSON);
#   - `host-sim report --quick`: host ns/step, pivots and solve paths at h = 1 ms
#     (out/performance/report/report.json, read as JSON);
#   - the page's wasm modules (scripts/lib.sh `build_web`): their sizes, plain and gzipped.
# Usage: bash scripts/performance.sh [--render-only]
#   --render-only  write docs/performance.md from the files a previous full run left in out/
#                  (nothing is measured; the stamp still names the current commit and machine).
# Takes about as long as scripts/firmware-report.sh plus release builds of rapier2d and rapier3d
# (minutes).
set -euo pipefail
cd "$(dirname "$0")/.."

render_only=0
for arg in "$@"; do
  case $arg in
    --render-only) render_only=1 ;;
    -h | --help) sed -n '2,14p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "performance.sh: unknown argument '$arg' (expected --render-only or --help)" >&2; exit 2 ;;
  esac
done

REPORT_DIR=out/performance/report
if [ "$render_only" = 0 ]; then
  # Runs scripts/setup.sh and builds host-sim; prints its report, which is read from its files below.
  bash scripts/firmware-report.sh >/dev/null
  . scripts/lib.sh
  builds_tagged emu-3d
  node tests/pico/harness.mjs --uf2 "$FIRMWARE_TARGET_DIR/uf2/${TAGGED[0]%% *}.uf2" --max-cycles 290000000 \
    >out/firmware/pico-stick-3d-emu.json
  $HOST_CARGO bench --locked -p meterstick-tests --features rapier --bench rapier
  $HOST_CARGO bench --locked -p meterstick-tests --features rapier3d --bench rapier3d
  target/release/host-sim report --quick --out "$REPORT_DIR" \
    --firmware-figures out/firmware/report.md --bench-figures out/bench/rapier.md >/dev/null
  wasm=$(build_web)
  echo "built $wasm and its siblings" >&2
else
  . scripts/lib.sh
fi

for f in out/firmware/report.md out/firmware/qemu-m4f-icount.json out/firmware/qemu-m0-icount.json \
  out/firmware/qemu-m33-icount.json out/firmware/qemu-m4f-spatial-icount.json out/firmware/qemu-m33-spatial-icount.json out/firmware/pico-stick-3d-emu.json out/bench/rapier.md out/bench/rapier3d.md "$REPORT_DIR/report.json" "${WEB_MODULES[@]}"; do
  [ -s "$f" ] || { echo "performance.sh: $f is missing: run without --render-only first" >&2; exit 1; }
done

commit=$(git rev-parse --short=12 HEAD)
dirty=""
if ! git diff --quiet HEAD -- . ':!docs/performance.md'; then dirty=" (with uncommitted changes)"; fi
rustc_version=$($HOST_CARGO rustc --version 2>/dev/null || rustc --version)
qemu_version=$(qemu-system-arm --version | head -n 1)

python3 - "$commit$dirty" "$rustc_version" "$qemu_version" "$REPORT_DIR/report.json" \
  "$FIRMWARE_TARGET_DIR/elf" "${WEB_MODULES[@]}" >docs/performance.md <<'PY'
import datetime, gzip, json, os, subprocess, sys

commit, rustc, qemu, report_json, elf_dir, *modules = sys.argv[1:]

def cpu_model():
    with open("/proc/cpuinfo") as f:
        for line in f:
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    return "unknown CPU"

def flash_ram(name):
    """(flash, static RAM) in bytes of a firmware ELF, as scripts/firmware-report.sh counts them."""
    out = subprocess.run(["size", os.path.join(elf_dir, name + ".elf")], check=True,
                         capture_output=True, text=True).stdout.splitlines()[-1].split()
    text, data, bss = (int(x) for x in out[:3])
    return text + data, data + bss

def icount(build):
    with open(f"out/firmware/{build}-icount.json") as f:
        return {s["scene"]: s for s in json.load(f)["timing"]["scenes"]}

def n(x):
    return f"{x:,.0f}"

def table(header, rows):
    """A Markdown table: its header's cells, then each row's."""
    print("| " + " | ".join(header) + " |")
    print("|" + "---|" * len(header))
    for cells in rows:
        print("| " + " | ".join(cells) + " |")

def mean_worst(scene):
    """A timed scene's `mean / worst` instructions per step."""
    return f"{n(scene['mean_instructions'])} / {n(scene['worst_instructions'])}"

with open(report_json) as f:
    report = json.load(f)
host = [r for r in report["sweep"] if abs(r["h"] - 1e-3) < 1e-12]
if not host:
    sys.exit("performance.sh: no h = 1 ms row in " + report_json)

cores = [("Cortex-M4F", "qemu-m4f", "mps2-an386", "the Black Pill's STM32F411"),
         ("Cortex-M33F", "qemu-m33", "mps2-an505", "the Pico 2's RP2350"),
         ("Cortex-M0", "qemu-m0", "microbit", "the Pico's RP2040, compiler_builtins' floats")]
timings = {build: icount(build) for _, build, _, _ in cores}
today = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")

print("# Performance")
print()
print("Generated by `bash scripts/performance.sh`; do not edit by hand (run it again).")
print()
print(f"- commit `{commit}`, {today}")
print(f"- machine: {cpu_model()}, {os.cpu_count()} cores (shared: wall-clock figures are noisy; "
      "instruction counts are deterministic)")
print(f"- `{rustc}`; `{qemu}`")
print()
print("The scene throughout: the meter stick's slow run (finger 1 at 0.1 m/s from x1 = -0.35 m, h = 1 ms, "
      "7,900 steps to Balanced) unless a table says otherwise; the fast run is 5 m/s.")
print()
print("## Headline figures")
print()
print("| quantity | value |")
print("|---|---|")
f32_6 = next(r for r in host if r["config"] == "core f32 6x6")
print(f"| host, core f32 6x6, ns per step (`host-sim report`) | {f32_6['ns_per_step']:.0f} |")
for label, build, machine, board in cores:
    slow = timings[build]["slow"]
    print(f"| {label} ({board}): instructions per step, mean / worst | {mean_worst(slow)} |")
MULTIBODY = (("block-on-block", "block-on-block"), ("stack", "the 3-block stack"), ("disc-on-board", "disc-on-board"))
for scene, title in MULTIBODY:
    if scene not in timings["qemu-m4f"]:
        sys.exit(f"performance.sh: out/firmware/qemu-m4f-icount.json has no {scene} run "
                 "(the M4F firmware runs the scenes of several bodies: see firmware/Cargo.toml)")
    print(f"| Cortex-M4F, {title} (f32, defaults): instructions per step, mean / worst | "
          f"{mean_worst(timings['qemu-m4f'][scene])} |")
# The scenes in three dimensions run in builds of their own (firmware/Cargo.toml, `qemu-spatial`).
SPATIAL = (("puck", "puck"), ("billiard", "billiard ball"), ("curling", "curling stone (8 points)"),
           ("meter-stick-3d", "meter stick in 3D (3 points)"))
spatial_cores = [(label, build + "-spatial", machine) for label, build, machine, _ in cores[:2]]
spatial = {build: icount(build) for _, build, _ in spatial_cores}
print("| Cortex-M4F, the " + " / the ".join(t for _, t in SPATIAL) + " (f32, defaults): instructions per step, "
      "mean / worst | " + "; ".join(mean_worst(spatial["qemu-m4f-spatial"][s]) for s, _ in SPATIAL) + " |")
if "tablecloth-mu2-flagged" in timings["qemu-m4f"]:
    print("| Cortex-M4F, the tablecloth at `mu = 2` (f32): its "
          f"{n(timings['qemu-m4f']['tablecloth-mu2-flagged']['steps'])} flagged steps, instructions per step, "
          f"mean / worst | {mean_worst(timings['qemu-m4f']['tablecloth-mu2-flagged'])} |")
flash, ram = flash_ram("rig-m4f-6x6-nolog")
print(f"| flash / static RAM of `rig-m4f-6x6-nolog` (the smallest rig build) | {n(flash)} B / {n(ram)} B |")
flash, ram = flash_ram("rig-m4f-link")
print(f"| flash / static RAM of `rig-m4f-link` (what `cargo run --release` flashes) | {n(flash)} B / {n(ram)} B |")
print()
print("## The host")
print()
print("`host-sim report --quick`'s timed runs at h = 1 ms (median of the repeats, one run at a time; "
      "the solve paths are described in `docs/formulation.md`, \"Solving a step\"; the reference "
      "solves each step's LCP by enumerating its bases):")
print()
print("| configuration | ns/step | steps/s | pivots/step | steps by path: free / warm / candidate / lemke |")
print("|---|---|---|---|---|")
for r in host:
    paths = r.get("paths")
    by_path = " / ".join(n(paths[p]) for p in ("free", "warm", "candidate", "lemke")) if paths else "-"
    pivots = "- (enumeration)" if r["pivots_per_step"] is None else f"{r['pivots_per_step']:.4f}"
    print(f"| {r['config']} | {r['ns_per_step']:,.0f} | {n(1e9 / r['ns_per_step'])} | {pivots} | {by_path} |")
print()
print("Criterion benchmarks of each piece (one Lemke solve, one step, a whole run): "
      "`cargo bench -p meterstick-tests --bench core`.")
print()
print("## Against rapier2d")
print()
print("`cargo bench -p meterstick-tests --features rapier --bench rapier`: rapier2d (kinematic fingers, "
      "contact recycling off, one Coulomb coefficient: mu_k) and the core on the same scene, then the 3-block "
      "stack (cuboid blocks on a fixed cuboid table, the pair's coefficient mu, the same fall judge) in rapier2d "
      "and in the core's Stack3, in one process, as it printed:")
print()
with open("out/bench/rapier.md") as f:
    print(f.read().rstrip())
print()
print("## Against rapier3d")
print()
print("`cargo bench -p meterstick-tests --features rapier3d --bench rapier3d`: rapier3d 0.36 (f32) and the core (f32) "
      "on the puck on an incline and the billiard ball at their defaults (rapier: a tilted fixed cuboid for the plane, "
      "the puck as its own cylinder and as a ball with its rotations locked, contact recycling off, one Coulomb "
      "coefficient mu_k, its default solver and friction model; see the bench's module doc), the curling stone (the "
      "uniform disc: rapier's cylinder; its friction model holds sliding and twisting apart, so its spin stops long "
      "before its slide, where Coulomb's law on the face stops both together), then the anisotropy "
      "measured the same way in both (the puck on a level table at 16 headings; the ball's rolling velocity against "
      "the 5/7 law), in one process, as it printed:")
print()
with open("out/bench/rapier3d.md") as f:
    print(f.read().rstrip())
print()
print("## The microcontrollers")
print()
print("Instructions per step under QEMU (`-icount shift=0`: one instruction per ns of virtual time, "
      "SysTick read around every tick of the rig loop, calibrated against a loop of known length); "
      "f32, the 6x6 layout with the 8x8 fallback:")
print()
table(["core (QEMU machine)", "board it stands for", "slow: mean / worst", "fast: mean / worst"],
      [[f"{label} (`{machine}`)", board] + [mean_worst(timings[build][s]) for s in ("slow", "fast")]
       for label, build, machine, board in cores])
print()
print("The scenes of several bodies at their defaults (f32, through the core's scene interface, not the rig loop: "
      "the view's `step`, the scene's step and the view's checksum of it; "
      "issue targets on the M4F: block-on-block mean <= 5,000 / worst <= 25,000, the 3-block stack "
      "<= 12,000 / <= 100,000; disc-on-board has none), with the deepest the stack grew (painted RAM read back, "
      "`firmware/src/stack_peak.rs`):")
print()
def peak(t, s):
    return "-" if s not in t or t[s].get("stack_peak_bytes") is None else n(t[s]["stack_peak_bytes"])
table(["core (QEMU machine)"] + [f"{s}: mean / worst" for s, _ in MULTIBODY]
      + ["stack peak (B): slow run / " + " / ".join(s for s, _ in MULTIBODY)],
      [[f"{label} (`{machine}`)"]
       + [mean_worst(timings[build][s]) if s in timings[build] else "not run" for s, _ in MULTIBODY]
       + [" / ".join(peak(timings[build], s) for s in ("slow",) + tuple(s for s, _ in MULTIBODY))]
       for label, build, machine, _ in cores])
STACK_RIG = (("stack-rig-held", "held"), ("stack-rig-fell", "falls"))
print()
print("The 3-block stack through the stack rig (`meterstick_rig::StackRig` on headless pins, "
      "`firmware/src/qemu.rs`; 200 steps each): the catalogue's stack for 0.2 s (it holds) and at "
      "overhang 1.02 (it falls; its first step, leaving rest, is the worst):")
print()
table(["core (QEMU machine)"] + [f"{s} ({what}): mean / worst" for s, what in STACK_RIG]
      + ["stack peak (B): " + " / ".join(s for s, _ in STACK_RIG)],
      [[f"{label} (`{machine}`)"]
       + [mean_worst(timings[build][s]) if s in timings[build] else "not run" for s, _ in STACK_RIG]
       + [" / ".join(peak(timings[build], s) for s, _ in STACK_RIG)]
       for label, build, machine, _ in cores])
print()
print("The scenes in three dimensions at their defaults (f32, through the core's scene interface, "
      "`SceneParams::build_view_in`: the view's bookkeeping included; the `qemu-m4f-spatial` and "
      "`qemu-m33-spatial` builds), with the deepest the stack grew (issue targets on the M4F: the curling "
      "stone with its default points mean <= 40,000; the meter stick in 3D mean <= 8,000, worst <= 30,000):")
print()
table(["core (QEMU machine)"] + [f"{t}: mean / worst" for _, t in SPATIAL]
      + ["stack peak (B): " + " / ".join(s for s, _ in SPATIAL)],
      [[f"{label} (`{machine}`)"] + [mean_worst(spatial[build][s]) for s, _ in SPATIAL]
       + [" / ".join(peak(spatial[build], s) for s, _ in SPATIAL)]
       for label, build, machine in spatial_cores])
with open("out/firmware/pico-stick-3d-emu.json") as f:
    emu3d = json.load(f)["run"]["cycles_per_step"]
print()
print(f"The boards' rigs of the meter stick in 3D (`rig-stick-3d`: the carriage on a rail at the path's heading): "
      f"the Pico 2's `pico2-stick-3d.uf2` (its Cortex-M33F's figures above, within the 150,000 cycles of h = 1 ms "
      f"at 150 MHz); the Pico's (RP2040, Cortex-M0+ without an FPU) on the emulated RP2040 (rp2040js, "
      f"`pico-stick-3d-builtins`, compiler_builtins' floats, its first {n(emu3d['n'])} steps): "
      f"{n(round(emu3d['mean']))} / {n(emu3d['max'])} cycles a step, mean / worst, against the 125,000 of h = 1 ms "
      f"at 125 MHz: it does not keep up in real time (the rig runs a step a tick, late, at about "
      f"{125e6 / emu3d['mean']:.0f} steps/s).")
m4f = timings["qemu-m4f"]
if all(m4f[s].get("stack_peak_bytes") is not None for s in ("stack", "block-on-block")):
    print()
    print(f"The Cortex-M0 build (`microbit`: 256 KiB of flash, 16,384 B of RAM) runs the scenes of one body "
          f"only: with those of several bodies its firmware overflows the flash (by 156,512 B at 0abe64e), and "
          f"the 3-block stack needs {n(m4f['stack']['stack_peak_bytes'])} B of stack on the M4F, more than its "
          f"whole RAM (block-on-block {n(m4f['block-on-block']['stack_peak_bytes'])} B).")
def stack_rows(build):
    with open(f"out/firmware/{build}-icount.json") as f:
        t = json.load(f)["timing"]
    return t["stack_room_bytes"], {p["scene"]: p["peak_bytes"] for p in t["stack_peaks"]}
ONE_BODY = ("slow", "fast", "incline", "ladder", "three-fingers", "cylinder", "painleve")
print()
print("The scenes of one body: the deepest each run's stack grew against the RAM the stack may grow into "
      "(the stack top less the static data), `peak / room` in bytes, f32; the other scenes at their defaults "
      "in the reduced layout with `N = 16`:")
print()
stacks = {build: stack_rows(build) for _, build, _, _ in cores}
table(["core (QEMU machine)"] + list(ONE_BODY),
      [[f"{label} (`{machine}`)"]
       + [f"{n(stacks[build][1][s])} / {n(stacks[build][0])}" if s in stacks[build][1] and stacks[build][0]
          else "-" for s in ONE_BODY]
       for label, build, machine, _ in cores])
print()
print("The slow run's steps by the path that answered their LCP, each path's mean / worst instructions:")
print()
print("| core | free | warm | candidate | lemke |")
print("|---|---|---|---|---|")
for label, build, _, _ in cores:
    paths = {p["path"]: p for p in timings[build]["slow"]["paths"]}
    cells = []
    for name in ("free", "warm", "candidate", "lemke"):
        p = paths[name]
        cells.append(f"{n(p['steps'])} steps, {mean_worst(p)}"
                     if p["steps"] else "0")
    print(f"| {label} | " + " | ".join(cells) + " |")
print()
print("Flash and static RAM of every firmware build (`scripts/firmware-report.sh`, as it wrote them; "
      "the builds' features are listed in `scripts/lib.sh` and described in `docs/hardware.md`):")
print()
with open("out/firmware/report.md") as f:
    lines = f.read().splitlines()
start = next(i for i, l in enumerate(lines) if l.startswith("| build |"))
end = next(i for i in range(start, len(lines)) if not lines[i].startswith("|"))
print("\n".join(lines[start:end]))
print()
print("## The page")
print()
print("The wasm modules `scripts/web.sh` builds (`scripts/lib.sh` `build_web`; release, no debug info):")
print()
print("| module | scenes | bytes | gzipped |")
print("|---|---|---|---|")
holds = {"meterstick_web.wasm": "meter stick, incline, ladder (two contacts)",
         "meterstick_web_k1.wasm": "cylinder, Painlevé's rod (one contact)",
         "meterstick_web_k3.wasm": "three fingers (three contacts)",
         "meterstick_web_mb.wasm": "block-on-block, tablecloth, stack, disc-on-board (several bodies)",
         "meterstick_web_sp.wasm": "puck, billiard, curling, meter stick in three dimensions, f32 (feature `sp`)",
         "meterstick_web_sp64.wasm": "the same in f64 (features `sp`, `sp64`)",
         "meterstick_web_st.wasm": "the stack in three dimensions, f32 (feature `st`)",
         "meterstick_web_st64.wasm": "the same in f64 (features `st`, `st64`)"}
for m in modules:
    with open(m, "rb") as f:
        data = f.read()
    name = os.path.basename(m)
    print(f"| `{name}` | {holds.get(name, '-')} | {n(len(data))} | {n(len(gzip.compress(data, 9)))} |")
print()
print("The scenes in three dimensions have a module for each precision: in one module with both they are 8")
print("steppers, each with its own copy of the contact solve, Lemke's method and the load's rule per LCP capacity,")
print("404,931 B (473,523 B before the puck and the ball were held in the curling stone's LCP capacity, 32 rows,")
print("which leaves two capacities, 32 and the rod's 12, with the same bits), over the page's 350 kB a module;")
print('`opt-level = "z"` makes it larger (490,496 B), and no `wasm-opt` is in the build. The planar modules are')
print("unchanged by them, byte for byte.")
PY
echo "wrote docs/performance.md" >&2
