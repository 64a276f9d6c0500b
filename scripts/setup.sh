#!/usr/bin/env bash
# Installs what slender needs on a fresh Debian 12 machine. Idempotent; run as root
# (or with sudo available). Skips apt-get when everything is already there.
set -euo pipefail
PKGS=(build-essential cmake pkg-config libeigen3-dev liblua5.4-dev libhdf5-dev libfftw3-dev
      libgtest-dev python3 python3-numpy python3-matplotlib python3-h5py python3-pytest
      snakemake slurm-wlm munge)
missing=()
for p in "${PKGS[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all packages present"
  exit 0
fi
SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO="sudo"
echo "setup: installing ${missing[*]}"
$SUDO apt-get update -qq
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
