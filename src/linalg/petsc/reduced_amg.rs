//! Algebraic multigrid on the coupled rows, with the stiff structure split off: the
//! preconditioner of the Krylov solver `linear_solver: reduced_amg` (issue 20).
//!
//! **Why GAMG on the whole Jacobian fails.** A staged dam's Jacobian holds a row for every DOF
//! of the mesh, placed or not: the nodes of fill not yet placed and the constrained DOFs are
//! decoupled rows (a diagonal entry only). Smoothed-aggregation multigrid (GAMG) on that whole
//! matrix fails at the first fill stage of the medium seed mesh (PC failed, PETSc reason −11;
//! `-ksp_view`: 35,151 rows coarsened to 108). The likely cause, not traced inside GAMG: the
//! decoupled nodes become aggregates of one node, which cannot carry the six rigid-body
//! modes, so the coarse operators are singular. With the decoupled rows taken out it carries
//! the first two fill stages and fails in the third; with the translations only as near-null
//! space it carries the whole construction, but once the slab is cast it needs some 490 GMRES
//! iterations per solve (impoundment, relative tolerance 1e-10). The face slab (25.5 GPa, one
//! element through its thickness) and the zero-thickness interfaces and joints, whose normal
//! stiffness is orders of magnitude above the neighbouring rockfill, are what defeats it.
//!
//! **What this shell does.** y = P⁻¹x in three parts:
//! - the decoupled rows by their diagonal, y_i = x_i / a_ii;
//! - the coupled nodes (a node with any coupled DOF keeps all three, so the block has block
//!   size 3) as one block, extracted from the preconditioning matrix at every Jacobian;
//! - on that block a multiplicative field split (block Gauss–Seidel, swept forth and back
//!   under CG): the **structure** (the nodes of zero-thickness elements, both faces, and of
//!   the blocks with incompatible modes, i.e. the face slab; [`ReducedAmg::new`]'s
//!   `structure`) by a complete LU (SuperLU_DIST over the ranks), the **fill** by GAMG with
//!   the rigid-body translations as near-null space.
//!
//! **The same bits at every run.** The structure was first factored by MUMPS over the ranks,
//! whose dynamic scheduling sums in an order that follows message timing: two runs of the
//! embedded default dam on 2 ranks took 373 and 374 Newton iterations and ended 3.3e-3 of a
//! field apart, and three runs of the medium Mohr–Coulomb scene 1,148–1,163 ([`crate::performance`]).
//! With the fill's GAMG replaced by block Jacobi the runs still differed; with the structure
//! by block Jacobi and LU they did not, nor with SuperLU_DIST (`cfrd compare --tolerance 0`:
//! 0 for every such pair), which is the default now (test
//! `multigrid_on_the_coupled_rows_gives_the_same_bits_at_every_run`). The same bits hold for
//! one rank count; other rank counts split the fill and the structure otherwise.
//!
//! **Lagged.** Building the block's preconditioner (extracting the block, factoring the
//! structure, setting the multigrid up) costs as much as several GMRES iterations: on the
//! medium seed mesh's `impound_2` (runs below) 44 builds and 193 GMRES iterations took 10.6 s
//! of linear solves, 11 builds and 345 iterations 7.8 s, some 0.15 s a build and 0.02 s an
//! iteration. Within a stage (the solver is made afresh at every stage) the multigrid of an
//! earlier Jacobian is kept (the structure's factors: below) while the solves need at most
//! 20 Krylov iterations (`-reduced_refresh_after N`; 0 builds it at every Jacobian), and
//! built afresh at the Jacobian after a solve that needed more or whose preconditioner
//! failed, or at once when the coupled nodes change.
//!
//! **What goes stale is the structure.** Between those builds the structure alone is
//! factored afresh at every Jacobian whose last solve needed more than
//! `-reduced_structure_refresh_after N` applications (default 0: every Jacobian), the fill's
//! multigrid kept; SuperLU_DIST keeps the sparsity pattern's ordering and the row
//! permutation of the stage's first factorization (`SamePattern_SameRowPerm`), since the
//! interfaces change the values, not the pattern. The run summary counts the structure's
//! factorizations as `factorizations` and the multigrid's set-ups as `multigrid_builds`.
//! Why (the fine seed mesh's `fill_051` from the checkpoint after slab stage I, 2 ranks, one
//! run each, the machine otherwise idle; prototypes of this code selected by options): with the whole preconditioner lagged as above 134 GMRES
//! iterations for 10 Newton iterations; built afresh at every Jacobian 87; the multigrid
//! afresh on lagged structure factors 145; the structure afresh on the lagged multigrid 88,
//! in 14.2 s of linear solves against 18.2 s. The hyperbolic interface's tangent follows its
//! stress, and the slab hangs on it: a stale factor of that coupling costs GMRES iterations,
//! a stale multigrid of the fill hardly any.
//!
//! **Zero pivots.** SuperLU_DIST pivots statically (the row order chosen before the
//! numbers are known), so a structure block that a state leaves singular, or nearly so,
//! meets a zero pivot. This happened on the medium GP-interface seed scene with looser
//! forcing terms (`-snes_ksp_ew_rtolmax 0.05`): a predicted start of `slab_3` with internal
//! forces of 3.8e26 N (such starts are now dropped by the solver's step) gave
//! `U(i,i) is exactly zero`, and every cut-back after it failed the same way (PC failed,
//! PETSc reason −11) until the run stopped. Pivots below √ε·‖A‖ are therefore replaced by
//! that value (`-mat_superlu_dist_replacetinypivot`): the factors stay a preconditioner, and
//! GMRES on the true Jacobian makes up the difference. Where no pivot is that small nothing
//! changes: none was replaced in the 10 factorizations each of the fine seed mesh's
//! `fill_051` and `impound_1` (`-reduced_fieldsplit_structure_mat_superlu_dist_statprint`,
//! the same Newton and GMRES iterations as without), and the medium hyperbolic scene gave the
//! same bits as with c991192's build (`cfrd compare --tolerance 0`: 0 for every field; the
//! build of bcb863c's code with c991192's forcing terms).
//!
//! **Inexact Newton.** With this solver the Newton corrections are solved only as tightly as
//! Newton's own convergence needs (Eisenstat–Walker forcing terms, PETSc's `-snes_ksp_ew`;
//! the scene's `rtol` is then not used): to a relative 0.03, or more tightly where PETSc's
//! default rule asks for it as Newton converges (`-snes_ksp_ew_rtol0`, `-snes_ksp_ew_rtolmax`;
//! `-snes_ksp_ew false` solves to `rtol`). Looser forcing terms save GMRES iterations but may
//! cost Newton iterations, i.e. assemblies and, since the structure is factored at every
//! Jacobian, factorizations.
//!
//! From 0.01 to 0.03 (commit bcb863c and the one after it; 2 ranks, one run each, the rest of
//! the machine stopped; the fine seed mesh's stages restarted from the checkpoints after
//! `slab_1` and after `slab_3` with c991192's build, `-log_view` and the option given or
//! not; the medium scenes whole, with a build of bcb863c's code and the forcing terms of the
//! row):
//!
//! | run | forcing terms | Newton iterations | GMRES iterations | linear solves | stage or run time |
//! |---|---|---|---|---|---|
//! | fine `fill_051` | 0.01 | 10 | 88 | 15.0 s (`KSPSolve`) | 27.0 s |
//! | fine `fill_051` | 0.03 | 10 | 70 | – | – |
//! | fine `fill_051` | 0.05 | 10 | 61 | 11.5 s | 23.1 s |
//! | fine `impound_1` | 0.01 | 11 | 71 | 30.8 s | 52.2 s |
//! | fine `impound_1` | 0.03 | 10 | 44 | – | – |
//! | fine `impound_1` | 0.05 | 10 | 36 | 24.3 s | 43.5 s |
//! | medium GP interface, whole | 0.01 | 529 | 4,289 | 95.3 s (`phase_seconds`) | 190.9 s |
//! | medium GP interface, whole | 0.03 | 531 | 3,230 | 79.5 s | 176.9 s |
//! | medium GP interface, whole | 0.05 | 534 | 2,849 | 76.1 s | 168.5 s |
//! | medium hyperbolic, whole | 0.01 | 512 | 4,149 | 74.6 s | 148.0 s |
//! | medium hyperbolic, whole | 0.03 | 513 | 3,128 | 75.4 s | 159.9 s |
//! | medium hyperbolic, whole | 0.05 | 523 | 2,786 | 69.4 s | 151.0 s |
//!
//! (The fine stages with 0.03, build of e25ea71, shared the machine with the tests: their
//! counts only.) The medium hyperbolic runs spread by more than their differences (its assembly took
//! 71.4–81.7 s for 512–523 Newton iterations); the GP interface's solves and the fine
//! stages' gain a sixth to a fifth. 0.05 is not the default because it costs Newton
//! iterations on the small GP dam of `tests/cfrd_dam.rs` (2 ranks): 293 against the
//! canonical LU's 257, more than the 10 % that test allows; 0.03 took 273 (1 rank 272)
//! against 262 and 0.02 264 (268) in runs with the option given to every run of the test.
//!
//! The GP-interface seed scenes give 0.01 (`-snes_ksp_ew_rtol0 0.01 -snes_ksp_ew_rtolmax
//! 0.01` in their `petsc_options`): with 0.03 the medium one's slab table after impoundment lay
//! 0.079 MPa from the canonical LU's, with 0.01 within 0.018 MPa, where the construction agrees
//! to 6e-4 MPa either way (the slipping GP interface follows the converged states;
//! `crate::performance`, "Linear solvers on the seed dam").
//!
//! The earlier choice of 0.01, measured on the medium hyperbolic scene, 2 ranks, restarted
//! from the checkpoint after slab stage I (`cfrd run inputs/scenes/seed_medium_hyperbolic.yaml --restart CK
//! --stop-after-stage 19 --linear-solver reduced_amg`, one run each, the same build, alone on
//! the machine; `stage_seconds` of `summary.json`; single runs, whose assembly time alone
//! varied by up to 40 % between runs of the same Newton iterations):
//!
//! | `fill_018` | wall time | Newton iterations | GMRES iterations | preconditioners built |
//! |---|---|---|---|---|
//! | exact corrections (rtol 1e-7), built every Jacobian | 23.5 s | 30 | 1,007 | 30 |
//! | PETSc's forcing terms (0.3, at most 0.9), built every Jacobian | 14.9 s | 40 | 229 | 40 |
//! | PETSc's forcing terms, lagged (20) | 12.4 s | 40 | 311 | 1 |
//! | forcing terms 0.05, at most 0.1, lagged (20) | 10.6 s | 30 | 325 | 1 |
//! | forcing terms at most 0.01, lagged (20): then the defaults | 13.8 s | 31 | 390 | 2 |
//!
//! On `impound_2` (restarted after `impound_1`): 40.8 s, 31 Newton and 1,243 GMRES iterations
//! with exact corrections; 19.5 s, 37 and 446 with 0.05 / 0.1 (6 builds); 20.6 s, 31 and 515
//! with the defaults (8 builds). With PETSc's forcing terms, building at every Jacobian took
//! 24.2 s (44 builds), lagged after 12 iterations 20.9 s (11), after 20 19.9 s (3), after 40
//! 27.6 s (1 build, 684 GMRES iterations). The 0.01 kept Newton's iterations those of exact
//! corrections: on the small GP dam of `tests/cfrd_dam.rs` (2 ranks) 265 against the
//! canonical LU's 260, where 0.05 / 0.1 took 296. That was with the whole preconditioner
//! lagged, when a Newton iteration cost little beyond its assembly.
//!
//! Options take the prefix `reduced_`: `-reduced_split false` drops the split (GAMG on the
//! whole block), `-reduced_near_null_modes 6` gives GAMG the rotations too (the default is 3:
//! with all six the fill's GAMG reports PC failed at the medium mesh's impoundment, and the
//! whole block's in its third fill stage), `-reduced_fieldsplit_fill_pc_type hypre`,
//! `-reduced_fieldsplit_structure_pc_factor_mat_solver_type ...` and so on choose the parts.
//! Memory and work split between the ranks: each holds its rows of the matrix, its share of
//! the multigrid hierarchy and of the structure's factors.
#![allow(unsafe_code)]

use super::coupling::mark_coupled_rows;
use super::error::{call, chk, to_petsc_int, to_usize, PetscError};
use super::options::{bool_option, default_option, int_option};
use super::pc_shell::{self, PcShell};
use super::vector::{SubVector, Vector};
use crate::linalg::ffi as p;
use std::ffi::{c_char, CStr, CString};
use std::ptr::null_mut;

/// The name the shell reports (`-ksp_view`), and by which it is recognised.
pub const REDUCED_AMG_NAME: &CStr = c"multigrid on the coupled rows";

/// The options prefix of the inner multigrid solve.
const PREFIX: &str = "reduced_";

/// State of the shell: the coupled rows of the current stage, their block and its multigrid.
pub struct ReducedAmg {
    comm: mpi::ffi::MPI_Comm,
    /// Inner solver: `preonly` with GAMG on the coupled block.
    ksp: p::KSP,
    /// The owned coupled rows (global indices, whole nodes).
    rows: Vec<i32>,
    /// `rows` as a block index set of block size 3.
    is: p::IS,
    /// The coupled block of the preconditioning matrix.
    sub: p::Mat,
    /// Coupling marks, laid out like the rows.
    flags: p::Vec,
    /// Diagonal of the preconditioning matrix (the decoupled rows' solution is b_i / a_ii).
    diag: p::Vec,
    /// The owned DOFs of the stiff structure (slab, interfaces, joints), increasing.
    structure: Vec<i32>,
    /// Applications since the last Jacobian: the last solve's Krylov iterations (plus one).
    applies: u32,
    /// Build the block's preconditioner afresh at the next Jacobian once a solve needed more
    /// applications than this (`-reduced_refresh_after`, [`REFRESH_AFTER`]).
    refresh_after: u32,
    /// Factor the structure afresh (keeping the fill's multigrid) at the next Jacobian once a
    /// solve needed more applications than this (`-reduced_structure_refresh_after`,
    /// [`STRUCTURE_REFRESH_AFTER`]).
    structure_refresh_after: u32,
    /// The inner solver is a field split whose sub-solvers exist (set up once).
    split_ready: bool,
    /// Structure factorizations (with the multigrid set up or kept) not yet counted.
    builds: u64,
    /// Set-ups of the fill's multigrid (or of the unsplit block's) not yet counted.
    multigrid_builds: u64,
    /// The last build or application failed: the next Jacobian builds afresh.
    failed: bool,
}

/// The preconditioner of an earlier Jacobian of the stage is kept while the solves it serves
/// need at most this many Krylov iterations (module docs, "Lagged").
const REFRESH_AFTER: p::PetscInt = 20;

/// The structure alone is factored afresh, the fill's multigrid kept, at every Jacobian whose
/// last solve needed more than this many applications: the interfaces' tangent is what goes
/// stale (module docs, "Lagged").
const STRUCTURE_REFRESH_AFTER: p::PetscInt = 0;

impl ReducedAmg {
    /// The shell's state on communicator `comm`; `symmetric` (CG outside) keeps GAMG's
    /// Chebyshev smoothers and sweeps the split forth and back, otherwise the levels are
    /// smoothed by Richardson + SOR (see `configure_ksp`);
    /// `structure`: this rank's DOFs of the stiff structure (global indices, increasing), the
    /// split factored apart from the fill.
    pub fn new(
        comm: mpi::ffi::MPI_Comm,
        symmetric: bool,
        structure: Vec<i32>,
    ) -> Result<Box<ReducedAmg>, PetscError> {
        if symmetric {
            // CG needs a symmetric preconditioner: the split's sweep forth and back
            default_option(
                &format!("-{PREFIX}pc_fieldsplit_type"),
                "symmetric_multiplicative",
            )?;
        } else {
            for level in ["", "fieldsplit_fill_"] {
                default_option(&format!("-{PREFIX}{level}mg_levels_ksp_type"), "richardson")?;
                default_option(&format!("-{PREFIX}{level}mg_levels_pc_type"), "sor")?;
            }
        }
        default_option(&format!("-{PREFIX}fieldsplit_structure_pc_type"), "lu")?;
        default_option(
            &format!("-{PREFIX}fieldsplit_structure_pc_factor_mat_solver_type"),
            "superlu_dist",
        )?;
        // the interfaces change the structure's values, not its pattern or pivots' order
        default_option(
            &format!("-{PREFIX}fieldsplit_structure_mat_superlu_dist_fact"),
            "SamePattern_SameRowPerm",
        )?;
        // a state that leaves the structure singular (module docs, "Zero pivots")
        default_option(
            &format!("-{PREFIX}fieldsplit_structure_mat_superlu_dist_replacetinypivot"),
            "true",
        )?;
        default_option(&format!("-{PREFIX}fieldsplit_fill_pc_type"), "gamg")?;
        Ok(Box::new(ReducedAmg {
            comm,
            ksp: null_mut(),
            rows: Vec::new(),
            is: null_mut(),
            sub: null_mut(),
            flags: null_mut(),
            diag: null_mut(),
            structure,
            applies: 0,
            refresh_after: int_option("-reduced_refresh_after", REFRESH_AFTER)?
                .max(0)
                .unsigned_abs(),
            structure_refresh_after: int_option("-reduced_structure_refresh_after", STRUCTURE_REFRESH_AFTER)?
                .max(0)
                .unsigned_abs(),
            split_ready: false,
            builds: 0,
            multigrid_builds: 0,
            failed: false,
        }))
    }

    /// Makes `pc` apply this shell.
    pub(crate) fn install(&self, pc: p::PC) -> Result<(), PetscError> {
        pc_shell::install(pc, self)
    }

    /// Builds the inner solver's preconditioner on the current block: the structure's factors
    /// and, unless `keep_multigrid` (a split set up before), the fill's multigrid; a failure
    /// of the multigrid or the factorization is `pc`'s.
    fn build(&mut self, pc: p::PC, keep_multigrid: bool) -> Result<(), PetscError> {
        if self.split_ready {
            self.keep_fill_multigrid(keep_multigrid)?;
        }
        self.builds += 1;
        self.multigrid_builds += u64::from(!keep_multigrid);
        call!(KSPSetOperators(self.ksp, self.sub, self.sub))?;
        call!(KSPSetUp(self.ksp))?;
        let mut inner: p::PC = null_mut();
        let mut failed: p::PCFailedReason = 0;
        call!(KSPGetPC(self.ksp, &mut inner))?;
        call!(PCGetFailedReason(inner, &mut failed))?;
        if failed != 0 {
            self.failed = true;
            call!(PCSetFailedReason(pc, p::PC_SUBPC_ERROR))?;
        }
        let mut kind: p::PCType = std::ptr::null();
        call!(PCGetType(inner, &mut kind))?;
        // SAFETY: PETSc's type name, a NUL-terminated static string.
        self.split_ready = unsafe { std::ffi::CStr::from_ptr(kind) }.to_bytes()
            == &p::PCFIELDSPLIT[..p::PCFIELDSPLIT.len() - 1];
        Ok(())
    }

    /// Makes the fill's split keep (`keep`) or set up afresh its multigrid at its next set-up.
    fn keep_fill_multigrid(&mut self, keep: bool) -> Result<(), PetscError> {
        let mut inner: p::PC = null_mut();
        call!(KSPGetPC(self.ksp, &mut inner))?;
        let (mut n, mut subs): (i32, *mut p::KSP) = (0, null_mut());
        call!(PCFieldSplitGetSubKSP(inner, &mut n, &mut subs))?;
        let set = match n {
            // SAFETY: the split's two sub-solvers, the fill's second (`set_splits`).
            2 => call!(KSPSetReusePreconditioner(*subs.add(1), keep.into())),
            _ => Ok(()),
        };
        let (line, empty) = (0, c"".as_ptr());
        // SAFETY: the array PETSc allocated for the caller (PCFieldSplitGetSubKSP's contract).
        let slot = &mut subs as *mut *mut p::KSP as *mut std::ffi::c_void;
        let freed = unsafe { p::PetscFreeA(1, line, empty, empty, slot) };
        set.and(chk(freed, "PetscFree"))
    }

    /// Structure factorizations since the last call (with or without a new multigrid).
    pub fn take_builds(&mut self) -> u64 {
        std::mem::take(&mut self.builds)
    }

    /// Set-ups of the multigrid since the last call.
    pub fn take_multigrid_builds(&mut self) -> u64 {
        std::mem::take(&mut self.multigrid_builds)
    }

    /// The owned rows of every node with a coupled DOF (all three of its DOFs), increasing.
    fn coupled_nodes(&self) -> Result<Vec<i32>, PetscError> {
        let flags = Vector::borrowed(self.flags);
        let (lo, _) = flags.ownership_range_raw()?;
        let nodes: Vec<usize> = flags.read(|f| {
            f.chunks(3)
                .enumerate()
                .filter(|(_, node)| node.iter().any(|&m| m > 0.0))
                .map(|(k, _)| k)
                .collect()
        })?;
        let mut rows = Vec::with_capacity(3 * nodes.len());
        for k in nodes {
            let first = lo + 3 * to_petsc_int(k, "coupled node")?;
            rows.extend((0..3).map(|c| first + c));
        }
        Ok(rows)
    }

    /// Whether `local` holds on any rank (collective).
    fn any_rank(&self, local: bool) -> Result<bool, PetscError> {
        let (mine, mut any) = (i32::from(local), 0i32);
        // SAFETY: one int in and out on the solver's communicator, called on every rank.
        let rc = unsafe {
            mpi::ffi::MPI_Allreduce(
                &mine as *const i32 as *const std::ffi::c_void,
                &mut any as *mut i32 as *mut std::ffi::c_void,
                1,
                mpi::ffi::RSMPI_INT32_T,
                mpi::ffi::RSMPI_MAX,
                self.comm,
            )
        };
        chk(rc, "MPI_Allreduce")?;
        Ok(any != 0)
    }

    /// A new coupled block of `pmat` on `rows`, with the rigid-body modes of `pmat`'s
    /// near-null space restricted to it and orthonormalized.
    fn new_block(&mut self, pmat: p::Mat, rows: Vec<i32>) -> Result<(), PetscError> {
        self.destroy_block();
        let blocks: Vec<i32> = rows.iter().step_by(3).map(|&r| r / 3).collect();
        let n_blocks = to_petsc_int(blocks.len(), "coupled nodes")?;
        call!(ISCreateBlock(
            self.comm,
            3,
            n_blocks,
            blocks.as_ptr(),
            p::PETSC_COPY_VALUES,
            &mut self.is
        ))?;
        self.rows = rows;
        call!(MatCreateSubMatrix(
            pmat,
            self.is,
            self.is,
            p::MAT_INITIAL_MATRIX,
            &mut self.sub
        ))?;
        let mut ns: p::MatNullSpace = null_mut();
        call!(MatGetNearNullSpace(pmat, &mut ns))?;
        if ns.is_null() {
            return self.new_inner_solver(null_mut());
        }
        let mut sub_ns = self.restricted_null_space(ns, self.is)?;
        let set = call!(MatSetNearNullSpace(self.sub, sub_ns));
        let inner = set.and_then(|()| self.new_inner_solver(sub_ns));
        // SAFETY: the matrix keeps its own reference.
        unsafe { p::MatNullSpaceDestroy(&mut sub_ns) };
        inner
    }

    /// A new inner solver for the coupled block: GAMG on the whole block, or, where the block
    /// holds structure DOFs on some rank (and `-reduced_split` is not false), a multiplicative
    /// field split with LU on the structure and GAMG on the fill, whose near-null space is
    /// `sub_ns` restricted to it.
    fn new_inner_solver(&mut self, sub_ns: p::MatNullSpace) -> Result<(), PetscError> {
        // SAFETY: created here or null, destroyed once.
        unsafe { p::KSPDestroy(&mut self.ksp) };
        self.split_ready = false;
        call!(KSPCreate(self.comm, &mut self.ksp))?;
        let prefix = CString::new(PREFIX).expect("no NUL");
        call!(KSPSetOptionsPrefix(self.ksp, prefix.as_ptr()))?;
        call!(KSPSetType(self.ksp, p::KSPPREONLY.as_ptr() as *const c_char))?;
        let mut pc: p::PC = null_mut();
        call!(KSPGetPC(self.ksp, &mut pc))?;
        let structure: Vec<usize> = (0..self.rows.len())
            .step_by(3)
            .filter(|&k| self.structure.binary_search(&self.rows[k]).is_ok())
            .collect();
        if self.any_rank(!structure.is_empty())? && split_wanted()? {
            call!(PCSetType(pc, p::PCFIELDSPLIT.as_ptr() as *const c_char))?;
            self.set_splits(pc, &structure, sub_ns)?;
        } else {
            call!(PCSetType(pc, p::PCGAMG.as_ptr() as *const c_char))?;
        }
        call!(KSPSetFromOptions(self.ksp))
    }

    /// The two splits of the coupled block: `structure` (local row positions of structure
    /// nodes, first DOF each) and the fill (the other nodes), the latter with the near-null
    /// space `sub_ns` restricted to it.
    fn set_splits(
        &mut self,
        pc: p::PC,
        structure: &[usize],
        sub_ns: p::MatNullSpace,
    ) -> Result<(), PetscError> {
        let (mut lo, mut hi) = (0, 0);
        call!(MatGetOwnershipRange(self.sub, &mut lo, &mut hi))?;
        let is_structure: Vec<bool> = {
            let mut m = vec![false; self.rows.len() / 3];
            for &k in structure {
                m[k / 3] = true;
            }
            m
        };
        let blocks = |want: bool| -> Result<Vec<i32>, PetscError> {
            (0..is_structure.len())
                .filter(|&b| is_structure[b] == want)
                .map(|b| Ok(lo / 3 + to_petsc_int(b, "node of the coupled block")?))
                .collect()
        };
        for (name, want) in [("structure", true), ("fill", false)] {
            let b = blocks(want)?;
            let n_blocks = to_petsc_int(b.len(), "nodes of a split")?;
            let mut is: p::IS = null_mut();
            call!(ISCreateBlock(
                self.comm,
                3,
                n_blocks,
                b.as_ptr(),
                p::PETSC_COPY_VALUES,
                &mut is
            ))?;
            let mut composed = Ok(());
            if !want && !sub_ns.is_null() {
                composed = self.compose_null_space(is, sub_ns);
            }
            let c_name = CString::new(name).expect("no NUL");
            let set = composed.and_then(|()| call!(PCFieldSplitSetIS(pc, c_name.as_ptr(), is)));
            // SAFETY: the field split keeps its own reference.
            unsafe { p::ISDestroy(&mut is) };
            set?;
        }
        Ok(())
    }

    /// Attaches `sub_ns` restricted to the rows `is` of the coupled block to `is`, where the
    /// field split looks for its split's near-null space.
    fn compose_null_space(&self, is: p::IS, sub_ns: p::MatNullSpace) -> Result<(), PetscError> {
        let mut ns = self.restricted_null_space(sub_ns, is)?;
        let key = CString::new("nearnullspace").expect("no NUL");
        let r = call!(PetscObjectCompose(
            is as p::PetscObject,
            key.as_ptr(),
            ns as p::PetscObject
        ));
        // SAFETY: the index set keeps its own reference.
        unsafe { p::MatNullSpaceDestroy(&mut ns) };
        r
    }

    /// The near-null space `ns` restricted to the rows `is` of its vectors.
    fn restricted_null_space(&self, ns: p::MatNullSpace, is: p::IS) -> Result<p::MatNullSpace, PetscError> {
        let modes = self.restricted_modes(ns, is)?;
        let mut out: p::MatNullSpace = null_mut();
        let made = to_petsc_int(modes.len(), "near-null modes").and_then(|n| {
            call!(MatNullSpaceCreate(
                self.comm,
                p::PETSC_FALSE,
                n,
                modes.as_ptr(),
                &mut out
            ))
        });
        // SAFETY: the null space keeps its own references to the vectors.
        for mut v in modes {
            unsafe { p::VecDestroy(&mut v) };
        }
        made.map(|()| out)
    }

    /// The vectors of `ns` on the coupled rows, orthonormalized by modified Gram–Schmidt
    /// (a mode with nothing left is dropped).
    fn restricted_modes(&self, ns: p::MatNullSpace, is: p::IS) -> Result<Vec<p::Vec>, PetscError> {
        let (mut has_const, mut n, mut vecs) = (p::PETSC_FALSE, 0, std::ptr::null());
        call!(MatNullSpaceGetVecs(ns, &mut has_const, &mut n, &mut vecs))?;
        let mut modes: Vec<p::Vec> = Vec::new();
        for k in 0..to_usize(n, "near-null vectors")?.min(near_null_modes()?) {
            // SAFETY: `n` vectors owned by the null space.
            let v = unsafe { *vecs.add(k) };
            let mut copy: p::Vec = null_mut();
            let view = SubVector::get(v, is)?;
            call!(VecDuplicate(view.sub, &mut copy))?;
            call!(VecCopy(view.sub, copy))?;
            view.restore()?;
            for &q in &modes {
                let mut d = 0.0;
                call!(VecDot(copy, q, &mut d))?;
                call!(VecAXPY(copy, -d, q))?;
            }
            let mut norm = 0.0;
            call!(VecNormalize(copy, &mut norm))?;
            if norm > 1e-12 {
                modes.push(copy);
            } else {
                // SAFETY: created by VecDuplicate above, destroyed once.
                unsafe { p::VecDestroy(&mut copy) };
            }
        }
        Ok(modes)
    }

    /// Destroys the coupled block and its index set (null handles are accepted).
    fn destroy_block(&mut self) {
        // SAFETY: handles created by this shell, destroyed once.
        unsafe {
            p::MatDestroy(&mut self.sub);
            p::ISDestroy(&mut self.is);
        }
    }
}

impl PcShell for ReducedAmg {
    const NAME: &'static CStr = REDUCED_AMG_NAME;

    /// Finds the coupled nodes of the preconditioning matrix and, when they changed or the last
    /// solve needed more than `refresh_after` applications, extracts their block (a new one
    /// with its near-null space when they changed) and builds its preconditioner; when it
    /// needed more than `structure_refresh_after`, factors the structure afresh and keeps the
    /// fill's multigrid; otherwise the earlier one stays (module docs, "Lagged").
    fn setup(&mut self, pc: p::PC) -> Result<(), PetscError> {
        let (mut a, mut pmat): (p::Mat, p::Mat) = (null_mut(), null_mut());
        call!(PCGetOperators(pc, &mut a, &mut pmat))?;
        if self.flags.is_null() {
            call!(MatCreateVecs(pmat, &mut self.flags, &mut self.diag))?;
        }
        mark_coupled_rows(pmat, self.flags)?;
        call!(MatGetDiagonal(pmat, self.diag))?;
        let rows = self.coupled_nodes()?;
        let changed = self.any_rank(rows != self.rows)?;
        let applies = std::mem::take(&mut self.applies);
        let stale = applies > self.refresh_after || std::mem::take(&mut self.failed);
        if changed || self.sub.is_null() {
            self.new_block(pmat, rows)?;
        } else if stale || (self.split_ready && applies > self.structure_refresh_after) {
            call!(MatCreateSubMatrix(
                pmat,
                self.is,
                self.is,
                p::MAT_REUSE_MATRIX,
                &mut self.sub
            ))?;
        } else {
            return Ok(());
        }
        self.build(pc, !(stale || changed || !self.split_ready))
    }

    /// y = P⁻¹ x: the decoupled rows by their diagonal, the coupled block by the multigrid.
    fn apply(&mut self, pc: p::PC, x: p::Vec, y: p::Vec) -> Result<(), PetscError> {
        self.applies += 1;
        call!(VecPointwiseDivide(y, x, self.diag))?;
        let xs = SubVector::get(x, self.is)?;
        let ys = SubVector::get(y, self.is)?;
        let solved = call!(KSPSolve(self.ksp, xs.sub, ys.sub));
        xs.restore()?;
        ys.restore()?;
        solved?;
        let mut reason = 0;
        call!(KSPGetConvergedReason(self.ksp, &mut reason))?;
        if reason < 0 {
            self.failed = true;
            call!(PCSetFailedReason(pc, p::PC_SUBPC_ERROR))?;
        }
        Ok(())
    }
}

impl Drop for ReducedAmg {
    fn drop(&mut self) {
        self.destroy_block();
        // SAFETY: handles created by this shell, destroyed once.
        unsafe {
            p::KSPDestroy(&mut self.ksp);
            p::VecDestroy(&mut self.flags);
            p::VecDestroy(&mut self.diag);
        }
    }
}

/// How many of the near-null space's vectors the multigrid gets (`-reduced_near_null_modes`;
/// default the three translations, 6 adds the rotations; module docs).
fn near_null_modes() -> Result<usize, PetscError> {
    to_usize(
        int_option("-reduced_near_null_modes", 3)?.max(0),
        "-reduced_near_null_modes",
    )
}

/// Whether the coupled block is split into structure and fill (`-reduced_split`, default
/// true).
fn split_wanted() -> Result<bool, PetscError> {
    bool_option("-reduced_split", true)
}
