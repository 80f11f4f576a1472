#!/usr/bin/env python3
"""Renames the before ids of a change report made against an aggregated map to the ids of the
simulator's before truth, so that `evaluate changes --before TRUTH` can score it (docs/update.md
"Figures"). An aggregated element takes the id of the truth element of its class nearest to it:
point and planar elements and stop lines by centre distance (at most --max-distance m), lane lines
by the median distance of their points to the truth line (at most --max-distance m). Several
changes of one truth element keep the most confident; changes of elements without a truth partner
(false elements of the map) are dropped and counted on stderr.

usage: changes-to-truth-ids.py CHANGES.json MAP.json TRUTH_BEFORE.json OUT.json [--max-distance M]
"""
import json
import math
import sys


def centre(points):
    return (sum(p[0] for p in points) / len(points), sum(p[1] for p in points) / len(points))


def seg_dist(p, a, b):
    dx, dy = b[0] - a[0], b[1] - a[1]
    l2 = dx * dx + dy * dy
    u = 0.0 if l2 == 0 else max(0.0, min(1.0, ((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / l2))
    return math.hypot(a[0] + u * dx - p[0], a[1] + u * dy - p[1])


def line_dist(p, line):
    if len(line) == 1:
        return math.hypot(p[0] - line[0][0], p[1] - line[0][1])
    return min(seg_dist(p, a, b) for a, b in zip(line, line[1:]))


def partner(inst, truth, max_d):
    best, best_id = max_d, None
    for t in truth:
        if t["class"] != inst["class"]:
            continue
        if inst["class"] == "lane_line":
            ds = sorted(line_dist(p, t["points"]) for p in inst["points"])
            d = ds[len(ds) // 2]
        else:
            a, b = centre(inst["points"]), centre(t["points"])
            d = math.hypot(a[0] - b[0], a[1] - b[1])
        if d < best:
            best, best_id = d, t["id"]
    return best_id


def main():
    args = sys.argv[1:]
    max_d = 2.0
    if "--max-distance" in args:
        i = args.index("--max-distance")
        max_d = float(args[i + 1])
        del args[i:i + 2]
    changes_path, map_path, truth_path, out_path = args
    doc = json.load(open(changes_path))
    amap = {i["id"]: i for i in json.load(open(map_path))["instances"]}
    truth_doc = json.load(open(truth_path))
    truth = truth_doc["instances"]
    kept, dropped, best = [], 0, {}
    for c in doc["changes"]:
        if "before_id" not in c:
            kept.append(c)
            continue
        tid = partner(amap[c["before_id"]], truth, max_d)
        if tid is None:
            dropped += 1
            continue
        prev = best.get(tid)
        if prev is None or c.get("confidence", 0) > prev.get("confidence", 0):
            best[tid] = c
        c["before_id"] = tid
        if c.get("after_id") is not None and c["kind"] != "added":
            c["after_id"] = tid
    kept += list(best.values())
    taken = {c["after_id"] for c in kept if c["kind"] != "added" and "after_id" in c}
    next_id = max([i["id"] for i in truth] + [0]) + 1
    for c in kept:  # additions: ids clear of the truth's
        if c["kind"] == "added":
            c["after_id"] = next_id
            next_id += 1
    doc["changes"] = kept
    doc["origin"] = truth_doc["origin"]
    json.dump(doc, open(out_path, "w"), indent=1)
    print(f"{len(kept)} changes kept, {dropped} of map elements without a truth partner dropped",
          file=sys.stderr)


if __name__ == "__main__":
    main()
