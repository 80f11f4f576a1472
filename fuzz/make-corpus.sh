#!/usr/bin/env bash
# Seed corpora of the fuzz targets, made at fuzz time from the samples and small outputs of the
# tools, plus the small committed seeds of fuzz/seeds/<target>/:
#   fuzz/make-corpus.sh BIN_DIR SEEDS_DIR
# BIN_DIR holds the release tools (build/bin). A small crowd batch (simulate frames -> lsm-build
# -> georef -> tile -> align -> balance -> aggregate -> stitch, scripts/crowd.mk) gives LSMs in
# JSON and CBOR, vector maps (plain JSON, compact CBOR), the OSM export, tiles.json, align
# summaries, calibration.json and raw drive folders; a 2-frame simulate-lidar drive and
# lidar-semantic-map give KITTI calibration, OXTS, timestamps, Velodyne scans, semantics, labels,
# poses, PLY and PCD; configs/ the configurations; ../shared/data (when present) the real KITTI
# and Lanelet2 files. Large files are cut to small, still valid, seeds (fuzz/shrink.py).
set -euo pipefail
bin=$(cd "$1" && pwd)
seeds=$2
root=$(cd "$(dirname "$0")/.." && pwd)
shared=${MAPFUSE_SHARED:-$root/../shared}/data
work=$(mktemp -d "${TMPDIR:-/tmp}/mapfuse-corpus-XXXXXX")
trap 'rm -rf "$work"' EXIT
rm -rf "$seeds"
mkdir -p "$seeds"
seed() { mkdir -p "$seeds/$1"; cat > "$seeds/$1/$2"; }  # seed TARGET NAME < bytes
shrink() { python3 "$root/fuzz/shrink.py" "$@"; }
start=$(date +%s)

# ---- crowd batch: 3 short drives on a small procedural world
cat > "$work/sim.json" <<'JSON'
{"seed": 5, "level": "frames", "traversals": 3, "vehicles": 2, "routes": 1,
 "route_length": 150.0, "world_grid_size": 2, "world_block_length": 120.0}
JSON
"$bin/simulate" -q --config "$work/sim.json" -o "$work/sim" >/dev/null
make -s -f "$root/scripts/crowd.mk" BIN="$bin" FRAMES_DIR="$work/sim/frames" WORK="$work/crowd" \
  TILE_SIZE=80 TILE_MARGIN=20 >/dev/null 2>&1
make -s -f "$root/scripts/crowd.mk" BIN="$bin" FRAMES_DIR="$work/sim/frames" \
  WORK="$work/crowd-untiled" >/dev/null 2>&1
crowd=$work/crowd

n=0
for f in "$work"/crowd-untiled/align/*.lsm.json; do
  shrink lsm-json "$f" 6 | seed fuzz_lsm "aligned-$((n++)).json"
done
# the smallest tile LSMs (CBOR), distinct contents only
for f in $(ls -Sr "$crowd"/tiles/tile_*/*.cbor | head -6); do
  seed fuzz_lsm "tile-$(md5sum < "$f" | cut -c1-8).cbor" < "$f"
done
shrink vector-map-json "$work/sim/truth/vector_map.json" 10 | seed fuzz_vector_map truth.json
shrink vector-map-json "$work/crowd-untiled/aggregate/map.json" 10 | seed fuzz_vector_map map.json
seed fuzz_vector_map map.cbor < "$work/crowd-untiled/aggregate/map.cbor"
seed fuzz_vector_map stitched.cbor < "$crowd/stitch/map.cbor"
for m in "$crowd"/tiles/tile_*/aggregate/map.cbor; do
  seed fuzz_vector_map "$(basename "$(dirname "$(dirname "$m")")").cbor" < "$m"
done
seed fuzz_lanelet2_osm aggregate.osm < "$(ls -Sr "$crowd"/tiles/tile_*/aggregate/map.osm | head -1)"
seed fuzz_tiles_manifest tiles.json < "$crowd/tiles/tiles.json"
for s in "$crowd"/tiles/tile_*/align/align.summary.json; do
  seed fuzz_align_summary "$(basename "$(dirname "$(dirname "$s")")").json" < "$s"
done
seed fuzz_align_summary untiled.json < "$work/crowd-untiled/align/align.summary.json"
seed fuzz_aggregate_summary untiled.json < "$work/crowd-untiled/aggregate/aggregate.summary.json"
seed fuzz_aggregate_summary stitched.json < "$(ls "$crowd"/tiles/tile_*/aggregate/aggregate.summary.json | head -1)"
drive=$(ls -d "$work"/sim/frames/*/ | head -1)
seed fuzz_camera_calib calibration.json < "$drive/calibration.json"
shrink drive-frames "$drive" 6 | seed fuzz_drive_frames drive.txt
seed fuzz_semantic_image mask.png < "$(ls "$drive"/masks/*.png | head -1)"

# ---- OpenDRIVE: the junction map of the unit tests (lanes, links, road marks, signals,
# objects), cut out of tests/sim/test_opendrive.cpp so that seed and test stay one text
python3 - "$root/tests/sim/test_opendrive.cpp" <<'PY' | seed fuzz_opendrive junction.xodr
import re, sys
m = re.search(r'kJunctionMap = R"\((.*?)\)";', open(sys.argv[1]).read(), re.S)
sys.stdout.write(m.group(1) if m else sys.exit("make-corpus: no kJunctionMap in " + sys.argv[1]))
PY

# ---- Lanelet2 content checks: the map of tests/sim/test_lanelet2_content.cpp (lanelets, a
# regulatory element with its members), cut out of the test as the junction map above
python3 - "$root/tests/sim/test_lanelet2_content.cpp" <<'PY' | seed fuzz_lanelet2_osm content.osm
import re, sys
m = re.search(r'kMap = R"\((.*?)\)";', open(sys.argv[1]).read(), re.S)
sys.stdout.write(m.group(1) if m else sys.exit("make-corpus: no kMap in " + sys.argv[1]))
PY

# ---- stitch: the crowd batch's tiles.json and each tile's map, in the manifest's order
{
  cat "$crowd/tiles/tiles.json"
  for name in $(python3 -c 'import json, sys; print(" ".join(t["name"] for t in json.load(open(sys.argv[1]))["tiles"]))' "$crowd/tiles/tiles.json"); do
    printf '\n====\n'
    cat "$crowd/tiles/$name/aggregate/map.cbor"
  done
} | seed fuzz_stitch crowd.txt

# ---- configurations: one byte chooses the stage (fuzz_config.cpp's order), then the file
i=0
for stage in aggregate align balance evaluate evaluate-voxels georef lidar-semantic-map \
             lsm-build simulate simulate-lidar tile stitch; do
  { printf "\\$(printf '%03o' "$i")"; cat "$root/configs/$stage.json"; } | seed fuzz_config "$stage.json"
  i=$((i + 1))
done
printf '\014{}' | seed fuzz_config info.json  # info (index 12) has no parameters

# ---- KITTI raw: a 2-frame synthetic drive and its voxel map
"$bin/simulate-lidar" -q --seed 3 --frames 2 -o "$work/kitti" > "$work/kitti.txt"
kd=$(cat "$work/kitti.txt")
date_dir=$(dirname "$kd")
"$bin/lidar-semantic-map" -q "$kd" -o "$work/voxels" >/dev/null
kitti_calib() {  # kitti_calib DATE_DIR: cam, velo (and imu) as one input
  cat "$1/calib_cam_to_cam.txt"; printf '====\n'; cat "$1/calib_velo_to_cam.txt"
  if [ -f "$1/calib_imu_to_velo.txt" ]; then printf '====\n'; cat "$1/calib_imu_to_velo.txt"; fi
}
kitti_calib "$date_dir" | seed fuzz_kitti_calib sim.txt
seed fuzz_oxts sim.txt < "$(ls "$kd"/oxts/data/*.txt | head -1)"
seed fuzz_kitti_timestamps velodyne.txt < "$kd/velodyne_points/timestamps.txt"
head -c 1024 "$(ls "$kd"/velodyne_points/data/*.bin | head -1)" | seed fuzz_velodyne scan.bin
head -c 512 "$(ls "$work"/voxels/labels/*.label | head -1)" | seed fuzz_semantic_labels scan.label
shrink prob "$(ls "$kd"/semantics_02/*.prob | head -1)" 6 4 | seed fuzz_semantic_image frame.prob
seed fuzz_kitti_poses voxels.txt < "$work/voxels/poses.txt"
shrink ply "$work/voxels/map.ply" 40 | seed fuzz_ply map.ply
shrink pcd "$work/voxels/map.pcd" 40 | seed fuzz_pcd map.pcd

# ---- OpenDRIVE survey-style quirks (docs/formats.md "Map content checks"): a spherical
# georeference, negative road-mark sOffsets, road-mark objects, a plan-view gap, a dangling link
seed fuzz_opendrive survey-quirks.xodr <<'XODR'
<?xml version="1.0"?><OpenDRIVE><header><geoReference><![CDATA[+proj=tmerc +a=6378137 +b=6378137 +lon_0=11.5 +x_0=-0 +y_0=-5453802.49 +k=1.0 +units=m +nadgrids=@null +wktext +no_defs]]></geoReference></header>
<road id="1" length="120" junction="-1"><link><successor elementType="road" elementId="9" contactPoint="start"/></link>
<planView><geometry s="0" x="0" y="0" hdg="0" length="60"><line/></geometry>
<geometry s="60" x="60.5" y="0" hdg="0" length="60"><paramPoly3 aU="0" bU="60" cU="0" dU="0" aV="0" bV="0" cV="2" dV="-1" pRange="normalized"/></geometry></planView>
<lanes><laneSection s="0"><left><lane id="1" type="driving"><width sOffset="0" a="3.5" b="0" c="0" d="0"/><roadMark sOffset="-4.575" type="solid"/></lane></left>
<center><lane id="0" type="none"><roadMark sOffset="-4.575" type="broken" color="white"/></lane></center>
<right><lane id="-1" type="driving"><width sOffset="0" a="3.5" b="0" c="0" d="0"/><roadMark sOffset="0" type="solid"/></lane></right></laneSection></lanes>
<objects><object id="7" type="roadMark" subtype="arrowLeft" name="arrow" s="40" t="-1.75" hdg="0" length="5" width="1.2"/>
<object id="8" type="roadMark" name="text" s="20" t="1.75"><outline><cornerLocal u="0" v="0" z="0"/><cornerLocal u="2" v="0" z="0"/><cornerLocal u="2" v="1" z="0"/></outline></object></objects>
</road></OpenDRIVE>
XODR

# ---- real data, when ../shared is there
if [ -d "$shared" ]; then
  kitti=$shared/kitti_raw/2011_09_26
  [ -f "$kitti/calib_cam_to_cam.txt" ] && kitti_calib "$kitti" | seed fuzz_kitti_calib real.txt
  d5=$kitti/2011_09_26_drive_0005_sync
  [ -d "$d5" ] && seed fuzz_oxts real.txt < "$(ls "$d5"/oxts/data/*.txt | head -1)"
  [ -d "$d5" ] && head -n 20 "$d5/velodyne_points/timestamps.txt" | seed fuzz_kitti_timestamps real.txt
  [ -d "$d5" ] && head -c 2048 "$(ls "$d5"/velodyne_points/data/*.bin | head -1)" |
    seed fuzz_velodyne real.bin
  odo=$shared/kitti_odometry
  [ -f "$odo/poses/00.txt" ] && seed fuzz_kitti_poses real.txt < "$odo/poses/00.txt"
  [ -f "$odo/sequences/00/calib.txt" ] &&
    seed fuzz_kitti_calib odometry.txt < "$odo/sequences/00/calib.txt"
  # a KITTI odometry sequence cut to two scans of 64 points, with made-up labels (road, 40)
  seq=$odo/sequences/00
  if [ -f "$seq/calib.txt" ] && [ -f "$odo/poses/00.txt" ]; then
    {
      cat "$seq/calib.txt"; printf '\n====\n0.0\n0.103607\n\n====\n'
      head -n 2 "$odo/poses/00.txt"; printf '\n====\n\n====\n'  # no image_2
      for k in 000000 000001; do
        head -c 1024 "$seq/velodyne/$k.bin"; printf '\n====\n'
        python3 -c 'import struct, sys; sys.stdout.buffer.write(struct.pack("<64I", *[40] * 64))'
        [ $k = 000001 ] || printf '\n====\n'
      done
    } | seed fuzz_kitti_sequence real.bin
  fi
  osm=$shared/maps/lanelet2_karlsruhe_mapping_example.osm
  [ -f "$osm" ] && shrink osm "$osm" 4 | seed fuzz_lanelet2_osm karlsruhe.osm
  xodr=$shared/maps/MONAEast.xodr  # 153 KB, within fuzz_opendrive's max_len (fuzz/run.sh)
  if [ -f "$xodr" ]; then
    seed fuzz_opendrive monaeast.xodr < "$xodr"
    # small cuts of it: each of its junctions with its roads, and its first three roads alone
    for j in 0 1 2 3; do shrink xodr "$xodr" $j 8 | seed fuzz_opendrive "monaeast-junction$j.xodr"; done
    shrink xodr "$xodr" -1 3 | seed fuzz_opendrive monaeast-roads.xodr
  fi
  # OpenDRIVE as it exists: the esmini corpus (80 maps, local frames, direct junctions, LHT, ...)
  for x in "$shared"/maps/opendrive-esmini/*.xodr; do
    [ -f "$x" ] && [ "$(stat -c %s "$x")" -le 262144 ] &&
      seed fuzz_opendrive "esmini-$(basename "$x")" < "$x"
  done
fi

# ---- the committed seeds (fuzz/seeds/<target>/: small hand-made inputs, and findings' inputs)
for d in "$root"/fuzz/seeds/*/; do
  mkdir -p "$seeds/$(basename "$d")"
  cp "$d"* "$seeds/$(basename "$d")/"
done
# fuzz_opendrive_drive drives what fuzz_opendrive reads
cp "$seeds"/fuzz_opendrive/* "$seeds/fuzz_opendrive_drive/"

echo "fuzz: seeds for $(ls "$seeds" | wc -l) targets, $(find "$seeds" -type f | wc -l) files," \
  "$(du -sk "$seeds" | cut -f1) KB in $(( $(date +%s) - start )) s" >&2
