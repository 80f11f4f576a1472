#!/usr/bin/env python3
"""Batch trust check of a crowd run (issue 33): the map against its own inputs.

Reads every georef.summary.json under WORK/georef and names each drive whose odometry and GPS
disagree: GPS residual rms per axis above georef's `trust_sigma_ratio` reported sigmas
or more than `trust_max_rejected_share` of its fixes rejected (`trusted: false`;
docs/fusion.md). Writes WORK/check.json; exits 3 when the share of untrusted
drives exceeds --max-untrusted-share (default 0: any untrusted drive fails the batch), naming the
drives and their residuals on stderr; 2 on usage errors; 0 otherwise. It also reports how far
align tied the batch together (issue 36; align.summary.json `ties`, untiled or per tile): the
share of 500 m stretches whose registrations reach no other drive sits at one drive's GPS error
in the map, and above --warn-untied-share (default 0.1) a warning names it (exit unchanged).

    python3 scripts/crowd_check.py WORK [--max-untrusted-share 0.1]
"""
import argparse
import glob
import json
import os
import sys


def alignTies(work):
    """Stretches and untied share over align's summaries (untiled, else every tile's)."""
    files = glob.glob(os.path.join(work, "align", "align.summary.json")) or sorted(
        glob.glob(os.path.join(work, "tiles", "*", "align", "align.summary.json")))
    stretches = untied = 0
    stretch_m = None
    for f in files:
        with open(f) as fh:
            t = json.load(fh).get("ties")
        if not t:
            continue
        stretches += t["stretches"]
        untied += t["by_tied_traversals"].get("0", 0)
        stretch_m = t["stretch_m"]
    if not stretches:
        return None
    return {"stretch_m": stretch_m, "stretches": stretches, "untied_share": untied / stretches}


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("work", help="the batch's WORK folder (scripts/crowd.mk)")
    ap.add_argument("--max-untrusted-share", type=float, default=0.0,
                    help="share of untrusted drives above which the batch fails (default 0)")
    ap.add_argument("--warn-untied-share", type=float, default=0.1,
                    help="warn above this share of 500 m stretches tied to no other drive")
    a = ap.parse_args()
    files = sorted(glob.glob(os.path.join(a.work, "georef", "*", "georef.summary.json")))
    if not files:
        print(f"crowd_check: {a.work}/georef: no georef.summary.json", file=sys.stderr)
        return 2
    drives = []
    for f in files:
        with open(f) as fh:
            s = json.load(fh)
        for d in s["lsms"]:
            drives.append({"drive_id": d["drive_id"], "trusted": d.get("trusted", True),
                           "residual_h_rms_m": d.get("residual_h_rms_m"),
                           "residual_v_rms_m": d.get("residual_v_rms_m"),
                           "residual_v_mean_m": d.get("residual_v_mean_m"),
                           "gps_rejected": d["gps_rejected"], "gps_used": d["gps_used"],
                           "odom_vertical_slope": d.get("odom_vertical_slope", 0.0),
                           "odom_scale_error": d.get("odom_scale_error", 0.0)})
    bad = [d for d in drives if not d["trusted"]]
    share = len(bad) / len(drives)
    failed = share > a.max_untrusted_share
    out = {"drives": drives, "untrusted": [d["drive_id"] for d in bad],
           "untrusted_share": share, "max_untrusted_share": a.max_untrusted_share,
           "passed": not failed}
    ties = alignTies(a.work)
    if ties:
        out["ties"] = ties
        if ties["untied_share"] > a.warn_untied_share:
            print(f"crowd_check: warning: {100 * ties['untied_share']:.1f} % of"
                  f" {ties['stretches']} stretches of {ties['stretch_m']:.0f} m are tied to no other"
                  f" drive (align.summary.json ties): there the map has one drive's GPS error",
                  file=sys.stderr)
    tmp = os.path.join(a.work, "check.json.tmp")
    with open(tmp, "w") as fh:
        json.dump(out, fh, indent=1)
    os.replace(tmp, os.path.join(a.work, "check.json"))
    for d in bad:
        print(f"crowd_check: drive {d['drive_id']}: odometry and GPS disagree "
              f"({d['gps_rejected']} of {d['gps_rejected'] + d['gps_used']} GPS fixes rejected, residual rms "
              f"horizontal {d['residual_h_rms_m']:.2f} m, vertical {d['residual_v_rms_m']:.2f} m, "
              f"vertical mean {d['residual_v_mean_m']:+.2f} m, odometry height slope "
              f"{d['odom_vertical_slope']:+.4f}, scale error {d['odom_scale_error']:+.4f})",
              file=sys.stderr)
    if failed:
        print(f"crowd_check: {len(bad)} of {len(drives)} drives untrusted (share {share:.2f} > "
              f"{a.max_untrusted_share}): the map is not trusted", file=sys.stderr)
        return 3
    return 0


if __name__ == "__main__":
    sys.exit(main())
