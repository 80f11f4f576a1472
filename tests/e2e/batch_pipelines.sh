#!/usr/bin/env bash
# e2e: the batch layer on a small simulated sample (6 drives). scripts/crowd.mk untiled and
# tiled (TILE_SIZE 300 m -> several tiles, align per tile, balance, aggregate per tile, stitch;
# a second make redoes nothing), the Snakemake workflow (scripts/Snakefile)
# untiled and tiled giving byte-identical maps, a second make run that redoes nothing, and a batch
# killed mid-way whose rerun keeps the finished drives and ends with the same map.
set -euo pipefail
BIN="${MAPFUSE_BIN_DIR:?}"
SRC="${MAPFUSE_SOURCE_DIR:?}"
command -v snakemake >/dev/null || { echo "FAIL: snakemake missing (scripts/install-deps.sh)"; exit 1; }
TMP="$(mktemp -d)"
trap 'rm -rf "$TMP"' EXIT
cd "$TMP"   # snakemake keeps its state in ./.snakemake
shopt -s nullglob
fail() { echo "FAIL: $*"; exit 1; }
# Stops a batch started with setsid and waits until every process of its group has exited:
# waiting for make alone let a killed tool finish or undo its output set after the checks
# below had listed the outputs (a CI run saw a tile's align summary vanish between two lines).
stop_batch() {
  kill -TERM -- -"$1" 2>/dev/null || true
  wait "$1" 2>/dev/null || true
  for _ in $(seq 1 600); do
    kill -0 -- -"$1" 2>/dev/null || return 0
    sleep 0.05
  done
  fail "batch $1 still running 30 s after SIGTERM"
}

"$BIN/simulate" -q --traversals 6 --route-length 800 -o sim >/dev/null
MK=(make -s -j2 -f "$SRC/scripts/crowd.mk" BIN="$BIN" LSM_DIR=sim/lsm
    TRUTH=sim/truth/vector_map.json)
SK=(snakemake -q -s "$SRC/scripts/Snakefile" --cores 2 --config lsm_dir=sim/lsm bin="$BIN"
    truth=sim/truth/vector_map.json)

# ---- Make, untiled, then a rerun that has nothing to do
"${MK[@]}" WORK=mk >/dev/null
[[ -s mk/aggregate/map.cbor && -s mk/evaluate/evaluate.summary.json ]] || fail "crowd.mk map"
[[ "$(make -f "$SRC/scripts/crowd.mk" BIN="$BIN" LSM_DIR=sim/lsm \
      TRUTH=sim/truth/vector_map.json WORK=mk)" == *"Nothing to be done"* ]] || fail "make rerun redid work"

# ---- Make, tiled
"${MK[@]}" WORK=mkt TILE_SIZE=300 >/dev/null
tiles=$(wc -l < mkt/tiles/tiles.txt)
(( tiles >= 4 )) || fail "expected >= 4 tiles, got $tiles"
python3 - mkt/stitch/stitch.summary.json mkt/balance/balance.summary.json <<'PY' || fail "stitch / balance summary"
import json, sys
s = json.load(open(sys.argv[1]))
assert s["tiles"] >= 4, s
b = json.load(open(sys.argv[2]))
assert b["tiles"] == s["tiles"] and b["pieces"] >= b["tiles"] and b["groups"] >= b["tiles"], b
assert b["rms_residual_m"] < 0.5, b
PY
[[ "$(make -f "$SRC/scripts/crowd.mk" BIN="$BIN" LSM_DIR=sim/lsm TRUTH=sim/truth/vector_map.json \
      WORK=mkt TILE_SIZE=300)" == *"Nothing to be done"* ]] || fail "tiled make rerun redid work"

# ---- Snakemake, the same rules: byte-identical maps
"${SK[@]}" work=sk >/dev/null 2>sk.log || { cat sk.log; fail "snakemake untiled"; }
cmp -s sk/aggregate/map.cbor mk/aggregate/map.cbor || fail "snakemake map differs from crowd.mk's"
"${SK[@]}" work=skt tile_size=300 >/dev/null 2>skt.log || { cat skt.log; fail "snakemake tiled"; }
cmp -s skt/stitch/map.cbor mkt/stitch/map.cbor || fail "tiled snakemake map differs from crowd.mk's"

# ---- killed mid-way: stop the batch once every drive is georeferenced, rerun
setsid "${MK[@]}" WORK=kill >/dev/null 2>&1 &
pid=$!
for _ in $(seq 1 600); do
  done_drives=(kill/georef/*.d/georef.summary.json)
  (( ${#done_drives[@]} == 6 )) && break
  sleep 0.05
done
stop_batch "$pid"
stage="finished"; [[ -f kill/aggregate/map.cbor ]] || stage="killed before aggregate"
echo "kill: $stage"
# Drives georeferenced before the kill (their summary, the file georef commits last and make
# targets, exists) must be untouched by the rerun. A drive killed while georef was committing
# has no summary: the rerun makes it again.
finished=()
for s in kill/georef/*.d/georef.summary.json; do finished+=("$(dirname "$s")"/*.lsm.cbor); done
stamps() { (( $# == 0 )) || stat -c '%n %y' "$@"; }
stamp_before=$(stamps "${finished[@]}")
sleep 1
"${MK[@]}" WORK=kill >/dev/null
stamp_after=$(stamps "${finished[@]}")
[[ "$stamp_before" == "$stamp_after" ]] || fail "rerun redid finished georef drives"
cmp -s kill/aggregate/map.cbor mk/aggregate/map.cbor || fail "map after kill + rerun differs"

# ---- tiled, killed once some tiles are aligned: the rerun keeps those tiles' align output and
# ends with the same map as the uninterrupted tiled run
setsid "${MK[@]}" WORK=killt TILE_SIZE=300 >/dev/null 2>&1 &
pid=$!
for _ in $(seq 1 1200); do
  aligned_tiles=(killt/tiles/*/align/align.summary.json)
  (( ${#aligned_tiles[@]} >= 2 )) && break
  sleep 0.05
done
stop_batch "$pid"
aligned_tiles=(killt/tiles/*/align/align.summary.json)
echo "kill tiled: ${#aligned_tiles[@]} tiles aligned before the kill"
stamp_before=$(stamps "${aligned_tiles[@]}")
sleep 1
"${MK[@]}" WORK=killt TILE_SIZE=300 >/dev/null
[[ "$stamp_before" == "$(stamps "${aligned_tiles[@]}")" ]] || fail "tiled rerun redid aligned tiles"
cmp -s killt/stitch/map.cbor mkt/stitch/map.cbor || fail "tiled map after kill + rerun differs"
echo "batch_pipelines: ok ($tiles tiles)"
