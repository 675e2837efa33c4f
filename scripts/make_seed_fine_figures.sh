#!/usr/bin/env bash
# The fine seed dam's interface-model comparison: draws the figures of the
# fine seed scenes run in parts, each with its own scripts/run_in_parts.sh (they take an hour or
# more each on 2 cores, so they are not started here):
#   scripts/run_in_parts.sh inputs/scenes/seed_fine_<model>.yaml FINE_DIR/<model> 2
# for model in hyperbolic, mohr_coulomb, gp_interface. Kept in scripts/figures/:
#   seed_fine_<model>_fig*.png  each run's Figs. 7-11, drawn over all its parts (`cfrd profiles`)
#   seed_fine_slab.png          slab stresses and deflection of the models that finished (seed Figs. 8, 9)
#   seed_hyperbolic_meshes.png  the hyperbolic slab of the coarse, medium and fine meshes, when
#                               STATIC_RUNS names the run directory of
#                               `MEDIUM=1 scripts/make_seed_static_figures.sh STATIC_RUNS`
#   seed_fine_runs.csv          the rows of seed_static_runs.csv for the fine runs: wall time
#                               summed over FINE_DIR/<model>/parts.csv, the largest part's memory
#
# Usage: scripts/make_seed_fine_figures.sh FINE_DIR
#   A part that was paused (kill -STOP, to keep other work off its clock) or killed gets its net
#   seconds written into parts.csv by hand; an empty peak_rss_kib (a killed part without
#   /usr/bin/time's report) is skipped. CFRD_BIN names the binary instead of building one.
set -euo pipefail

[ $# -eq 1 ] || { echo "usage: $0 FINE_DIR" >&2; exit 2; }
fine_dir="$(realpath "$1")"
source "$(dirname "${BASH_SOURCE[0]}")/run_dir_preamble.sh" "$fine_dir"
figures="$root/scripts/figures"
mkdir -p "$figures"

draw() { # model: the figures of FINE_DIR/<model>'s parts drawn together, and its row
    local dir="$fine_dir/$1" p last
    last="$(ls -d "$dir"/part_*/ | sort -V | tail -n 1)"
    last="${last%/}"
    [ -f "$last/summary.json" ] || { echo "$dir has not finished (no summary.json)" >&2; return 1; }
    local parts=()
    for p in $(ls -d "$dir"/part_*/ | sort -V); do
        p="${p%/}"
        if [ -f "$p/results.h5" ]; then parts+=("$p"); else echo "$p: no results.h5, not drawn" >&2; fi
    done
    "$bin" profiles "inputs/scenes/seed_fine_$1.yaml" "${parts[@]}" -o "$dir/profiles" >&2 || return 1
    for f in "$dir"/profiles/fig*.png; do cp "$f" "$figures/seed_fine_$1_$(basename "$f")"; done
    python3 scripts/summary_row.py "$last/summary.json" "fine_$1" 2 "$dir/parts.csv" >> "$rows"
}

rows="$figures/seed_fine_runs.csv"
echo "model,ranks,wall_s,peak_rss_mib,newton_iterations,steps,cutbacks,interface_points,open,slipping,max_newton_per_step,factorizations" > "$rows"
models=()
for m in hyperbolic mohr_coulomb gp_interface; do
    if [ -d "$fine_dir/$m" ] && draw "$m"; then models+=("$m"); fi
done
if [ ${#models[@]} -ge 2 ]; then
    overlay=()
    for m in "${models[@]}"; do overlay+=("$m=$fine_dir/$m/profiles"); done
    "$bin" overlay "${overlay[@]}" -o "$figures/seed_fine_slab.png"
fi
if [ -n "${STATIC_RUNS:-}" ] && [ -d "$fine_dir/hyperbolic/profiles" ]; then
    "$bin" overlay coarse="$STATIC_RUNS/hyperbolic_2" medium="$STATIC_RUNS/medium_hyperbolic_2" \
        fine="$fine_dir/hyperbolic/profiles" -o "$figures/seed_hyperbolic_meshes.png"
fi
cat "$rows"
echo "figures written to $figures (fine runs: ${models[*]})"
