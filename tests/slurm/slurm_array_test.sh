#!/usr/bin/env bash
# ctest slurm_array: a real one-node Slurm cluster on localhost runs tools/slurm/render_array.sh
# (4 array tasks of stage4 on builtin:cornell, then the pt_merge job), and the merged image
# must equal a one-run render bit for bit (the squared-luminance sums to 1e-14); then a task
# requeued mid-render (as preemption does) must resume its checkpoint, and its part must
# equal the same range rendered without a stop. Everything the test
# starts is stopped by its PID on every exit. Skipped (77) where Slurm is not installed.
#
# usage: slurm_array_test.sh BIN_DIR EXR_IDENTICAL
#   BIN_DIR        the build's bin/ (the stages and pt_merge)
#   EXR_IDENTICAL  the pt_exr_identical program (tests/slurm/exr_identical.cpp)
# Environment: PT_SLURM_TIMEOUT (seconds each wait may take, default 300),
# PT_SLURM_KEEP=1 keeps the cluster's folder (config, logs, images) for a look afterwards.
set -euo pipefail

me=slurm_array
[ $# -eq 2 ] || { echo "usage: slurm_array_test.sh BIN_DIR EXR_IDENTICAL" >&2; exit 2; }
bin=$(realpath -- "$1")
identical=$(realpath -- "$2")
src=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
timeout=${PT_SLURM_TIMEOUT:-300}
# The daemons live in /usr/sbin, which a user's PATH may not have.
export PATH=$PATH:/usr/sbin:/sbin

for program in slurmctld slurmd sbatch squeue scontrol scancel sinfo munged munge; do
  command -v "$program" >/dev/null || {
    echo "$me: skipped: Slurm is not installed ($program not found); on Debian: sudo apt-get install slurm-wlm munge (.ci/run installs them)"
    exit 77
  }
done
for program in stage4_direct_indirect pt_merge; do
  [ -x "$bin/$program" ] || { echo "$me: FAILED: $bin/$program is not built" >&2; exit 1; }
done

# The cluster's folder. Every process the test starts in the background carries
# PT_SLURM_TEST_DIR=$dir in its environment (the daemons, slurmstepd and the jobs, which
# get it from sbatch's environment), which is how the clean-up finds what is left of them.
dir=$(mktemp -d "${TMPDIR:-/tmp}/pt-slurm.XXXXXX")
chmod 0755 "$dir"  # munged wants its socket's folder searchable by all
mark=PT_SLURM_TEST_DIR=$dir
export SLURM_CONF=$dir/slurm.conf
unset SLURM_JOB_ID SLURM_ARRAY_JOB_ID SLURM_ARRAY_TASK_ID SLURM_CPUS_ON_NODE
daemons=()  # PIDs of munged, slurmctld, slurmd

say() { echo "$me: [${SECONDS} s] $*"; }
fail() {
  echo "$me: FAILED after ${SECONDS} s: $*" >&2
  for log in "$dir"/*.log "$dir"/*/*.parts/slurm-*.out; do
    [ -f "$log" ] || continue
    echo "--- $log (last lines)" >&2
    tail -n 15 "$log" >&2
  done
  exit 1
}

# PIDs of the processes that carry the mark: with "all", every one; without, the jobs' (not
# the daemons nor their children, such as slurmctld's slurmscriptd).
marked_pids() {
  local file pid parent d
  for file in $(grep -lxzF "$mark" /proc/[0-9]*/environ 2>/dev/null); do
    pid=${file#/proc/}; pid=${pid%/environ}
    if [ "${1:-}" != all ]; then
      parent=$(awk '/^PPid:/ {print $2}' "/proc/$pid/status" 2>/dev/null) || continue
      for d in "${daemons[@]}"; do [ "$pid" = "$d" ] || [ "$parent" = "$d" ] && continue 2; done
    fi
    echo "$pid"
  done
  return 0
}

cleanup() {
  local status=$? pid i
  trap - EXIT INT TERM
  # The jobs first: slurmstepd can outlive slurmd.
  if [ ${#daemons[@]} -gt 0 ]; then
    timeout 10 scancel --quiet --user "$(id -un)" 2>/dev/null || true
    for ((i = 0; i < 50; i++)); do [ -z "$(marked_pids)" ] && break; sleep 0.2; done
  fi
  for pid in "${daemons[@]}"; do kill -TERM "$pid" 2>/dev/null || true; done
  for ((i = 0; i < 50; i++)); do
    local alive=0
    for pid in "${daemons[@]}"; do kill -0 "$pid" 2>/dev/null && alive=1; done
    [ $alive = 0 ] && break
    sleep 0.2
  done
  # Whatever is left of it (a daemon that did not stop, a stray slurmstepd or job), by PID.
  for pid in "${daemons[@]}" $(marked_pids all); do kill -KILL "$pid" 2>/dev/null || true; done
  wait 2>/dev/null || true
  if [ "${PT_SLURM_KEEP:-0}" = 1 ]; then
    echo "$me: kept $dir" >&2
  else
    rm -rf "$dir"
  fi
  exit $status
}
trap cleanup EXIT
trap 'exit 130' INT
trap 'exit 143' TERM

# Waits until "$@" succeeds, at most $timeout seconds; else fails with the description $1.
wait_for() {
  local what=$1 deadline=$((SECONDS + timeout))
  shift
  until "$@" >/dev/null 2>&1; do
    [ $SECONDS -lt $deadline ] || fail "$what did not happen within $timeout s (PT_SLURM_TIMEOUT)"
    sleep 0.2
  done
}

# Two free ports on the loopback interface.
read -r port_ctld port_d < <(python3 -c '
import socket
s = [socket.socket() for _ in range(2)]
for x in s: x.bind(("127.0.0.1", 0))
print(*[x.getsockname()[1] for x in s])')

# munge: its own key (0400) and socket; Slurm finds it through AuthInfo=socket=.
mkdir -p "$dir/state" "$dir/spool"
head -c 1024 /dev/urandom >"$dir/munge.key"
chmod 0400 "$dir/munge.key"
env "$mark" munged --foreground --force --socket="$dir/munge.sock" --key-file="$dir/munge.key" \
  --pid-file="$dir/munged.pid" --seed-file="$dir/munged.seed" --log-file="$dir/munged.log" \
  >>"$dir/munged.log" 2>&1 &
daemons+=($!)
wait_for "munged answering on $dir/munge.sock" bash -c "munge -n -S '$dir/munge.sock' | unmunge -S '$dir/munge.sock'"

user=$(id -un)
cat >"$SLURM_CONF" <<EOF
# A one-node cluster on localhost for the test slurm_array (tests/slurm/slurm_array_test.sh).
ClusterName=ptlocal
SlurmctldHost=localhost
SlurmUser=$user
SlurmdUser=$user
AuthType=auth/munge
CredType=cred/munge
# cred_expire: a requeued job waits this long before it starts again (default 120 s).
AuthInfo=socket=$dir/munge.sock,cred_expire=10
# The daemons bind to localhost's address, not to every interface: the test stays on loopback.
CommunicationParameters=NoCtldInAddrAny,NoInAddrAny
SlurmctldPort=$port_ctld
SlurmdPort=$port_d
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/slurmctld.log
SlurmdLogFile=$dir/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
MpiDefault=none
SchedulerType=sched/builtin
# The pending jobs are looked at every 2 s rather than every 60 s (a requeued task waits for that).
SchedulerParameters=sched_interval=2
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
ReturnToService=2
MinJobAge=86400
KillWait=30
NodeName=localhost CPUs=$(nproc) State=UNKNOWN
PartitionName=pt Nodes=localhost Default=YES MaxTime=INFINITE State=UP
EOF
env "$mark" slurmctld -D -i -f "$SLURM_CONF" >>"$dir/slurmctld.log" 2>&1 &
daemons+=($!)
env "$mark" slurmd -D -N localhost -f "$SLURM_CONF" >>"$dir/slurmd.log" 2>&1 &
daemons+=($!)
node_idle() { sinfo -h -n localhost -o %t | grep -qx idle; }
wait_for "the node localhost becoming idle in Slurm" node_idle
say "a Slurm cluster runs on localhost (ports $port_ctld, $port_d) in $dir"

scene=(--backend cpu --scene builtin:cornell --width 32 --height 32 --seed 7)

# Waits until the jobs $@ have left the queue, then requires each of their tasks to have
# COMPLETED with exit code 0 (their records live: MinJobAge is a day).
wait_jobs() {
  local ids=$1 line
  jobs_done() { [ -z "$(squeue -h -j "$ids" -o %i 2>/dev/null)" ] && squeue -h -o %i >/dev/null; }
  wait_for "the jobs $ids finishing" jobs_done
  while read -r line; do
    [[ $line == *JobState=COMPLETED* && $line == *" ExitCode=0:0"* ]] ||
      fail "a job did not complete: $(grep -oE '(JobId|ArrayTaskId|JobState|ExitCode)=[^ ]*' <<<"$line" | tr '\n' ' ')"
  done < <(for id in ${ids//,/ }; do scontrol -o show job "$id"; done)
}

# 1. The script's array of 4 tasks, merged, against the one run.
"$bin/stage4_direct_indirect" "${scene[@]}" --spp 64 --out "$dir/one_run.exr" >/dev/null
read -r array merge < <(env "$mark" "$src/tools/slurm/render_array.sh" --parsable --out "$dir/frame/merged.exr" \
  --spp 64 --tasks 4 --bin "$bin" --cpus-per-task 1 -- "${scene[@]}") || fail "render_array.sh did not submit"
say "submitted job array $array (4 tasks) and merge job $merge"
wait_jobs "$array,$merge"
grep -q "backend cpu (1 thread" "$dir/frame/merged.parts/slurm-${array}_0.out" ||
  fail "task 0 did not render on the 1 CPU Slurm gave it (SLURM_CPUS_ON_NODE)"
# The squared-luminance sums may differ in their last bits (docs/film.md); all else bit for bit.
"$identical" --tolerance film.YY=1e-14 "$dir/one_run.exr" "$dir/frame/merged.exr" ||
  fail "the merge of the 4 tasks' parts differs from the one-run render"
say "the merge of 4 array tasks equals the one-run render (bit for bit, the squared-luminance sums to 1e-14)"

# 2. Preemption: task 0 of 2 requeued while it renders (scontrol requeue sends SIGTERM, as
# preemption does) must resume its checkpoint, and its part must equal the part rendered
# without a stop, bit for bit (the merge's own exactness is part 1's).
long=(--backend cpu --scene builtin:cornell --width 32 --height 32 --seed 11)
"$bin/stage4_direct_indirect" "${long[@]}" --samples 0:2048 --out "$dir/part0_uninterrupted.exr" >/dev/null
read -r array merge < <(env "$mark" "$src/tools/slurm/render_array.sh" --parsable --out "$dir/preempt/merged.exr" \
  --spp 4096 --tasks 2 --bin "$bin" --cpus-per-task 1 --checkpoint 0.001 -- "${long[@]}") ||
  fail "render_array.sh did not submit"
say "submitted job array $array (2 tasks of 2048 spp, a checkpoint after every pass) and merge job $merge"
parts=$dir/preempt/merged.parts
checkpoint_or_done() {
  compgen -G "$parts/part000of002_*.exr.ckpt" ||
    scontrol -o show job "${array}_0" | grep -qE 'JobState=(COMPLETED|FAILED|CANCELLED)'
}
wait_for "task 0's first checkpoint" checkpoint_or_done
if scontrol requeue "${array}_0" 2>"$dir/requeue.err"; then
  wait_jobs "$array,$merge"
  grep -q "resumes" "$parts/slurm-${array}_0.out" ||
    fail "task 0 was requeued but did not resume its checkpoint"
  scontrol -o show job "${array}_0" | grep -q " Restarts=1 " || fail "task 0 was not restarted once"
  say "task 0, requeued mid-render, resumed its checkpoint"
else
  # The task ended between its first checkpoint and the requeue: nothing to resume.
  wait_jobs "$array,$merge"
  say "task 0 finished before it could be requeued ($(cat "$dir/requeue.err")); the resume was not exercised"
fi
"$identical" "$dir/part0_uninterrupted.exr" "$parts/part000of002_samples_0-2047.exr" ||
  fail "the part of the requeued task differs from the same part rendered without a stop"
[ -f "$dir/preempt/merged.exr" ] || fail "the merge job wrote no image"
say "the requeued task's part equals the part rendered without a stop, bit for bit"
