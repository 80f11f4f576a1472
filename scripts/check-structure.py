#!/usr/bin/env python3
"""The structural rules of docs/design.md, checked on the source tree (run by the e2e test
`structure`, so by CI):
  - layers: core -> geo -> lanelet -> io -> cli -> areas -> stages -> apps; no include from a lower layer
    to a higher one, and no circle between areas;
  - thin stages: no libmapfuse/src/stages/*.cpp over 120 lines; no `_detail` header;
  - thin tools: no app main() over 25 lines;
  - short functions: no function of libmapfuse/ or apps/ over 120 lines (split it into named
    steps);
  - io only reads and writes: no io file over 300 lines;
  - public headers only where needed: a header in libmapfuse/include/mapfuse/<area>/ is included
    by another area, a stage, an app, a fuzz target or a benchmark (tests aside), or by such a
    public header; else it moves to libmapfuse/src/<area>/;
  - parameters said once: no hand-written validate() / requireParam / settings() copy left
    (every rule lives in a `visit` declaration; tests/core checks each key is declared once), and
    every field of a struct with a `visit` is declared there (or is itself a struct with a
    `visit`, declared in its own); a value that is no parameter is a named constant outside it.
Files still being converted are listed, with the reason, in scripts/structure-pending.txt: their
violations are printed as PENDING and do not fail the check; a pending file that no longer
violates anything must leave the list (the check fails until it does), so the list only shrinks.
usage: scripts/check-structure.py [ROOT]   (exit 1 and one line per violation)"""
import os
import re
import sys

ROOT = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..")
LIB = os.path.join(ROOT, "libmapfuse")
RANK = {"core": 0, "geo": 1, "lanelet": 2, "io": 3, "cli": 4, "stages": 6}
AREA_RANK = 5
MAX_STAGE_LINES = 120
MAX_FUNCTION_LINES = 120
MAX_IO_LINES = 300
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

# ---- source text without comments and literals (for the function and field checks)
def code_of(path):
    t = open(path, errors="replace").read()
    out, i, n = [], 0, len(t)
    while i < n:
        c = t[i]
        if t.startswith("//", i):
            j = t.find("\n", i)
            i = n if j < 0 else j
            continue
        if t.startswith("/*", i):
            j = t.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append("\n" * t.count("\n", i, j))
            i = j
            continue
        m = re.match(r'R"([^(]*)\(', t[i:i + 20]) if c == "R" else None
        if m:
            end = ")" + m.group(1) + '"'
            j = t.find(end, i + m.end())
            j = n if j < 0 else j + len(end)
            out.append('""' + "\n" * t.count("\n", i, j))
            i = j
            continue
        if c == '"' or (c == "'" and not (i > 0 and (t[i - 1].isalnum()))):
            j = i + 1
            while j < n and t[j] != c:
                j += 2 if t[j] == "\\" else 1
            out.append(c + c)
            i = j + 1
            continue
        out.append(c)
        i += 1
    return "".join(out)


def matching(t, i):
    depth = 0
    for j in range(i, len(t)):
        if t[j] == "{":
            depth += 1
        elif t[j] == "}":
            depth -= 1
            if depth == 0:
                return j
    return len(t) - 1


def function_spans(t):
    """(first line, lines, name) of every function body at namespace or class scope."""
    spans, stack, last, i = [], [], 0, 0
    while i < len(t):
        c = t[i]
        if c == ";":
            last = i + 1
        elif c == "{":
            head = t[last:i]
            if re.search(r"\bnamespace\b", head) or re.search(r'extern\s*""\s*$', head.strip()):
                stack.append("ns")
            elif re.search(r"\b(struct|class|union|enum)\b[^()]*$", head):
                stack.append("class")
            elif (all(k in ("ns", "class") for k in stack) and ")" in head
                  and not re.match(r"\s*(if|for|while|switch|catch|do|else|return)\b", head)
                  and "=" not in head.split("(")[0]):
                j = matching(t, i)
                start = t.count("\n", 0, last + len(head) - len(head.lstrip())) + 1
                names = re.findall(r"([~\w:]+|operator\S+)\s*\(", head)
                spans.append((start, t.count("\n", 0, j) + 2 - start,
                              names[0] if names else head.strip()[:40]))
                i, last = j + 1, j + 1
                continue
            else:
                stack.append("other")
            last = i + 1
        elif c == "}":
            if stack:
                stack.pop()
            last = i + 1
        i += 1
    return spans


# ---- short functions
for base in (LIB, os.path.join(ROOT, "apps")):
    for path in files(base):
        for start, length, name in function_spans(code_of(path)):
            if length > MAX_FUNCTION_LINES:
                problems.append(f"function: {os.path.relpath(path, ROOT)}:{start} {name} has "
                                f"{length} lines (> {MAX_FUNCTION_LINES})")

# ---- io only reads and writes
for base in (os.path.join(LIB, "src", "io"), os.path.join(LIB, "include", "mapfuse", "io")):
    for path in files(base):
        lines = sum(1 for _ in open(path))
        if lines > MAX_IO_LINES:
            problems.append(f"io: {os.path.relpath(path, ROOT)} has {lines} lines "
                            f"(> {MAX_IO_LINES}: io reads and writes; the rest belongs in an area)")

# ---- public headers only where needed
PUBLIC = os.path.join(LIB, "include", "mapfuse")
includes = {}  # file relative to ROOT -> {"area/header.hpp"}
for base in ("libmapfuse", "apps", "fuzz", "tests", os.path.join("scripts", "bench")):
    for path in files(os.path.join(ROOT, base), (".hpp", ".cpp", ".h", ".cc")):
        rel = os.path.relpath(path, ROOT)
        includes[rel] = {m.group(1) for line in open(path, errors="replace")
                         for m in [re.match(r'\s*#include\s+"mapfuse/([a-z_0-9]+/[\w.]+)"', line)]
                         if m}


def owner_of(rel):
    parts = rel.split(os.sep)
    if parts[0] != "libmapfuse":
        return parts[0]  # apps, fuzz, tests, scripts (the benchmarks)
    return parts[3] if parts[1] == "include" else parts[2]


needed = set()
for rel, hs in includes.items():
    who = owner_of(rel)
    if who != "tests":
        needed |= {h for h in hs if h.split("/")[0] != who}
grew = True
while grew:  # what a needed public header includes is needed too
    grew = False
    for h in list(needed):
        for g in includes.get(os.path.join("libmapfuse", "include", "mapfuse", h), ()):
            if g not in needed:
                needed.add(g)
                grew = True
for area in sorted(os.listdir(PUBLIC)):
    for name in sorted(os.listdir(os.path.join(PUBLIC, area))):
        if f"{area}/{name}" not in needed:
            problems.append(f"header: libmapfuse/include/mapfuse/{area}/{name} is used by "
                            f"{area} only: move it to libmapfuse/src/{area}/")

# ---- every field of a declared struct is declared
declared_structs = {}  # struct name -> its code, for the structs with a visit()
for path in files(LIB, (".hpp",)):
    t = code_of(path)
    for m in re.finditer(r"\bstruct\s+(\w+)\s*(?::[^{;]*)?\{", t):
        if re.search(r"void\s+visit\s*\(", t[m.end():matching(t, m.end() - 1)]):
            declared_structs[m.group(1)] = path
for path in files(LIB, (".hpp",)):
    t = code_of(path)
    for m in re.finditer(r"\bstruct\s+(\w+)\s*(?::[^{;]*)?\{", t):
        end = matching(t, m.end() - 1)
        body = t[m.end():end]
        vm = re.search(r"void\s+visit\s*\(", body)
        if not vm:
            continue
        vstart = body.index("{", vm.end())
        vbody = body[vstart:matching(body, vstart)]
        depth, stmt, statements = 0, "", []
        for ch in body:
            if ch == "{":
                depth += 1
            elif ch == "}":
                depth -= 1
                if depth == 0:
                    stmt += "{}"
                    continue
            if depth == 0:
                stmt += ch
                if ch == ";":
                    statements.append(stmt.strip())
                    stmt = ""
        for s in statements:
            s = s.replace("{}", " ")
            if re.match(r"(static|using|template|friend|typedef|enum|struct|class|public|"
                        r"private|protected)\b", s) or "(" in s.split("=")[0]:
                continue
            fm = re.match(r"(.+?)\s+(\w+)\s*(=.*)?;$", s, re.S)
            if not fm or re.search(r"\b" + fm.group(2) + r"\b", vbody):
                continue
            if re.sub(r".*::", "", fm.group(1).strip()) in declared_structs:
                continue  # composed of a struct that declares its own fields
            problems.append(f"params: {os.path.relpath(path, ROOT)} {m.group(1)}::{fm.group(2)} "
                            f"is not declared in its visit() (declare it, or make it a named "
                            f"constant outside the struct with the reason)")

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
