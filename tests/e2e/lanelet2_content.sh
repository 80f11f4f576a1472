#!/usr/bin/env bash
# e2e (issue 37): simulate never writes what its own readers refuse. One small Lanelet2 map
# (two lanelets of 55 m, lane lines, a stop line, a traffic light regulatory element) and
# copies of it with one content fault each (docs/formats.md "Map content checks"): what the
# reader refuses is exit 3 with the file, element and field named and no output written; what
# is dropped with a warning is exit 0, the warning on stderr and in the summary's
# input_warnings, and the truth simulate wrote reads back with `info` and scores against itself
# with `evaluate map`.
set -euo pipefail
HERE="$(cd "$(dirname "$0")" && pwd)"
source "$HERE/lib/scratch.sh"  # BIN; TMP, the working folder
fail() { echo "lanelet2_content: $*" >&2; exit 1; }

cat > base.osm <<'OSM'
<?xml version='1.0' encoding='UTF-8'?>
<osm version='0.6' generator='test'>
  <node id='1' lat='49.0000000' lon='8.4000000'/>
  <node id='2' lat='49.0005000' lon='8.4000000'/>
  <node id='3' lat='49.0010000' lon='8.4000000'/>
  <node id='4' lat='49.0000000' lon='8.4000500'/>
  <node id='5' lat='49.0005000' lon='8.4000500'/>
  <node id='6' lat='49.0010000' lon='8.4000500'/>
  <node id='8' lat='49.0010100' lon='8.4000600'/>
  <node id='9' lat='49.0010100' lon='8.4000700'/>
  <way id='10'><nd ref='1'/><nd ref='2'/><tag k='type' v='line_thin'/><tag k='subtype' v='solid'/></way>
  <way id='11'><nd ref='2'/><nd ref='3'/><tag k='type' v='line_thin'/><tag k='subtype' v='solid'/></way>
  <way id='12'><nd ref='4'/><nd ref='5'/><tag k='type' v='line_thin'/><tag k='subtype' v='dashed'/></way>
  <way id='13'><nd ref='5'/><nd ref='6'/><tag k='type' v='line_thin'/><tag k='subtype' v='dashed'/></way>
  <way id='14'><nd ref='3'/><nd ref='6'/><tag k='type' v='stop_line'/></way>
  <way id='15'><nd ref='8'/><nd ref='9'/><tag k='type' v='traffic_light'/></way>
  <relation id='20'><member type='way' ref='10' role='left'/><member type='way' ref='12' role='right'/>
    <tag k='type' v='lanelet'/><tag k='subtype' v='road'/></relation>
  <relation id='21'><member type='way' ref='11' role='left'/><member type='way' ref='13' role='right'/>
    <member type='relation' ref='30' role='regulatory_element'/>
    <tag k='type' v='lanelet'/><tag k='subtype' v='road'/></relation>
  <relation id='30'><member type='way' ref='15' role='refers'/><member type='way' ref='14' role='ref_line'/>
    <tag k='type' v='regulatory_element'/><tag k='subtype' v='traffic_light'/></relation>
</osm>
OSM
# variant NAME FROM TO: NAME.osm = base.osm with the first FROM replaced by TO
variant() {
  python3 -c "import sys; s=open('base.osm').read(); assert sys.argv[2] in s, sys.argv[2]
open(sys.argv[1] + '.osm', 'w').write(s.replace(sys.argv[2], sys.argv[3], 1))" "$@"
}
sim() { timeout 120 "$BIN/simulate" -q --map "$1.osm" --traversals 1 --route-length 60 -o "out_$1"; }
# refused NAME PATTERN: exit 3, stderr names the file and matches PATTERN, nothing written (the
# output folder holds at most its lock file)
refused() {
  local rc=0; sim "$1" >/dev/null 2>err.txt || rc=$?
  [[ $rc == 3 ]] || { cat err.txt; fail "$1: exit $rc, not 3"; }
  grep -qE "$1\.osm.*$2" err.txt || { cat err.txt; fail "$1: stderr lacks /$1.osm.*$2/"; }
  local left; left=$(find "out_$1" -type f ! -name .mapfuse.lock 2>/dev/null || true)
  [[ -z "$left" ]] || fail "$1: a refused run wrote $left"
}
# written NAME [WARNING]: exit 0 (WARNING on stderr and in input_warnings), the truth reads back
written() {
  sim "$1" >/dev/null 2>err.txt || { cat err.txt; fail "$1: simulate failed"; }
  if [[ $# -gt 1 ]]; then
    grep -qF "$2" err.txt || { cat err.txt; fail "$1: stderr lacks '$2'"; }
    python3 -c "import json, sys; w = json.load(open(sys.argv[1]))['input_warnings']
assert any(sys.argv[2] in k for k in w), w" "out_$1/simulate.summary.json" "$2" ||
      fail "$1: simulate.summary.json input_warnings lacks '$2'"
  fi
  "$BIN/info" "out_$1/truth/vector_map.json" >/dev/null 2>err.txt ||
    { cat err.txt; fail "$1: info refuses the truth simulate wrote"; }
  "$BIN/evaluate" map -q --truth "out_$1/truth/vector_map.json" -o "eval_$1" \
    --map "out_$1/truth/vector_map.json" >/dev/null 2>err.txt ||
    { cat err.txt; fail "$1: evaluate map refuses the truth simulate wrote"; }
}

written base
variant dup_relation "<relation id='30'>" "<relation id='20'>"
refused dup_relation "relation 20': duplicate relation id"
variant dup_way "<way id='15'>" "<way id='14'>"
refused dup_way "way 14': duplicate way id"
variant missing_node "<nd ref='9'/>" "<nd ref='99'/>"
refused missing_node "way 15'.*node ref 99 does not exist"
variant missing_rule "ref='30' role='regulatory_element'" "ref='31' role='regulatory_element'"
refused missing_rule "relation 21 member regulatory_element'.*relation ref 31 does not exist"
variant missing_light "ref='15' role='refers'" "ref='16' role='refers'"
refused missing_light "relation 30 member refers'.*way ref 16 does not exist"
variant same_bounds "ref='13' role='right'" "ref='11' role='right'"
refused same_bounds "relation 21 member right'.*left bound too"
variant bad_lon "lat='49.0005000' lon='8.4000500'" "lat='49.0005000' lon='188.4'"
refused bad_lon "node 5 lon'.*out of range"
variant antipode "lat='49.0010100' lon='8.4000700'" "lat='-49.0010100' lon='-171.6'"
refused antipode "way 15 has a node at ENU.*beyond 10000000 m"
variant far_light "lat='49.0010100' lon='8.4000700'" "lat='31.0' lon='8.4000700'"
written far_light "longer than 100 m (dropped)"
variant point_bound "<way id='13'><nd ref='5'/><nd ref='6'/>" "<way id='13'><nd ref='5'/><nd ref='5'/>"
written point_bound "lanelet with a bound shorter than 0.01 m (dropped)"
variant point_stop "<way id='14'><nd ref='3'/><nd ref='6'/>" "<way id='14'><nd ref='3'/><nd ref='3'/>"
written point_stop "lane or stop line way shorter than 0.01 m (dropped)"
python3 -c "import json; m = json.load(open('out_point_stop/truth/vector_map.json'))
assert not any(i['class'] == 'stop_line' for i in m['instances']), 'a stop line of no length'"
echo "lanelet2_content: 8 maps refused, 4 written and read back"
