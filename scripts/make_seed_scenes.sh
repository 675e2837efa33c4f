#!/usr/bin/env bash
# Writes the seed-dam scenes inputs/scenes/seed_{coarse,medium,fine}_{hyperbolic,mohr_coulomb,gp_interface}.yaml
# (issue 4) and inputs/scenes/seed_xfine_hyperbolic.yaml (the weak-scaling study's ~1M-DOF dam,
# issue 20). The files share one body; they differ only in the mesh resolution and the
# slab-cushion interface model. Edit this script, not the generated files, then rerun it:
#   bash scripts/make_seed_scenes.sh
set -euo pipefail
cd "$(dirname "$0")/.."

# resolution -> mesh.cfrd keys (omitted keys: the seed dam, src/mesh/dam_spec.rs CfrdSpec::default)
declare -A mesh=(
  [coarse]="{ fill_layers: 8, elements_per_panel: 1, rockfill_elements: 3, panel_width: 30.0, impoundment_stages: 3 }"
  [medium]="{ fill_layers: 30, elements_per_panel: 1, rockfill_elements: 8, impoundment_stages: 4 }"
  [fine]="{ fill_layers: 86, elements_per_panel: 2, rockfill_elements: 14, impoundment_stages: 6 }"
  [xfine]="{ fill_layers: 110, elements_per_panel: 4, rockfill_elements: 26, impoundment_stages: 6 }"
)
# the stiff interfaces and joints (k2 1e10 Pa/m, 2.5e10 Pa/m) stall the default GAMG preconditioner
# once the slab is placed; a direct solver is used where it is affordable. The coarse and medium
# meshes use the canonical LU (solver.linear_solver: canonical_lu): PETSc's own sequential LU on
# every rank in the mesh's DOF order, whose results are the same bit for bit on 1, 2 or 3 ranks
# (the 1-vs-2-rank comparison of the README). On the coarse mesh PETSc's own LU is the fastest
# direct solver (its first stage: MUMPS 12.1 s for 73 factorizations with the reference BLAS,
# PETSc's LU 1.1 s). The medium mesh factors with MUMPS
# (-canonical_pc_factor_mat_solver_type mumps) on OpenBLAS (libopenblas0-serial): restarted
# after its stage 24 (fill_024, 2 ranks), PETSc's LU did 29 Newton iterations in 200 s (95 % of
# the time in the factorization), MUMPS on the reference BLAS 18 in 120 s, MUMPS on OpenBLAS 99
# in 120 s (UMFPACK 44, SuperLU 5; MUMPS distributed over the 2 ranks, not canonical, 91 in
# 100 s); these runs factored the whole matrix, the constrained and unplaced DOFs included. The
# canonical LU now splits those rows off (linalg::petsc::CanonicalLu), which keeps the
# factorization to the placed mesh and makes MUMPS's results the same on 1 and 2 ranks too.
# The fine mesh (256k DOFs) used the same solver until issue 20: on 2 ranks its first 8 fill stages took 2.0 min
# and its first 15 8.3 min (with the partition balanced per construction band; with the factors
# reused within a stage, solver.reuse_factorization, the first 8 took 1.6 min and the first 14
# 4.6 min), where BoomerAMG
# (-pc_type hypre) took 13.0 min for the first 8; the default GAMG failed in the first fill stage
# (PC failed, SUBPC_ERROR; with -pc_gamg_threshold 0 in the third). The factorization's memory
# grows with the placed mesh: 1.2 GB per rank at fill_016, 3.6 GB at fill_047, 5.6 GB after
# slab_1 and 7.9 GB at fill_086 (README, "Seed dam status").
# Newton tolerance 1e-5 (spec section 8.1 gives 1e-4 as typical): the GP substepping (STOL 1e-4)
# leaves an out-of-balance noise of about STOL x stress x face area, measured on the coarse
# mesh's first fill layer as 3e3 N at a cushion corner node, 2e-6 of the layer's weight; the
# default 1e-8 lies below that floor and every step would be cut back. At most 15 Newton
# iterations: a step that stalls is cut back sooner.
# 8 load steps per stage: every Newton iteration integrates the GP points over the whole step
# increment from the committed state (35-70 substeps per update on average with one step per
# stage), so the cost of a stage is about (iterations per step) x (substeps of the stage's
# path), and a step too large to converge costs its 15 iterations before it is cut back.
# Measured on 2 ranks with the coarse hyperbolic scene: 1 step per stage 251 s (29 cut-backs,
# 390 Newton iterations in converged steps), 8 steps 37 s (5 cut-backs, 490), 16 steps 42 s
# (1 cut-back, 685); on the small GP dam of tests/cfrd_dam.rs (1 rank): 1 step 56 s, 4 steps
# 17 s, 8 steps 13 s, 16 steps 11 s, 32 steps 12 s. Smaller steps also follow the
# path-dependent load path more closely (the seed places its fill in 86 steps). The fine mesh's
# layers are 2 m thick, yet fewer steps per layer cost more there too: with two steps per fill
# layer (mesh.cfrd.fill_load_steps: 2) its first 9 fill stages took 211 s on 2 ranks, with 8
# steps 110 s (a new layer's GP points start unconfined, where the model is softest).
# The medium and fine meshes use the reduced multigrid (solver.linear_solver: reduced_amg, issue
# 20: the slab, interfaces and joints factored by SuperLU_DIST over the ranks, GAMG on the fill,
# inexact Newton; the same bits at every run on the same ranks): on 2 ranks the medium scenes'
# whole runs took 0.59-0.64 of the canonical LU's time with about 0.4 of its memory per rank,
# and their slab tables agree with the LU's to 0.011 MPa and 0.003 cm for the three interface
# models; the fine hyperbolic scene's whole run took 2.15 h with 1.6 GiB per rank, slab stage II
# without a cut-back, and its fill_051 restarted on either solver gave the same fields to 3e-4
# (cfrd::performance, "Linear solvers on the seed dam"). For the canonical LU's results (the same bit for bit on any rank count) run them with
# `--linear-solver canonical_lu -canonical_pc_factor_mat_solver_type mumps`. Their quake scenes
# keep the canonical LU with MUMPS (below).
# The medium and fine scenes start each load step from the last step's rate (solver.predictor:
# extrapolate): the medium hyperbolic scene took 0.82 of the time without it on 2 ranks, with
# 21 % fewer Newton and 29 % fewer GMRES iterations, its slab table within 0.0083 MPa and
# 0.0009 cm (cfrd::performance, "Newton iterations, load steps and the integration noise").
# The coarse scenes keep the plain start: there it cut back more often and saved no time.
# The medium and fine scenes stop Newton at a relative residual of 1e-4 (the coarse ones at
# 1e-5): against a reference of 32 load steps per stage the medium hyperbolic scene's slab table
# and crest settlement are as far off with 1e-4 as with 1e-5 (at most 3.1e-3 and 2.8e-3 against
# 3.4e-3 and 3.4e-3 of their largest magnitudes: the 8 load steps, not the tolerance, set the
# error), in 0.62 of the time (179.9 against 290.5 s on 2 ranks; cfrd::performance, "Accuracy
# against cost", "The medium mesh's Newton tolerance"). So does the extra-fine dam, which at
# 1e-5 stalled on the integration noise in fill_009 (relative residual 6.6e-5 after 8
# cut-backs, 2 ranks, build of ad29fd6). The quake scenes keep 1e-5, with which their runs and
# figures were verified.
# The fine scenes let an easy load step grow to twice the nominal one (solver.step_growth: 2; a
# step converged in one Newton iteration doubles the next, cfrd::solver::step_control): at most
# a quarter of a 2 m layer per step, less fill than the medium mesh's nominal eighth of its 5.7 m
# layers. Restarted after slab stage I, the fine hyperbolic scene's next four fill stages took
# 5 steps and 8 Newton iterations each instead of 8 and 10 (cfrd::performance, "The fine run").
# The extra-fine dam keeps equal steps, so that its weak-scaling checkpoints stay its own.
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
# The GP-interface scenes on the reduced multigrid solve each Newton correction to at most 0.01
# (PETSc's Eisenstat-Walker forcing terms; the solver's default is 0.03, cfrd::linalg::reduced_amg,
# "Inexact Newton"): the GP interface slips during the impoundment and follows the path of the
# converged states, so the medium scene's slab table after impoundment moved 0.079 MPa away from
# the canonical LU's with 0.03, and stays within 0.018 MPa of it with 0.01 (cfrd::performance,
# "Side by side: forcing terms of 0.03 and the predicted-start guard").
gp_forcing='petsc_options: "-snes_ksp_ew_rtol0 0.01 -snes_ksp_ew_rtolmax 0.01", '
# the interface models of a resolution (all three unless named): the extra-fine dam serves the
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
# The seed's earthquake (section 2.4: GP and ideal elasto-plastic interfaces) after impoundment,
# on the canonical LU (its dynamic stages were verified and timed with it; the reduced multigrid
# was not run on a dynamic stage):
# the same dams with the 20 s record of inputs/accel/seed_quake.yaml (cfrd accel; committed as
# inputs/accel/seed_quake.csv), Newmark average acceleration at the record's 0.01 s. The seed
# does not state its damping; generalized plasticity supplies the hysteretic damping and DUT
# analyses add at most a small viscous part (spec seismic section 3.3): Rayleigh 2 % at 1 and
# 5 Hz (the dam's first frequencies lie near 1-1.4 Hz, spec seismic section 4 item 9).
# The probes of the seed's dynamic figures (spec seismic section 3.6): slab element F-A at
# 2813 m (Fig. 14), interface elements I-B at the left bank at 2809 m, I-C at 2838 m (Figs.
# 18-19) and I-D at the crest, 2852 m (Fig. 20), besides I-A at 2711 m; the seed places F-A, I-C
# and I-D at the central section (src/quake_figures.rs).
quake_probes="[ { name: I-A, elevation: 2711.0 }, { name: I-B, elevation: 2809.0, at: left_bank }, { name: I-C, elevation: 2838.0 }, { name: I-D, elevation: 2852.0 }, { name: F-A, elevation: 2813.0, element: slab } ]"
for res in coarse medium; do
  for model in gp_interface mohr_coulomb; do
    f=inputs/scenes/seed_${res}_${model}_quake.yaml
    sed -e "s/^name: seed_${res}_${model}$/name: seed_${res}_${model}_quake/" \
        -e "s/^# requirement: the generated schedule runs every fill, slab and impoundment stage (static).$/# requirement: the generated schedule, then a 20 s three-component earthquake (seed section 2.4)./" \
        -e "s/^# seed Figs. 7-11 as CSV tables and PNG plots; I-A is the seed's interface element at 2711 m$/# seed Figs. 7-11 and, after the quake, Figs. 12-20 as CSV tables and PNG plots (seed probe elements)/" \
        -e "s/^output: { profiles: { probes: .* } }$/output: { profiles: { probes: ${quake_probes} } }/" \
        -e "s/${gp_forcing}//" \
        -e "s/linear_solver: reduced_amg, predictor: extrapolate }/linear_solver: canonical_lu, petsc_options: \"-canonical_pc_factor_mat_solver_type mumps\" }/" \
        -e "s/^solver: { newton_tol: 1.0e-4,/solver: { newton_tol: 1.0e-5,/" \
        "inputs/scenes/seed_${res}_${model}.yaml" > "$f"
    cat >> "$f" <<YAML
# the seed's quake: 3 / 3 / 2 m/s2 (x stream, y axis, z up), 20 s at 0.01 s; fields every 0.1 s
# (the probe histories of Figs. 14 and 18-20 are sampled at these steps)
earthquake: { record: ../accel/seed_quake.csv, damping: { ratio: 0.02, frequencies: [1.0, 5.0] }, output_every: 10 }
YAML
  done
done
echo "wrote inputs/scenes/seed_{coarse,medium,fine}_{hyperbolic,mohr_coulomb,gp_interface}.yaml, seed_xfine_hyperbolic.yaml"
echo "wrote inputs/scenes/seed_{coarse,medium}_{gp_interface,mohr_coulomb}_quake.yaml"
