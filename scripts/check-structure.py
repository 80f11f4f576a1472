#!/usr/bin/env python3
"""The structural rules of docs/design.md, checked on the source tree (run by the e2e test
`structure`, so by CI):
  - layers: core -> geo -> io -> cli -> areas -> stages -> apps; no include from a lower layer
    to a higher one, and no circle between areas;
  - thin stages: no libmapfuse/src/stages/*.cpp over 150 lines; no `_detail` header;
  - thin tools: no app main() over 25 lines;
  - parameters said once: no hand-written validate() / requireParam / settings() copy left
    (every rule lives in a `visit` declaration; tests/core checks each key is declared once).
Files still being converted are listed, with the reason, in scripts/structure-pending.txt: their
violations are printed as PENDING and do not fail the check; a pending file that no longer
violates anything must leave the list (the check fails until it does), so the list only shrinks.
usage: scripts/check-structure.py [ROOT]   (exit 1 and one line per violation)"""
import os
import re
import sys

ROOT = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..")
LIB = os.path.join(ROOT, "libmapfuse")
RANK = {"core": 0, "geo": 1, "io": 2, "cli": 3, "stages": 5}
AREA_RANK = 4
MAX_STAGE_LINES = 150
MAX_MAIN_LINES = 25
problems = []


def files(base, exts=(".hpp", ".cpp")):
    for d, _, names in os.walk(base):
        for n in sorted(names):
            if n.endswith(exts):
                yield os.path.join(d, n)


# ---- layers
edges = {}
for base in (os.path.join(LIB, "include", "mapfuse"), os.path.join(LIB, "src")):
    for path in files(base):
        area = os.path.relpath(path, base).split(os.sep)[0]
        for n, line in enumerate(open(path, errors="replace"), 1):
            m = re.match(r'\s*#include\s+"mapfuse/([a-z_0-9]+)/', line)
            if not m or m.group(1) == area:
                continue
            to = m.group(1)
            edges.setdefault(area, set()).add(to)
            if RANK.get(to, AREA_RANK) > RANK.get(area, AREA_RANK):
                problems.append(f"layer: {os.path.relpath(path, ROOT)}:{n} ({area}) includes {to}")


def find_cycle():
    state, stack = {}, []

    def visit(a):
        state[a] = 1
        stack.append(a)
        for b in sorted(edges.get(a, ())):
            if state.get(b) == 1:
                return stack[stack.index(b):] + [b]
            if not state.get(b):
                c = visit(b)
                if c:
                    return c
        state[a] = 2
        stack.pop()
        return None

    for a in sorted(edges):
        if not state.get(a):
            c = visit(a)
            if c:
                return c
    return None


cycle = find_cycle()
if cycle:
    problems.append("circle between areas: " + " -> ".join(cycle))

# ---- thin stages
for path in files(os.path.join(LIB, "src", "stages"), (".cpp",)):
    lines = sum(1 for _ in open(path))
    if lines > MAX_STAGE_LINES:
        problems.append(f"stage: {os.path.relpath(path, ROOT)} has {lines} lines (> {MAX_STAGE_LINES})")
for path in files(LIB):
    if "_detail" in os.path.basename(path):
        problems.append(f"stage: {os.path.relpath(path, ROOT)} is a _detail file")

# ---- thin tools: main() from its line to the closing brace at column 0
for path in files(os.path.join(ROOT, "apps"), (".cpp",)):
    text = open(path).read().split("\n")
    for i, line in enumerate(text):
        if re.match(r"int main\(", line):
            end = next((j for j in range(i, len(text)) if text[j] == "}"), len(text) - 1)
            if end - i + 1 > MAX_MAIN_LINES:
                problems.append(f"tool: {os.path.relpath(path, ROOT)} main() has {end - i + 1} "
                                f"lines (> {MAX_MAIN_LINES})")

# ---- parameters said once
for path in files(LIB):
    for n, line in enumerate(open(path), 1):
        if re.search(r"\brequireParam\(|\bvoid validate\(\) const|::validate\(\) const|"
                     r"Settings settings\(\) const", line):
            problems.append(f"params: {os.path.relpath(path, ROOT)}:{n}: a rule or copy outside "
                            f"the declarations: {line.strip()}")

pending = {}
pending_file = os.path.join(ROOT, "scripts", "structure-pending.txt")
if os.path.exists(pending_file):
    for line in open(pending_file):
        line = line.split("#", 1)[0].strip()
        if line:
            pending[line] = False
failing = []
for p in problems:
    path = p.split(": ", 1)[1].split(":", 1)[0].split(" ", 1)[0]
    if path in pending:
        pending[path] = True
        print("PENDING " + p)
    else:
        failing.append(p)
        print(p)
for path, used in pending.items():
    if not used:
        failing.append(f"pending: {path} no longer violates anything; remove it from "
                       f"scripts/structure-pending.txt")
        print(failing[-1])
print(f"check-structure: {len(failing)} problem(s), "
      f"{len(problems) - len(failing) + sum(not u for u in pending.values())} pending",
      file=sys.stderr)
sys.exit(1 if failing else 0)
