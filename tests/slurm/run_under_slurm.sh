#!/usr/bin/env bash
# Starts a private single-node SLURM (slurmctld, slurmd, munge) in a temporary directory, runs
# scripts/slurm/emergent.sbatch with 2 tasks, checks the job's output, and tears it all down.
# Needs Debian's slurmctld slurmd slurm-client munge (not installed by scripts/setup: SLURM is
# what clusters provide; this script is the check that emergent runs under it).
# Facts it relies on: shared/notes/slurm.md.
# usage: EMERGENT_TEST_SLURM=1 tests/slurm/run_under_slurm.sh   (repository root, after a build)
set -euo pipefail
root=$PWD
# Opt-in (it starts daemons on ports 6817/6818): exit 77, which ctest reports as skipped.
[ "${EMERGENT_TEST_SLURM:-0}" = 1 ] || { echo "skipped: set EMERGENT_TEST_SLURM=1 to run"; exit 77; }
for tool in slurmctld slurmd sbatch squeue munged; do
  command -v $tool >/dev/null || { echo "skipped: $tool not installed"; exit 77; }
done
work=$(mktemp -d /tmp/emergent-slurm.XXXXXX)
chmod 755 "$work"
host=$(hostname)
cpus=$(nproc)
mem=$(( $(slurmd -C | grep -o 'RealMemory=[0-9]*' | cut -d= -f2) - 512 ))
pids=()
cleanup() {
  scancel --full --quiet -u "$(id -un)" 2>/dev/null || true
  sleep 1
  for p in "${pids[@]}"; do kill "$p" 2>/dev/null || true; done
  sleep 1
  pkill -f "slurmstepd.*$work" 2>/dev/null || true
  rm -rf "$work"
}
trap cleanup EXIT
mkdir -p "$work"/{munge,state,spool,pmix,log}
chmod 700 "$work/munge"
dd if=/dev/urandom of="$work/munge/munge.key" bs=1024 count=1 status=none
chmod 400 "$work/munge/munge.key"
munged --key-file="$work/munge/munge.key" --socket="$work/munge/socket" \
  --pid-file="$work/munge/munged.pid" --log-file="$work/log/munged.log" --seed-file="$work/munge/seed" \
  --force
pids+=("$(cat "$work/munge/munged.pid")")
cat >"$work/slurm.conf" <<CONF
ClusterName=emergent-test
SlurmctldHost=$host(127.0.0.1)
AuthType=auth/munge
AuthInfo=socket=$work/munge/socket
CryptoType=crypto/munge
MpiDefault=pmix
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
ReturnToService=2
SlurmctldPidFile=$work/slurmctld.pid
SlurmdPidFile=$work/slurmd.pid
SlurmdSpoolDir=$work/spool
StateSaveLocation=$work/state
SlurmctldLogFile=$work/log/slurmctld.log
SlurmdLogFile=$work/log/slurmd.log
SlurmUser=root
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core_Memory
DefMemPerCPU=1024
MailProg=/bin/true
NodeName=$host NodeAddr=127.0.0.1 CPUs=$cpus RealMemory=$mem State=UNKNOWN
PartitionName=debug Nodes=ALL Default=YES MaxTime=10 State=UP
CONF
echo "PMIxCliTmpDirBase=$work/pmix" >"$work/mpi.conf"
export SLURM_CONF=$work/slurm.conf
slurmctld -f "$SLURM_CONF" && sleep 1
pids+=("$(cat "$work/slurmctld.pid")")
slurmd -f "$SLURM_CONF" -N "$host" && sleep 2
pids+=("$(cat "$work/slurmd.pid")")
for _ in $(seq 30); do sinfo -h -o %T 2>/dev/null | grep -q idle && break; sleep 0.5; done
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 EMERGENT_ROOT=$root
job=$(sbatch --parsable -n 2 --time=5 -o "$work/job.out" -D "$work" "$root/scripts/slurm/emergent.sbatch" \
  lj-fluid --preset tiny --set n_cells=6 --set progress_interval=0 --summary-json "$work/summary.json")
for _ in $(seq 120); do squeue -h -j "$job" 2>/dev/null | grep -q . || break; sleep 0.5; done
# srun can report success after a failed launch: check what the job produced.
if ! grep -q '"ranks": 2' "$work/summary.json" 2>/dev/null; then
  echo "FAIL: job $job did not run emergent on 2 ranks"; tail -20 "$work/job.out" 2>/dev/null
  tail -5 "$work/log/slurmctld.log" "$work/log/slurmd.log"; exit 1
fi
echo "ok: $(grep -m1 'lj-fluid:' "$work/job.out")"
