"""docs/performance-map-bound.md from bench_map_bound.sh's rows (one JSON object per map)."""
import csv
import datetime
import json
import os
import statistics
import subprocess
import sys

rows_file, out, load, traversals, cells_file = sys.argv[1:]
rows = [json.loads(line) for line in open(rows_file)]
cpu = subprocess.run("lscpu | sed -n 's/^Model name: *//p'", shell=True, capture_output=True,
                     text=True).stdout.strip()
seeds = sorted({r["seed"] for r in rows}, key=lambda s: (s != 42, s))
by = {(r["seed"], r["name"]): r for r in rows}
variants = [("default", "default chain (gba_sgicp)"),
            ("oracle", "oracle: drives' own GPS bias off, default align"),
            ("sgicp", "align --method sgicp"),
            ("partners1", "align --gba-max-partners 1"),
            ("odometry0.003", "align --odom-sigma-per-m 0.003")]


def lat(r, col, key="rms_m"):
    return r["bound"]["lateral"][col][key]


lines = [
    "# Where the map's absolute error comes from (issue 22)", "",
    f"Produced by `scripts/bench/bench_map_bound.sh` on {datetime.date.today()}.", "",
    f"- machine: 2 cores, {cpu}, load average at start {load}.",
    f"- command: per seed `simulate --seed S --traversals {traversals}` (procedural world,"
    " 4 routes of 1.5 km: seed 42 is bench_localize.sh's map), `make -j2 -f scripts/crowd.mk"
    " map` (georef, align gba_sgicp, aggregate), then `bench_map_bound` (scripts/bench/"
    "bench_map_bound.cpp): the simulator is rerun in-process from simulate.config.json, so every"
    " GPS fix's true error and multipath flag are known.",
    "- figures: per map lane-line sample (every 1 m), n the unit normal of the nearest true lane"
    " line; all are across the road, m, RMS (mean of absolute values in brackets) over the"
    " samples. **map**: n . (map - true line). **bound**: n . the mean GPS error of the inlier"
    " fixes of the map's traversals that drove past the sample (within 50 m, heading within"
    " 30 deg: a 100 m stretch); where the GPS of those traversals puts the road on average, what"
    " a map anchored on it cannot beat without other absolute information. **global**: n . the"
    " mean GPS error of all inlier fixes of all traversals: a map of exact shape placed by"
    " least squares on all the GPS. **georef / align lines**: n . the mean error of those"
    " stages' lane-line points near the sample (their mean over the traversals).", "",
    "## Per seed", "",
    "| seed | expected global, per axis | bound (100 m) | global | georef lines | align lines |"
    " map | map / bound |",
    "|---|---|---|---|---|---|---|---|"]
for s in seeds:
    r = by.get((s, "default"))
    if not r:
        continue
    b = r["bound"]

    def cell(col):
        return f"{lat(r, col):.3f} ({lat(r, col, 'mean_abs_m'):.3f})"

    lines.append(f"| {s} | {b['expected_global_mean_per_axis_m']:.3f} | {cell('bound')} |"
                 f" {cell('global')} | {cell('georef_lines')} | {cell('align_lines')} |"
                 f" {cell('map')} | {lat(r, 'map') / lat(r, 'bound'):.2f} |")
defaults = [by[(s, "default")] for s in seeds if (s, "default") in by]
if defaults:
    mean = lambda col, key="rms_m": statistics.mean(lat(r, col, key) for r in defaults)
    lines.append(f"| mean | {defaults[0]['bound']['expected_global_mean_per_axis_m']:.3f} |"
                 f" {mean('bound'):.3f} ({mean('bound', 'mean_abs_m'):.3f}) |"
                 f" {mean('global'):.3f} ({mean('global', 'mean_abs_m'):.3f}) |"
                 f" {mean('georef_lines'):.3f} | {mean('align_lines'):.3f} |"
                 f" {mean('map'):.3f} ({mean('map', 'mean_abs_m'):.3f}) |"
                 f" {statistics.mean(lat(r, 'map') / lat(r, 'bound') for r in defaults):.2f} |")
    e = defaults[0]["bound"]
    lines += ["",
              f"Expected: a drive's GPS error per axis {e['expected_drive_gps_error_per_axis_m']:.2f}"
              " m (bias of 1-3 m in a random direction, plus its random walk averaged over a"
              f" {e['drive_seconds_mean']:.0f} s drive), so the mean of {traversals} independent"
              f" drives is {e['expected_global_mean_per_axis_m']:.3f} m per axis and"
              f" {e['expected_global_mean_abs_lateral_m']:.3f} m mean absolute across any road:"
              " the expected lateral error of even a map of exact shape placed on all the GPS."]

lines += ["", "## Ablations of align on the same georeferenced drives", "",
          "Quality figures of `evaluate map` (lane lines; issue 18 bars on the 2 km x 50 bench:"
          " relative precision <= 0.03 m, completeness >= 0.98, every class >= 0.95, redundancy"
          " <= 0.02). Align seconds are wall time under the load above (noisy).", "",
          "| seed | align | georef lines | align lines | map lateral RMS m | lane abs mean m |"
          " lane rel. precision m | lane completeness | min class completeness | max redundancy |"
          " align s |",
          "|---|---|---|---|---|---|---|---|---|---|---|"]
for s in seeds:
    for name, label in variants:
        r = by.get((s, name))
        if not r:
            continue
        lines.append(f"| {s} | {label} | {lat(r, 'georef_lines'):.3f} |"
                     f" {lat(r, 'align_lines'):.3f} | {lat(r, 'map'):.3f} |"
                     f" {r['lane_abs_mean_m']:.3f} |"
                     f" {r['lane_rel_precision_m']:.4f} | {r['lane_completeness']:.3f} |"
                     f" {r['min_class_completeness']:.3f} | {r['max_redundancy']:.3f} |"
                     f" {r['align_seconds']:.1f} |")
for name, label in variants:
    rs = [by[(s, name)] for s in seeds if (s, name) in by]
    if not rs:
        continue
    lines.append(f"| mean | {label} | {statistics.mean(lat(r, 'georef_lines') for r in rs):.3f} |"
                 f" {statistics.mean(lat(r, 'align_lines') for r in rs):.3f} |"
                 f" {statistics.mean(lat(r, 'map') for r in rs):.3f} |"
                 f" {statistics.mean(r['lane_abs_mean_m'] for r in rs):.3f} |"
                 f" {statistics.mean(r['lane_rel_precision_m'] for r in rs):.4f} |"
                 f" {min(r['lane_completeness'] for r in rs):.3f} (min) |"
                 f" {min(r['min_class_completeness'] for r in rs):.3f} (min) |"
                 f" {max(r['max_redundancy'] for r in rs):.3f} (max) | |")

if os.path.exists(cells_file):
    lines += ["", "## Per 100 m stretch, seed 42", "",
              "100 m x 100 m cells of the map's lane-line samples (cells with >= 100 samples),"
              " RMS across the road, m; fixes: GPS fixes of the traversals past a sample.", "",
              "| cell x m | cell y m | samples | fixes | bound | global | georef lines |"
              " align lines | map | map - bound |",
              "|---|---|---|---|---|---|---|---|---|---|"]
    for c in csv.DictReader(open(cells_file)):
        if int(c["samples"]) < 100:
            continue
        lines.append(f"| {float(c['cell_x_m']):.0f} | {float(c['cell_y_m']):.0f} |"
                     f" {c['samples']} | {c['fixes_per_sample']} |"
                     f" {float(c['bound_rms_m']):.3f} | {float(c['global_rms_m']):.3f} |"
                     f" {float(c['georef_lines_rms_m']):.3f} |"
                     f" {float(c['align_lines_rms_m']):.3f} | {float(c['map_rms_m']):.3f} |"
                     f" {float(c['map_minus_bound_rms_m']):.3f} |")
open(out, "w").write("\n".join(lines) + "\n")
print(f"bench: wrote {out}", file=sys.stderr)
