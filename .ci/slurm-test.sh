#!/usr/bin/env bash
# A sharded study on a real single-node Slurm (Debian's slurm-wlm and munge on localhost):
#  1. a 4-task job array and its dependent merge (examples/slurm) give the same cells.csv,
#     meta.json and plots, byte for byte, as one unsharded run on this machine;
#  2. the same with one array task killed mid-run and requeued by `scontrol requeue`: the task
#     resumes from its journal and the merge is still identical.
# ROCKING names a built binary (default: built here with the test profile).
# Installs the packages with apt-get when missing (as root, or through sudo; `--install` does only
# that); the daemons' state lives in a temporary directory and they are stopped on exit.
set -euo pipefail
cd "$(dirname "$0")/.."
repo=$PWD
start=$SECONDS
SUDO=
[ "$(id -u)" = 0 ] || SUDO=sudo

if ! command -v slurmctld >/dev/null || ! command -v munged >/dev/null; then
    echo "== apt-get install slurm-wlm munge"
    $SUDO apt-get update -qq
    $SUDO env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq slurm-wlm munge >/dev/null
fi
# `--install`: only the packages (.ci/run starts this in the background while Rust compiles).
[ "${1:-}" = --install ] && exit 0

if [ -z "${ROCKING:-}" ]; then
    echo "== build rocking (test profile, as cargo test builds it)"
    cargo build --profile test -p rocking-cli --bin rocking --quiet
    ROCKING=$repo/target/debug/rocking
fi
export ROCKING

work=$(mktemp -d /tmp/rocking-slurm.XXXXXX)
chmod 755 "$work"
pids=()
started_munged=
cleanup() {
    local rc=$?
    set +e
    if [ -n "${SLURM_CONF:-}" ] && [ -f "$work/slurmctld.pid" ]; then
        scancel --quiet --user="$(id -un)" 2>/dev/null
    fi
    for p in "$work/slurmd.pid" "$work/slurmctld.pid"; do
        [ -f "$p" ] && $SUDO kill "$(cat "$p")" 2>/dev/null
    done
    if [ -n "$started_munged" ] && [ -f /run/munge/munged.pid ]; then
        $SUDO kill "$(cat /run/munge/munged.pid)" 2>/dev/null
    fi
    if [ $rc -ne 0 ]; then
        echo "FAILED (exit $rc); logs:" >&2
        for f in "$work"/*.log "$work"/run/*.out; do
            [ -f "$f" ] && { echo "-- $f" && tail -n 15 "$f"; } >&2
        done
    fi
    sleep 1
    $SUDO rm -rf "$work"
    exit $rc
}
trap cleanup EXIT

echo "== munged"
if ! munge -n 2>/dev/null | unmunge >/dev/null 2>&1; then
    $SUDO mkdir -p /run/munge
    $SUDO chown munge:munge /run/munge
    $SUDO runuser -u munge -- /usr/sbin/munged
    started_munged=1
fi
munge -n | unmunge | grep -q 'STATUS: *Success'

echo "== slurm.conf (one node: $(hostname -s), $(nproc) CPUs)"
host=$(hostname -s)
mkdir -p "$work/state" "$work/spool" "$work/run"
export SLURM_CONF=$work/slurm.conf
cat >"$SLURM_CONF" <<EOF
ClusterName=rockingci
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=16817
SlurmdPort=16818
SlurmUser=root
AuthType=auth/munge
# A killed job's credential is revoked for this long, and a requeued job waits as long
# (default 120 s).
AuthInfo=cred_expire=5
CredType=cred/munge
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/slurmctld.pid
SlurmdPidFile=$work/slurmd.pid
SlurmctldLogFile=$work/slurmctld.log
SlurmdLogFile=$work/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SchedulerType=sched/backfill
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
MpiDefault=none
ReturnToService=2
JobRequeue=1
MinJobAge=600
SchedulerParameters=bf_interval=1
NodeName=$host NodeAddr=127.0.0.1 CPUs=$(nproc) State=UNKNOWN
PartitionName=ci Nodes=$host Default=YES MaxTime=INFINITE State=UP
EOF

echo "== slurmctld, slurmd"
$SUDO env SLURM_CONF="$SLURM_CONF" slurmctld -i
$SUDO env SLURM_CONF="$SLURM_CONF" slurmd
for _ in $(seq 60); do
    state=$(sinfo -h -o %T 2>/dev/null || true)
    [ "$state" = idle ] && break
    sleep 1
done
[ "$state" = idle ] || { echo "the node is not idle: '$state'" >&2; exit 1; }
sinfo

# The study: the Fig-8 spectrum on a 160 x 180 grid (28800 cells): each of the 4 tasks runs for
# about 5 s, long enough to be killed mid-run.
scene=$repo/scenes/spectra/fig8.toml
axes=(--axis excitation.omega_p_over_p=1:10:160 --axis excitation.amplitude=1:20:180)
files=(cells.csv meta.json spectrum.png spectrum.svg)

echo "== one machine: rocking spectrum $scene ${axes[*]}"
"$ROCKING" spectrum "$scene" "${axes[@]}" --quiet --out "$work/whole"

job_field() { scontrol show job "$1" 2>/dev/null | tr ' ' '\n' | sed -n "s/^$2=//p" | head -n1; }

# Waits until job $1 (the merge) has ended; fails after $2 seconds.
wait_ended() {
    local state
    for _ in $(seq "$2"); do
        state=$(job_field "$1" JobState)
        case $state in
        COMPLETED | FAILED | CANCELLED | TIMEOUT | NODE_FAIL | OUT_OF_MEMORY) return 0 ;;
        esac
        sleep 1
    done
    echo "job $1 did not end in $2 s (state $state)" >&2
    squeue >&2
    return 1
}

same_as_whole() {
    for f in "${files[@]}"; do
        cmp "$work/whole/$f" "$1/merged/$f"
    done
    echo "  merged == one machine, byte for byte: ${files[*]}"
}

cd "$work/run"
submit() { "$repo/examples/slurm/submit.sh" 4 "$1" spectrum "$scene" "${axes[@]}"; }

echo "== job array of 4 shards and a dependent merge"
read -r array merge < <(submit "$work/a")
echo "  array job $array, merge job $merge"
wait_ended "$merge" 180
cat "rocking-merge-$merge.out"
[ "$(job_field "$merge" JobState)" = COMPLETED ] || { scontrol show job "$merge"; exit 1; }
same_as_whole "$work/a"

echo "== again, with task 2 killed mid-run and requeued"
read -r array merge < <(submit "$work/b")
echo "  array job $array, merge job $merge"
journal=$work/b/shard-2/cells.journal
for _ in $(seq 600); do
    [ -f "$journal" ] && [ "$(wc -l <"$journal")" -ge 20 ] && break
    sleep 0.2
done
[ "$(job_field "${array}_2" JobState)" = RUNNING ] || { echo "task 2 is not running" >&2; exit 1; }
before=$(($(wc -l <"$journal") - 1))
# Slurm kills the running task (SIGTERM, then SIGKILL) and puts it back in the queue, as on
# preemption or a node failure. (A task killed outside Slurm ends FAILED, and Slurm 22.05 then
# keeps the merge's afterok dependency unsatisfiable even after a requeue.)
scontrol requeue "${array}_2"
echo "  task ${array}_2 killed by scontrol requeue with $before cells journaled: $(job_field "${array}_2" JobState), restarts $(job_field "${array}_2" Restarts)"
wait_ended "$merge" 180
cat "rocking-shard-${array}_2.out"
grep -Eq "[1-9][0-9]* resumed" "rocking-shard-${array}_2.out"
cat "rocking-merge-$merge.out"
[ "$(job_field "$merge" JobState)" = COMPLETED ] || { scontrol show job "$merge"; exit 1; }
same_as_whole "$work/b"
echo "== Slurm test passed in $((SECONDS - start)) s"
