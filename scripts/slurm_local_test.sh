#!/usr/bin/env bash
# Real Slurm test on this machine: starts a private single-node Slurm cluster (munged, slurmctld,
# slurmd from Debian's slurm-wlm and munge packages; installed with apt-get if missing, needs
# root), submits a small matrix with tools/slurm/submit.sh as a 2-shard array plus the dependent
# merge job, waits, and checks that the merged report equals the report of a local vb_batch run
# of the same matrix, file for file. Everything (config, state, logs, results) lives in one
# temporary directory; the daemons it started are stopped at the end. Takes ~1 minute.
#   usage: scripts/slurm_local_test.sh [BUILD_DIR]     (default build; run scripts/build.sh first)
# Exit 0 = equal reports; 1 = test failed (details printed, directory kept); 2 = cannot run.
set -euo pipefail
cd "$(dirname "$0")/.."
src=$(pwd)
bin=$(cd "${1:-build}/tools" 2>/dev/null && pwd) || { echo "slurm test: no ${1:-build}/tools; build first" >&2; exit 2; }
[ -x "$bin/vb_batch" ] || { echo "slurm test: $bin/vb_batch missing; build first" >&2; exit 2; }

if ! command -v slurmctld > /dev/null || ! command -v munged > /dev/null; then
  [ "$(id -u)" = 0 ] || { echo "slurm test: slurm-wlm/munge missing and not root" >&2; exit 2; }
  DEBIAN_FRONTEND=noninteractive apt-get install -y -q slurm-wlm munge > /dev/null
fi
[ "$(id -u)" = 0 ] || { echo "slurm test: must run as root (daemons run as root here)" >&2; exit 2; }

d=$(mktemp -d /tmp/vb_slurm_test.XXXXXX)
mkdir -p "$d/state" "$d/spool" "$d/munge"
host=$(hostname -s)
cpus=$(nproc)
cleanup() {
  local rc=$? started=() p f
  for f in "$d/slurmctld.pid" "$d/slurmd.pid" "$d/munged.pid"; do
    [ -s "$f" ] && started+=("$(cat "$f")")
  done
  for p in "${started[@]}"; do kill "$p" 2> /dev/null || true; done
  # wait until they are gone (slurmctld saves its state on exit) before removing their files
  for _ in $(seq 1 100); do
    alive=0
    for p in "${started[@]}"; do kill -0 "$p" 2> /dev/null && alive=1; done
    [ $alive = 0 ] && break
    sleep 0.1
  done
  if [ $rc = 0 ]; then rm -rf "$d"; else echo "slurm test: kept $d for inspection" >&2; fi
}
trap cleanup EXIT

# munge: a private key and socket, so no system-wide munged is needed or disturbed.
dd if=/dev/urandom of="$d/munge/munge.key" bs=1024 count=1 status=none
chmod 600 "$d/munge/munge.key"
munged --force --key-file="$d/munge/munge.key" --socket="$d/munge/munge.socket" \
  --pid-file="$d/munged.pid" --log-file="$d/munged.log" --seed-file="$d/munge/seed"

cat > "$d/slurm.conf" << CONF
ClusterName=vbtest
SlurmctldHost=$host
SlurmUser=root
SlurmdUser=root
SlurmctldPort=16817
SlurmdPort=16818
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$d/munge/munge.socket
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
MpiDefault=none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SlurmctldPidFile=$d/slurmctld.pid
SlurmdPidFile=$d/slurmd.pid
SlurmdSpoolDir=$d/spool
StateSaveLocation=$d/state
SlurmctldLogFile=$d/slurmctld.log
SlurmdLogFile=$d/slurmd.log
NodeName=$host CPUs=$cpus RealMemory=2000 State=UNKNOWN
PartitionName=vbtest Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF="$d/slurm.conf"
slurmctld -i
slurmd
for _ in $(seq 1 60); do
  state=$(sinfo -h -o %T 2> /dev/null || true)
  [ "$state" = idle ] && break
  sleep 1
done
[ "$state" = idle ] || { echo "slurm test: node not idle (state '$state'); see $d/*.log" >&2; exit 1; }
echo "slurm test: single-node cluster up ($host, $cpus CPUs, config $d/slurm.conf)"

# The matrix of the integration test: 2 rigid tasks x 2 pairs (success and stuck) + a deformable
# task (error trials), short time limit.
matrix=("$src/tasks/env010.yaml" "$src/tasks/env042.yaml" "$src/tasks/env061.yaml"
        --pairs 0,1 --time-limit 32 --traj-every 20)

"$bin/vb_batch" "${matrix[@]}" --quiet --out "$d/local" > /dev/null
"$bin/vb_report" "$d/local" > /dev/null

read -r _ array_id _ merge_id < <(tools/slurm/submit.sh --shards 2 --cpus 1 --mem 500M \
  --time 00:10:00 --out "$d/slurm" --bin "$bin" -- "${matrix[@]}" --quiet)
echo "slurm test: submitted array $array_id and merge $merge_id"
for _ in $(seq 1 300); do
  [ -z "$(squeue -h -j "$array_id,$merge_id" 2> /dev/null)" ] && break
  sleep 1
done
[ -z "$(squeue -h -j "$array_id,$merge_id" 2> /dev/null)" ] ||
  { echo "slurm test: jobs still queued after 300 s" >&2; squeue >&2; exit 1; }
cat "$d/slurm/logs/merge.out" 2> /dev/null || true
[ -f "$d/slurm/merged/report/report.md" ] ||
  { echo "slurm test: no merged report; logs:" >&2; tail -n 20 "$d"/slurm/logs/* >&2; exit 1; }

status=0
for f in "$d/local/report"/*; do
  name=$(basename "$f")
  [ -f "$f" ] || continue
  if ! cmp -s "$f" "$d/slurm/merged/report/$name"; then
    echo "slurm test: $name differs between the local run and the Slurm run" >&2
    status=1
  fi
done
[ "$(ls "$d/local/report" | wc -l)" = "$(ls "$d/slurm/merged/report" | wc -l)" ] ||
  { echo "slurm test: different report file sets" >&2; status=1; }
[ $status = 0 ] && echo "slurm test: PASS - merged 2-shard Slurm report equals the local report ($(ls "$d/local/report" | wc -l) files)"
exit $status
