#!/usr/bin/env bash
# e2e: scripts/kitti.mk over the real KITTI raw folder of ../shared (drive 0005: one frame with
# OXTS; drive "sfnd": frames 0-4 without OXTS -> LiDAR odometry): lidar-semantic-map then
# lsm-build on the LiDAR poses, per drive; a second make has nothing to do; a deleted output is
# rebuilt alone. Skips (77) without the shared data or the ENet model.
set -euo pipefail
BIN="${MAPFUSE_BIN_DIR:?}"
SRC="${MAPFUSE_SOURCE_DIR:?}"
SHARED="${MAPFUSE_SHARED:?}"
KITTI="$SHARED/data/kitti_raw"
MODEL="$SHARED/models/enet-cityscapes/enet-model.net"
[[ -d "$KITTI/2011_09_26/2011_09_26_drive_sfnd_sync" && -f "$MODEL" ]] ||
  { echo "SKIP: KITTI raw drives or ENet model absent under $SHARED"; exit 77; }
TMP="$(mktemp -d)"
trap 'rm -rf "$TMP"' EXIT
fail() { echo "FAIL: $*"; exit 1; }
MK=(make -s -j2 -f "$SRC/scripts/kitti.mk" BIN="$BIN" KITTI="$KITTI" WORK="$TMP/out"
    MODEL="$MODEL" LAST_FRAME=4)

"${MK[@]}" >/dev/null
for d in 2011_09_26_drive_0005_sync 2011_09_26_drive_sfnd_sync; do
  [[ -s "$TMP/out/lidar/$d/map.ply" && -s "$TMP/out/lidar/$d/topdown.png" ]] || fail "$d lidar map"
  [[ -s "$TMP/out/lsm/$d/$d.lsm.json" && -s "$TMP/out/lsm/$d/$d.bev.png" ]] || fail "$d LSM"
done
python3 - "$TMP/out" <<'PY'
import json, sys
out = sys.argv[1]
sfnd = "2011_09_26_drive_sfnd_sync"
lidar = json.load(open(f"{out}/lidar/{sfnd}/lidar-semantic-map.summary.json"))
lsm = json.load(open(f"{out}/lsm/{sfnd}/lsm-build.summary.json"))
poses = [l.split() for l in open(f"{out}/lidar/{sfnd}/poses.txt") if l.strip()]
assert len(poses) == 5, len(poses)               # frames 0-4, one KITTI pose line each
travel = sum((float(a) - float(b)) ** 2 for a, b in zip(poses[-1][3::4], poses[0][3::4])) ** 0.5
assert 0.3 < travel < 10.0, travel               # a slow car (~2 m/s): not zero, not km
assert lsm["egomotion"] == "poses" and lsm["frames"] == 5, lsm
assert lsm["ranged_markings"] > 0, lsm           # lane markings seen on the real images
# poses.txt is T_world_cam0: the camera drives along its own z axis, and the LSM built on it
# (body x forward) moves forward too, not sideways (issue 24: it turned by 90 deg).
dz = float(poses[-1][11]) - float(poses[0][11])
assert dz > 0.9 * travel, (dz, travel)
kf = json.load(open(f"{out}/lsm/{sfnd}/{sfnd}.lsm.json"))["keyframes"]
t0, t1 = kf[0]["pose"]["t"], kf[-1]["pose"]["t"]
if len(kf) > 1:
    assert t1[0] - t0[0] > 0.9 * sum((a - b) ** 2 for a, b in zip(t1, t0)) ** 0.5, (t0, t1)
print(f"sfnd: {travel:.2f} m odometry over 4 steps, {lsm['ranged_markings']} ranged markings")
PY
make -q -f "$SRC/scripts/kitti.mk" BIN="$BIN" KITTI="$KITTI" WORK="$TMP/out" LAST_FRAME=4 ||
  fail "second make would redo work"
rm "$TMP/out/lsm/2011_09_26_drive_sfnd_sync/lsm-build.summary.json"
[[ "$("${MK[@]}" -n | grep -c 'bin/lsm-build')" == 1 ]] || fail "rerun should only redo one lsm-build"
[[ "$("${MK[@]}" -n | grep -c 'bin/lidar-semantic-map')" == 0 ]] || fail "rerun redid a lidar map"
echo OK
