#!/usr/bin/env bash
# A one-node Slurm cluster on localhost: `cluster.sh start` installs Debian's slurm-wlm and munge when missing
# (as root), starts munged, slurmctld and slurmd with tests/slurm/slurm.conf (its own munge socket and two free ports,
# so clusters of two test runs on one machine stay apart) and waits until the node is idle;
# `cluster.sh stop` stops the daemons this script started. Prints `export SLURM_CONF=…` for sbatch on start.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
run="${SPECTRAL_SLURM_RUN:-/tmp/spectral-slurm}"
conf="$run/slurm.conf"

start() {
  if ! command -v slurmctld >/dev/null || ! command -v munged >/dev/null; then
    [ "$(id -u)" = 0 ] || { echo "slurm-wlm and munge are not installed and this is not root" >&2; exit 3; }
    (apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq slurm-wlm munge >/dev/null) \
      || { echo "could not install slurm-wlm munge" >&2; exit 3; }
  fi
  [ "$(id -u)" = 0 ] || { echo "the one-node cluster runs its daemons as root" >&2; exit 3; }
  stop quiet || true
  mkdir -p "$run/state" "$run/spool" "$run/munge"
  # Two free loopback ports (the kernel's choice), for slurmctld and slurmd.
  read -r ctld_port slurmd_port < <(python3 -c 'import socket
s = [socket.socket() for _ in range(2)]
for x in s: x.bind(("127.0.0.1", 0))
print(*(x.getsockname()[1] for x in s))')
  sed -e "s#@RUN@#$run#g" -e "s#@CPUS@#$(nproc)#g" -e "s#@CTLD_PORT@#$ctld_port#g" -e "s#@SLURMD_PORT@#$slurmd_port#g" \
      "$here/slurm.conf" > "$conf"
  [ -s /etc/munge/munge.key ] || { dd if=/dev/urandom bs=1 count=1024 of=/etc/munge/munge.key 2>/dev/null; chmod 400 /etc/munge/munge.key; }
  chown root:root /etc/munge/munge.key
  munged --force --socket="$run/munge/munge.socket" --pid-file="$run/munge/munged.pid" \
         --log-file="$run/munge/munged.log" --seed-file="$run/munge/munged.seed" --key-file=/etc/munge/munge.key
  export SLURM_CONF="$conf"
  slurmctld -f "$conf" -i
  slurmd -f "$conf" -N localhost
  sleep 1
  # Our daemons, not another cluster's on the same ports: each wrote its pid file and is alive.
  for pidfile in "$run/slurmctld.pid" "$run/slurmd.pid"; do
    if ! [ -s "$pidfile" ] || ! kill -0 "$(cat "$pidfile")" 2>/dev/null; then
      echo "$(basename "$pidfile" .pid) did not start (ports $ctld_port/$slurmd_port); logs in $run" >&2
      tail -n 5 "$run/slurmctld.log" "$run/slurmd.log" >&2 2>/dev/null || true
      stop quiet; exit 1
    fi
  done
  for _ in $(seq 1 60); do
    state=$(sinfo -h -N -o '%T' 2>/dev/null | head -n1 || true)
    case "$state" in idle*) echo "export SLURM_CONF=$conf"; return 0 ;; esac
    sleep 1
  done
  echo "the node did not come up (state '${state:-none}'); logs in $run" >&2
  tail -n 20 "$run/slurmctld.log" "$run/slurmd.log" >&2 || true
  exit 1
}

stop() {
  for pidfile in "$run/slurmd.pid" "$run/slurmctld.pid" "$run/munge/munged.pid"; do
    if [ -s "$pidfile" ]; then
      pid=$(cat "$pidfile")
      kill "$pid" 2>/dev/null || true
      for _ in $(seq 1 20); do kill -0 "$pid" 2>/dev/null || break; sleep 0.25; done
      rm -f "$pidfile"
    fi
  done
  [ "${1:-}" = quiet ] || echo "slurm daemons stopped"
}

case "${1:-}" in
  start) start ;;
  stop) stop ;;
  *) echo "usage: $0 start|stop" >&2; exit 2 ;;
esac
