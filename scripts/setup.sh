#!/usr/bin/env bash
# Installs the Debian 12 packages the project builds with, when missing.
# As root it runs apt-get; otherwise it prints the exact command and stops.
# Usage: scripts/setup.sh [extra packages...]
set -euo pipefail
case "${1:-}" in
  -h|--help)
    cat <<'USAGE'
usage: scripts/setup.sh [EXTRA_PACKAGE...]
Installs the missing Debian 12 packages the project builds with (cmake g++ make libstb-dev
libtinyobjloader-dev doctest-dev nlohmann-json3-dev nettle-dev bubblewrap, and any given). As root it runs apt-get,
first waiting up to 10 minutes for another apt (unattended-upgrades) to release its lock;
otherwise it prints the sudo apt-get command and exits 1.
USAGE
    exit 0 ;;
esac

packages=(cmake g++ make libstb-dev libtinyobjloader-dev libtinyexr-dev doctest-dev nlohmann-json3-dev nettle-dev bubblewrap "$@")
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0

if [ "$(id -u)" -eq 0 ]; then
  echo "setup: installing ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  # On a fresh machine unattended-upgrades often holds apt's lock for
  # minutes: wait for it and say so, instead of failing with apt's raw
  # message. DPkg::Lock::Timeout covers a lock taken between the two steps.
  lock_wait=600
  "$(dirname "$0")/wait_for_apt_lock.sh" "$lock_wait"
  apt-get -o DPkg::Lock::Timeout="$lock_wait" update -qq
  apt-get -o DPkg::Lock::Timeout="$lock_wait" install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
else
  echo "setup: missing Debian packages. Install them with:" >&2
  echo "    sudo apt-get install ${missing[*]}" >&2
  exit 1
fi
