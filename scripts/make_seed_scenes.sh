#!/usr/bin/env bash
# Writes the seed-dam scenes inputs/scenes/seed_{coarse,medium,fine}_{hyperbolic,mohr_coulomb,gp_interface}.yaml,
# inputs/scenes/seed_xfine_hyperbolic.yaml (the ~1M-DOF dam of the weak-scaling study) and the
# quake scenes inputs/scenes/seed_{coarse,medium}_{gp_interface,mohr_coulomb}_quake.yaml. The
# static files share one body and differ only in the mesh resolution, the solver settings and
# the slab-cushion interface model. Edit this script, not the generated files, then rerun it:
#   bash scripts/make_seed_scenes.sh
# Measurements behind the settings: cfrd::performance (rustdoc).
set -euo pipefail
cd "$(dirname "$0")/.."

# resolution -> mesh.cfrd keys (omitted keys: the seed dam, src/mesh/dam_spec.rs CfrdSpec::default)
declare -A mesh=(
  [coarse]="{ fill_layers: 8, elements_per_panel: 1, rockfill_elements: 3, panel_width: 30.0, impoundment_stages: 3 }"
  [medium]="{ fill_layers: 30, elements_per_panel: 1, rockfill_elements: 8, impoundment_stages: 4 }"
  [fine]="{ fill_layers: 86, elements_per_panel: 2, rockfill_elements: 14, impoundment_stages: 6 }"
  [xfine]="{ fill_layers: 110, elements_per_panel: 4, rockfill_elements: 26, impoundment_stages: 6 }"
)
# Solver settings per resolution.
# - Linear solver: the default GAMG fails once the slab is placed (the stiff interfaces and
#   joints, k2 1e10 and 2.5e10 Pa/m). The coarse scenes use the canonical LU (PETSc's own LU on
#   every rank in the mesh's DOF order, the fastest factorization at 3,360 DOFs), whose results
#   are the same bit for bit on any rank count: the goldens and the 1-vs-2-rank comparison rest
#   on it. The medium, fine and extra-fine scenes use the reduced multigrid (GAMG on the fill,
#   the slab, interfaces and joints factored by SuperLU_DIST, inexact Newton): on the medium
#   mesh under half the canonical LU's time and memory per rank, its slab tables within
#   0.02 MPa and 0.1 cm of the LU's. `--linear-solver canonical_lu
#   -canonical_pc_factor_mat_solver_type mumps` gives the LU's results for comparison.
# - newton_tol: the GP substepping (STOL 1e-4) leaves an out-of-balance noise of about 2e-6 of a
#   fill layer's weight, so 1e-5 is the coarse (and quake) scenes' tolerance; on the medium mesh
#   1e-4 is as accurate against a 32-load-step reference (the 8 load steps, not the tolerance,
#   set the error) in about 0.6 of the time, so the medium, fine and extra-fine scenes use it.
#   At most 15 Newton iterations: a step that stalls is cut back sooner.
# - 8 load steps per stage: every Newton iteration integrates the GP points over the whole step
#   increment, so larger steps cost more substeps and cut-backs than they save (and follow the
#   path-dependent load path less closely).
# - predictor: extrapolate (medium and up): a step starts from the last step's rate, about 20 %
#   fewer Newton iterations on the medium mesh; on the coarse mesh it saves no time.
# - step_growth: 2 (fine only): a step converged in one Newton iteration doubles the next, up
#   to a quarter of a 2 m layer: fill_051-fill_054 in 20 steps and 32 Newton iterations instead
#   of 32 and 40. The medium and extra-fine scenes keep equal steps, on which their comparisons
#   and checkpoints stand.
declare -A solver=(
  [coarse]="solver: { newton_tol: 1.0e-5, newton_max_iterations: 15, load_steps: 8, linear_solver: canonical_lu }"
  [medium]="solver: { newton_tol: 1.0e-4, newton_max_iterations: 15, load_steps: 8, linear_solver: reduced_amg, predictor: extrapolate }"
  [fine]="solver: { newton_tol: 1.0e-4, newton_max_iterations: 15, load_steps: 8, step_growth: 2, linear_solver: reduced_amg, predictor: extrapolate }"
  [xfine]="solver: { newton_tol: 1.0e-4, newton_max_iterations: 15, load_steps: 8, linear_solver: reduced_amg, predictor: extrapolate }"
)
declare -A note=(
  [coarse]="coarse mesh (panels 30 m, wider than the seed's 12-18 m)"
  [medium]="medium mesh (panels 15 m)"
  [fine]="fine mesh (86 fill layers as in the seed, about the paper's 74 521 elements)"
  [xfine]="extra-fine mesh (110 fill layers, 1 018 689 DOFs; the weak-scaling study's ~1M-DOF dam)"
)
# The GP-interface scenes on the reduced multigrid solve each Newton correction to forcing
# terms of at most 0.01 (the solver's default is 0.03): the slipping GP interface follows the
# path of the converged states, and with 0.03 its medium slab table after impoundment lies
# 0.079 MPa from the canonical LU's, with 0.01 within 0.018 MPa.
gp_forcing='petsc_options: "-snes_ksp_ew_rtol0 0.01 -snes_ksp_ew_rtolmax 0.01", '
# the interface models of a resolution (all three unless named); the extra-fine dam serves the
# weak-scaling study only
declare -A models=([xfine]="hyperbolic")
declare -A law=(
  [hyperbolic]="Clough-Duncan hyperbolic interface, seed Table 3 (k1 600, k2 1e7 kPa/m, n 0.85, phi 41.5, Rf 0.9)"
  [mohr_coulomb]="ideal elasto-plastic (Mohr-Coulomb) interface, seed Table 4 (k1 300, k2 1e7 kPa/m, n 0.8, phi 41.5)"
  [gp_interface]="generalized-plasticity interface, seed Table 2"
)
for res in coarse medium fine xfine; do
  for model in ${models[$res]:-hyperbolic mohr_coulomb gp_interface}; do
    f=inputs/scenes/seed_${res}_${model}.yaml
    solver_line=${solver[$res]}
    if [ "$model" = gp_interface ] && [[ $solver_line == *reduced_amg* ]]; then
      solver_line=${solver_line/linear_solver: reduced_amg/${gp_forcing}linear_solver: reduced_amg}
    fi
    cat > "$f" <<YAML
# Seed dam (Liu, Kong & Zou 2015, seed/summary.md section 2): construction in fill layers, face
# slab in three stages (stage I cast at fill el. 2780 m, II and III after the fill), then
# impoundment to el. 2840 m. ${note[$res]}.
# Slab-cushion interface: ${law[$model]}.
# Generated by scripts/make_seed_scenes.sh; edit the script, not this file.
# requirement: the generated schedule runs every fill, slab and impoundment stage (static).
# spec: seismic.md section 5 (geometry), models.md sections 1-6 (materials, interface, joints).
name: seed_${res}_${model}
units: SI
mesh:
  cfrd: ${mesh[$res]}
materials:
  # seed Table 1 (the defaults); transition and cushion use the same values in the seed
  rockfill: { model: rockfill_gp }
  transition: { model: rockfill_gp }
  cushion: { model: rockfill_gp }
  slab: { model: elastic, young: 25.5e9, poisson: 0.167, density: 2400.0 }
  interface: { model: ${model} }
  # vertical and perimetric joints, seed section 2.2(2) (the defaults; spec section 6.2)
  joint: { model: joint }
blocks:
  fill_*_cushion: { material: cushion }
  fill_*_transition: { material: transition }
  fill_*_rockfill: { material: rockfill }
  # one hexahedron through the slab's thickness: incompatible modes, or it locks in bending
  # (spec seismic section 4 item 6; tests/modal.rs, cfrd::element::hex8_modes)
  slab_*: { material: slab, element: incompatible_modes }
  interface_*: { material: interface }
  joint_*: { material: joint }
boundary:
  - { set: foundation, fix: [x, y, z] }
  - { set: plinth, fix: [x, y, z] }
loads:
  gravity: { g: [0.0, 0.0, -9.81] }
${solver_line}
# seed Figs. 7-11 as CSV tables and PNG plots; I-A is the seed's interface element at 2711 m
output: { profiles: { probes: [ { name: I-A, elevation: 2711.0 } ] } }
YAML
  done
done
# The seed's earthquake after impoundment (seed section 2.4: the GP and ideal elasto-plastic
# interfaces) on the three dams: the static scene as it is (its construction and impoundment,
# its solver), then the 20 s record of inputs/accel/seed_quake.yaml (cfrd accel; committed as
# inputs/accel/seed_quake.csv) at the record's 0.01 s, HHT-alpha with alpha = -0.1 (Newmark's
# average acceleration leaves the response at the step's Nyquist frequency undamped: single-step
# crest acceleration spikes, cfrd::verification), Newton to 1e-5 in the quake, on the dynamic
# stages' default distributed solver. The seed does not state
# its damping: generalized plasticity supplies the hysteretic damping, plus Rayleigh 2 % at 1
# and 5 Hz (the dam's first frequencies are 1.1-1.4 Hz). Probes of the seed's dynamic figures:
# slab element F-A at 2813 m (Fig. 14), interface elements I-B at the left bank at 2809 m, I-C
# at 2838 m (Figs. 18-19) and I-D at the crest, 2852 m (Fig. 20), besides I-A at 2711 m; F-A,
# I-C and I-D at the central section (src/post/quake_figures.rs).
quake_probes="[ { name: I-A, elevation: 2711.0 }, { name: I-B, elevation: 2809.0, at: left_bank }, { name: I-C, elevation: 2838.0 }, { name: I-D, elevation: 2852.0 }, { name: F-A, elevation: 2813.0, element: slab } ]"
for res in coarse medium fine; do
  for model in gp_interface mohr_coulomb; do
    f=inputs/scenes/seed_${res}_${model}_quake.yaml
    sed -e "s/^name: seed_${res}_${model}$/name: seed_${res}_${model}_quake/" \
        -e "s/^# requirement: the generated schedule runs every fill, slab and impoundment stage (static).$/# requirement: the generated schedule, then a 20 s three-component earthquake (seed section 2.4)./" \
        -e "s/^# seed Figs. 7-11 as CSV tables and PNG plots; I-A is the seed's interface element at 2711 m$/# seed Figs. 7-11 and, after the quake, Figs. 12-20 as CSV tables and PNG plots (seed probe elements)/" \
        -e "s/^output: { profiles: { probes: .* } }$/output: { profiles: { probes: ${quake_probes} } }/" \
        "inputs/scenes/seed_${res}_${model}.yaml" > "$f"
    cat >> "$f" <<YAML
# the seed's quake: 3 / 3 / 2 m/s2 (x stream, y axis, z up), 20 s at 0.01 s; fields every 0.1 s
# (the probe histories of Figs. 14 and 18-20 are sampled at these steps)
earthquake: { record: ../accel/seed_quake.csv, damping: { ratio: 0.02, frequencies: [1.0, 5.0] }, output_every: 10, newton_tol: 1.0e-5, hht_alpha: -0.1 }
YAML
  done
done
echo "wrote inputs/scenes/seed_{coarse,medium,fine}_{hyperbolic,mohr_coulomb,gp_interface}.yaml, seed_xfine_hyperbolic.yaml"
echo "wrote inputs/scenes/seed_{coarse,medium,fine}_{gp_interface,mohr_coulomb}_quake.yaml"
