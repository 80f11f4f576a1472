# Sourced by the e2e scripts of issue 19 (output_sets*.sh): the check that a tool's outputs are
# replaced as a set. Needs NAME (printed in the messages) set by the caller.

fail() { echo "FAIL: $*"; exit 1; }
snapshot() { (cd "$1" && find . -type f ! -name '.mapfuse.lock' -print0 | sort -z | xargs -0 sha1sum); }

# check TOOL OUT VICTIM CMD...: CMD writes into OUT; VICTIM is one of its outputs (relative).
# A failed run (a folder in VICTIM's place, found only when the outputs are committed) exits 4
# naming it and leaves every earlier output byte-identical with no temporary file; a second run
# while another holds the folder's lock is refused at once (exit 4).
check() {
  local tool=$1 out=$2 victim=$3; shift 3
  "$@" >/dev/null 2>&1 || fail "$tool: first run failed"
  [[ -f "$out/$victim" ]] || fail "$tool: $out/$victim not written"
  rm "$out/$victim" && mkdir "$out/$victim"
  local before; before=$(snapshot "$out")
  local rc=0; "$@" >/dev/null 2>err.txt || rc=$?
  [[ $rc == 4 ]] || { cat err.txt; fail "$tool: a folder in an output's place gave exit $rc, not 4"; }
  grep -qF "$victim" err.txt || { cat err.txt; fail "$tool: the message does not name $victim"; }
  [[ "$(snapshot "$out")" == "$before" ]] || fail "$tool: a failed run changed earlier outputs"
  [[ -z "$(find "$out" -name '*.tmp-*')" ]] || fail "$tool: temporary files left behind"
  rmdir "$out/$victim"
  flock "$out/.mapfuse.lock" sleep 5 & local holder=$!
  sleep 0.3
  rc=0; "$@" >/dev/null 2>err.txt || rc=$?
  kill $holder 2>/dev/null || true; wait $holder 2>/dev/null || true
  [[ $rc == 4 ]] || { cat err.txt; fail "$tool: a locked output folder gave exit $rc, not 4"; }
  grep -q "another mapfuse run" err.txt || { cat err.txt; fail "$tool: lock message"; }
  echo "$NAME: $tool ok"
}
