#!/usr/bin/env bash
# e2e: the Snakemake workflow (scripts/Snakefile), unchanged, on a real Slurm cluster. Starts a
# private single-node Slurm (Debian's slurmctld + slurmd, authenticated by its own munged) under a
# temporary folder on free ports, submits the sample batch of batch_pipelines.sh through
# Snakemake's Slurm executor (`--slurm`, Snakemake 7.19-7.x) untiled, then tiled in the same
# folder (the `tile` checkpoint; the finished per-drive jobs are not resubmitted), and checks that
#   - every rule ran as a Slurm job: Slurm's job-completion record (sacct -c) lists one COMPLETED
#     job per Snakemake job on the cluster's node, per rule the number of drives / tiles, each
#     one submitted by Snakemake itself;
#   - the maps, evaluate's summaries and every aligned / balanced LSM and per-tile map equal byte
#     for byte those of a local make run (scripts/crowd.mk) of the same batch.
# The daemons are always stopped and the folder removed (trap), also on failure or a signal.
# Exit 77 (ctest: skipped, with a "SKIP: ..." line) only when the daemons cannot start here (not
# root, munged / slurmctld / slurmd refuse to run); MAPFUSE_REQUIRE_SLURM=1 makes that a failure.
# The batch is CI's small one unless MAPFUSE_SLURM_SIMULATE gives simulate's options and
# MAPFUSE_SLURM_TILE_SIZE the tile size (issue 36's bench: the 100 km network batch, run by
# scripts/bench/bench_slurm_scale.sh).
set -euo pipefail
BIN="${MAPFUSE_BIN_DIR:?}"
SRC="${MAPFUSE_SOURCE_DIR:?}"
START=$SECONDS
fail() { echo "FAIL: $*"; exit 1; }
skip() {
  if [[ "${MAPFUSE_REQUIRE_SLURM:-0}" == 1 ]]; then fail "(MAPFUSE_REQUIRE_SLURM=1) $*"; fi
  echo "SKIP: $*"; exit 77
}
for tool in snakemake munged mungekey munge slurmctld slurmd sbatch srun sinfo squeue scontrol \
            sacct; do
  command -v "$tool" >/dev/null || fail "$tool missing (scripts/install-deps.sh installs it)"
done
(( $(id -u) == 0 )) || skip "slurmd must run as root to start jobs (running as uid $(id -u))"

# Its own folder under /tmp: munge's socket path must stay short (108 bytes) and every folder
# above it searchable by all (munged refuses otherwise).
T="$(mktemp -d /tmp/mapfuse-slurm.XXXXXX)"
chmod 755 "$T"
mkdir -p "$T/etc" "$T/key" "$T/munge" "$T/state" "$T/spool" "$T/log" "$T/run"
chmod 700 "$T/key"

# Nothing of an enclosing Slurm job (ctest run inside an allocation) may leak into this cluster.
for v in $(compgen -e | grep '^SLURM_' || true); do unset "$v"; done
export SLURM_CONF="$T/etc/slurm.conf"
export USER="${USER:-$(id -un)}"   # Snakemake's Slurm executor reads $USER

SK_PID=""
dump_logs() {
  for f in "$T"/log/*.log; do
    [[ -s "$f" ]] && { echo "---- ${f#"$T"/} (last 20 lines)"; tail -n 20 "$f"; }
  done
  return 0
}
ours() {   # <pid>: alive and started by this test (its command line names our folder)
  [[ -n "$1" ]] && tr '\0' ' ' < "/proc/$1/cmdline" 2>/dev/null | grep -qF "$T/"
}
stop_daemon() {   # <pid file>: ask our daemon to stop (TERM), wait up to 5 s, then kill it
  local pid
  pid="$(cat "$1" 2>/dev/null)"
  ours "$pid" || return 0
  kill -TERM "$pid" 2>/dev/null
  for _ in $(seq 1 50); do ours "$pid" || return 0; sleep 0.1; done
  echo "cleanup: $(basename "$1" .pid) (pid $pid) ignored TERM, killing it"
  kill -KILL "$pid" 2>/dev/null
}
cleanup() {
  local rc=$?
  set +e
  [[ -n "$SK_PID" ]] && kill -TERM "$SK_PID" 2>/dev/null && wait "$SK_PID" 2>/dev/null
  if ours "$(cat "$T/run/slurmctld.pid" 2>/dev/null)"; then
    # Cancel what is left and let its job steps end while the controller still listens.
    squeue -h -o %i 2>/dev/null | xargs -r scancel 2>/dev/null
    for _ in $(seq 1 50); do [[ -z "$(squeue -h 2>/dev/null)" ]] && break; sleep 0.2; done
  fi
  stop_daemon "$T/run/slurmd.pid"
  stop_daemon "$T/run/slurmctld.pid"
  stop_daemon "$T/run/munged.pid"
  (( rc == 0 || rc == 77 )) || dump_logs
  rm -rf "$T"
  exit "$rc"
}
trap cleanup EXIT
trap 'exit 130' INT TERM

# ---- munge: a fresh key and a daemon on our own socket
mungekey -c -k "$T/key/munge.key" >/dev/null 2>&1 || fail "mungekey could not create a key"
munged -S "$T/munge/munge.sock" --key-file="$T/key/munge.key" --pid-file="$T/run/munged.pid" \
       --log-file="$T/log/munged.log" --seed-file="$T/run/munged.seed" >/dev/null 2>&1 \
  || skip "munged does not start here: $(tail -n 1 "$T/log/munged.log" 2>/dev/null)"
munge -n -S "$T/munge/munge.sock" | unmunge -S "$T/munge/munge.sock" >/dev/null 2>&1 \
  || skip "munge credentials do not round-trip through our munged"

# ---- slurm.conf: one node (this machine's CPUs and memory) in one partition. No cgroups and no
# accounting database: processes tracked by /proc, each job bound to the CPUs it was given (as
# on a production cluster: a 1-CPU job runs 1 OpenMP thread), completed jobs written to a
# job-completion file that `sacct -c` reads. Free ports, so parallel runs and a system Slurm on
# the default ports (6817/6818) do not clash.
read -r CTLD_PORT SLURMD_PORT < <(python3 -c '
import socket
s = [socket.socket() for _ in range(2)]
for x in s: x.bind(("127.0.0.1", 0))
print(*[x.getsockname()[1] for x in s])')
HOST="$(hostname -s)"   # slurmctld only runs on the host SlurmctldHost names
CPUS="$(nproc)"
MEM_MB=$(awk '/^MemTotal:/ { print int($2 / 1024 * 0.9) }' /proc/meminfo)
NODE=mapfuse-node
PARTITION=mapfuse
cat > "$SLURM_CONF" <<EOF
ClusterName=mapfuse
SlurmctldHost=$HOST(127.0.0.1)
SlurmctldPort=$CTLD_PORT
SlurmdPort=$SLURMD_PORT
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$T/munge/munge.sock
SlurmUser=root
SlurmdUser=root
StateSaveLocation=$T/state
SlurmdSpoolDir=$T/spool
SlurmctldPidFile=$T/run/slurmctld.pid
SlurmdPidFile=$T/run/slurmd.pid
SlurmctldLogFile=$T/log/slurmctld.log
SlurmdLogFile=$T/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/affinity
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/filetxt
JobCompLoc=$T/log/jobcomp.txt
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SlurmdParameters=config_overrides
ReturnToService=2
MpiDefault=none
MailProg=/bin/true
MinJobAge=600
NodeName=$NODE NodeHostname=$HOST NodeAddr=127.0.0.1 CPUs=$CPUS RealMemory=$MEM_MB State=UNKNOWN
PartitionName=$PARTITION Nodes=$NODE Default=YES MaxTime=60 State=UP
EOF

last_lines() { tail -q -n 2 "$@" 2>/dev/null | tr '\n' ' '; }
slurmctld -f "$SLURM_CONF" >"$T/log/slurmctld.out" 2>&1 \
  || skip "slurmctld does not start here: $(last_lines "$T"/log/slurmctld.{log,out})"
slurmd -f "$SLURM_CONF" -N "$NODE" >"$T/log/slurmd.out" 2>&1 \
  || skip "slurmd does not start here: $(last_lines "$T"/log/slurmd.{log,out})"
state=""
for _ in $(seq 1 150); do
  state="$(sinfo -h -n "$NODE" -o %t 2>/dev/null || true)"
  [[ "$state" == idle ]] && break
  sleep 0.2
done
if [[ "$state" != idle ]]; then
  dump_logs
  skip "the Slurm node did not come up idle within 30 s (sinfo state: '${state:-none}'; logs above)"
fi
echo "slurm: node $NODE idle ($CPUS CPUs, ${MEM_MB} MB) after $((SECONDS - START)) s"

# ---- the sample batch of batch_pipelines.sh, and its maps from a local make run
WORK_DIR="$T/batch"   # the cluster's "shared file system": the node is this machine
TILE_SIZE=${MAPFUSE_SLURM_TILE_SIZE:-600}  # 4 tiles of the sample batch (300 m: 8, twice the jobs)
read -r -a SIM_ARGS <<< "${MAPFUSE_SLURM_SIMULATE:---traversals 6 --route-length 800}"
mkdir -p "$WORK_DIR"
cd "$WORK_DIR"        # snakemake keeps its state (and the Slurm job logs) in ./.snakemake
"$BIN/simulate" -q "${SIM_ARGS[@]}" -o sim >/dev/null
MK=(make -s -j2 -f "$SRC/scripts/crowd.mk" BIN="$BIN" LSM_DIR=sim/lsm
    TRUTH=sim/truth/vector_map.json)
in_background() {   # <what> <command...>: waited for, so that a signal reaches the trap at once
  local what="$1" rc=0   # (bash runs a trap only after the foreground command returns: a TERM
  shift                  # during a minutes-long local run left the daemons running meanwhile)
  "$@" >/dev/null &
  SK_PID=$!
  wait "$SK_PID" || rc=$?
  SK_PID=""
  (( rc == 0 )) || fail "$what (exit $rc)"
}
in_background "local make run (untiled)" "${MK[@]}" WORK=local
in_background "local make run (tiled)" "${MK[@]}" WORK=local_tiled TILE_SIZE=$TILE_SIZE
echo "local: make untiled and tiled done after $((SECONDS - START)) s"

# ---- the same Snakefile through Slurm. Resources come from the command line: the partition,
# and memory / wall time every job asks for (sbatch --mem / -t). Snakemake 7 polls each job's
# state at most this often per second (any value above 1 it replaces by 0.03, one poll per
# 33 s: right for a shared production scheduler, minutes of idling here).
SK=(snakemake -s "$SRC/scripts/Snakefile" --slurm --jobs 8
    --default-resources "slurm_partition=$PARTITION" mem_mb=2000 runtime=60
    --max-status-checks-per-second 1 --latency-wait 10
    --config lsm_dir=sim/lsm bin="$BIN" truth=sim/truth/vector_map.json)
slurm_run() {   # <log> <config...>: in the background, so that a signal reaches the trap at once
  local log="$1" rc=0
  shift
  "${SK[@]}" "$@" >"$log" 2>&1 &
  SK_PID=$!
  wait "$SK_PID" || rc=$?
  SK_PID=""
  (( rc == 0 )) || { tail -n 60 "$log"; fail "snakemake --slurm $* (exit $rc, log above)"; }
  echo "slurm: snakemake $* done after $((SECONDS - START)) s"
}
same() { cmp -s "$1" "$2" || fail "$1 differs from the local run's $2"; }
n=0   # intermediate files compared

# Untiled: map, every aligned LSM and evaluate's summary equal the local run's.
slurm_run slurm.log work=slurm
same slurm/aggregate/map.cbor local/aggregate/map.cbor
same slurm/evaluate/evaluate.summary.json local/evaluate/evaluate.summary.json
for f in local/align/*.cbor; do same "slurm${f#local}" "$f"; n=$((n + 1)); done

# Tiled, in the same folder (as a user retiling a finished batch): the per-drive georef output
# is reused, tile -> align per tile -> balance -> aggregate per tile -> stitch -> evaluate are
# new jobs. The tile checkpoint makes the per-tile jobs once the tile list exists.
slurm_run slurm_tiled.log work=slurm tile_size=$TILE_SIZE
same slurm/stitch/map.cbor local_tiled/stitch/map.cbor
same slurm/evaluate/evaluate.summary.json local_tiled/evaluate/evaluate.summary.json
for f in local_tiled/balance/*/*.cbor local_tiled/tiles/*/aggregate/map.cbor; do
  same "slurm${f#local_tiled}" "$f"; n=$((n + 1))
done
tiles=$(wc -l < slurm/tiles/tiles.txt)
drives=$(find sim/lsm -name "*.cbor" | wc -l)
(( tiles >= 3 )) || fail "expected >= 3 tiles, got $tiles"
(( n >= drives + 2 * tiles )) || fail "compared only $n intermediate files"

# ---- every rule ran as a Slurm job on the node: the job-completion record (sacct -c), one
# COMPLETED job per Snakemake job, named snakejob_<rule>_<n>.
sacct -c -n -P -o JobID,JobName,State,NodeList > sacct.txt || fail "sacct -c"
python3 - sacct.txt "$NODE" "$drives" "$tiles" slurm.log slurm_tiled.log <<'PY' \
  || { cat sacct.txt; fail "Slurm job record"; }
import collections, re, sys
path, node, drives, tiles = sys.argv[1], sys.argv[2], int(sys.argv[3]), int(sys.argv[4])
rows = [l.split("|") for l in open(path).read().split("\n") if l.strip()]
bad = [r for r in rows if r[2] != "COMPLETED" or r[3] != node]
assert not bad, f"jobs not COMPLETED on {node}: {bad}"
by_rule = collections.Counter(re.fullmatch(r"snakejob_(\w+?)_\d+", r[1]).group(1) for r in rows)
# untiled: origin, georef per drive, align, aggregate, evaluate; then tiled (georef reused):
# tile, align per tile, balance, aggregate per tile, stitch, evaluate
want = collections.Counter({"origin": 1, "georef": drives, "align": 1, "aggregate": 1,
                            "evaluate": 2, "tile": 1, "align_tile": tiles, "balance": 1,
                            "aggregate_tile": tiles, "stitch": 1})
assert by_rule == want, f"Slurm jobs by rule {dict(by_rule)}, expected {dict(want)}"
# Snakemake submitted each of them itself (its log names the Slurm job id of every job).
submitted = set()
for log in sys.argv[5:]:
    submitted |= set(re.findall(r"submitted with SLURM jobid (\d+)", open(log).read()))
assert submitted == {r[0] for r in rows}, (sorted(submitted), sorted(r[0] for r in rows))
print(f"slurm: {len(rows)} jobs COMPLETED on {node}: " +
      ", ".join(f"{k} {v}" for k, v in sorted(by_rule.items())))
PY
[[ -z "$(squeue -h)" ]] || fail "jobs still queued: $(squeue -h)"
echo "slurm_cluster: ok ($drives drives, $tiles tiles; maps, evaluate summaries and $n aligned /" \
     "balanced / per-tile files identical to the local run; $((SECONDS - START)) s)"
