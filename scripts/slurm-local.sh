#!/usr/bin/env bash
# A single-node Slurm cluster on localhost, for the farm tests and for trying
# the pipeline scripts: munged (as user munge, with its own key), slurmctld
# and slurmd, all state, logs, sockets and pid files in one folder. No
# systemd: the daemons daemonize and are stopped by their pid files.
#
#   scripts/slurm-local.sh start [DIR]   # prints: export SLURM_CONF=DIR/slurm.conf
#   scripts/slurm-local.sh stop  [DIR]   # stops the daemons started in DIR
#
# DIR defaults to $WEFT_SLURM_DIR, else /tmp/weft-slurm. Needs root (the
# daemons run as root and munge) and the packages slurmctld slurmd
# slurm-client munge (scripts/install-deps.sh). A start that cannot bring the
# node up exits 1 with the reason and the daemons' last log lines.
set -euo pipefail

cmd=${1:-}
dir=${2:-${WEFT_SLURM_DIR:-/tmp/weft-slurm}}

die() {
  echo "slurm-local: error: $*" >&2
  exit 1
}

free_port() {
  python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])'
}

write_conf() {
  local host=$1 cpus=$2
  cat >"$dir/slurm.conf" <<CONF
ClusterName=weftlocal
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$(free_port)
SlurmdPort=$(free_port)
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$dir/munge/munge.socket
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/log/slurmctld.log
SlurmdLogFile=$dir/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
SchedulerType=sched/builtin
MpiDefault=none
ReturnToService=2
MaxArraySize=100000
MaxJobCount=200000
MinJobAge=30
SlurmdTimeout=30
InactiveLimit=0
KillWait=5
NodeName=$host NodeAddr=127.0.0.1 CPUs=$cpus State=UNKNOWN
PartitionName=local Nodes=ALL Default=YES MaxTime=INFINITE State=UP
CONF
}

start_munge() {
  id munge >/dev/null 2>&1 || die "no user 'munge' (install the munge package)"
  mkdir -p "$dir/munge"
  runuser -u munge -- test -x "$dir" || die "user munge cannot enter $dir (a parent folder is private; use a folder under a world-readable one)"
  dd if=/dev/urandom of="$dir/munge/munge.key" bs=1024 count=1 status=none
  chown -R munge:munge "$dir/munge"
  chmod 0700 "$dir/munge"
  chmod 0400 "$dir/munge/munge.key"
  runuser -u munge -- munged --force --key-file="$dir/munge/munge.key" --socket="$dir/munge/munge.socket" \
    --pid-file="$dir/munge/munged.pid" --log-file="$dir/munge/munged.log" --seed-file="$dir/munge/munged.seed" \
    || die "munged did not start: $(tail -n 3 "$dir/munge/munged.log" 2>/dev/null | tr '\n' ' ')"
  munge -S "$dir/munge/munge.socket" -n </dev/null | unmunge -S "$dir/munge/munge.socket" >/dev/null \
    || die "munged does not answer on $dir/munge/munge.socket"
}

wait_for_node() {
  local host=$1
  for _ in $(seq 1 60); do
    state=$(SLURM_CONF="$dir/slurm.conf" sinfo -h -n "$host" -o %T 2>/dev/null || true)
    case "$state" in idle*|mixed*|allocated*) return 0 ;; esac
    sleep 0.5
  done
  die "node $host did not come up (state '${state:-none}'); slurmctld: $(tail -n 3 "$dir/log/slurmctld.log" 2>/dev/null | tr '\n' ' ') slurmd: $(tail -n 3 "$dir/log/slurmd.log" 2>/dev/null | tr '\n' ' ')"
}

start() {
  [ "$(id -u)" -eq 0 ] || die "run as root (the local cluster's daemons run as root and munge)"
  for tool in munged slurmctld slurmd sinfo sbatch; do
    command -v "$tool" >/dev/null || die "$tool not found (scripts/install-deps.sh installs slurmctld slurmd slurm-client munge)"
  done
  [ ! -f "$dir/slurmctld.pid" ] || die "a cluster already runs in $dir (stop it first)"
  local host cpus
  host=$(hostname -s)
  cpus=$(nproc)
  mkdir -p "$dir"/{state,spool,log}
  chmod 0755 "$dir"
  write_conf "$host" "$cpus"
  start_munge
  slurmctld -c -f "$dir/slurm.conf" || die "slurmctld did not start: $(tail -n 3 "$dir/log/slurmctld.log" 2>/dev/null | tr '\n' ' ')"
  slurmd -f "$dir/slurm.conf" -N "$host" || die "slurmd did not start: $(tail -n 3 "$dir/log/slurmd.log" 2>/dev/null | tr '\n' ' ')"
  wait_for_node "$host"
  echo "export SLURM_CONF=$dir/slurm.conf"
}

stop_pidfile() {
  local file=$1 pid
  [ -f "$file" ] || return 0
  pid=$(cat "$file")
  if [ -n "$pid" ] && kill -0 "$pid" 2>/dev/null; then
    kill "$pid"
    for _ in $(seq 1 50); do
      kill -0 "$pid" 2>/dev/null || break
      sleep 0.1
    done
    kill -0 "$pid" 2>/dev/null && kill -9 "$pid"
  fi
  rm -f "$file"
}

stop() {
  [ -d "$dir" ] || die "no cluster folder $dir"
  stop_pidfile "$dir/slurmd.pid"
  stop_pidfile "$dir/slurmctld.pid"
  stop_pidfile "$dir/munge/munged.pid"
  echo "slurm-local: stopped the cluster in $dir"
}

case "$cmd" in
  start) start ;;
  stop) stop ;;
  *) die "usage: $0 start|stop [DIR]" ;;
esac
