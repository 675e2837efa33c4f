#!/usr/bin/env bash
# One command: install what is missing, build, run the embedded default scene on 2 ranks.
set -euo pipefail
cd "$(dirname "$0")/.."
bash ci/install-deps.sh
source ci/env.sh
cargo build --release --locked
out=${1:-out/default}
mpirun -n 2 target/release/cfrd run -o "$out"
