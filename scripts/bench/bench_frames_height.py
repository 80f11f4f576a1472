#!/usr/bin/env python3
"""Heights of a crowd run against the simulator's truth (issue 33).

Keyframe error: each aligned LSM keyframe against the true pose at its stamp (vertical and
horizontal RMS, per drive and over all). Element height error: every map point of a class
against the nearest true point of the same class within --radius m horizontally (true
polylines resampled every 0.25 m): mean and RMS of map z - true z per class and over all.
Origins may differ (WGS84 ENU conversion). Prints one JSON document.

    bench_frames_height.py --aligned WORK/align --truth-traj TRUTH_DIR \
        --map WORK/aggregate/map.json --truth TRUTH_DIR/vector_map.json
"""
import argparse
import glob
import json
import math
import os

A, F = 6378137.0, 1 / 298.257223563
E2 = F * (2 - F)


def ecef(lat, lon, alt):
    la, lo = math.radians(lat), math.radians(lon)
    n = A / math.sqrt(1 - E2 * math.sin(la) ** 2)
    return [(n + alt) * math.cos(la) * math.cos(lo), (n + alt) * math.cos(la) * math.sin(lo),
            (n * (1 - E2) + alt) * math.sin(la)]


class Enu:
    def __init__(self, o):
        self.lat, self.lon = math.radians(o["lat"]), math.radians(o["lon"])
        self.o = ecef(o["lat"], o["lon"], o["alt"])
        sl, cl, so, co = math.sin(self.lat), math.cos(self.lat), math.sin(self.lon), math.cos(self.lon)
        self.R = [[-so, co, 0], [-sl * co, -sl * so, cl], [cl * co, cl * so, sl]]  # ecef -> enu

    def to_ecef(self, p):
        R = self.R
        return [self.o[i] + sum(R[j][i] * p[j] for j in range(3)) for i in range(3)]

    def from_ecef(self, x):
        d = [x[i] - self.o[i] for i in range(3)]
        return [sum(self.R[j][i] * d[i] for i in range(3)) for j in range(3)]


def converter(src, dst):
    if all(abs(src[k] - dst[k]) < 1e-12 for k in ("lat", "lon", "alt")):
        return lambda p: list(p)
    a, b = Enu(src), Enu(dst)
    return lambda p: b.from_ecef(a.to_ecef(p))


def rms(v):
    return math.sqrt(sum(x * x for x in v) / len(v)) if v else None


def keyframes(aligned, truth_dir, truth_origin):
    per, allv, allh = {}, [], []
    for f in sorted(glob.glob(os.path.join(aligned, "*.json"))):
        if f.endswith("summary.json") or f.endswith("config.json"):
            continue
        lsm = json.load(open(f))
        if "keyframes" not in lsm:
            continue
        tf = os.path.join(truth_dir, lsm["drive_id"] + ".trajectory.json")
        if not os.path.exists(tf):
            continue
        tr = json.load(open(tf))
        conv = converter(lsm["origin"], tr["origin"])
        truth = sorted((p["stamp"], p["pose"]["t"]) for p in tr["poses"])
        stamps = [t for t, _ in truth]
        dv, dh = [], []
        for k in lsm["keyframes"]:
            import bisect
            i = bisect.bisect_left(stamps, k["stamp"] - 1e-4)
            if i >= len(stamps) or abs(stamps[i] - k["stamp"]) > 1e-3:
                continue
            p, t = conv(k["pose"]["t"]), truth[i][1]
            dv.append(p[2] - t[2])
            dh.append(math.hypot(p[0] - t[0], p[1] - t[1]))
        per[lsm["drive_id"]] = {"vertical_rms_m": rms(dv), "vertical_mean_m": sum(dv) / len(dv) if dv else None,
                                "horizontal_rms_m": rms(dh), "keyframes": len(dv)}
        allv += dv
        allh += dh
    return {"vertical_rms_m": rms(allv), "horizontal_rms_m": rms(allh), "drives": per}


def resample(pts, step=0.25):
    out = [pts[0]]
    for a, b in zip(pts, pts[1:]):
        n = max(1, int(math.dist(a, b) / step))
        out += [[a[j] + (b[j] - a[j]) * i / n for j in range(3)] for i in range(1, n + 1)]
    return out


def elements(map_doc, truth_doc, radius):
    conv = converter(map_doc["origin"], truth_doc["origin"])
    grid = {}
    for inst in truth_doc["instances"]:
        if not inst.get("points"):
            continue
        for p in resample(inst["points"]):
            grid.setdefault((inst["class"], int(p[0] // radius), int(p[1] // radius)), []).append(p)
    per, alle = {}, []
    for inst in map_doc["instances"]:
        for q in inst.get("points") or []:
            q = conv(q)
            best, bz = radius, None
            cx, cy = int(q[0] // radius), int(q[1] // radius)
            for dx in (-1, 0, 1):
                for dy in (-1, 0, 1):
                    for p in grid.get((inst["class"], cx + dx, cy + dy), []):
                        d = math.hypot(p[0] - q[0], p[1] - q[1])
                        if d < best:
                            best, bz = d, q[2] - p[2]
            if bz is not None:
                per.setdefault(inst["class"], []).append(bz)
                alle.append(bz)
    return {"rms_m": rms(alle), "mean_m": sum(alle) / len(alle) if alle else None, "points": len(alle),
            "classes": {c: {"rms_m": rms(v), "mean_m": sum(v) / len(v), "points": len(v)} for c, v in per.items()}}


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--aligned", required=True)
    ap.add_argument("--truth-traj", required=True)
    ap.add_argument("--map", required=True)
    ap.add_argument("--truth", required=True)
    ap.add_argument("--radius", type=float, default=1.5, help="m, horizontal match radius")
    a = ap.parse_args()
    truth = json.load(open(a.truth))
    out = {"keyframes": keyframes(a.aligned, a.truth_traj, truth["origin"]),
           "element_height": elements(json.load(open(a.map)), truth, a.radius)}
    print(json.dumps(out, indent=1))


if __name__ == "__main__":
    main()
