#!/usr/bin/env bash
# Tiled against untiled over several simulate seeds (issue 9: "a tiled run over the Karlsruhe
# map with 4+ tiles produces a map whose evaluate metrics are within 5 % of the untiled run"):
# per seed, `simulate --map karlsruhe.osm --traversals 50 --seed S`, then `make -f
# scripts/crowd.mk` untiled and with TILE_SIZE=150 (7-24 tiles); evaluate metrics per class,
# pooled over the seeds (every matched element of every seed counts once, as in one large
# evaluation) with a 95 % bootstrap interval over seeds, and the mean of the per-seed values.
# Writes docs/performance-tiling.md.
# Usage: scripts/bench/bench_tiling.sh [BIN_DIR] [WORK]   env: SEEDS="42 1 2 ... 15"
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
bin=$(cd "${1:-$root/build/bin}" && pwd)
work=${2:-$(mktemp -d)}
seeds=${SEEDS:-"42 1 2 3 4 5 6 7 8 9 10 11 12 13 14 15"}
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
  "$bin/bench_tile_keyframes" --sim "$sim" --tiled "$work/w${s}_$tile" \
    --untiled "$work/w${s}_untiled" > "$work/keyframes_$s.json"
  echo "bench_tiling: seed $s done" >&2
done
python3 - "$work" "$tile" "$seeds" "$root/docs/performance-tiling.md" <<'PY'
import datetime, glob, json, random, subprocess, sys
work, tile, seeds, out = sys.argv[1], sys.argv[2], sys.argv[3].split(), sys.argv[4]
model = subprocess.run("lscpu | sed -n 's/^Model name: *//p'", shell=True, capture_output=True,
                       text=True).stdout.strip()
runs = ["untiled", tile]
ev = {(s, t): {c["class"]: c for c in json.load(open(
          f"{work}/w{s}_{t}/evaluate/evaluate.summary.json"))["maps"][0]["classes"]}
      for s in seeds for t in runs}
classes = sorted({cls for v in ev.values() for cls in v})
tiles = [len(glob.glob(f"{work}/w{s}_{tile}/tiles/*/")) for s in seeds]

# Each metric as a ratio of sums over seeds, so that pooling weighs every element (or metre of
# line) once: (numerator, denominator) contributed by one seed's class entry.
def parts(c, k):
    if k == "instances":
        return c["map_count"], 1
    if k in ("abs", "rel"):
        e = c["absolute_error" if k == "abs" else "relative_error"]
        return e["count"] * (e["mean"] or 0.0), e["count"]
    if c["measure"] == "length":
        if k == "completeness":
            return c["covered_truth_length_m"], c["truth_length_m"]
        return (c["map_length_m"] - min(c["matched_map_length_m"], c["covered_truth_length_m"]),
                c["map_length_m"])
    if k == "completeness":
        return c["matched_truth"], c["truth_count"]
    return c["map_count"] - c["matched_map"], c["map_count"]

def pooled(cls, k, t, sample):
    num = den = 0.0
    for s in sample:
        c = ev[(s, t)].get(cls)
        if c:
            n, d = parts(c, k)
            num, den = num + n, den + d
    return num / den if den else None

def per_seed_mean(cls, k, t):
    vals = []
    for s in seeds:
        c = ev[(s, t)].get(cls)
        if c:
            n, d = parts(c, k)
            if d:
                vals.append(n / d)
    return sum(vals) / len(vals) if vals else None

random.seed(1)
boot = [[random.choice(seeds) for _ in seeds] for _ in range(2000)]
keys = [("instances", "instances"), ("completeness", "completeness"),
        ("redundancy", "redundancy"), ("abs", "abs. error m"), ("rel", "rel. precision m")]

def cell(a, b, fmt, ci=None):
    if a is None or b is None:
        return "–"
    diff = f" ({100 * (b - a) / a:+.0f} %" if a else " ("
    if a and ci:
        diff += f", {ci[0]:+.0f}..{ci[1]:+.0f}"
    diff = diff + ")" if diff != " (" else ""
    return f"{fmt.format(a)} / {fmt.format(b)}{diff}"

def table(value, with_ci):
    rows = ["| class | " + " | ".join(name for _, name in keys) + " |", "|---" * (len(keys) + 1) + "|"]
    for cls in classes:
        cells = []
        for k, _ in keys:
            a, b = value(cls, k, "untiled"), value(cls, k, tile)
            fmt = "{:.1f}" if k == "instances" else "{:.3f}"
            ci = None
            if with_ci and a:
                d = []
                for sample in boot:
                    x, y = pooled(cls, k, "untiled", sample), pooled(cls, k, tile, sample)
                    if x and y is not None:
                        d.append(100 * (y - x) / x)
                d.sort()
                if d:
                    ci = (d[int(0.025 * len(d))], d[int(0.975 * len(d)) - 1])
            cells.append(cell(a, b, fmt, ci))
        rows.append(f"| {cls} | " + " | ".join(cells) + " |")
    return rows

lines = ["# Tiled against untiled, several seeds", "",
         f"Measured by `scripts/bench/bench_tiling.sh` on {datetime.date.today()} (2 cores, {model}).",
         f"Per seed ({len(seeds)} seeds: {' '.join(seeds)}): `simulate --map"
         " lanelet2_karlsruhe_mapping_example.osm --traversals 50 --seed S`, then `make -j2 -f"
         f" scripts/crowd.mk` untiled and with `TILE_SIZE={tile}` ({min(tiles)}-{max(tiles)} tiles,"
         " 50 m margins, stitch), evaluate with its defaults.", "",
         "A seed's map holds 0-7 elements of a discrete class and 100-800 m of lane line, so one"
         " element can move a per-seed figure by tens of per cent. The first table pools the seeds"
         " (every matched element, metre of line or lane-width sample of every seed counts once, as"
         " in one evaluation of a map 16 times as large); after the difference, the 95 % bootstrap"
         " interval of that difference when the seeds are resampled.", "",
         "Pooled over the seeds: untiled / tiled (difference, 95 % interval); instances: mean per seed"
         " that has the class:", ""]
lines += table(lambda cls, k, t: pooled(cls, k, t, seeds), True)
lines += ["", "Mean of the per-seed values, untiled / tiled (difference):", ""]
lines += table(per_seed_mean, False)
kf = [json.load(open(f"{work}/keyframes_{s}.json")) for s in seeds]
mean = lambda k: sum(x[k] for x in kf) / len(kf)
lines += ["", "Keyframes against the simulator's truth (`bench_tile_keyframes`): per tile, the mean"
          " error of the keyframes its core holds; over the tiles, the keyframe-weighted RMS of those"
          " horizontal means; mean over the seeds. It says where each run puts each tile. The last"
          " column: how far the pieces of one tile sit from each other after the tile's own align"
          " (RMS over pieces of their mean error about the tile's mean).", "",
          "| untiled m | tiled, own align m | tiled, balanced m | own align - untiled m |"
          " balanced - untiled m | pieces of a tile about its mean m |", "|---|---|---|---|---|---|",
          f"| {mean('untiled_m'):.3f} | {mean('tiled_m'):.3f} | {mean('balanced_m'):.3f} |"
          f" {mean('tiled_minus_untiled_m'):.3f} | {mean('balanced_minus_untiled_m'):.3f} |"
          f" {mean('piece_spread_in_tile_m'):.3f} |"]
bal = [json.load(open(f"{work}/w{s}_{tile}/balance/balance.summary.json")) for s in seeds]
lines += ["", f"balance per seed: {min(b['pieces'] for b in bal)}-{max(b['pieces'] for b in bal)}"
          f" pieces in {min(b['groups'] for b in bal)}-{max(b['groups'] for b in bal)} groups, of"
          f" which {min(b['single_piece_groups'] for b in bal)}-"
          f"{max(b['single_piece_groups'] for b in bal)} hold one piece;"
          f" {min(b['keyframes'] for b in bal)}-{max(b['keyframes'] for b in bal)} drive keyframes;"
          f" {min(b['seconds'] for b in bal):.2f}-{max(b['seconds'] for b in bal):.2f} s."]
lines += ["", "Notes: the crosswalk absolute error counts a crosswalk that only the tiled run matches"
          " where one seed's untiled map misses it (seed 12 on 2026-11-24: 1.41 m off; without it"
          " the tiled error is 2 % below the untiled one). The same 16 seeds before the tiled chain"
          " had `balance` (commit 6e93330, pooled): signs +7 % (+1..+17), poles +5 % (-0..+13),"
          " crosswalks +10 % absolute error, lane redundancy +2 %."]
open(out, "w").write("\n".join(lines) + "\n")
print(f"bench_tiling: wrote {out}", file=sys.stderr)
PY
