#!/usr/bin/env bash
# Installs the Debian packages cfrd needs, if any is missing (see ../shared/spec/stack.md §1).
# Safe to run again: does nothing when everything is present.
set -euo pipefail
# libopenblas0-serial: an optimized, single-threaded BLAS behind libblas.so.3 (Debian's
# alternatives pick it over the reference BLAS). MUMPS, the factorization of
# `linear_solver: canonical_lu`, spends most of its time in BLAS: on the medium seed dam it
# made the factorization 5.5 times faster. Serial, so results do not depend on thread timing.
# libslepc-real-dev: SLEPc 3.18, built on Debian's PETSc 3.18, for the modal analysis
# (shift-and-invert eigensolver of the `modal` stage option).
PKGS=(libpetsc-real-dev libslepc-real-dev libopenmpi-dev openmpi-bin libhdf5-openmpi-dev libmetis-dev libclang-dev pkg-config fonts-dejavu-core libopenblas0-serial)
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
