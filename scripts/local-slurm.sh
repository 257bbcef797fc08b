#!/usr/bin/env bash
# A single-node Slurm cluster on this machine, for trying and testing the cohort workflow's Slurm profile
# (workflow/profiles/slurm/, docs/cohorts.md) without a real cluster.
#
#   scripts/local-slurm.sh start   # munged, slurmctld and slurmd; prints the line that points Slurm's commands at it
#   scripts/local-slurm.sh stop    # stops the three daemons this script started
#   scripts/local-slurm.sh env     # prints: export SLURM_CONF=...
#
# Everything lives in one folder (FACEHEX_SLURM_DIR, default /tmp/facehex-slurm): its own munge key and socket, its own
# slurm.conf on its own ports, logs and state; nothing under /etc is read or changed, and a system Slurm or munge keeps
# running untouched. Slurm's commands (sbatch, squeue, ...) find this cluster through SLURM_CONF. Needs root (slurmd
# starts jobs as their users) and the Debian packages slurm-wlm and munge (scripts/install-deps.sh).
# Exit codes: 0 done, 1 error (one line on stderr), 77 the cluster cannot run here (no root, or a missing package).
set -euo pipefail

DIR=${FACEHEX_SLURM_DIR:-/tmp/facehex-slurm}
CTLD_PORT=${FACEHEX_SLURMCTLD_PORT:-16817}
SLURMD_PORT=${FACEHEX_SLURMD_PORT:-16818}
NODE=facehex-local

die() { echo "local-slurm: $*" >&2; exit 1; }
cannot_run() { echo "local-slurm: cannot start a Slurm cluster here: $*" >&2; exit 77; }

write_config() {
  local cpus mem_mb
  cpus=$(nproc)
  # Memory is a consumable resource, so a job's --mem is honoured; a share is left to the daemons and the system.
  mem_mb=$(awk '/^MemTotal:/ {print int($2 / 1024 * 0.9)}' /proc/meminfo)
  cat > "$DIR/slurm.conf" <<EOF
ClusterName=facehex-local
SlurmctldHost=localhost(127.0.0.1)
SlurmctldPort=$CTLD_PORT
SlurmdPort=$SLURMD_PORT
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$DIR/munge.socket
StateSaveLocation=$DIR/state
SlurmdSpoolDir=$DIR/spool/%n
SlurmctldPidFile=$DIR/slurmctld.pid
SlurmdPidFile=$DIR/slurmd.pid
SlurmctldLogFile=$DIR/slurmctld.log
SlurmdLogFile=$DIR/slurmd.log
# No cgroups: the node may itself be a container.
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
MpiDefault=none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core_Memory
ReturnToService=2
# Finished jobs stay visible to scontrol long enough for the workflow's status check.
MinJobAge=600
NodeName=$NODE NodeHostname=$(hostname) NodeAddr=127.0.0.1 CPUs=$cpus RealMemory=$mem_mb State=UNKNOWN
PartitionName=main Nodes=$NODE Default=YES MaxTime=INFINITE State=UP
EOF
}

pid_alive() { [ -f "$1" ] && kill -0 "$(cat "$1")" 2>/dev/null; }

start() {
  [ "$(id -u)" -eq 0 ] || cannot_run "it needs root (slurmd starts jobs as their users)"
  for exe in munged slurmctld slurmd sbatch scontrol; do
    command -v "$exe" > /dev/null || cannot_run "$exe is missing (install slurm-wlm and munge: scripts/install-deps.sh)"
  done
  if pid_alive "$DIR/slurmctld.pid" && pid_alive "$DIR/slurmd.pid" && pid_alive "$DIR/munged.pid"; then
    echo "local-slurm: already running in $DIR" >&2
    echo "export SLURM_CONF=$DIR/slurm.conf"
    return 0
  fi
  stop > /dev/null 2>&1 || true
  mkdir -p "$DIR/state" "$DIR/spool"
  chmod 700 "$DIR"
  [ -f "$DIR/munge.key" ] || (umask 077 && dd if=/dev/urandom of="$DIR/munge.key" bs=1024 count=1 status=none)
  # --force: the folder may be under /tmp, which munged would refuse as shared.
  munged --force --key-file="$DIR/munge.key" --socket="$DIR/munge.socket" --pid-file="$DIR/munged.pid" \
    --log-file="$DIR/munged.log" --seed-file="$DIR/munged.seed" || die "munged did not start (see $DIR/munged.log)"
  write_config
  export SLURM_CONF=$DIR/slurm.conf
  slurmctld -f "$SLURM_CONF" || die "slurmctld did not start (see $DIR/slurmctld.log)"
  slurmd -f "$SLURM_CONF" -N "$NODE" || die "slurmd did not start (see $DIR/slurmd.log)"
  for _ in $(seq 1 60); do
    if sinfo -h -n "$NODE" -o %t 2>/dev/null | grep -qx idle; then
      echo "local-slurm: node $NODE is up ($(nproc) CPUs); logs in $DIR" >&2
      echo "export SLURM_CONF=$SLURM_CONF"
      return 0
    fi
    sleep 0.5
  done
  die "the node did not come up within 30 s (see $DIR/slurmctld.log and $DIR/slurmd.log)"
}

stop() {
  local stopped=0
  for daemon in slurmd slurmctld munged; do
    local pidfile="$DIR/$daemon.pid"
    if pid_alive "$pidfile"; then
      local pid
      pid=$(cat "$pidfile")
      kill "$pid"
      for _ in $(seq 1 40); do kill -0 "$pid" 2>/dev/null || break; sleep 0.25; done
      stopped=$((stopped + 1))
    fi
    rm -f "$pidfile"
  done
  echo "local-slurm: stopped $stopped daemons" >&2
}

case "${1:-}" in
  start) start ;;
  stop) stop ;;
  env) echo "export SLURM_CONF=$DIR/slurm.conf" ;;
  *) echo "usage: $0 start|stop|env" >&2; exit 2 ;;
esac
