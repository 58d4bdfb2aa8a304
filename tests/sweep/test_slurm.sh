#!/usr/bin/env bash
# `sessile sweep submit` on a real single-node Slurm cluster started here
# (docs/sweep.md, "Testing with Slurm"): munged, slurmctld and slurmd from
# Debian's slurm-wlm and munge (tools/install.sh installs them, enabling no
# daemon), a generated slurm.conf with proctrack/linuxproc, every key, socket,
# spool, state and log under the test's temporary folder, ports of its own.
# A 6-point sweep (2 noise values x 3 seeds of `sphere`) submitted as one job
# array must give the local engine's bytes; a task cancelled while it runs
# (scancel) must resume on resubmission to the same bytes.  Every daemon is
# stopped by its pid.  Needs root; FAILS (never skips) when Slurm cannot start.
set -u
S="$1"
. "$(dirname "$0")/../common/harness.sh"
. "$(dirname "$0")/sweep_common.sh"
PIDS=()
stop_daemons() {
  # our cluster's jobs first (their slurmstepd would outlive slurmd), then the daemons
  [ -e "$T/slurm.conf" ] && SLURM_CONF="$T/slurm.conf" timeout 10 scancel -u "$(id -un)" >/dev/null 2>&1
  for p in "${PIDS[@]}"; do kill -TERM "$p" 2>/dev/null; done
  for p in "${PIDS[@]}"; do
    for _ in $(seq 50); do kill -0 "$p" 2>/dev/null || break; sleep 0.1; done
    kill -KILL "$p" 2>/dev/null
  done
  rm -rf "$T"
}
trap stop_daemons EXIT
fatal() { echo "FAIL $*"; fails=$((fails + 1)); finish; exit 1; }

[ "$(id -u)" = 0 ] || fatal "Slurm cannot start: the test starts munged, slurmctld and slurmd as root"
for c in munged slurmctld slurmd sbatch squeue scancel sinfo; do
  command -v "$c" >/dev/null || fatal "Slurm cannot start: '$c' is missing (tools/install.sh installs slurm-wlm and munge)"
done
host=$(hostname -s)
port=$((20000 + RANDOM % 20000))
cpus=$(nproc); [ "$cpus" -gt 2 ] && cpus=2

# --- munge: a key of our own, its socket in $T --------------------------------------
mkdir -p "$T/state" "$T/spool" "$T/munge"
chmod 700 "$T/munge"
head -c 1024 /dev/urandom >"$T/munge/munge.key" && chmod 400 "$T/munge/munge.key"
munged -F --force --socket="$T/munge/munge.sock" --key-file="$T/munge/munge.key" \
  --pid-file="$T/munge/munged.pid" --log-file="$T/munge/munged.log" --seed-file="$T/munge/munge.seed" \
  >"$T/munged.out" 2>&1 &
PIDS+=($!)
for _ in $(seq 1200); do [ -S "$T/munge/munge.sock" ] && break; sleep 0.05; done # at most 60 s
[ -S "$T/munge/munge.sock" ] || fatal "Slurm cannot start: munged did not make its socket: $(tail -3 "$T/munged.out" "$T/munge/munged.log" 2>&1)"

cat >"$T/slurm.conf" <<EOF
ClusterName=sessiletest
SlurmctldHost=$host
SlurmctldPort=$port
SlurmdPort=$((port + 1))
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$T/munge/munge.sock
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
StateSaveLocation=$T/state
SlurmdSpoolDir=$T/spool
SlurmctldPidFile=$T/slurmctld.pid
SlurmdPidFile=$T/slurmd.pid
SlurmctldLogFile=$T/slurmctld.log
SlurmdLogFile=$T/slurmd.log
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
JobAcctGatherType=jobacct_gather/none
MpiDefault=none
ReturnToService=2
KillWait=10
NodeName=$host CPUs=$cpus State=UNKNOWN
PartitionName=debug Nodes=$host Default=YES MaxTime=INFINITE State=UP
EOF
export SLURM_CONF="$T/slurm.conf"
slurmctld -D -f "$T/slurm.conf" >"$T/slurmctld.out" 2>&1 &
PIDS+=($!)
slurmd -D -f "$T/slurm.conf" >"$T/slurmd.out" 2>&1 &
PIDS+=($!)
idle=0
for _ in $(seq 1200); do # at most 120 s: slurmd registers with slurmctld
  [ "$(sinfo -h -o %T 2>/dev/null)" = idle ] && idle=1 && break
  sleep 0.1
done
[ $idle = 1 ] || fatal "Slurm cannot start: the node is not idle: $(sinfo 2>&1 | tail -2) $(tail -3 "$T/slurmctld.log" "$T/slurmd.log" 2>&1)"
check "a single-node Slurm cluster is up (sinfo: idle)" true

# --- the sweep, locally and on Slurm ------------------------------------------------
write_sweep "$T/sweep.json" 200 1
for d in local s1; do "$S" sweep plan "$T/sweep.json" --out "$T/$d" >/dev/null || fatal "sweep plan"; done
"$S" sweep run "$T/local" -j 2 >/dev/null
check "the local engine's reference completes" eval '"$S" sweep status "$T/local" | grep -q "6 points: 6 completed"'

job_of() { sed -n 's/.*job array \([0-9]*\).*/\1/p' "$T/out"; }
wait_job() { # the job's tasks all gone from squeue (at most 120 s)
  for _ in $(seq 1200); do [ -z "$(squeue -h -j "$1" 2>/dev/null)" ] && return 0; sleep 0.1; done; return 1
}

run sweep submit "$T/s1" --max-parallel 2 --time 10
j1=$(job_of)
check "sweep submit: one job array of 6 tasks, its id recorded" eval \
  'rc_is 0 && [ -n "$j1" ] && grep -q "0-5%2" "$T/out" && grep -q "\"$j1\"" "$T/s1/slurm.json"'
check "... the array's tasks run and end" wait_job "$j1"
run sweep status "$T/s1"
check "... status: every point completed" eval 'grep -q "6 points: 6 completed" "$T/out"'
check "... the bytes of the local engine" same "$T/local" "$T/s1"

# --- scancel a running task, resubmit: it resumes to the same bytes --------------------
# A sweep of its own, 2 points of 100 000 sphere iterations (seconds each, a
# checkpoint every 10 000): the 6-point sweep's runs take a fraction of a
# second, too short to be caught running under load.
cat >"$T/long.json" <<EOF2
{"generator": "sphere", "iterations": 100000, "options": ["--no-preview", "--every", "10000"],
 "base": {"level": 5},
 "axes": [{"parameter": "noise", "values": [0.01, 0.03]}],
 "seeds": {"count": 1, "first": 1},
 "metrics": ["checkpoint.iteration"]}
EOF2
for d in local2 s2; do "$S" sweep plan "$T/long.json" --out "$T/$d" >"$T/out" 2>&1 || fatal "sweep plan (long): $(cat "$T/out")"; done
"$S" sweep run "$T/local2" -j 2 >/dev/null
check "the long sweep's local reference completes" eval '"$S" sweep status "$T/local2" | grep -q "2 points: 2 completed"'
run sweep submit "$T/s2" --max-parallel 1
j2=$(job_of)
running=0
for _ in $(seq 2400); do # at most 120 s: scheduled, started, 10 000 iterations done
  if [ -e "$T/s2/runs/0000/checkpoint.bin" ] && squeue -h -r -j "$j2" -o "%i %T" | grep -q "^${j2}_0 RUNNING"; then running=1; break; fi
  sleep 0.05
done
check "task 0 runs (and has checkpointed)" [ $running = 1 ]
run sweep status "$T/s2"
check "status while it runs: 0000 running, Slurm's state beside it" eval 'grep -q "^0000 running (slurm $j2: RUNNING)" "$T/out"'
scancel "${j2}_0"
wait_job "$j2"
run sweep status "$T/s2"
check "scancel: point 0000 interrupted with its state saved, the other completed" eval \
  'grep -q "^0000 interrupted" "$T/out" && grep -q "2 points: 1 completed" "$T/out" && grep -q "\"state\":[[:space:]]*\"interrupted\"" "$T/s2/runs/0000/manifest.json"'
run sweep submit "$T/s2"
j3=$(job_of)
check "resubmission: only the unfinished point (--array=0)" eval 'rc_is 0 && grep -q "(1 points: 0)" "$T/out"'
wait_job "$j3"
run sweep status "$T/s2"
check "... every point completed" eval 'grep -q "2 points: 2 completed" "$T/out"'
check "... point 0000 resumed (starts 2) from its checkpoint" eval \
  'grep -q "\"starts\":[[:space:]]*2" "$T/s2/runs/0000/manifest.json" && grep -q "\"resumed_from_iteration\":[[:space:]]*[1-9]" "$T/s2/runs/0000/manifest.json"'
check "... to the local engine's bytes" same "$T/local2" "$T/s2" 0000 0001
run sweep submit "$T/s2"
check "a third submit has nothing to do" eval 'rc_is 0 && grep -q "nothing to submit" "$T/out"'
finish
