#!/usr/bin/env bash
# Installs the Debian packages cfrd needs, if any is missing (see ../shared/spec/stack.md §1).
# Safe to run again: does nothing when everything is present.
set -euo pipefail
PKGS=(libpetsc-real-dev libopenmpi-dev openmpi-bin libhdf5-openmpi-dev libmetis-dev libclang-dev pkg-config fonts-dejavu-core)
missing=()
for p in "${PKGS[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi
echo "installing Debian packages: ${missing[*]}"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "error: need root or sudo to install ${missing[*]}" >&2; exit 1; }
  SUDO=sudo
fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -q -o DPkg::Lock::Timeout=300
# --no-install-recommends is enough (stack.md §1); never run two installs at once.
$SUDO apt-get install -y -q --no-install-recommends -o DPkg::Lock::Timeout=300 "${missing[@]}"
