"""Instruction profile from a QEMU `-d in_asm,exec,nochain` log (see cortex-m-profile.sh).

count LOG OUT.json: instruction addresses of each translated block (in_asm) times the block's
executions (one `Trace` line per execution with nochain) -> executions per instruction address.
report OUT.json ELF STEPS: per function (inclusive over inline frames), per innermost function,
per source line, and the calls per step of the soft-float and memory routines.
"""
import collections
import json
import re
import subprocess
import sys


def count(log, out):
    blocks, runs, current = {}, collections.Counter(), None
    trace = re.compile(r'^Trace \d+: \S+ \[[0-9a-f]+/([0-9a-f]+)/')
    insn = re.compile(r'^0x([0-9a-f]{8}):')
    with open(log, errors='replace') as f:
        for line in f:
            if line.startswith('Trace'):
                m = trace.match(line)
                if m:
                    runs[int(m.group(1), 16)] += 1
            elif line.startswith('IN:'):
                current = None
            elif (m := insn.match(line)):
                pc = int(m.group(1), 16)
                if current is None:
                    current = pc
                    blocks[current] = []
                blocks[current].append(pc)
            elif not line.strip():
                current = None
    per_pc = collections.Counter()
    for start, n in runs.items():
        for pc in blocks.get(start, []):
            per_pc[pc] += n
    json.dump({str(k): v for k, v in per_pc.items()}, open(out, 'w'))


def strip_generics(name):
    for _ in range(4):
        name = re.sub(r'<[^<>]*>', '', name)
    return name[-80:]


def report(counts_file, elf, steps):
    per_pc = {int(k): v for k, v in json.load(open(counts_file)).items()}
    steps = float(steps)
    out = subprocess.run(['llvm-addr2line', '-a', '-f', '-i', '-C', '-e', elf],
                         input=''.join(f'{pc:#x}\n' for pc in sorted(per_pc)),
                         capture_output=True, text=True, check=True).stdout.splitlines()
    frames, current, i = {}, None, 0
    while i < len(out):
        if out[i].startswith('0x'):
            current = int(out[i], 16)
            frames[current] = []
            i += 1
        else:
            frames[current].append((out[i], out[i + 1] if i + 1 < len(out) else '?'))
            i += 2
    inclusive, innermost, lines = collections.Counter(), collections.Counter(), collections.Counter()
    for pc, n in per_pc.items():
        fr = frames.get(pc) or [('?', '?')]
        for name in {strip_generics(f) for f, _ in fr}:
            inclusive[name] += n
        innermost[strip_generics(fr[0][0])] += n
        lines[re.sub(r'^.*/(src/)', r'\1', fr[0][1].split(' ')[0])] += n
    print(f'instructions per step: {sum(per_pc.values()) / steps:,.0f}')
    for title, table, k in (('inclusive, by function (inline frames)', inclusive, 40),
                            ('self, by innermost function', innermost, 25), ('by source line', lines, 40)):
        print(f'\n== {title} ==')
        for name, n in table.most_common(k):
            print(f'{n / steps:10.1f}  {name}')
    symbols = subprocess.run(['llvm-nm', '--defined-only', elf], capture_output=True, text=True).stdout
    print('\n== calls per step (entries of library routines) ==')
    calls = []
    for line in symbols.splitlines():
        parts = line.split()
        if len(parts) == 3 and re.search(r'aeabi|sf3|sincos|mem(cpy|set|clr|move)|sqrt', parts[2]):
            n = per_pc.get(int(parts[0], 16) & ~1, 0)
            if n:
                calls.append((n / steps, parts[2]))
    for n, name in sorted(calls, reverse=True):
        print(f'{n:10.1f}  {name}')


if __name__ == '__main__':
    if sys.argv[1] == 'count':
        count(sys.argv[2], sys.argv[3])
    else:
        report(*sys.argv[2:5])
