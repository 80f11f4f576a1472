#!/usr/bin/env bash
# Tiled against untiled over several simulate seeds (issue 9: "a tiled run over the Karlsruhe
# map with 4+ tiles produces a map whose evaluate metrics are within 5 % of the untiled run"):
# per seed, `simulate --map karlsruhe.osm --traversals 50 --seed S`, then `make -f
# scripts/crowd.mk` untiled and with TILE_SIZE=150 (7 tiles); evaluate metrics per class,
# averaged over the seeds. Writes docs/performance-tiling.md.
# Usage: scripts/bench/bench_tiling.sh [BIN_DIR] [WORK]   env: SEEDS="42 1 2 3 4 5 6 7"
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
bin=$(cd "${1:-$root/build/bin}" && pwd)
work=${2:-$(mktemp -d)}
seeds=${SEEDS:-"42 1 2 3 4 5 6 7"}
tile=150
shared="${MAPFUSE_SHARED:-$root/../shared}"
osm="$shared/data/maps/lanelet2_karlsruhe_mapping_example.osm"
if [[ ! -f "$osm" ]]; then
  echo "bench_tiling: $osm absent, skipped" >&2
  exit 0
fi
mkdir -p "$work"
for s in $seeds; do
  sim="$work/sim$s"
  [[ -d "$sim" ]] || "$bin/simulate" -q --traversals 50 --map "$osm" --seed "$s" -o "$sim" >/dev/null
  for t in untiled "$tile"; do
    w="$work/w${s}_$t"
    rm -rf "$w"
    vars=()
    [[ $t == untiled ]] || vars=(TILE_SIZE="$t")
    make -s -j2 -f "$root/scripts/crowd.mk" BIN="$bin" LSM_DIR="$sim/lsm" WORK="$w" \
      TRUTH="$sim/truth/vector_map.json" TRUTH_TRAJ="$sim/truth" "${vars[@]}" >/dev/null
  done
  echo "bench_tiling: seed $s done" >&2
done
python3 - "$work" "$tile" "$seeds" "$root/docs/performance-tiling.md" <<'PY'
import datetime, glob, json, subprocess, sys
work, tile, seeds, out = sys.argv[1], sys.argv[2], sys.argv[3].split(), sys.argv[4]
model = subprocess.run("lscpu | sed -n 's/^Model name: *//p'", shell=True, capture_output=True,
                       text=True).stdout.strip()
keys = [("map_count", "instances"), ("completeness", "completeness"),
        ("redundancy", "redundancy"), ("abs", "abs. error m"), ("rel", "rel. precision m")]
def get(c, k):
    if k == "abs":
        return (c.get("absolute_error") or {}).get("mean") or 0.0
    if k == "rel":
        return c.get("relative_precision_m") or 0.0
    return c.get(k) or 0.0
acc = {}
tiles = []
for s in seeds:
    tiles.append(len(glob.glob(f"{work}/w{s}_{tile}/tiles/*/")))
    for t in ["untiled", tile]:
        ev = json.load(open(f"{work}/w{s}_{t}/evaluate/evaluate.summary.json"))
        for c in ev["maps"][0]["classes"]:
            for k, _ in keys:
                acc.setdefault((c["class"], k, t), []).append(get(c, k))
lines = ["# Tiled against untiled, several seeds", "",
         f"Measured by `scripts/bench/bench_tiling.sh` on {datetime.date.today()} (2 cores, {model}).",
         f"Per seed ({' '.join(seeds)}): `simulate --map lanelet2_karlsruhe_mapping_example.osm"
         " --traversals 50 --seed S`, then `make -j2 -f scripts/crowd.mk` untiled and with"
         f" `TILE_SIZE={tile}` ({min(tiles)}-{max(tiles)} tiles, 50 m margins, stitch), evaluate"
         " with its defaults. Cells: mean over the seeds, untiled / tiled (difference).", "",
         "| class | " + " | ".join(name for _, name in keys) + " |",
         "|---" * (len(keys) + 1) + "|"]
for cls in sorted({k[0] for k in acc}):
    cells = []
    for k, _ in keys:
        a = acc.get((cls, k, "untiled"), [])
        b = acc.get((cls, k, tile), [])
        if not a or not b:
            cells.append("–")
            continue
        ma, mb = sum(a) / len(a), sum(b) / len(b)
        diff = f" ({100 * (mb - ma) / ma:+.0f} %)" if ma else ""
        fmt = "{:.1f}" if k == "map_count" else "{:.3f}"
        cells.append(f"{fmt.format(ma)} / {fmt.format(mb)}{diff}")
    lines.append(f"| {cls} | " + " | ".join(cells) + " |")
open(out, "w").write("\n".join(lines) + "\n")
print(f"bench_tiling: wrote {out}", file=sys.stderr)
PY
