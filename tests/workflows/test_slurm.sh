#!/usr/bin/env bash
# The two-point phase-diagram smoke sweep on a single-node Slurm cluster that this test
# starts in a temporary folder (munged on its own socket and key, slurmctld and slurmd
# from a minimal slurm.conf, on free ports; nothing in /etc or /run is touched),
# submitted with Snakemake's Slurm executor and the repository's profile
# (workflows/profiles/slurm). The daemons are stopped on exit, also on failure.
# Needs root and Debian's slurm-wlm, munge and snakemake; prints "skipped" otherwise.
#
#   tests/workflows/test_slurm.sh [SLENDER_BINARY]      (default: build/slender)
set -euo pipefail
export PATH="$PATH:/usr/sbin:/sbin"
repo="$(cd "$(dirname "$0")/../.." && pwd)"
bin="$(realpath "${1:-$repo/build/slender}")"

skip() { echo "workflow slurm: skipped ($*)"; exit 0; }
[[ $(id -u) -eq 0 ]] || skip "needs root to start munged, slurmctld and slurmd"
for tool in snakemake munged mungekey setpriv slurmctld slurmd sbatch sinfo scontrol; do
  command -v "$tool" > /dev/null || skip "no $tool"
done
id munge > /dev/null 2>&1 || skip "no munge user"
[[ -x "$bin" ]] || { echo "workflow slurm: no slender binary at $bin" >&2; exit 1; }

tmp="$(mktemp -d /tmp/slender-slurm.XXXXXX)"
chmod 755 "$tmp"
pids=()
cleanup() {
  local rc=$?
  for pid in "${pids[@]}"; do kill "$pid" 2> /dev/null || true; done
  for pid in "${pids[@]}"; do wait "$pid" 2> /dev/null || true; done
  if [[ $rc -ne 0 ]]; then
    for log in "$tmp"/slurm/*.log "$tmp"/munge/munged.log; do
      [[ -f "$log" ]] && { echo "--- $log"; tail -n 20 "$log"; }
    done
  fi
  rm -rf "$tmp"
}
trap cleanup EXIT
fail() { echo "workflow slurm: FAILED: $*" >&2; exit 1; }

# munged as the munge user, with its own key and socket
mkdir -p "$tmp/munge" "$tmp/slurm/spool" "$tmp/slurm/state" "$tmp/work"
mungekey --create --keyfile="$tmp/munge/munge.key"
chown -R munge:munge "$tmp/munge"
chmod 755 "$tmp/munge"  # its clients (slurmctld, slurmd, srun) reach the socket in it
setpriv --reuid=munge --regid=munge --init-groups munged --foreground \
  --socket="$tmp/munge/munge.socket" --key-file="$tmp/munge/munge.key" \
  --pid-file="$tmp/munge/munged.pid" --seed-file="$tmp/munge/munged.seed" \
  2> "$tmp/munge/munged.log" &
pids+=($!)
for _ in $(seq 50); do [[ -S "$tmp/munge/munge.socket" ]] && break; sleep 0.1; done
[[ -S "$tmp/munge/munge.socket" ]] || fail "munged did not start"

read -r ctld_port slurmd_port < <(/usr/bin/python3 -c '
import socket
s = [socket.socket() for _ in range(2)]
for x in s: x.bind(("127.0.0.1", 0))
print(*(x.getsockname()[1] for x in s))')
host="$(hostname)"
cat > "$tmp/slurm/slurm.conf" << CONF
ClusterName=slendertest
SlurmctldHost=$host
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$tmp/munge/munge.socket
StateSaveLocation=$tmp/slurm/state
SlurmdSpoolDir=$tmp/slurm/spool
SlurmctldPidFile=$tmp/slurm/slurmctld.pid
SlurmdPidFile=$tmp/slurm/slurmd.pid
MailProg=/bin/true
SelectType=select/cons_tres
SelectTypeParameters=CR_Core_Memory
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
MpiDefault=none
ReturnToService=2
$(slurmd -C | head -n 1)
PartitionName=test Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF="$tmp/slurm/slurm.conf"
# in the foreground (-D) they log to stderr
slurmctld -D -i 2> "$tmp/slurm/slurmctld.log" &
pids+=($!)
slurmd -D 2> "$tmp/slurm/slurmd.log" &
pids+=($!)
for _ in $(seq 60); do
  [[ "$(sinfo -h -N -o %t 2> /dev/null)" == idle ]] && break
  sleep 0.5
done
[[ "$(sinfo -h -N -o %t 2> /dev/null)" == idle ]] || fail "the node is not idle: $(sinfo -N 2>&1)"
echo "slurm: node $host idle (ports $ctld_port, $slurmd_port)"

# the sweep, submitted job by job (the executor reads USER to guess an account)
export USER="${USER:-$(id -un)}"
export LD_LIBRARY_PATH="$(dirname "$bin")${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
results="$tmp/work/results/phase_diagram_smoke"
t0=$SECONDS
snakemake -s "$repo/workflows/phase_diagram.smk" --profile "$repo/workflows/profiles/slurm" \
  --configfile "$repo/workflows/config/phase_diagram_smoke.yaml" --config slender="$bin" \
  --directory "$tmp/work" > "$tmp/snakemake.log" 2>&1 || { tail -n 40 "$tmp/snakemake.log"; fail "snakemake"; }
submitted=$(grep -c "has been submitted with SLURM jobid" "$tmp/snakemake.log" || true)
[[ $submitted -eq 2 ]] || { tail -n 40 "$tmp/snakemake.log"; fail "$submitted Slurm jobs, expected 2"; }
/usr/bin/python3 - "$results" << 'PY' || fail "results"
import csv, glob, json, os, sys
results = sys.argv[1]
points = sorted(glob.glob(os.path.join(results, "points", "*.json")))
assert len(points) == 2, points
for p in points:
    rec = json.load(open(p))
    assert rec["status"] == "ok", rec
rows = list(csv.DictReader(open(os.path.join(results, "phase_diagram_f10.csv"))))
assert len(rows) == 2 and all(0.1 < float(r["phi"]) < 1 and r["class"] for r in rows), rows
PY
echo "slurm: 2 points ran as Slurm jobs, table and plots made in $((SECONDS - t0)) s"

# resume: a job cancelled mid-run (as at its time limit: SIGTERM, then SIGKILL) is
# submitted again (the profile's restart-times) and its deck continues from its checkpoint
t0=$SECONDS
work="$tmp/work/results/pack3d_smoke/work/low_torsion_R6_seed1"
snakemake -s "$repo/workflows/pack3d.smk" --profile "$repo/workflows/profiles/slurm" \
  --configfile "$repo/workflows/config/pack3d_smoke.yaml" --config slender="$bin" 'R=[6]' 'seeds=[1]' \
  --directory "$tmp/work" > "$tmp/pack3d.log" 2>&1 &
sm=$!
for _ in $(seq 240); do [[ -f "$work/low_torsion_restart.h5" ]] && break; sleep 0.25; done
[[ -f "$work/low_torsion_restart.h5" ]] || { tail -n 40 "$tmp/pack3d.log"; fail "no checkpoint from the R = 6 run"; }
scancel "$(squeue -h -o %i)"
wait "$sm" || { tail -n 40 "$tmp/pack3d.log"; fail "snakemake (pack3d)"; }
submitted=$(grep -c "has been submitted with SLURM jobid" "$tmp/pack3d.log" || true)
[[ $submitted -eq 2 ]] || { tail -n 40 "$tmp/pack3d.log"; fail "$submitted Slurm jobs for one cancelled point, expected 2"; }
/usr/bin/python3 - "$tmp/work/results/pack3d_smoke/points/low_torsion_R6_seed1.json" << 'PY' || fail "resumed record"
import json, sys
rec = json.load(open(sys.argv[1]))
assert rec["status"] == "ok" and rec["resumed_from"] == "low_torsion_restart.h5", rec
assert 0.5 < rec["result"]["phi"] < 1, rec["result"]
PY
echo "slurm: a cancelled job was submitted again and continued from its checkpoint in $((SECONDS - t0)) s"
echo "workflow slurm: ok"
