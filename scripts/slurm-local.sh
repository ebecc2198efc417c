#!/usr/bin/env bash
# A one-node Slurm cluster on this machine, for `neopipe batch`'s tests and measurements
# (docs/cluster.md): Debian's slurm-wlm and munge, installed through scripts/setup.sh --slurm.
#
#   scripts/slurm-local.sh start   munge key, munged, a slurm.conf naming this host with its real CPU
#                                  count and memory (slurmd -C), slurmctld, slurmd; waits (bounded)
#                                  until the node takes jobs. Running already: checks it, and is done.
#   scripts/slurm-local.sh stop    cancels every job, stops slurmd, slurmctld and munged (by their
#                                  pid files), and waits until none is left.
#   scripts/slurm-local.sh status  whether the daemons run and what sinfo says.
#
# Needs root (or sudo). Every wait is bounded: a daemon that does not come up fails the script with
# the tail of its log, never hangs it. Jobs run as the submitting user, root included (Slurm allows
# root's jobs; SlurmUser is root here so the daemons need no accounts or spool permissions).
set -euo pipefail
cd "$(dirname "$0")/.."

state=/var/lib/neopipe-slurm  # this cluster's own files: config, spool, state, logs, pid files
conf_dir=/etc/slurm
conf=$conf_dir/slurm.conf
munge_socket_dir=/run/munge
wait_seconds=${SLURM_LOCAL_WAIT:-30}

sudo=""
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "slurm-local: needs root or sudo" >&2; exit 1; }
  sudo=sudo
fi

say() { echo "slurm-local: $*"; }
fail() { echo "slurm-local: error: $*" >&2; exit 1; }

pid_alive() {  # pid file -> true if its process runs
  [ -f "$1" ] && $sudo kill -0 "$($sudo cat "$1")" 2>/dev/null
}

wait_for() {  # seconds, description, command...: polls every 0.2 s
  local seconds=$1 what=$2
  shift 2
  local deadline=$((SECONDS + seconds))
  until "$@" >/dev/null 2>&1; do
    [ $SECONDS -lt $deadline ] || return 1
    sleep 0.2
  done
}

stop_pid_file() {  # pid file, name: SIGTERM, then SIGKILL after 10 s
  local file=$1 name=$2
  [ -f "$file" ] || return 0
  local pid
  pid=$($sudo cat "$file")
  if $sudo kill -0 "$pid" 2>/dev/null; then
    $sudo kill -TERM "$pid" 2>/dev/null || true
    if ! wait_for 10 "$name to stop" bash -c "! kill -0 $pid"; then
      say "$name (pid $pid) ignored SIGTERM for 10 s: killing it"
      $sudo kill -KILL "$pid" 2>/dev/null || true
      wait_for 5 "$name to die" bash -c "! kill -0 $pid" || fail "$name (pid $pid) would not stop"
    fi
  fi
  $sudo rm -f "$file"
}

node_ready() {  # the node is idle or mixed/allocated: it takes jobs
  local s
  s=$(timeout 5 sinfo -h -N -o '%T' 2>/dev/null | head -1)
  case "$s" in idle*|mixed*|allocated*|completing*) return 0 ;; *) return 1 ;; esac
}

write_config() {
  local node
  # slurmd -C: this host's name, CPUs, sockets, cores, threads and RealMemory, as slurm.conf wants them.
  node=$(slurmd -C | head -1)
  [[ "$node" == NodeName=* ]] || fail "slurmd -C did not describe this node: $node"
  local host=${node#NodeName=}
  host=${host%% *}
  $sudo mkdir -p "$conf_dir" "$state"/{ctld,spool,log}
  $sudo tee "$conf" >/dev/null <<CONF
# Written by neopipe's scripts/slurm-local.sh: a one-node cluster on $host. Overwritten by each start.
ClusterName=neopipe-local
SlurmctldHost=$host
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
StateSaveLocation=$state/ctld
SlurmdSpoolDir=$state/spool
SlurmctldPidFile=$state/slurmctld.pid
SlurmdPidFile=$state/slurmd.pid
SlurmctldLogFile=$state/log/slurmctld.log
SlurmdLogFile=$state/log/slurmd.log
# Containers and CI runners rarely delegate cgroups: track processes by their parent, bind nothing.
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
MpiDefault=none
SchedulerType=sched/backfill
# One CPU is the unit handed out: array tasks of one CPU each fill the node.
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
ReturnToService=2
SlurmdTimeout=30
KillWait=5
MinJobAge=60
MaxArraySize=100001
$node State=UNKNOWN
PartitionName=local Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
  # cgroup.conf is read even with the plugins above off; an empty one keeps slurmd from guessing.
  [ -f "$conf_dir/cgroup.conf" ] || echo "CgroupPlugin=autodetect" | $sudo tee "$conf_dir/cgroup.conf" >/dev/null
}

start() {
  ./scripts/setup.sh --slurm
  command -v slurmctld >/dev/null || fail "slurmctld not installed after scripts/setup.sh --slurm"

  # munge: a key (the package makes one; make one if it did not), its socket folder, the daemon.
  if ! $sudo test -s /etc/munge/munge.key; then
    say "creating a munge key"
    $sudo mungekey --create --force
    $sudo chown munge:munge /etc/munge/munge.key
    $sudo chmod 0400 /etc/munge/munge.key
  fi
  $sudo mkdir -p "$munge_socket_dir"
  $sudo chown munge:munge "$munge_socket_dir"
  $sudo chmod 0755 "$munge_socket_dir"
  if ! timeout 5 munge -n </dev/null 2>/dev/null | timeout 5 unmunge >/dev/null 2>&1; then
    say "starting munged"
    $sudo runuser -u munge -- /usr/sbin/munged
    wait_for "$wait_seconds" munged bash -c 'munge -n </dev/null | unmunge' || fail "munged did not answer in ${wait_seconds} s"
  fi

  if pid_alive "$state/slurmctld.pid" && pid_alive "$state/slurmd.pid" && node_ready; then
    say "already running: $(timeout 5 sinfo -h -N -o '%N %T %c CPUs %m MB' | head -1)"
    return 0
  fi
  # Daemons this script did not start (a distribution's service, another cluster) hold the ports.
  for d in slurmctld slurmd; do
    for pid in $(pgrep -x "$d" || true); do
      if [ "$pid" != "$($sudo cat "$state/$d.pid" 2>/dev/null || true)" ] &&
         ! wait_for 10 "$d $pid to end" bash -c "! kill -0 $pid"; then  # one of ours still shutting down
        fail "a $d not started by this script runs (pid $pid; systemctl stop $d?): stop it first"
      fi
    done
  done
  # Half a cluster (one daemon left from a crash) is stopped first, so the config is fresh.
  stop_pid_file "$state/slurmd.pid" slurmd
  stop_pid_file "$state/slurmctld.pid" slurmctld
  write_config
  say "starting slurmctld"
  $sudo slurmctld -i  # -i: ignore (discard) the state of an earlier run that does not fit the new config
  wait_for "$wait_seconds" slurmctld timeout 5 scontrol ping || {
    $sudo tail -5 "$state/log/slurmctld.log" >&2 || true
    fail "slurmctld did not answer scontrol ping in ${wait_seconds} s ($state/log/slurmctld.log)"
  }
  say "starting slurmd"
  $sudo slurmd
  if ! wait_for "$wait_seconds" "the node" node_ready; then
    # A node that was down (an earlier crash) stays down until told otherwise.
    timeout 5 scontrol update nodename="$(hostname -s)" state=resume >/dev/null 2>&1 || true
    wait_for 10 "the node" node_ready || {
      $sudo tail -5 "$state/log/slurmd.log" >&2 || true
      fail "the node did not become idle in ${wait_seconds} s: $(timeout 5 sinfo -h -N -o '%N %T %E' 2>&1)"
    }
  fi
  say "running: $(timeout 5 sinfo -h -N -o '%N %T %c CPUs %m MB, partition %P' | head -1)"
}

stop() {
  if command -v scancel >/dev/null && pid_alive "$state/slurmctld.pid"; then
    timeout 10 scancel --full --quiet --user="$(id -un)" 2>/dev/null || true
    timeout 10 scancel --full --quiet --state=PENDING 2>/dev/null || true
    timeout 10 scancel --full --quiet 2>/dev/null || true
    # Give running steps a moment to end before their slurmd goes away.
    wait_for 10 "jobs to end" bash -c '[ -z "$(timeout 5 squeue -h 2>/dev/null)" ]' || true
  fi
  stop_pid_file "$state/slurmd.pid" slurmd
  stop_pid_file "$state/slurmctld.pid" slurmctld
  # Steps whose slurmd is gone: their slurmstepd ends with them; end what is left of them.
  local pids
  pids=$(pgrep -x slurmstepd || true)
  if [ -n "$pids" ]; then
    $sudo kill -TERM $pids 2>/dev/null || true
    wait_for 10 slurmstepd bash -c "! pgrep -x slurmstepd" || $sudo kill -KILL $pids 2>/dev/null || true
  fi
  local munged_pid_file=/run/munge/munged.pid
  [ -f "$munged_pid_file" ] || munged_pid_file=/var/run/munge/munged.pid
  stop_pid_file "$munged_pid_file" munged
  for d in slurmctld slurmd munged slurmstepd; do
    if pgrep -x "$d" >/dev/null; then fail "$d still runs (pids $(pgrep -x "$d" | tr '\n' ' '))"; fi
  done
  say "stopped: no slurmctld, slurmd or munged left"
}

status() {
  for d in munged slurmctld slurmd; do
    if pgrep -x "$d" >/dev/null; then say "$d: running"; else say "$d: not running"; fi
  done
  timeout 5 sinfo -N 2>/dev/null || true
}

case "${1:-}" in
  start) start ;;
  stop) stop ;;
  status) status ;;
  *) echo "usage: scripts/slurm-local.sh start|stop|status" >&2; exit 2 ;;
esac
