//! [`CanonicalLu`], the direct solver whose results do not depend on the rank count.
#![allow(unsafe_code)]

use super::coupling::mark_coupled_rows;
use super::error::{call, to_petsc_int, to_usize, PetscError};
use super::gather::Gather;
use super::lagged_lu::LaggedLu;
use super::pc_shell::{self, PcShell};
use super::vector::Vector;
use crate::linalg::ffi as p;
use std::ffi::CStr;
use std::ptr::null_mut;

/// A direct solver whose result does not depend on the rank count (a preconditioner shell
/// under `preonly`): at every Jacobian the rows coupled to others are found, their block of the
/// distributed matrix is gathered on every rank, permuted into the mesh's own DOF order (node by
/// node in input order, the `canonical` list giving the PETSc index of each) and factored by a
/// sequential LU; each solve gathers the right-hand side in the same order and keeps the owned
/// part of the solution.
///
/// Decoupled rows are those with no nonzero off the diagonal in their row or column: the
/// constrained DOFs (their rows and columns are zeroed, `Matrix::zero_rows_columns_only`) and
/// the nodes of fill not yet placed. Their solution is a division. The gather, the permutation
/// and the factorization see only the placed part of the mesh, not the stored zeros of the rest
/// (on the fine seed mesh, before this, a third of the time went into gathering the whole
/// matrix); the symbolic factorization is reused while the coupled rows stay the same (within
/// a stage).
///
/// The factorization is PETSc's own sequential LU unless the options choose another package:
/// `-canonical_pc_factor_mat_solver_type mumps` (the medium seed scenes use it) factors with
/// MUMPS, which with an optimized BLAS (`libopenblas0-serial`, installed by
/// `ci/install-deps.sh`) was 5.5 times faster than PETSc's LU on the medium seed dam (35,151
/// DOFs, README "Seed dam status"). With the decoupled rows split off both give the same results
/// bit for bit on 1 and 2 ranks (tests `cfrd_dam`); without the split, MUMPS's 1-rank solves
/// differed from its 2-rank ones in the last bits (measured), which the path-dependent
/// plasticity carried to 6e-3 in the results of the coarse seed run. MUMPS orders the block
/// with PORD: Debian's MUMPS is built without METIS and SCOTCH (`-canonical_mat_mumps_icntl_7
/// 5` or `3` falls back, the parallel analysis `icntl_28 2` fails with INFO(1) = −38). At the
/// first slab stage of the medium seed dam (restarted after fill_017) the factors held 12.9 M
/// entries with PORD, 14.2 M with AMF and 18.4 M with AMD or QAMD; a METIS nested dissection
/// handed to MUMPS as its pivot order (a registered PETSc ordering, tried and removed) gave
/// 12.6 M, 2 % fewer, not worth a second code path.
///
/// Reuse of factors (`solver.reuse_factorization`, on by default). Within a stage the Jacobian
/// changes little from one Newton iteration or load step to the next, and on the fine seed mesh
/// the factorizations took most of the time. With reuse the factors of an earlier Jacobian are
/// kept as the preconditioner of right-preconditioned GMRES on the current coupled block
/// (relative tolerance 1e-9 on the true residual); the block is factored again at the next
/// Jacobian once a solve needed more than 8 GMRES iterations, and at once when GMRES does not
/// converge in 30 (the solve is then repeated with the new factors), so a changed tangent (an
/// interface opening, rockfill yielding) costs a factorization, not a failed step. A new stage
/// (a new coupled set) always starts with a factorization. `-canonical_refactor_after N`,
/// `-canonical_ksp_max_it N` and `-canonical_ksp_rtol R` change the three numbers. On the fine
/// seed mesh (2 ranks) the first 11 fill stages took 170 s with refactoring after 8 iterations,
/// 186 s after 4 and 201 s after 30 (with GMRES allowed 100); its first 8 fill stages took 90 s,
/// against 120 s with a factorization at every Jacobian. Measured on the small GP dam of
/// `tests/cfrd_dam.rs` (test `reused_factors_give_the_results_of_fresh_factors`): 72
/// factorizations instead of 361 for 264 Newton iterations, and results within the difference
/// the Newton tolerance itself makes. The decisions depend only on the sequential inner solve,
/// which is the same on every rank, so the results stay rank-count independent.
///
/// The gathered, permuted matrix is the same bit for bit at any rank count (the assembly is
/// rank-count independent, see `solver::discretization`), and so are the split, the
/// fill-reducing ordering, the factors and every solution: with it a staged elasto-plastic run
/// gives the same result on 1 and 2 ranks, not merely the same to a tolerance. Its cost is that
/// of a serial direct solve on every rank, so it suits meshes up to some 10⁵ DOFs. Its options
/// take the prefix `canonical_` (e.g. `-canonical_pc_factor_mat_ordering_type rcm`).
pub struct CanonicalLu {
    canonical: Vec<i32>,
    /// Per row (distributed like the matrix): nonzero when the row's DOF is coupled.
    flags: Option<Vector>,
    /// The matrix diagonal (distributed like the matrix).
    diag: Option<Vector>,
    /// Gathers a distributed vector into the canonical order on every rank.
    gather: Option<Gather>,
    /// For every owned entry: its position in the canonical order.
    local_pos: Vec<usize>,
    /// Canonical positions of the coupled rows (increasing), the rows the factorization sees.
    keep: Vec<usize>,
    /// The PETSc indices of the coupled rows, increasing (what is gathered).
    is_rows: p::IS,
    /// For every coupled row in canonical order: its place among `is_rows`.
    is_perm: p::IS,
    /// The gathered coupled block (array of one, from `MatCreateSubMatrices`).
    sub: *mut p::Mat,
    /// The coupled block in canonical order, the matrix factored (kept while the coupled rows
    /// stay the same, so its symbolic factorization is reused).
    reduced: p::Mat,
    /// For every canonical position: its index among the coupled rows, or `None` when
    /// decoupled.
    reduced_index: Vec<Option<usize>>,
    /// Diagonal in canonical order (the solution of a decoupled row is b_i / a_ii).
    diagonal: Vec<f64>,
    /// The inner sequential LU (its factors possibly those of an earlier Jacobian).
    inner: LaggedLu,
    rhs: Option<Vector>,
    solution: Option<Vector>,
}

impl CanonicalLu {
    /// The solver's state for the PETSc indices `canonical` of the DOFs in the mesh's order;
    /// `reuse`: keep factors of earlier Jacobians; `time_stepping`: for a dynamic stage
    /// ([`super::lagged_lu`]).
    pub(super) fn new(
        canonical: Vec<i32>,
        reuse: bool,
        time_stepping: bool,
    ) -> Result<Box<CanonicalLu>, PetscError> {
        // SAFETY: a constant handle set by MPI_Init.
        let self_comm = unsafe { mpi::ffi::RSMPI_COMM_SELF };
        Ok(Box::new(CanonicalLu {
            canonical,
            flags: None,
            diag: None,
            gather: None,
            local_pos: Vec::new(),
            keep: Vec::new(),
            is_rows: null_mut(),
            is_perm: null_mut(),
            sub: null_mut(),
            reduced: null_mut(),
            reduced_index: Vec::new(),
            diagonal: Vec::new(),
            inner: LaggedLu::new(self_comm, "canonical_", reuse, None, time_stepping)?,
            rhs: None,
            solution: None,
        }))
    }

    /// Makes `ksp` apply this solver (`preonly` with the shell preconditioner).
    pub(super) fn install(&self, ksp: p::KSP) -> Result<(), PetscError> {
        pc_shell::install_preonly(ksp, self)
    }

    /// Numeric factorizations since the last call.
    pub(super) fn take_factorizations(&mut self) -> u64 {
        self.inner.take_factorizations()
    }

    /// Rows of the matrices this rank's solver holds ([`LaggedLu::held_rows`]): the gathered
    /// Jacobian's, all of them.
    pub(super) fn held_rows(&self) -> Result<Option<u64>, PetscError> {
        self.inner.held_rows()
    }

    /// Krylov iterations of the last solve (1 for a direct solve).
    pub(super) fn last_iterations(&self) -> u32 {
        self.inner.last_iterations
    }

    /// The absolute tolerance of a dynamic stage's solves (`LaggedLu::set_absolute_tolerance`).
    pub(super) fn set_absolute_tolerance(&mut self, atol: f64) -> Result<(), PetscError> {
        self.inner.set_absolute_tolerance(atol)
    }

    /// Which rows of `pmat` are coupled, in canonical order, and the diagonal in that order.
    ///
    /// A row is decoupled when no entry off the diagonal in its row or column is nonzero: the
    /// constrained DOFs and the nodes of fill not yet placed. Each rank marks its own rows and
    /// the columns of their nonzero entries (a count, so the sum is exact in any order); the
    /// marks are then gathered in the canonical order, so every rank finds the same split.
    fn coupling(&mut self, pmat: p::Mat) -> Result<(Vec<bool>, Vec<f64>), PetscError> {
        if self.flags.is_none() {
            let (mut right, mut left): (p::Vec, p::Vec) = (null_mut(), null_mut());
            call!(MatCreateVecs(pmat, &mut right, &mut left))?;
            let (flags, diag) = (Vector { raw: right }, Vector { raw: left });
            let (lo, hi) = flags.ownership_range()?;
            let mut inverse = vec![0usize; self.canonical.len()];
            for (i, &g) in self.canonical.iter().enumerate() {
                inverse[to_usize(g, "DOF index")?] = i;
            }
            self.local_pos = inverse[lo..hi].to_vec();
            self.gather = Some(Gather::new(&flags, &self.canonical)?);
            self.flags = Some(flags);
            self.diag = Some(diag);
        }
        let (Some(flags), Some(diag), Some(gather)) =
            (self.flags.as_mut(), self.diag.as_mut(), self.gather.as_mut())
        else {
            unreachable!("created above");
        };
        mark_coupled_rows(pmat, flags.raw)?;
        call!(MatGetDiagonal(pmat, diag.raw))?;
        let coupled: Vec<bool> = gather
            .gather(flags)?
            .read(|s| s.iter().map(|&f| f > 0.0).collect())?;
        let diagonal: Vec<f64> = gather.gather(diag)?.read(|s| s.to_vec())?;
        Ok((coupled, diagonal))
    }

    /// Starts over with the coupled rows `keep` (canonical positions, increasing): new index
    /// sets, a new block and so a new symbolic factorization (at a new stage).
    fn new_coupled_set(&mut self, keep: Vec<usize>) -> Result<(), PetscError> {
        // SAFETY: handles created here, destroyed once (null is accepted).
        unsafe {
            if !self.sub.is_null() {
                p::MatDestroySubMatrices(1, &mut self.sub);
            }
            self.sub = null_mut();
            p::MatDestroy(&mut self.reduced);
            p::ISDestroy(&mut self.is_rows);
            p::ISDestroy(&mut self.is_perm);
        }
        let n = self.canonical.len();
        self.reduced_index = vec![None; n];
        for (k, &i) in keep.iter().enumerate() {
            self.reduced_index[i] = Some(k);
        }
        let mut rows: Vec<i32> = keep.iter().map(|&i| self.canonical[i]).collect();
        rows.sort_unstable();
        let perm = keep
            .iter()
            .map(|&i| {
                let place = rows.binary_search(&self.canonical[i]).expect("a gathered row");
                to_petsc_int(place, "place of a gathered row")
            })
            .collect::<Result<Vec<p::PetscInt>, PetscError>>()?;
        let (n_rows, n_perm) = (
            to_petsc_int(rows.len(), "coupled rows")?,
            to_petsc_int(perm.len(), "coupled rows")?,
        );
        self.keep = keep;
        // SAFETY: a constant handle set by MPI_Init.
        let self_comm = unsafe { mpi::ffi::RSMPI_COMM_SELF };
        call!(ISCreateGeneral(
            self_comm,
            n_rows,
            rows.as_ptr(),
            p::PETSC_COPY_VALUES,
            &mut self.is_rows
        ))?;
        call!(ISCreateGeneral(
            self_comm,
            n_perm,
            perm.as_ptr(),
            p::PETSC_COPY_VALUES,
            &mut self.is_perm
        ))?;
        self.rhs = Some(Vector::seq(self.keep.len())?);
        self.solution = Some(Vector::seq(self.keep.len())?);
        Ok(())
    }

    /// Solves the coupled block into `solution` from `rhs` ([`LaggedLu::solve`]). Returns
    /// whether the solve succeeded.
    fn solve_coupled(&mut self) -> Result<bool, PetscError> {
        let (Some(rhs), Some(solution)) = (self.rhs.as_ref(), self.solution.as_ref()) else {
            unreachable!("set up before the first solve");
        };
        self.inner.solve(rhs.raw, solution.raw)
    }
}

impl PcShell for CanonicalLu {
    const NAME: &'static CStr = c"canonical LU (mesh DOF order, rank-count independent)";

    /// Finds the coupled rows of the preconditioning matrix of `pc`, gathers their block on
    /// every rank, permutes it into the canonical order and factors it.
    fn setup(&mut self, pc: p::PC) -> Result<(), PetscError> {
        let (mut a, mut pmat): (p::Mat, p::Mat) = (null_mut(), null_mut());
        call!(PCGetOperators(pc, &mut a, &mut pmat))?;
        let (coupled, diagonal) = self.coupling(pmat)?;
        let n = self.canonical.len();
        let keep: Vec<usize> = (0..n).filter(|&i| coupled[i]).collect();
        let singular = (0..n).any(|i| !coupled[i] && diagonal[i] == 0.0);
        self.diagonal = diagonal;
        let block = if keep != self.keep || self.is_rows.is_null() {
            self.new_coupled_set(keep)?;
            p::MAT_INITIAL_MATRIX
        } else {
            p::MAT_REUSE_MATRIX
        };
        let mut failed: p::PCFailedReason = 0;
        if !self.keep.is_empty() {
            call!(MatCreateSubMatrices(
                pmat,
                1,
                &self.is_rows,
                &self.is_rows,
                block,
                &mut self.sub
            ))?;
            // B(k, l) = A(canonical[keep[k]], canonical[keep[l]])
            let mut b: p::Mat = null_mut();
            // SAFETY (inside the call): `sub` holds one matrix after MatCreateSubMatrices.
            call!(MatPermute(*self.sub, self.is_perm, self.is_perm, &mut b))?;
            if self.reduced.is_null() {
                self.reduced = b;
                call!(KSPSetOperators(self.inner.ksp, self.reduced, self.reduced))?;
            } else {
                let copied = call!(MatCopy(b, self.reduced, p::SAME_NONZERO_PATTERN));
                // SAFETY: created by MatPermute above, destroyed once.
                unsafe {
                    p::MatDestroy(&mut b);
                }
                copied?;
            }
            // a new coupled set (a new stage) is always factored
            let fresh = self.inner.wants_factors() || block == p::MAT_INITIAL_MATRIX;
            failed = self.inner.factor(!fresh)?;
        }
        if failed != 0 || singular {
            // a zero pivot: the Newton step fails as a linear solve and is cut back
            call!(PCSetFailedReason(pc, p::PC_SUBPC_ERROR))?;
        }
        Ok(())
    }

    /// y = A⁻¹ x through the canonical factors.
    fn apply(&mut self, pc: p::PC, x: p::Vec, y: p::Vec) -> Result<(), PetscError> {
        let (x, mut y) = (Vector::borrowed(x), Vector::borrowed(y));
        let (Some(gather), Some(rhs)) = (self.gather.as_mut(), self.rhs.as_mut()) else {
            unreachable!("set up before the first solve");
        };
        let b = gather.gather(&x)?;
        let keep = &self.keep;
        b.read(|full| rhs.write(|r| r.iter_mut().zip(keep).for_each(|(o, &i)| *o = full[i])))??;
        if !self.keep.is_empty() && !self.solve_coupled()? {
            call!(PCSetFailedReason(pc, p::PC_SUBPC_ERROR))?;
        }
        let (Some(gather), Some(solution)) = (self.gather.as_ref(), self.solution.as_ref()) else {
            unreachable!("set up before the first solve");
        };
        let b = gather.last();
        let (local_pos, reduced_index, diagonal) = (&self.local_pos, &self.reduced_index, &self.diagonal);
        b.read(|full| {
            solution.read(|s| {
                y.write(|out| {
                    for (o, &k) in out.iter_mut().zip(local_pos) {
                        *o = match reduced_index[k] {
                            Some(r) => s[r],
                            None => full[k] / diagonal[k],
                        };
                    }
                })
            })
        })???;
        Ok(())
    }
}

impl Drop for CanonicalLu {
    fn drop(&mut self) {
        // SAFETY: each handle was created once by PETSc (or is null, which the destroy calls
        // accept) and is destroyed once here.
        unsafe {
            if !self.sub.is_null() {
                p::MatDestroySubMatrices(1, &mut self.sub);
            }
            p::MatDestroy(&mut self.reduced);
            p::ISDestroy(&mut self.is_rows);
            p::ISDestroy(&mut self.is_perm);
        }
    }
}
