#!/usr/bin/env bash
# Issue 23's "no behaviour change" check: runs the demo (scripts/demo.sh) with the tools of two
# builds and compares every output byte for byte, summaries (*.summary.json) without their
# timing fields (keys seconds*, *_seconds, seconds_*, timings_s). Both runs use the same paths
# (<work>/bin, <work>/models, <work>/out), so the paths written into summaries agree.
# usage: scripts/demo-identical.sh BEFORE_BUILD AFTER_BUILD [WORK=/tmp/demo-identical]
#   (each BUILD a build folder with bin/ and models/; about 1 minute per run)
# Prints one line per differing file and a count; exit 1 when any file differs.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
before=$(cd "${1:?usage: demo-identical.sh BEFORE_BUILD AFTER_BUILD [WORK]}" && pwd)
after=$(cd "${2:?usage: demo-identical.sh BEFORE_BUILD AFTER_BUILD [WORK]}" && pwd)
work=${3:-/tmp/demo-identical}

run() {  # run BUILD NAME: the demo with BUILD's tools, outputs kept in <work>/NAME
  rm -rf "$work/bin" "$work/models" "$work/out" "$work/$2"
  mkdir -p "$work"
  cp -a "$1/bin" "$1/models" "$work/"
  bash "$root/scripts/demo.sh" "$work/bin" "$work/out" > "$work/$2.log" 2>&1
  mv "$work/out" "$work/$2"
}
run "$before" before
run "$after" after

python3 - "$work/before" "$work/after" <<'PY'
import json, os, re, sys
a, b = sys.argv[1], sys.argv[2]
timing = re.compile(r"^seconds|seconds_|_seconds|^timings_s$")
def strip(x):
    if isinstance(x, dict):
        return {k: strip(v) for k, v in x.items() if not timing.search(k)}
    if isinstance(x, list):
        return [strip(v) for v in x]
    return x
files = bad = 0
for d, _, names in os.walk(a):
    for n in sorted(names):
        if n == ".mapfuse.lock":
            continue  # holds the pid of the run
        pa = os.path.join(d, n)
        rel = os.path.relpath(pa, a)
        pb = os.path.join(b, rel)
        files += 1
        if not os.path.exists(pb):
            print("only before:", rel); bad += 1; continue
        da, db = open(pa, "rb").read(), open(pb, "rb").read()
        if da == db:
            continue
        if n.endswith(".summary.json") and strip(json.loads(da)) == strip(json.loads(db)):
            continue
        print("differs:", rel); bad += 1
for d, _, names in os.walk(b):
    for n in names:
        rel = os.path.relpath(os.path.join(d, n), b)
        if n != ".mapfuse.lock" and not os.path.exists(os.path.join(a, rel)):
            print("only after:", rel); bad += 1
print(f"demo-identical: {files} files, {bad} differ (summary timings aside)")
sys.exit(1 if bad else 0)
PY
