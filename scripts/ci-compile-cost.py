#!/usr/bin/env python3
"""Cold compile cost of the sanitizer build's options, measured on a sample of translation units.

    scripts/ci-compile-cost.py RELEASE_BUILD SANITIZE_BUILD [--every N] [--configs a,b,...]

RELEASE_BUILD is a configured gcc release tree (build/), SANITIZE_BUILD a configured clang
MAPFUSE_FUZZ tree (build-sanitize/); their compile_commands.json give the exact commands. Every
N-th translation unit (sorted by path; library, tools and tests, not benchmarks or fuzz targets) is
compiled once per configuration, without ccache, at the caller's priority, and the CPU seconds
(user + sys of the compiler, from getrusage) are summed. CPU time, not wall time, so that the
figure holds on a loaded machine; docs/reliability.md "CI time" extrapolates it to all units.

Configurations (derived from the two trees' commands by changing flags only):
  release      gcc -O3, the release build as configured (the reference)
  clang-O2     clang ASan + UBSan + fuzzer-no-link, -O2 -gline-tables-only (the old sanitizer build)
  clang-O1     the same at -O1
  clang-O0     the same at -O0
  gcc-O1       gcc ASan + UBSan at -O1 (unit tests only: gcc has no libFuzzer)
  unity-O1     the first 8 library units of one area (--unity-area, default io) glued into one
               translation unit (what CMAKE_UNITY_BUILD does) against the same 8 one by one
"""
import argparse
import json
import os
import re
import resource
import shlex
import subprocess
import sys
import tempfile
from collections import defaultdict

SAN = "-fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer"


def load(build):
    with open(os.path.join(build, "compile_commands.json")) as f:
        return {os.path.realpath(e["file"]): e for e in json.load(f)}


def strip_launcher(cmd):
    parts = shlex.split(cmd)
    while parts and os.path.basename(parts[0]) == "ccache":
        parts = parts[1:]
    return parts


def with_output(parts, out):
    i = parts.index("-o")
    return parts[:i + 1] + [out] + parts[i + 2:]


def clang_at(parts, opt):
    s = " ".join(shlex.quote(p) for p in parts)
    s, n = re.subn(r"-O[0-3s] -gline-tables-only", f"{opt} -gline-tables-only", s)
    if n != 1:
        sys.exit("ci-compile-cost: no -O<n> -gline-tables-only in " + s[:200])
    return shlex.split(s)


def gcc_sanitized(parts):
    s = " ".join(shlex.quote(p) for p in parts)
    s, n = re.subn(r"-O3 -DNDEBUG", f"-O1 -g1 {SAN}", s)
    if n != 1:
        sys.exit("ci-compile-cost: no -O3 -DNDEBUG in " + s[:200])
    return shlex.split(s)


def cpu_of(argv, cwd):
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    r = subprocess.run(argv, cwd=cwd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    if r.returncode != 0:
        sys.stderr.write(f"compile failed: {' '.join(argv[-1:])}\n{r.stderr[:2000]}\n")
        return None
    return cpu


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("release")
    ap.add_argument("sanitize")
    ap.add_argument("--every", type=int, default=12)
    ap.add_argument("--configs", default="release,clang-O2,clang-O1,gcc-O1,clang-O0,unity-O1")
    ap.add_argument("--unity-area", default="io")
    a = ap.parse_args()
    rel, san = load(a.release), load(a.sanitize)
    common = sorted(f for f in rel if f in san and "/scripts/bench/" not in f)
    sample = common[::a.every]
    configs = a.configs.split(",")
    tmp = tempfile.mkdtemp(prefix="ci-compile-cost-")
    out = os.path.join(tmp, "x.o")
    env_note = open("/proc/loadavg").read().split()[:3]
    print(f"# {len(sample)} of {len(common)} units (every {a.every}th), load before {env_note}")
    totals = defaultdict(float)
    rows = []
    for f in sample:
        row = [os.path.relpath(f, os.path.dirname(os.path.abspath(a.release)))]
        for c in configs:
            if c == "unity-O1":
                continue
            if c == "release":
                argv = strip_launcher(rel[f]["command"])
                cwd = rel[f]["directory"]
            elif c.startswith("clang-"):
                argv = clang_at(strip_launcher(san[f]["command"]), "-" + c.split("-")[1])
                cwd = san[f]["directory"]
            elif c == "gcc-O1":
                argv = gcc_sanitized(strip_launcher(rel[f]["command"]))
                cwd = rel[f]["directory"]
            cpu = cpu_of(with_output(argv, out), cwd)
            totals[c] += cpu or 0.0
            row.append(f"{cpu:.1f}" if cpu is not None else "FAIL")
        rows.append(row)
        print("\t".join(row), flush=True)
    if "unity-O1" in configs:
        # One unity batch of 8 library units of one area (what CMAKE_UNITY_BUILD's default
        # batch size glues together) against the same 8 compiled one by one.
        files = [f for f in common if f"/libmapfuse/src/{a.unity_area}/" in f][:8]
        single = 0.0
        for f in files:
            argv = clang_at(strip_launcher(san[f]["command"]), "-O1")
            single += cpu_of(with_output(argv, out), san[f]["directory"]) or 0.0
        src = os.path.join(tmp, "unity.cpp")
        with open(src, "w") as u:
            u.writelines(f'#include "{f}"\n' for f in files)
        argv = clang_at(strip_launcher(san[files[0]]["command"]), "-O1")
        argv[-1] = src
        batch = cpu_of(with_output(argv, out), san[files[0]]["directory"])
        print(f"# unity: {len(files)} {a.unity_area} units one by one {single:.1f} s CPU, as one "
              f"batch {batch if batch is None else round(batch, 1)} s (clang-O1)", flush=True)
    print("# totals (CPU s over the sample): " +
          ", ".join(f"{c} {totals[c]:.1f}" for c in configs if c != "unity-O1"))
    if totals.get("release"):
        print("# ratio to release: " + ", ".join(
            f"{c} {totals[c] / totals['release']:.2f}" for c in configs
            if c not in ("release", "unity-O1")))
    print(f"# load after {open('/proc/loadavg').read().split()[:3]}")


if __name__ == "__main__":
    main()
