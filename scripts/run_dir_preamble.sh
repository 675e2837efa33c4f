# Shared start of the scripts that run seed scenes one after another into a run directory
# (accuracy_cost.sh, make_seed_static_figures.sh). Sourced with the caller's arguments: builds
# cfrd in release mode and sets root (the repository), bin (the cfrd binary; CFRD_BIN, if set,
# names one to use instead of building, e.g. a copy that a rebuild cannot replace during long
# runs), runs (the first argument, or a new temporary directory; created) and the MPI
# environment of ci/env.sh with a 90-minute limit per mpirun.
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
if [ -z "${CFRD_BIN:-}" ]; then
    cargo build --release
fi
bin="${CFRD_BIN:-${CARGO_TARGET_DIR:-$root/target}/release/cfrd}"
runs="${1:-$(mktemp -d)}"
mkdir -p "$runs"
source ci/env.sh
export MPIEXEC_TIMEOUT=5400
