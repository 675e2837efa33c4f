#!/usr/bin/env bash
# Regenerates the material-point figures of the docs (kept in git) into scripts/figures/:
# the interface cross-check (figure and table), the rockfill GP triaxial and cyclic triaxial
# tests and the GP interface cyclic shear. Builds cfrd in release mode first.
#
# Usage: scripts/make_point_figures.sh            (from anywhere in the repository)
# The same files are produced without the native stack by the ignored test
#   cargo test --release --no-default-features --lib make_point_figures -- --ignored
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
cargo build --release
bin="${CARGO_TARGET_DIR:-$root/target}/release/cfrd"
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT

figures="$root/scripts/figures"
mkdir -p "$figures"
for name in interface_crosscheck rockfill_gp_triaxial rockfill_gp_cyclic gp_interface_cnl_cyclic; do
    "$bin" point "inputs/point/$name.yaml" -o "$out"
    cp "$out/$name.png" "$figures/"
done
cp "$out/interface_crosscheck_table.csv" "$figures/"
echo "figures written to $figures"
