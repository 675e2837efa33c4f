#!/usr/bin/env bash
# Seed static study on the coarse mesh: runs the three coarse seed
# scenes (hyperbolic, Mohr-Coulomb and GP slab-cushion interface) through construction and
# impoundment on 2 ranks and on 1 rank, compares the 1- and 2-rank results field by field, and
# makes the figures and tables the README shows, kept in scripts/figures/:
#   seed_static_slab.png         slab stresses and deflection of the three models (seed Figs. 8, 9)
#   seed_static_<model>_fig*.png each run's own Figs. 7-11 (2 ranks)
#   seed_static_runs.csv         wall time, peak memory, Newton iterations, cut-backs, factorizations per run
#   seed_static_compare.txt      largest 1-vs-2-rank difference per model
#
# Usage: scripts/make_seed_static_figures.sh [RUN_DIR]
#   RUN_DIR (default: a new temporary directory) keeps the runs; when RUN_DIR/<model>_<n>
#   already holds a finished run (summary.json), that run is not repeated.
#   MEDIUM=1 also runs the three medium scenes on 2 ranks (RUN_DIR/medium_<model>_2, each 7-10
#   minutes on 2 cores with their reduced multigrid), overlays their slab profiles as
#   seed_medium_slab.png, copies
#   their figures as seed_medium_<model>_fig*.png and adds their rows to seed_static_runs.csv.
#   The fine scenes run for an hour or more each: scripts/make_seed_fine_figures.sh draws them.
# The scenes use the canonical LU (solver.linear_solver: canonical_lu), so the 1- and 2-rank
# results are expected to be identical.
set -euo pipefail

source "$(dirname "${BASH_SOURCE[0]}")/run_dir_preamble.sh" "$@"
models=(hyperbolic mohr_coulomb gp_interface)

run() { # model ranks
    local m=$1 n=$2 out="$runs/$1_$2"
    [ -f "$out/summary.json" ] && return 0
    /usr/bin/time -v mpirun -n "$n" "$bin" run "inputs/scenes/seed_coarse_$m.yaml" -o "$out" \
        > "$runs/$1_$2.log" 2>&1
}
for m in "${models[@]}"; do run "$m" 2; done
for m in "${models[@]}"; do run "$m" 1; done
if [ "${MEDIUM:-0}" = 1 ]; then
    for m in "${models[@]}"; do
        [ -f "$runs/medium_${m}_2/summary.json" ] && continue
        /usr/bin/time -v mpirun -n 2 "$bin" run "inputs/scenes/seed_medium_$m.yaml" \
            -o "$runs/medium_${m}_2" > "$runs/medium_${m}_2.log" 2>&1
    done
fi
medium=()
for m in "${models[@]}"; do
    [ -f "$runs/medium_${m}_2/summary.json" ] && medium+=("$m")
done

figures="$root/scripts/figures"
mkdir -p "$figures"
"$bin" overlay hyperbolic="$runs/hyperbolic_2" mohr_coulomb="$runs/mohr_coulomb_2" \
    gp_interface="$runs/gp_interface_2" -o "$figures/seed_static_slab.png"
for m in "${models[@]}"; do
    for f in "$runs/${m}_2"/fig*.png; do
        cp "$f" "$figures/seed_static_${m}_$(basename "$f")"
    done
done
for m in "${medium[@]}"; do
    for f in "$runs/medium_${m}_2"/fig*.png; do
        cp "$f" "$figures/seed_medium_${m}_$(basename "$f")"
    done
done
if [ ${#medium[@]} -eq 3 ]; then
    "$bin" overlay hyperbolic="$runs/medium_hyperbolic_2" mohr_coulomb="$runs/medium_mohr_coulomb_2" \
        gp_interface="$runs/medium_gp_interface_2" -o "$figures/seed_medium_slab.png"
fi
{
    echo "model,ranks,wall_s,peak_rss_mib,newton_iterations,steps,cutbacks,interface_points,open,slipping,max_newton_per_step,factorizations"
    row() { python3 scripts/summary_row.py "$1/summary.json" "$2" "$3" "${4:-}"; }
    for m in "${models[@]}"; do
        for n in 2 1; do row "$runs/${m}_$n" "$m" "$n"; done
    done
    for m in "${medium[@]}"; do
        row "$runs/medium_${m}_2" "medium_$m" 2
    done
} > "$figures/seed_static_runs.csv"
{
    for m in "${models[@]}"; do
        printf '%s: ' "$m"
        "$bin" compare "$runs/${m}_1/results.h5" "$runs/${m}_2/results.h5" | tail -n 1
    done
} > "$figures/seed_static_compare.txt"
cat "$figures/seed_static_runs.csv" "$figures/seed_static_compare.txt"
echo "figures written to $figures (runs in $runs)"
