#!/usr/bin/env bash
# A throwaway one-node Slurm cluster on this machine, for testing scripts/farm/gpurt-slurm.sh for real.
# Everything (munge key and socket, slurm.conf, state, spool, logs, pid files) lives in DIR, so it
# leaves /etc/slurm, /etc/munge and /run/munge alone, can run beside a system Slurm, and works on
# a fresh machine and again and again. Needs root (slurmd runs jobs as their user) and the Debian
# packages slurmctld, slurmd, slurm-client and munge, which it does not install.
#
#   tests/farm/slurm-localhost.sh start DIR   # then: . DIR/env; sbatch ...
#   tests/farm/slurm-localhost.sh stop DIR
#
# start exits 2 naming what is missing, 1 (with the daemons' log tails) when the node does not come
# up idle within 60 s; stop cancels the jobs left and ends the daemons by their recorded ids.
set -euo pipefail

usage() { echo "usage: $0 start|stop DIR" >&2; exit 1; }
[ $# -eq 2 ] || usage
action="$1"
case "$action" in start|stop) ;; *) usage ;; esac
[ "$action" = start ] || [ -d "$2" ] || exit 0
mkdir -p "$2"
dir="$(cd "$2" && pwd)"
# slurm.conf has no quoting for paths.
case "$dir" in *[[:space:]]*) echo "$0: $dir: no spaces, please" >&2; exit 1 ;; esac
conf="$dir/slurm.conf"
daemons=(munged slurmctld slurmd)

running() {  # running NAME: the recorded process is alive and still that program (ids get reused)
  local pid
  pid="$(cat "$dir/$1.pid" 2>/dev/null)" || return 1
  [ -n "$pid" ] && [ "$(ps -p "$pid" -o comm= 2>/dev/null)" = "$1" ]
}

stop() {
  # Jobs first: slurmstepd detaches from slurmd, so ending slurmd alone would leave jobs running.
  if running slurmctld; then
    local ids
    mapfile -t ids < <(SLURM_CONF="$conf" squeue -h -o %A 2>/dev/null | sort -u)
    if [ ${#ids[@]} -gt 0 ]; then
      SLURM_CONF="$conf" scancel "${ids[@]}" 2>/dev/null || true
      for _ in $(seq 100); do
        [ -z "$(SLURM_CONF="$conf" squeue -h -o %A 2>/dev/null)" ] && break
        sleep 0.1
      done
    fi
  fi
  # All at once: each takes about 2 s to end on TERM.
  local name alive pids=()
  for name in "${daemons[@]}"; do
    if running "$name"; then pids+=("$(cat "$dir/$name.pid")"); fi
  done
  [ ${#pids[@]} -eq 0 ] || kill -TERM "${pids[@]}" 2>/dev/null || true
  for _ in $(seq 100); do
    alive=0
    for name in "${daemons[@]}"; do running "$name" && alive=1; done
    [ "$alive" -eq 0 ] && break
    sleep 0.1
  done
  for name in "${daemons[@]}"; do
    if running "$name"; then kill -KILL "$(cat "$dir/$name.pid")" 2>/dev/null || true; fi
    rm -f "$dir/$name.pid"
  done
}

fail() {
  echo "$0: $1" >&2
  local name log
  for name in "${daemons[@]}"; do
    # A daemon that dies before it opens its log says why on stderr only.
    log="$dir/log/$name.log"
    [ -s "$log" ] || log="$dir/log/$name.stderr"
    if [ -s "$log" ]; then echo "--- $log" >&2; tail -n 20 "$log" >&2; fi
  done
  stop
  exit 1
}

free_port() {  # free_port FROM: the first port from FROM on that nobody listens on
  local p="$1"
  while ss -Htan "( sport = :$p )" 2>/dev/null | grep -q .; do p=$((p + 1)); done
  echo "$p"
}

wait_for() {  # wait_for SECONDS COMMAND...: polls COMMAND until it succeeds
  local end=$((SECONDS + $1))
  shift
  until "$@" >/dev/null 2>&1; do
    [ "$SECONDS" -lt "$end" ] || return 1
    sleep 0.2
  done
}

if [ "$action" = stop ]; then stop; exit 0; fi

missing=()
for cmd in munged slurmctld slurmd sbatch sinfo squeue scancel munge ss; do
  command -v "$cmd" >/dev/null || missing+=("$cmd")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "$0: missing ${missing[*]} (Debian: apt-get install slurmctld slurmd slurm-client munge iproute2)" >&2
  exit 2
fi
if [ "$(id -u)" -ne 0 ]; then
  echo "$0: must run as root (slurmd runs each job as its user)" >&2
  exit 2
fi
for name in "${daemons[@]}"; do
  if running "$name"; then echo "$0: $name already runs for $dir (stop it first)" >&2; exit 1; fi
done

# A fresh cluster each time: no jobs or node state recovered from the last one.
rm -rf "$dir/munge" "$dir/state" "$dir/spool" "$dir/run" "$dir/log"
mkdir -p "$dir/munge" "$dir/state" "$dir/spool" "$dir/run" "$dir/log"
# munged refuses a socket folder that others may write to; clients need to enter it.
chmod 0711 "$dir/munge"
sock="$dir/munge/munge.socket"
# Unix socket names are limited to 107 bytes.
[ ${#sock} -lt 100 ] || { echo "$0: $dir is too long a path for munge's socket" >&2; exit 1; }

# munged runs as us (root), so the key belongs to us; it takes --force to run as root.
key="$dir/munge/munge.key"
if command -v mungekey >/dev/null; then
  mungekey --create --keyfile="$key"
else
  dd if=/dev/urandom of="$key" bs=1024 count=1 status=none
fi
chmod 0400 "$key"
munged --foreground --force --socket="$sock" --key-file="$key" \
  --pid-file="$dir/munge/munged.pid" --log-file="$dir/log/munged.log" \
  --seed-file="$dir/munge/munged.seed" </dev/null >>"$dir/log/munged.log" 2>&1 &
echo $! >"$dir/munged.pid"
wait_for 10 munge -n -S "$sock" || fail "munged did not start"

host="$(hostname -s)"
ctld_port="$(free_port $((20000 + RANDOM % 20000)))"
slurmd_port="$(free_port $((ctld_port + 1)))"
: >"$dir/plugstack.conf"
# Node and controller are 127.0.0.1, whatever the host name resolves to. config_overrides: the
# node is what this file says even where the hardware (a container's CPU limit) differs.
# kill_invalid_depend: a stitch job whose tiles failed is cancelled, not left pending forever.
cat >"$conf" <<EOF
ClusterName=gpurt-localhost
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$sock
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/run/slurmctld.pid
SlurmdPidFile=$dir/run/slurmd.pid
SlurmctldLogFile=$dir/log/slurmctld.log
SlurmdLogFile=$dir/log/slurmd.log
SlurmctldDebug=info
SlurmdDebug=info
PlugStackConfig=$dir/plugstack.conf
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
MpiDefault=none
MailProg=/bin/true
ReturnToService=2
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SlurmdParameters=config_overrides
DependencyParameters=kill_invalid_depend
MaxArraySize=100001
MinJobAge=600
SlurmdTimeout=60
InactiveLimit=0
KillWait=5
NodeName=$host NodeAddr=127.0.0.1 CPUs=$(nproc) RealMemory=256 State=UNKNOWN
PartitionName=local Nodes=$host Default=YES MaxTime=INFINITE State=UP
EOF
echo "export SLURM_CONF=$conf" >"$dir/env"

slurmctld -D -f "$conf" </dev/null >"$dir/log/slurmctld.stderr" 2>&1 &
echo $! >"$dir/slurmctld.pid"
slurmd -D -f "$conf" -N "$host" </dev/null >"$dir/log/slurmd.stderr" 2>&1 &
echo $! >"$dir/slurmd.pid"

end=$((SECONDS + 60))
until [ "$(SLURM_CONF="$conf" sinfo -h -o %t 2>/dev/null)" = idle ]; do
  for name in "${daemons[@]}"; do running "$name" || fail "$name exited"; done
  [ "$SECONDS" -lt "$end" ] || fail "node $host did not come up idle in 60 s"
  sleep 0.2
done
echo "slurm on $host: SLURM_CONF=$conf (. $dir/env), slurmctld port $ctld_port, slurmd port $slurmd_port"
