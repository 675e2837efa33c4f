#!/usr/bin/env bash
# Accuracy versus cost on the seed dam: runs the coarse hyperbolic seed scene
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
# With QUAKE=1 the time integration of the seed quake is studied instead, on the
# coarse Mohr-Coulomb quake scene (inputs/scenes/seed_coarse_mohr_coulomb_quake.yaml, the 20 s
# record; 10-40 min a run): time steps 0.02 and 0.01 s (the scene's), lumped mass and HHT-alpha
# (alpha = -0.1) at 0.01 s, against the reference at 0.005 s (consistent mass, Newmark); fields
# every 0.1 s in all. `cfrd accuracy --quake` compares the residual (after - before the quake)
# slab stresses and deflection (seed Fig. 13) and the residual crest settlement:
#   scripts/figures/quake/accuracy_cost.csv, scripts/figures/quake/accuracy_cost.png
#
# Usage: scripts/accuracy_cost.sh [RUN_DIR]
#   RUN_DIR (default: a new temporary directory) keeps the runs; a run that already finished
#   there (summary.json) is not repeated. Runs one at a time: the wall times are only
#   comparable when nothing else runs on the machine.
set -euo pipefail

source "$(dirname "${BASH_SOURCE[0]}")/run_dir_preamble.sh" "$@"

# quake_variant NAME DT OUTPUT_EVERY EXTRA: the coarse quake scene at time step DT with the
# extra earthquake keys EXTRA (e.g. "mass: lumped, "), written to RUN_DIR/NAME.yaml
quake_variant() {
    local name=$1 dt=$2 every=$3 extra=$4
    sed -e "s|^earthquake: { record: [^,]*, |earthquake: { record: $root/inputs/accel/seed_quake.csv, dt: $dt, $extra |" \
        -e "s/output_every: 10 }/output_every: $every }/" \
        -e "s/^name: .*/name: quake_accuracy_$name/" \
        inputs/scenes/seed_coarse_mohr_coulomb_quake.yaml > "$runs/$name.yaml"
}

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

if [ "${QUAKE:-0}" = 1 ]; then
    quake_variant quake_reference 0.005 20 ""
    run quake_reference
    quake=()
    for v in "dt_0.01 0.01 10" "dt_0.02 0.02 5" "lumped 0.01 10 mass: lumped, " "hht 0.01 10 hht_alpha: -0.1, "; do
        read -r name dt every extra <<< "$v"
        quake_variant "$name" "$dt" "$every" "$extra"
        run "$name"
        [ -f "$runs/$name/summary.json" ] && quake+=("$name=$runs/$name")
    done
    mkdir -p scripts/figures/quake
    "$bin" accuracy --quake --reference "$runs/quake_reference" "${quake[@]}" -o scripts/figures/quake
    exit 0
fi

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
