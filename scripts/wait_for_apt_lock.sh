#!/usr/bin/env bash
# Waits until no other process holds apt's or dpkg's locks (an
# unattended-upgrades run on a fresh machine, another apt-get), saying who
# holds them, so that scripts/setup.sh does not fail at once with apt's raw
# "Could not get lock" message.
# Usage: scripts/wait_for_apt_lock.sh [SECONDS=600] [LOCK_FILE...]
# (default lock files: dpkg's lock-frontend and lock, apt's lists/lock).
# Exit 0 when the locks are free, 1 when one is still held after SECONDS.
set -euo pipefail
case "${1:-}" in
  -h|--help)
    cat <<'USAGE'
usage: scripts/wait_for_apt_lock.sh [SECONDS=600] [LOCK_FILE...]
Waits until no process holds apt's and dpkg's locks (default: /var/lib/dpkg/lock-frontend,
/var/lib/dpkg/lock, /var/lib/apt/lists/lock), saying which process holds them.
Exit 0 when they are free, 1 when one is still held after SECONDS.
USAGE
    exit 0 ;;
esac
timeout=${1:-600}
shift || true
locks=("$@")
[ ${#locks[@]} -gt 0 ] || locks=(/var/lib/dpkg/lock-frontend /var/lib/dpkg/lock /var/lib/apt/lists/lock)

# The process holding a lock on FILE, as "PID (NAME)", from /proc/locks
# (apt takes fcntl locks, flock(1) takes flock locks; both are listed there
# with the file's inode as the third part of MAJOR:MINOR:INODE).
holder() {
  [ -e "$1" ] || return 0
  local inode pid
  inode=$(stat -c %i "$1")
  pid=$(awk -v inode="$inode" '{ n = split($0, f, " "); for (i = 1; i <= n; i++) if (f[i] ~ /^[0-9a-f]+:[0-9a-f]+:[0-9]+$/) { split(f[i], d, ":"); if (d[3] == inode) { print f[i - 1]; exit } } }' /proc/locks)
  [ -n "$pid" ] && echo "$pid ($(cat "/proc/$pid/comm" 2>/dev/null || echo unknown))"
  return 0
}

start=$SECONDS
said=""
while :; do
  busy=""
  for lock in "${locks[@]}"; do
    who=$(holder "$lock")
    [ -n "$who" ] && { busy="$lock is held by process $who"; break; }
  done
  [ -z "$busy" ] && exit 0
  waited=$((SECONDS - start))
  if [ "$waited" -ge "$timeout" ]; then
    echo "setup: $busy, still after ${timeout} s; try again when it has finished" >&2
    exit 1
  fi
  if [ "$busy" != "$said" ]; then
    echo "setup: waiting for apt's lock: $busy (another package manager, often unattended-upgrades on a fresh machine; waiting up to ${timeout} s)" >&2
    said=$busy
  fi
  sleep 1
done
