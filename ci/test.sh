#!/usr/bin/env bash
# One command: install what is missing, then lint and run the whole test suite (including the
# 2- and 3-rank MPI tests, which the integration tests launch through mpirun).
set -euo pipefail
cd "$(dirname "$0")/.."
bash ci/install-deps.sh
source ci/env.sh
echo "== fmt"
cargo fmt --all -- --check
echo "== clippy"
cargo clippy --locked --workspace --all-targets -- -D warnings
echo "== docs"
RUSTDOCFLAGS="-D warnings" cargo doc --locked --workspace --no-deps --quiet
echo "== tests (release)"
cargo test --locked --workspace --release
echo "== tests without the native stack (materials, elements, mesh, scenes)"
cargo test --locked --no-default-features --lib --release
