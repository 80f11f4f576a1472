#!/usr/bin/env bash
# e2e (issues 33, 36): scripts/crowd_check.py, the batch's trust check, on real georef and align
# outputs of a small simulated batch, then on a copy with one drive made untrusted:
#   - all drives trusted: exit 0, check.json passed, align's ties reported (stretches, untied
#     share); above --warn-untied-share a warning on stderr, the exit still 0;
#   - one untrusted drive: exit 3 naming it (default --max-untrusted-share 0), check.json not
#     passed; --max-untrusted-share 0.5 lets the batch pass.
set -euo pipefail
HERE="$(cd "$(dirname "$0")" && pwd)"
SRC="${MAPFUSE_SOURCE_DIR:?}"
source "$HERE/lib/scratch.sh"  # BIN; TMP, the working folder
fail() { echo "crowd_check: $*" >&2; exit 1; }
check() { python3 "$SRC/scripts/crowd_check.py" "$@"; }
field() { python3 -c "import json,sys; d=json.load(open(sys.argv[1])); print(eval(sys.argv[2]))" "$@"; }

"$BIN/simulate" -q --traversals 4 --route-length 1200 -o sim >/dev/null
make -s -j2 -f "$SRC/scripts/crowd.mk" BIN="$BIN" LSM_DIR=sim/lsm WORK=work map >/dev/null

rc=0; check work 2>err.txt || rc=$?
((rc == 0)) || fail "trusted batch: exit $rc ($(cat err.txt))"
[[ $(field work/check.json 'd["passed"]') == True ]] || fail "check.json not passed"
stretches=$(field work/check.json 'd["ties"]["stretches"]')
((stretches >= 4)) || fail "ties: $stretches stretches for 4 drives of 1.2 km"
share=$(field work/check.json 'd["ties"]["untied_share"]')
python3 -c "import sys; sys.exit(0 if 0 <= $share <= 1 else 1)" || fail "untied share $share"
rc=0; check work --warn-untied-share -1 2>err.txt || rc=$?
((rc == 0)) || fail "a warning changed the exit ($rc)"
grep -q "tied to no other drive" err.txt || fail "no untied-share warning: $(cat err.txt)"

# One drive untrusted (its georef summary says so, as georef writes it for a drive whose
# odometry and GPS disagree).
summary=$(ls work/georef/*/georef.summary.json | head -1)
python3 - "$summary" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
s["lsms"][0]["trusted"] = False
json.dump(s, open(sys.argv[1], "w"))
PY
drive=$(field "$summary" 'd["lsms"][0]["drive_id"]')
rc=0; check work 2>err.txt || rc=$?
((rc == 3)) || fail "untrusted drive: exit $rc, expected 3"
grep -q "drive $drive" err.txt || fail "the untrusted drive is not named: $(cat err.txt)"
[[ $(field work/check.json 'd["passed"]') == False ]] || fail "check.json passed"
rc=0; check work --max-untrusted-share 0.5 2>err.txt || rc=$?
((rc == 0)) || fail "1 of 4 untrusted under --max-untrusted-share 0.5: exit $rc"
echo "crowd_check: ok ($stretches stretches, untied share $share)"
