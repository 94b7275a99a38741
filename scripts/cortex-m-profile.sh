#!/usr/bin/env bash
# Per-instruction profile of a QEMU firmware run (slow and fast scenes, as in firmware-report.sh):
# QEMU logs every translated block (-d in_asm) and every block executed (-d exec, nochain) into a
# FIFO; scripts/cortex_m_profile.py counts instructions per address and maps them to functions
# (inline frames included) and source lines with llvm-addr2line.
#   bash scripts/cortex-m-profile.sh m4f|m0 [steps]     (steps: divide the counts by it; 8077 = both scenes)
# Needs a built ELF (scripts/firmware-report.sh builds them) and llvm-addr2line. About 15 s (M4F), 75 s (M0).
set -euo pipefail
cd "$(dirname "$0")/.."
core=${1:?usage: cortex-m-profile.sh m4f|m0 [steps]}
steps=${2:-8077}
elf=$(ls firmware/target/*/elf/qemu-"$core".elf | head -n 1)
case $core in
  m4f) machine=(-machine mps2-an386 -cpu cortex-m4) ;;
  m0) machine=(-machine microbit) ;;
  *) echo "m4f or m0" >&2; exit 2 ;;
esac
command -v llvm-addr2line >/dev/null || { echo "needs llvm-addr2line (apt-get install llvm)" >&2; exit 1; }
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
mkfifo "$dir/log"
python3 scripts/cortex_m_profile.py count "$dir/log" "$dir/counts.json" &
counter=$!
qemu-system-arm "${machine[@]}" -nographic -monitor none -serial none \
  -semihosting-config enable=on,target=native -d in_asm,exec,nochain -D "$dir/log" -kernel "$elf" >/dev/null
wait "$counter"
python3 scripts/cortex_m_profile.py report "$dir/counts.json" "$elf" "$steps"
