#!/usr/bin/env bash
# Seed static study on the coarse mesh (issue 4, acceptance 2 and 5): runs the three coarse seed
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
#   FINE=DIR takes the fine hyperbolic run made with scripts/run_in_parts.sh (it takes hours on
#   2 cores, so it is not started here): draws the figures of all its parts that kept their
#   results together (`cfrd profiles`, into DIR/profiles; each part's own figures hold only
#   the stages it ran; parts killed by an older cfrd kept none),
#   copies them as seed_fine_hyperbolic_fig*.png, overlays the hyperbolic slab profiles of the three meshes as
#   seed_hyperbolic_meshes.png and adds a row fine_hyperbolic with the wall time summed over
#   DIR/parts.csv and the largest per-rank memory of the parts. A part that was paused (kill
#   -STOP, to keep other work off its clock) gets its net seconds written into parts.csv by
#   hand; an empty peak_rss_kib (a killed part without /usr/bin/time's report) is skipped.
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
fine=""
if [ -n "${FINE:-}" ]; then
    # the parts are the directories part_<k> (run_in_parts.sh keeps each part's log beside it)
    fine="$(ls -d "$FINE"/part_*/ | sort -V | tail -n 1)"
    fine="${fine%/}"
    [ -f "$fine/summary.json" ] || { echo "$fine has not finished (no summary.json)" >&2; exit 1; }
    # a part killed by a cfrd that published its results only at the end has no results.h5
    # (only its checkpoint): its stages are missing from the probe history
    parts=()
    for p in $(ls -d "$FINE"/part_*/ | sort -V); do
        p="${p%/}"
        if [ -f "$p/results.h5" ]; then parts+=("$p"); else echo "$p: no results.h5 (killed), its stages are not drawn"; fi
    done
    "$bin" profiles inputs/scenes/seed_fine_hyperbolic.yaml "${parts[@]}" -o "$FINE/profiles"
    for f in "$FINE"/profiles/fig*.png; do
        cp "$f" "$figures/seed_fine_hyperbolic_$(basename "$f")"
    done
    "$bin" overlay coarse="$runs/hyperbolic_2" medium="$runs/medium_hyperbolic_2" fine="$FINE/profiles" \
        -o "$figures/seed_hyperbolic_meshes.png"
fi
{
    echo "model,ranks,wall_s,peak_rss_mib,newton_iterations,steps,cutbacks,interface_points,open,slipping,max_newton_per_step,factorizations"
    row() { # run-directory label ranks [parts.csv]
        python3 - "$1/summary.json" "$2" "$3" "${4:-}" <<'PY'
import csv, json, sys
s = json.load(open(sys.argv[1]))
wall = s["total_seconds"]
rss = max(s["peak_memory_bytes_per_rank"]) / 2**20
if sys.argv[4]:  # a run in parts: the parts' wall times add up, the memory is the largest part's
    parts = list(csv.DictReader(open(sys.argv[4])))
    wall = sum(float(p["wall_seconds"]) for p in parts)
    rss = max([rss] + [float(p["peak_rss_kib"]) / 1024 for p in parts if p["peak_rss_kib"]])
print(f'{sys.argv[2]},{sys.argv[3]},{wall:.0f},{rss:.0f},{s["newton_iterations"]},{s["steps"]},'
      f'{s["cutbacks"]},{s["interface_points"]},{s["interface_open"]},{s["interface_slipping"]},'
      f'{max(s["newton_per_step"])},{s.get("factorizations", 0)}')
PY
    }
    for m in "${models[@]}"; do
        for n in 2 1; do row "$runs/${m}_$n" "$m" "$n"; done
    done
    for m in "${medium[@]}"; do
        row "$runs/medium_${m}_2" "medium_$m" 2
    done
    [ -z "$fine" ] || row "$fine" fine_hyperbolic 2 "$FINE/parts.csv"
} > "$figures/seed_static_runs.csv"
{
    for m in "${models[@]}"; do
        printf '%s: ' "$m"
        "$bin" compare "$runs/${m}_1/results.h5" "$runs/${m}_2/results.h5" | tail -n 1
    done
} > "$figures/seed_static_compare.txt"
cat "$figures/seed_static_runs.csv" "$figures/seed_static_compare.txt"
echo "figures written to $figures (runs in $runs)"
