#!/usr/bin/env bash
# Accuracy versus cost on the seed dam (issue 21): runs the coarse hyperbolic seed scene
# (inputs/scenes/seed_coarse_hyperbolic.yaml, GP rockfill, slab in three stages, impoundment)
# on 2 ranks with one setting changed at a time from the scene's own:
#   load steps per stage   1, 2, 4, 8 (the scene's), 16
#   STOL of the GP rockfill's integration   1e-3, 1e-4 (default), 1e-5, 1e-6
#   Newton tolerance       1e-4, 1e-5 (the scene's), 1e-6
#   interface integration  newton_cotes (nodal, default), gauss2x2
# and a reference run with the load path at its most accurate (16 load steps, STOL 1e-6, Newton
# tolerance 1e-6; the scene's nodal interface rule, so that the Gauss run shows what the rule
# changes). `cfrd accuracy` then gives each run's error in the slab stresses along the slope
# and the axis and the deflection (seed Figs. 8, 9, central section, after impoundment) and the
# crest settlement against the reference, with its wall time:
#   scripts/figures/accuracy_cost.csv   one row per run
#   scripts/figures/accuracy_cost.png   error against wall time, one panel per quantity
# With MEDIUM=1 the mesh joins as its own comparison: the medium scene (9,414 elements, 10-20
# min on 2 cores) at the scene's settings is the reference of the coarse runs with the scene's
# settings, 16 load steps and the Gauss rule (the fine mesh takes hours: not run here):
#   scripts/figures/mesh/accuracy_cost.csv, scripts/figures/mesh/accuracy_cost.png
#
# Usage: scripts/accuracy_cost.sh [RUN_DIR]
#   RUN_DIR (default: a new temporary directory) keeps the runs; a run that already finished
#   there (summary.json) is not repeated. Runs one at a time: the wall times are only
#   comparable when nothing else runs on the machine.
set -euo pipefail

source "$(dirname "${BASH_SOURCE[0]}")/run_dir_preamble.sh" "$@"

# variant NAME MESH STEPS STOL NEWTON_TOL RULE: writes the scene RUN_DIR/NAME.yaml
variant() {
    local name=$1 mesh=$2 steps=$3 stol=$4 tol=$5 rule=$6
    sed -e "s/load_steps: [0-9]*/load_steps: $steps/" \
        -e "s/newton_tol: [0-9.e-]*/newton_tol: $tol/" \
        -e "s/{ model: rockfill_gp }/{ model: rockfill_gp, integration: { stol: $stol } }/" \
        -e "s/interface_\*: { material: interface }/interface_*: { material: interface, rule: $rule }/" \
        -e "s/^name: .*/name: accuracy_$name/" \
        "inputs/scenes/seed_${mesh}_hyperbolic.yaml" > "$runs/$name.yaml"
}

# run NAME: runs RUN_DIR/NAME.yaml on 2 ranks into RUN_DIR/NAME unless it finished there
run() {
    local out="$runs/$1"
    [ -f "$out/summary.json" ] && return 0
    rm -rf "$out"
    echo "running $1"
    mpirun -n 2 "$bin" run "$runs/$1.yaml" -o "$out" -q --checkpoint none > "$runs/$1.log" 2>&1 \
        || echo "$1 failed (exit $?), see $runs/$1.log"
}

names=()
add() { variant "$@"; names+=("$1"); }
add scene coarse 8 1.0e-4 1.0e-5 newton_cotes
for s in 1 2 4 16; do add "steps_$s" coarse "$s" 1.0e-4 1.0e-5 newton_cotes; done
for t in 1.0e-3 1.0e-5 1.0e-6; do add "stol_$t" coarse 8 "$t" 1.0e-5 newton_cotes; done
for t in 1.0e-4 1.0e-6; do add "newton_$t" coarse 8 1.0e-4 "$t" newton_cotes; done
add gauss coarse 8 1.0e-4 1.0e-5 gauss2x2
variant reference coarse 16 1.0e-6 1.0e-6 newton_cotes

run reference
for n in "${names[@]}"; do run "$n"; done

pairs=()
for n in "${names[@]}"; do
    [ -f "$runs/$n/summary.json" ] && pairs+=("$n=$runs/$n")
done
mkdir -p scripts/figures
"$bin" accuracy --reference "$runs/reference" "${pairs[@]}" -o scripts/figures

if [ "${MEDIUM:-0}" = 1 ]; then
    variant medium medium 8 1.0e-4 1.0e-5 newton_cotes
    run medium
    mkdir -p scripts/figures/mesh
    "$bin" accuracy --reference "$runs/medium" "coarse=$runs/scene" \
        "coarse-16-steps=$runs/steps_16" "coarse-gauss-rule=$runs/gauss" -o scripts/figures/mesh
fi
