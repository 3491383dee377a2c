#!/bin/bash
# SPDX-License-Identifier: BSD-3-Clause
# The Slurm test of issue #20: `lmk slurm eval` on a real one-node Slurm cluster, started here.
#
# It writes a slurm.conf into a temporary directory (proctrack/linuxproc, task/none, SlurmUser
# root, state and spool there, its own munge key and socket), starts munged, slurmctld and slurmd
# in the foreground of this script, and checks:
#  1. a preset generated and evaluated by the job chain (a 4-task generation array, its merge, a
#     4-task evaluation array, the merge after it) gives the table and JSON of `lmk eval` on one
#     machine, byte for byte;
#  2. an array task cancelled with scancel leaves its pairs missing, the merge job fails naming
#     and counting them, and `submit.sh K` resubmits that task alone, which computes exactly those
#     pairs, after which the merge gives the one-machine table again.
# Every daemon it started is stopped by its pid on the way out, whatever happened.
#
# Usage: slurm_test.sh LMK. Exit 77 (skipped) without root or without Slurm and munge installed.
set -euo pipefail

LMK=$(readlink -f "$1")
skip() {
  echo "SKIPPED: $*"
  exit 77
}
[ "$(id -u)" = 0 ] || skip "a one-node Slurm with SlurmUser=root needs root"
for program in munged slurmctld slurmd sbatch squeue scancel scontrol sinfo; do
  command -v "$program" > /dev/null || skip "$program is not installed (scripts/install-deps.sh)"
done

T=$(mktemp -d /tmp/lmk-slurm-test.XXXXXX)
pids=()
steps_before=$(pgrep -x slurmstepd | tr '\n' ' ' || true)
stop_daemons() {
  local status=$?
  # Jobs first, while the controller still answers; then each daemon by the pid it was given.
  scancel --full --quiet --user=root 2> /dev/null || true
  for ((i = ${#pids[@]} - 1; i >= 0; i--)); do kill "${pids[i]}" 2> /dev/null || true; done
  for pid in "${pids[@]}"; do
    for _ in $(seq 50); do kill -0 "$pid" 2> /dev/null || break; sleep 0.2; done
    kill -9 "$pid" 2> /dev/null || true
  done
  # Job step daemons started by this cluster's slurmd (any not there before the test) outlive it
  # by a few seconds while they report to a controller that is gone.
  for pid in $(pgrep -x slurmstepd || true); do
    case " $steps_before " in *" $pid "*) continue ;; esac
    for _ in $(seq 75); do kill -0 "$pid" 2> /dev/null || break; sleep 0.2; done
    kill -9 "$pid" 2> /dev/null || true
  done
  if [ "$status" != 0 ]; then
    echo "--- logs of the failed run ($T) ---"
    tail -n 20 "$T"/log/* "$T"/job*/logs/* 2> /dev/null || true
  else
    rm -rf "$T"
  fi
  exit "$status"
}
trap stop_daemons EXIT

fail() {
  echo "FAILED: $*" >&2
  exit 1
}

# Two free TCP ports for slurmctld and slurmd, below the kernel's ephemeral range: a port in that
# range can become the local end of any other test's outgoing connection between this check and the
# daemon's bind (one CI run lost its 20 minutes so: slurmctld could not bind and every sinfo waited
# for it). Free means a bind succeeds, which is what the daemons will do.
free_ports() {
  python3 - "$(cut -f1 /proc/sys/net/ipv4/ip_local_port_range)" << 'PY'
import random, socket, sys
ephemeral_low = int(sys.argv[1])
start = random.randrange(10000, max(10001, ephemeral_low - 2000))
found = []
for port in range(start, ephemeral_low):
    with socket.socket() as probe:
        try:
            probe.bind(("", port))
        except OSError:
            continue
    found.append(port)
    if len(found) == 2:
        break
print(*found)
PY
}
host=$(hostname -s)
mkdir -p "$T/munge" "$T/state" "$T/spool" "$T/log"
chmod 700 "$T/munge"
head -c 1024 /dev/urandom > "$T/munge/munge.key"
chmod 400 "$T/munge/munge.key"
# The slurm.conf of a cluster whose daemons listen on the two ports given.
write_conf() {
  cat > "$T/slurm.conf" << EOF
ClusterName=lmktest
SlurmctldHost=$host(127.0.0.1)
SlurmUser=root
SlurmdUser=root
SlurmctldPort=$1
SlurmdPort=$2
AuthType=auth/munge
AuthInfo=socket=$T/munge/munge.sock
CredType=cred/munge
StateSaveLocation=$T/state
SlurmdSpoolDir=$T/spool
SlurmctldPidFile=$T/slurmctld.pid
SlurmdPidFile=$T/slurmd.pid
SlurmctldLogFile=$T/log/slurmctld.log
SlurmdLogFile=$T/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SchedulerType=sched/builtin
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
MpiDefault=none
ReturnToService=2
MinJobAge=3600
JobCompType=jobcomp/none
AccountingStorageType=accounting_storage/none
JobAcctGatherType=jobacct_gather/none
NodeName=$host NodeAddr=127.0.0.1 CPUs=$(nproc) State=UNKNOWN
PartitionName=lmk Nodes=$host Default=YES MaxTime=INFINITE State=UP
EOF
}
export SLURM_CONF="$T/slurm.conf"
# The whole test's own limit, under ctest's 1200 s, so that a stuck cluster fails here with its
# logs rather than being killed silently. A passing run takes about a minute.
give_up_at=$((SECONDS + 1000))

munged --foreground --force --socket="$T/munge/munge.sock" --key-file="$T/munge/munge.key" \
  --pid-file="$T/munge/munged.pid" --log-file="$T/log/munged.log" --seed-file="$T/munge/seed" &
pids+=($!)
for _ in $(seq 50); do [ -S "$T/munge/munge.sock" ] && break; sleep 0.2; done
[ -S "$T/munge/munge.sock" ] || fail "munged did not start"

# Starts slurmctld and slurmd on two free ports and waits until the node is idle, for at most a
# minute; returns 1 as soon as either daemon has exited, e.g. because a port was taken after all.
start_cluster() {
  read -r ctld_port slurmd_port <<< "$(free_ports)"
  [ -n "$slurmd_port" ] || fail "no two free ports below the ephemeral range"
  write_conf "$ctld_port" "$slurmd_port"
  slurmctld -D -f "$SLURM_CONF" > "$T/log/slurmctld.out" 2>&1 &
  local ctld_pid=$!
  slurmd -D -f "$SLURM_CONF" > "$T/log/slurmd.out" 2>&1 &
  local slurmd_pid=$!
  pids+=("$ctld_pid" "$slurmd_pid")
  local deadline=$((SECONDS + 60))
  while [ "$SECONDS" -lt "$deadline" ]; do
    kill -0 "$ctld_pid" 2> /dev/null && kill -0 "$slurmd_pid" 2> /dev/null || break
    [ "$(timeout 15 sinfo -h -o %T 2> /dev/null)" = idle ] && return 0
    sleep 0.2
  done
  echo "the cluster on ports $ctld_port and $slurmd_port did not come up:"
  tail -n 5 "$T"/log/slurmctld.out "$T"/log/slurmd.out "$T"/log/slurm*.log 2> /dev/null || true
  kill "$ctld_pid" "$slurmd_pid" 2> /dev/null || true
  wait "$ctld_pid" "$slurmd_pid" 2> /dev/null || true
  pids=("${pids[@]:0:${#pids[@]}-2}")
  return 1
}
started=false
for attempt in 1 2 3; do
  if start_cluster; then
    started=true
    break
  fi
  echo "attempt $attempt of 3 failed; trying two other ports"
done
$started || fail "the node did not come up in 3 attempts"
echo "slurm: one node '$host', controller on port $ctld_port, in $T"

# Waits until every job named is no longer pending or running; prints each one's state.
wait_jobs() {
  local jobs
  jobs=$(echo "$@" | tr ' ' ,)
  while [ -n "$(timeout 30 squeue -h -j "$jobs" -t PENDING,RUNNING,CONFIGURING 2> /dev/null)" ]; do
    [ "$SECONDS" -lt "$give_up_at" ] || fail "jobs $* still queued after $SECONDS s of the test"
    # A job whose dependency can never be satisfied stays pending for ever: that is its end.
    if timeout 30 squeue -h -j "$jobs" -o %r | grep -q DependencyNeverSatisfied; then break; fi
    sleep 1
  done
}
state_of() { scontrol show job "$1" | sed -n 's/.*JobState=\([A-Z_]*\).*/\1/p' | head -n 1; }

# 1. The whole chain on a small preset against one machine.
TYPES=simple/three_balls,simple/bowl_and_cup,cluttered/spray_with_clutter
"$LMK" slurm eval --dir "$T/jobA" --tasks 4 --cpus-per-task 1 --time 00:20:00 --submit \
  -- --preset paper --seeds 2 --types "$TYPES"
read -r evaluation merge < "$T/jobA/last-submission"
wait_jobs "${evaluation%%;*}" "${merge%%;*}"
[ "$(state_of "${merge%%;*}")" = COMPLETED ] || fail "the merge job ended $(state_of "${merge%%;*}")"
for log in "$T"/jobA/logs/gen-*_*.out; do
  grep -q "of the dataset's scenes are this shard's" "$log" || fail "$log: $(cat "$log")"
done
"$LMK" eval --preset paper --seeds 2 --types "$TYPES" --cache "$T/local" \
  --json "$T/single.json" > "$T/single.txt"
cmp "$T/jobA/table.txt" "$T/single.txt" || fail "the merged table differs from one machine's"
cmp "$T/jobA/evaluation.json" "$T/single.json" || fail "the merged JSON differs from one machine's"
[ -f "$T/jobA/report/report.html" ] || fail "the merge wrote no report"
echo "1. the merged table and JSON equal one machine's, byte for byte:"
cat "$T/single.txt"

# 2. A task cancelled before it ran, then resubmitted alone.
"$LMK" slurm eval --dir "$T/jobB" --tasks 4 --cpus-per-task 1 -- --dataset "$T/jobA/dataset"
held=$(sbatch --parsable --hold "$T/jobB/eval.sbatch")
held=${held%%;*}
scancel "${held}_3"
scontrol release "$held"
wait_jobs "$held"
merge=$(sbatch --parsable "$T/jobB/merge.sbatch")
merge=${merge%%;*}
wait_jobs "$merge"
[ "$(state_of "$merge")" = FAILED ] || fail "a merge without task 3 ended $(state_of "$merge")"
message=$(grep "merge: " "$T/jobB/logs/merge-$merge.out") || fail "no merge message"
echo "2. without task 3: $message"
missing=$(echo "$message" | sed -n 's/.*merge: \([0-9]*\) of [0-9]* pairs are not in the cache.*/\1/p')
[ -n "$missing" ] && [ "$missing" -gt 0 ] || fail "the merge named no missing pair: $message"
[ ! -f "$T/jobB/table.txt" ] || fail "a failed merge left a table"
bash "$T/jobB/submit.sh" 3
read -r evaluation merge < "$T/jobB/last-submission"
wait_jobs "${evaluation%%;*}" "${merge%%;*}"
[ "$(state_of "${merge%%;*}")" = COMPLETED ] || fail "the merge after the resubmission failed"
resubmitted=$(ls "$T"/jobB/logs/eval-"${evaluation%%;*}"_*.out)
[ "$(echo "$resubmitted" | wc -l)" = 1 ] || fail "the resubmission ran more than task 3: $resubmitted"
grep -q "($missing searched, 0 from the cache)" "$resubmitted" ||
  fail "task 3 did not compute exactly the $missing missing pairs: $(cat "$resubmitted")"
cmp "$T/jobB/table.txt" "$T/single.txt" || fail "the table after the resubmission differs"
echo "   resubmitted alone, task 3 computed those $missing pairs; the merged table equals one machine's"
echo "PASSED"
