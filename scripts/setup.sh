#!/usr/bin/env bash
# Installs the Debian 12 packages the project builds with, when missing.
# As root it runs apt-get; otherwise it prints the exact command and stops.
# Usage: scripts/setup.sh [extra packages...]
set -euo pipefail

packages=(cmake g++ make libstb-dev libtinyobjloader-dev libtinyexr-dev doctest-dev nlohmann-json3-dev "$@")
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0

if [ "$(id -u)" -eq 0 ]; then
  echo "setup: installing ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
else
  echo "setup: missing Debian packages. Install them with:" >&2
  echo "    sudo apt-get install ${missing[*]}" >&2
  exit 1
fi
