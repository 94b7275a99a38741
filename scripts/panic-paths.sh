#!/usr/bin/env bash
# Lists the panic paths left in a firmware build: the link-time check (the panic handler calls
# an undefined symbol) says only that there is one; this builds the same features with
# `panic-locate` (a handler that links), finds every call into core's panic functions in the
# ELF, and prints each call site's inline chain (function, file:line), innermost first.
# Usage: bash scripts/panic-paths.sh <target> <features>   e.g.
#        bash scripts/panic-paths.sh thumbv7em-none-eabihf board-blackpill
set -euo pipefail
cd "$(dirname "$0")/.."
. scripts/lib.sh
target=$1 features=$2
command -v llvm-objdump >/dev/null && command -v llvm-addr2line >/dev/null ||
  { echo "needs llvm-objdump and llvm-addr2line (apt-get install llvm)" >&2; exit 1; }
elf=$(build_firmware "panic-locate" "$target" "$features,panic-locate")
# Panic entry points: the handler and core's panicking functions (names vary by release).
syms=$(llvm-objdump -t --demangle "$elf" | awk '$NF ~ /rust_begin_unwind|panic|index_fail|slice_(start|end)_index|slice_index_order|unwrap_failed|expect_failed|str_index_overflow|assert_failed/ { print $1 }' | sed 's/^0*//')
if [ -z "$syms" ]; then echo "no panic function in $elf: no panic path"; exit 0; fi
pattern=$(echo "$syms" | paste -sd'|')
llvm-objdump -d --no-show-raw-insn "$elf" | grep -E "\s(bl|b|b\.w|blx)\s+0x($pattern)\b" |
  awk '{ sub(":", "", $1); print "0x" $1 }' | sort -u > /tmp/panic-sites.$$ || true
n=$(wc -l < /tmp/panic-sites.$$)
echo "$n call sites into panic functions in $elf"
while read -r addr; do
  echo "-- $addr"
  llvm-addr2line -f -i -C -e "$elf" "$addr" | paste - - | sed 's/^/   /' | awk '{ $1 = $1; print "   " $0 }' | head -8
done < /tmp/panic-sites.$$
rm -f /tmp/panic-sites.$$
