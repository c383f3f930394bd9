#!/usr/bin/env bash
# Installs the Debian 12 packages ICM needs, only those missing. Needs root (or sudo).
set -euo pipefail
packages=(build-essential cmake libcgal-dev libeigen3-dev libboost-dev libsuitesparse-dev
          libgtest-dev libbenchmark-dev libcli11-dev nlohmann-json3-dev doxygen python3 clang-format)
missing=()
for p in "${packages[@]}"; do
  dpkg -s "$p" >/dev/null 2>&1 || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  sudo_cmd=""
  [ "$(id -u)" -ne 0 ] && sudo_cmd="sudo"
  export DEBIAN_FRONTEND=noninteractive
  $sudo_cmd apt-get update -q
  $sudo_cmd apt-get install -y -q "${missing[@]}"
fi
