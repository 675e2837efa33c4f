#!/usr/bin/env bash
# Solver benchmark: the seed-like dam mesh at three sizes up to 1 million DOFs, on 1 and
# 2 ranks; static linear-elastic solve with the default solver (CG + GAMG with rigid-body modes,
# rtol 1e-10). Writes the markdown table to scripts/bench_solver.md (shown in the README).
# Usage: bash scripts/bench_solver.sh [DOFS...]   (default: 100000 300000 1000000)
set -euo pipefail
cd "$(dirname "$0")/.."
bash ci/install-deps.sh
source ci/env.sh
cargo build --release --locked --quiet
sizes=("${@:-100000 300000 1000000}")
read -r -a sizes <<< "${sizes[*]}"
out=scripts/bench_solver.md
tmp=$(mktemp)
{
  echo "| ranks | DOFs | elements | assembly (s) | solve (s) | KSP iterations | peak memory, max over ranks (MiB) | DOFs/s (assembly + solve) |"
  echo "|---|---|---|---|---|---|---|---|"
} > "$tmp"
for n in "${sizes[@]}"; do
  for np in 1 2; do
    echo "== $n DOFs on $np rank(s)" >&2
    mpirun -n "$np" target/release/cfrd bench solver --dofs "$n" -o "out/bench-$n-$np" | tee -a "$tmp"
  done
done
{
  cat "$tmp"
  echo
  echo "Measured $(date -u +%Y-%m-%d) on $(nproc) cores, $(free -g | awk '/Mem:/{print $2}') GiB, load average before the run: $(cut -d' ' -f1-3 /proc/loadavg)."
} > "$out"
rm -f "$tmp"
echo "table written to $out" >&2
