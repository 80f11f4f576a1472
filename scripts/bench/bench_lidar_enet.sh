#!/usr/bin/env bash
# Default lidar-semantic-map run with ENet on the real KITTI sfnd drive (issue 24): frames/s of
# the frame loop (reading + ENet of frame k+1 overlapped with the LiDAR work of frame k) and
# CPU-seconds per frame (user + sys of the whole run / frames, the load-independent figure),
# for the default (OpenCV's threads = cores), the network on one thread, and a half-scale input,
# whose label agreement with the default run is the oracle of its quality loss. Prints a
# Markdown section and puts it into docs/performance-lidar.md (replacing the previous one, between
# its markers; bench_lidar.sh keeps it); --no-doc only prints.
# usage: scripts/bench/bench_lidar_enet.sh [BIN_DIR=<root>/build/bin] [--no-doc]
# env:   FRAMES=30 REPS=3  (frames 0..FRAMES-1 of sfnd; median of REPS runs per variant)
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
bin=${1:-$root/build/bin}
update=${2:-}
frames=${FRAMES:-30}
reps=${REPS:-3}
shared=$(realpath -m "${MAPFUSE_SHARED:-$root/../shared}")
kitti="$shared/data/kitti_raw/2011_09_26/2011_09_26_drive_sfnd_sync"
model="$shared/models/enet-cityscapes/enet-model.net"
[[ -x "$bin/lidar-semantic-map" ]] || { echo "bench_lidar_enet: $bin/lidar-semantic-map not built" >&2; exit 2; }
[[ -d "$kitti" && -f "$model" ]] || { echo "bench_lidar_enet: $kitti or $model absent" >&2; exit 77; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
load=$(cut -d' ' -f1-3 /proc/loadavg)

run() {  # name rep [extra lidar-semantic-map args...]
  local name=$1 rep=$2
  shift 2
  /usr/bin/time -f '%U %S %e' -o "$tmp/$name.$rep.time" \
    "$bin/lidar-semantic-map" "$kitti" -o "$tmp/$name.$rep" --first-frame 0 \
    --last-frame $((frames - 1)) --pose-source odometry --model "$model" --quiet "$@" > /dev/null
}
for rep in $(seq 1 "$reps"); do
  run default "$rep"
  run net1thread "$rep" --enet-threads 1
  run half "$rep" --enet-scale 0.5
done

python3 - "$tmp" "$frames" "$reps" "$load" "$(nproc)" > "$tmp/section.md" <<'PY'
import glob, json, os, statistics, struct, sys
tmp, frames, reps, load, cores = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), sys.argv[4], sys.argv[5]
def runs(name):
    out = []
    for r in range(1, reps + 1):
        d = f"{tmp}/{name}.{r}"
        s = json.load(open(d + "/lidar-semantic-map.summary.json"))
        u, sy, wall = (float(x) for x in open(f"{d}.time").read().split()[-3:])
        t = s["timings_s"]
        out.append(dict(fps=t["frames_per_second"], wall=wall, cpu=(u + sy) / frames,
                        net=s["semantics"]["network_seconds"] / frames,
                        wait=t["wait_inputs"] / frames, em=s["error_minimization"],
                        projected=s["points_projected"]))
    return out
def labels(name):
    d = f"{tmp}/{name}.1/labels"
    return {f: open(os.path.join(d, f), "rb").read() for f in sorted(os.listdir(d))}
def agreement(a, b):
    same = total = 0
    for f in a:
        x, y = a[f], b[f]
        n = len(x) // 4
        lx = struct.unpack(f"<{n}I", x)
        ly = struct.unpack(f"<{n}I", y)
        same += sum((p & 0xFFFF) == (q & 0xFFFF) for p, q in zip(lx, ly))
        total += n
    return same / total
med = lambda rs, k: statistics.median(r[k] for r in rs)
ref = labels("default")
rows = [("default (OpenCV threads = cores, network overlapped with the LiDAR work)", "default"),
        ("network on one thread (--enet-threads 1), overlapped", "net1thread"),
        ("half-scale network input (--enet-scale 0.5)", "half")]
print("<!-- enet-begin -->")
print("## Default run with ENet on 2 cores (issue 24): `scripts/bench/bench_lidar_enet.sh`\n")
print(f"- real KITTI sfnd frames 0-{frames - 1} (no OXTS: LiDAR odometry), ENet through OpenCV DNN "
      f"{__import__('subprocess').run(['pkg-config', '--modversion', 'opencv4'], capture_output=True, text=True).stdout.strip()} "
      "(DNN_BACKEND_OPENCV on the CPU, the only CPU backend of Debian 12's build; parallel framework TBB), "
      "input 1242x375 padded to 1248x384")
print(f"- date: {__import__('datetime').datetime.now(__import__('datetime').timezone.utc):%Y-%m-%dT%H:%MZ}; "
      f"command: `FRAMES={frames} REPS={reps} scripts/bench/bench_lidar_enet.sh BIN_DIR`")
print(f"- machine: {cores} cores; load average at start: {load}; median of {reps} runs per row")
print("- frames/s: the frame loop (scan + ENet of frame k+1 read in a second thread while frame k is")
print("  projected, filtered and fused; summary timings_s.frames_per_second); CPU s/frame: user + sys")
print("  of the whole run (odometry, refinement, outputs included) / frames, the load-independent")
print("  figure; 2 / (CPU s/frame) is what 2 idle cores allow at best")
print("- label agreement: share of scan points whose label (labels/*.label) equals the default run's\n")
print("| run | frames/s (frame loop) | whole run wall s | CPU s/frame | 2 / CPU s/frame | network s/frame (its thread) | label agreement with default |")
print("|---|---:|---:|---:|---:|---:|---:|")
for title, name in rows:
    rs = runs(name)
    agree = 1.0 if name == "default" else agreement(ref, labels(name))
    print(f"| {title} | {med(rs, 'fps'):.2f} | {med(rs, 'wall'):.1f} | {med(rs, 'cpu'):.3f} | "
          f"{2 / med(rs, 'cpu'):.1f} | {med(rs, 'net'):.3f} | {100 * agree:.1f} % |")
first = runs("default")[0]
em, projected = first["em"], first["projected"]
print(f"\nError minimisation in the default run: {'on' if not em['skipped'] else 'OFF'}"
      + (f", forests {', '.join(em['labels'])} from {em['classifier_dir']}"
         f" (provenance: commit {em['provenance'].get('code_commit', '?')}, {em['provenance'].get('date', '?')}),"
         f" {em['rejected_clusters']} of {em['clusters']} clusters dropped"
         f" ({em['rejected_points']} of {projected} projected points,"
         f" {100 * em['rejected_points'] / max(projected, 1):.1f} %)" if not em['skipped'] else ""))
print("<!-- enet-end -->")
PY
cat "$tmp/section.md"
if [[ "$update" != --no-doc ]]; then
  python3 - "$tmp/section.md" "$root/docs/performance-lidar.md" <<'PY'
import re, sys
section, doc = open(sys.argv[1]).read().strip(), sys.argv[2]
text = open(doc).read()
pat = re.compile(r"<!-- enet-begin -->.*?<!-- enet-end -->", re.S)
text = pat.sub(lambda m: section, text) if pat.search(text) else text.rstrip() + "\n\n" + section + "\n"
open(doc, "w").write(text)
PY
fi
