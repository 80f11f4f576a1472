#!/usr/bin/env bash
# e2e (issue 24): lidar-semantic-map never replaces a previous output set with a failed run.
# On the real sfnd drive: a first run (frames 0-8, stride 2, ENet) writes the set; then
# - the same frames with one scan out of order (sfnd frame 40 in the place of frame 6) must stop
#   with exit 3 naming that frame, and
# - a run on fewer frames with a folder where topdown.png goes must stop with exit 4 naming it,
# each leaving every earlier output byte-identical and no temporary file; an output folder below
# a regular file is refused before any work (exit 4).
set -euo pipefail
source "$(cd "$(dirname "$0")" && pwd)/lib/kitti_sfnd.sh"  # BIN, DATE, DRIVE, MODEL; cd TMP
fail() { echo "FAIL: $*"; exit 1; }
snapshot() { (cd "$1" && find . -type f ! -name '.mapfuse.lock' -print0 | sort -z | xargs -0 sha1sum); }
run() {  # run DRIVE OUT [LAST]: frames 0, 2, ... LAST (default 8) of DRIVE
  "$BIN/lidar-semantic-map" "$1" -o "$2" --segmenter enet --model "$MODEL" \
    --pose-source odometry --first-frame 0 --last-frame "${3:-8}" --stride 2 --quiet
}

# A raw drive of links to sfnd: frame i is sfnd frame order[i] (scan and image).
mkdir -p shuffled/2011_09_26/2011_09_26_drive_shuf_sync/{velodyne_points,image_02}/data
for f in calib_cam_to_cam.txt calib_velo_to_cam.txt calib_imu_to_velo.txt; do
  ln -s "$DATE/$f" "shuffled/2011_09_26/$f"
done
SHUF=shuffled/2011_09_26/2011_09_26_drive_shuf_sync
order=(0 1 2 3 4 5 40 7 8)
for i in "${!order[@]}"; do
  printf -v dst '%010d' "$i"
  printf -v src '%010d' "${order[$i]}"
  ln -s "$DRIVE/velodyne_points/data/$src.bin" "$SHUF/velodyne_points/data/$dst.bin"
  ln -s "$DRIVE/image_02/data/$src.png" "$SHUF/image_02/data/$dst.png"
done

run "$DRIVE" out > /dev/null || fail "first run failed"
[[ -f out/map.ply && -f out/poses.txt && -f out/lidar-semantic-map.summary.json ]] ||
  fail "first run: outputs missing"
before=$(snapshot out)

# 1. A drive made to diverge: exit 3, the frame named, nothing replaced.
rc=0; run "$SHUF" out > /dev/null 2> err.txt || rc=$?
[[ $rc == 3 ]] || { cat err.txt; fail "a shuffled drive gave exit $rc, not 3"; }
grep -q "frame 6 (" err.txt || { cat err.txt; fail "the message does not name frame 6"; }
[[ "$(snapshot out)" == "$before" ]] || fail "a diverging run changed earlier outputs"
[[ -z "$(find out -name '*.tmp-*')" ]] || fail "temporary files left behind (diverging run)"
echo "lidar_output_set: diverging drive ok ($(grep -o 'frame 6 ([^)]*) is untrusted: [^;]*' err.txt))"

# 2. A failure found only when the outputs are replaced: exit 4, the file named, nothing replaced.
# The run covers fewer frames, so every file it would write differs from the first run's.
rm out/topdown.png && mkdir out/topdown.png
before=$(snapshot out)
rc=0; run "$DRIVE" out 6 > /dev/null 2> err.txt || rc=$?
[[ $rc == 4 ]] || { cat err.txt; fail "a folder in topdown.png's place gave exit $rc, not 4"; }
grep -qF topdown.png err.txt || { cat err.txt; fail "the message does not name topdown.png"; }
[[ "$(snapshot out)" == "$before" ]] || fail "a failed run changed earlier outputs"
[[ -z "$(find out -name '*.tmp-*')" ]] || fail "temporary files left behind (failed run)"
echo "lidar_output_set: failed run ok"

# 3. An output folder that cannot be created: exit 4 before any work.
touch afile
start=$(date +%s%N)
rc=0; run "$DRIVE" afile/out > /dev/null 2> err.txt || rc=$?
[[ $rc == 4 ]] || { cat err.txt; fail "an output below a regular file gave exit $rc, not 4"; }
ms=$(( ($(date +%s%N) - start) / 1000000 ))
echo "lidar_output_set: unwritable output folder refused in $ms ms"
echo "lidar_output_set: ok"
