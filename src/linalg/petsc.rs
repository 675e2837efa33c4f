//! A small safe layer over PETSc: owned handles destroyed on drop, `Result` errors carrying
//! PETSc's message, and only the Vec/Mat/KSP/PC/SNES operations cfrd needs (SNES drives the
//! Newton iterations through the [`SnesProblem`] callbacks).
//!
//! Start-up and shutdown order (`spec/stack.md` §4): MPI first (rsmpi), then [`Petsc::initialize`]
//! on the same communicator (through `SlepcInitialize`, which initializes PETSc and SLEPc at
//! once, so the eigensolvers of [`super::slepc`] need no second start-up); every PETSc object
//! must be dropped before the [`Petsc`] guard, which finalizes SLEPc and PETSc but leaves MPI to
//! rsmpi. nalgebra is column-major while `MatSetValues` expects
//! row-major blocks: [`Matrix::add_values`] takes row-major data and says so.
#![allow(unsafe_code)]

use super::ffi as p;
use super::lagged_lu::{distributed_context, DistributedLu, LaggedLu, DISTRIBUTED_LU_NAME};
use super::reduced_amg::{ReducedAmg, REDUCED_AMG_NAME};
use mpi::raw::AsRaw;
use mpi::topology::SimpleCommunicator;
use std::ffi::{c_char, CStr, CString};
use std::ptr::{null, null_mut};
use thiserror::Error;

/// A failed PETSc call.
#[derive(Debug, Clone, Error)]
#[error("PETSc error {code} in {call}: {message}")]
pub struct PetscError {
    /// PETSc's error code.
    pub code: i32,
    /// The PETSc function that failed.
    pub call: &'static str,
    /// PETSc's text for the code.
    pub message: String,
}

/// `Ok` for a zero PETSc error code, else the error with PETSc's text for the code.
pub(super) fn chk(code: p::PetscErrorCode, call: &'static str) -> Result<(), PetscError> {
    if code == 0 {
        return Ok(());
    }
    let mut text: *const c_char = null();
    // SAFETY: PetscErrorMessage only writes a pointer to a static string.
    let message = unsafe {
        if p::PetscErrorMessage(code, &mut text, null_mut()) == 0 && !text.is_null() {
            CStr::from_ptr(text).to_string_lossy().into_owned()
        } else {
            "unknown error".to_string()
        }
    };
    Err(PetscError { code, call, message })
}

macro_rules! call {
    ($f:ident ( $($arg:expr),* $(,)? )) => {
        chk(unsafe { p::$f($($arg),*) }, stringify!($f))
    };
}

/// One OpenMP thread per MPI rank, unless `OMP_NUM_THREADS` says otherwise: SuperLU_DIST (the
/// reduced multigrid's structure factorization, [`crate::linalg::reduced_amg`]) is built with
/// OpenMP, whose default of one thread per core makes every rank's threads compete for the
/// cores the other ranks run on (measured: the small default dam on 2 ranks had not ended after
/// 9 min, against 9 s with one thread). `omp_set_num_threads` is looked up at run time, so a
/// PETSc without OpenMP libraries needs nothing.
fn one_openmp_thread_per_rank() {
    if std::env::var_os("OMP_NUM_THREADS").is_some() {
        return;
    }
    // SAFETY: dlsym with a NUL-terminated name; the symbol, where found, is libgomp's
    // `void omp_set_num_threads(int)`, called once before any OpenMP region runs.
    unsafe {
        let f = libc::dlsym(libc::RTLD_DEFAULT, c"omp_set_num_threads".as_ptr());
        if !f.is_null() {
            let set: extern "C" fn(i32) = std::mem::transmute(f);
            set(1);
        }
    }
}

/// PETSc library guard: initialized on a communicator, finalized on drop.
pub struct Petsc {
    comm: mpi::ffi::MPI_Comm,
}

impl Petsc {
    /// Initializes PETSc and SLEPc on `world` (MPI must already be initialized by rsmpi):
    /// `SlepcInitialize` calls `PetscInitialize` itself. Errors are returned instead of printed
    /// (PETSc's return error handler is pushed).
    pub fn initialize(world: &SimpleCommunicator) -> Result<Petsc, PetscError> {
        let comm = world.as_raw();
        // SAFETY: PETSC_COMM_WORLD must be set before PetscInitialize (stack.md §4); single-threaded.
        unsafe {
            p::PETSC_COMM_WORLD = comm;
        }
        one_openmp_thread_per_rank();
        // PETSc keeps argv; the strings are leaked on purpose (once per process).
        let prog = CString::new("cfrd").expect("no NUL").into_raw();
        let argv: &'static mut [*mut c_char; 2] = Box::leak(Box::new([prog, null_mut()]));
        let mut argc: i32 = 1;
        let mut argv_ptr: *mut *mut c_char = argv.as_mut_ptr();
        call!(SlepcInitialize(&mut argc, &mut argv_ptr, null(), null()))?;
        call!(PetscPushErrorHandler(
            Some(p::PetscReturnErrorHandler),
            null_mut()
        ))?;
        Ok(Petsc { comm })
    }

    /// Inserts options such as `-ksp_type cg -pc_type gamg`; later calls override earlier ones.
    pub fn insert_options(&self, options: &str) -> Result<(), PetscError> {
        let c = CString::new(options).map_err(|_| PetscError {
            code: -1,
            call: "PetscOptionsInsertString",
            message: "option string contains a NUL byte".into(),
        })?;
        call!(PetscOptionsInsertString(null_mut(), c.as_ptr()))
    }

    /// Options set (in the scene or on the command line) that no PETSc object has read so far,
    /// as `-name value` (PETSc's own unused-option record, `PetscOptionsLeftGet`): at the end of
    /// a run, misspelled options or options of a solver the run did not use.
    pub fn unused_options(&self) -> Result<Vec<String>, PetscError> {
        let mut n: p::PetscInt = 0;
        let mut names: *mut *mut c_char = null_mut();
        let mut values: *mut *mut c_char = null_mut();
        call!(PetscOptionsLeftGet(null_mut(), &mut n, &mut names, &mut values))?;
        let text = |list: *mut *mut c_char, i: usize| -> String {
            // SAFETY: PETSc returned `n` entries in each list; an entry may be NULL (no value).
            unsafe {
                let s = *list.add(i);
                if s.is_null() {
                    String::new()
                } else {
                    CStr::from_ptr(s).to_string_lossy().into_owned()
                }
            }
        };
        let left = (0..n.max(0) as usize)
            .map(|i| {
                let (name, value) = (text(names, i), text(values, i));
                match value.is_empty() {
                    true => format!("-{name}"),
                    false => format!("-{name} {value}"),
                }
            })
            .collect();
        call!(PetscOptionsLeftRestore(
            null_mut(),
            &mut n,
            &mut names,
            &mut values
        ))?;
        Ok(left)
    }

    /// The communicator PETSc runs on.
    pub fn comm(&self) -> mpi::ffi::MPI_Comm {
        self.comm
    }
}

impl Drop for Petsc {
    fn drop(&mut self) {
        // SAFETY: all PETSc objects are owned by values that borrow nothing from here and must be
        // dropped before the guard (documented contract). SLEPc initialized PETSc, so
        // SlepcFinalize finalizes PETSc too.
        unsafe {
            p::SlepcFinalize();
        }
    }
}

/// A PETSc vector (MPI or sequential).
pub struct Vector {
    raw: p::Vec,
}

impl Vector {
    /// A distributed vector with `n_local` entries on this rank.
    pub fn mpi(petsc: &Petsc, n_local: usize, block_size: usize) -> Result<Vector, PetscError> {
        let mut raw: p::Vec = null_mut();
        call!(VecCreate(petsc.comm, &mut raw))?;
        let v = Vector { raw };
        call!(VecSetSizes(v.raw, n_local as i32, p::PETSC_DETERMINE))?;
        call!(VecSetBlockSize(v.raw, block_size as i32))?;
        call!(VecSetType(v.raw, p::VECMPI.as_ptr() as *const c_char))?;
        Ok(v)
    }

    /// A sequential (rank-local) vector of length `n`.
    pub fn seq(n: usize) -> Result<Vector, PetscError> {
        let mut raw: p::Vec = null_mut();
        call!(VecCreateSeq(mpi::ffi::RSMPI_COMM_SELF, n as i32, &mut raw))?;
        Ok(Vector { raw })
    }

    /// The raw handle, for the other safe layers of this module's parent (SLEPc).
    pub(super) fn raw(&self) -> p::Vec {
        self.raw
    }

    /// A new vector with the same layout (values not copied).
    pub fn duplicate(&self) -> Result<Vector, PetscError> {
        let mut raw: p::Vec = null_mut();
        call!(VecDuplicate(self.raw, &mut raw))?;
        Ok(Vector { raw })
    }

    /// Global index range `[lo, hi)` owned by this rank.
    pub fn ownership_range(&self) -> Result<(usize, usize), PetscError> {
        let (mut lo, mut hi) = (0, 0);
        call!(VecGetOwnershipRange(self.raw, &mut lo, &mut hi))?;
        Ok((lo as usize, hi as usize))
    }

    /// Sets every entry to `value`.
    pub fn set_all(&mut self, value: f64) -> Result<(), PetscError> {
        call!(VecSet(self.raw, value))
    }

    /// Adds (or inserts) values at global indices; negative indices are ignored. Call
    /// [`Vector::assemble`] afterwards.
    pub fn set_values(&mut self, idx: &[i32], values: &[f64], add: bool) -> Result<(), PetscError> {
        assert_eq!(idx.len(), values.len());
        let mode = if add { p::ADD_VALUES } else { p::INSERT_VALUES };
        call!(VecSetValues(
            self.raw,
            idx.len() as i32,
            idx.as_ptr(),
            values.as_ptr(),
            mode
        ))
    }

    /// Communicates off-process contributions.
    pub fn assemble(&mut self) -> Result<(), PetscError> {
        call!(VecAssemblyBegin(self.raw))?;
        call!(VecAssemblyEnd(self.raw))
    }

    /// Reads the local part.
    pub fn read<R>(&self, f: impl FnOnce(&[f64]) -> R) -> Result<R, PetscError> {
        let mut n = 0;
        call!(VecGetLocalSize(self.raw, &mut n))?;
        let mut ptr: *const f64 = null();
        call!(VecGetArrayRead(self.raw, &mut ptr))?;
        // SAFETY: PETSc guarantees `n` readable entries until VecRestoreArrayRead (the pointer
        // may be null when the rank holds no entries).
        let r = if n == 0 || ptr.is_null() {
            f(&[])
        } else {
            f(unsafe { std::slice::from_raw_parts(ptr, n as usize) })
        };
        call!(VecRestoreArrayRead(self.raw, &mut ptr))?;
        Ok(r)
    }

    /// Writes the local part.
    pub fn write<R>(&mut self, f: impl FnOnce(&mut [f64]) -> R) -> Result<R, PetscError> {
        let mut n = 0;
        call!(VecGetLocalSize(self.raw, &mut n))?;
        let mut ptr: *mut f64 = null_mut();
        call!(VecGetArray(self.raw, &mut ptr))?;
        // SAFETY: PETSc guarantees `n` writable entries until VecRestoreArray (the pointer may be
        // null when the rank holds no entries).
        let r = if n == 0 || ptr.is_null() {
            f(&mut [])
        } else {
            f(unsafe { std::slice::from_raw_parts_mut(ptr, n as usize) })
        };
        call!(VecRestoreArray(self.raw, &mut ptr))?;
        Ok(r)
    }

    /// `self ← self + alpha·x`.
    pub fn axpy(&mut self, alpha: f64, x: &Vector) -> Result<(), PetscError> {
        call!(VecAXPY(self.raw, alpha, x.raw))
    }

    /// Copies the values of `x` into `self`.
    pub fn copy_from(&mut self, x: &Vector) -> Result<(), PetscError> {
        call!(VecCopy(x.raw, self.raw))
    }

    /// Euclidean norm (collective).
    pub fn norm2(&self) -> Result<f64, PetscError> {
        let mut r = 0.0;
        call!(VecNorm(self.raw, p::NORM_2, &mut r))?;
        Ok(r)
    }

    /// Max norm (collective).
    pub fn norm_inf(&self) -> Result<f64, PetscError> {
        let mut r = 0.0;
        call!(VecNorm(self.raw, p::NORM_INFINITY, &mut r))?;
        Ok(r)
    }
}

impl Drop for Vector {
    fn drop(&mut self) {
        // SAFETY: raw was created by PETSc and is destroyed once.
        unsafe {
            p::VecDestroy(&mut self.raw);
        }
    }
}

/// Gathers selected global entries of a distributed vector into a local sequential vector.
pub struct Gather {
    ctx: p::VecScatter,
    local: Vector,
}

impl Gather {
    /// A gather of the global indices `from` of vectors laid out like `like`.
    pub fn new(like: &Vector, from: &[i32]) -> Result<Gather, PetscError> {
        let local = Vector::seq(from.len())?;
        let mut is: p::IS = null_mut();
        call!(ISCreateGeneral(
            mpi::ffi::RSMPI_COMM_SELF,
            from.len() as i32,
            from.as_ptr(),
            p::PETSC_COPY_VALUES,
            &mut is
        ))?;
        let mut ctx: p::VecScatter = null_mut();
        let r = call!(VecScatterCreate(like.raw, is, local.raw, null_mut(), &mut ctx));
        // SAFETY: the index set was created above and is no longer needed.
        unsafe {
            p::ISDestroy(&mut is);
        }
        r?;
        Ok(Gather { ctx, local })
    }

    /// Gathers the entries of `x` and returns them in the order of `from`.
    pub fn gather<'a>(&'a mut self, x: &Vector) -> Result<&'a Vector, PetscError> {
        call!(VecScatterBegin(
            self.ctx,
            x.raw,
            self.local.raw,
            p::INSERT_VALUES,
            p::SCATTER_FORWARD
        ))?;
        call!(VecScatterEnd(
            self.ctx,
            x.raw,
            self.local.raw,
            p::INSERT_VALUES,
            p::SCATTER_FORWARD
        ))?;
        Ok(&self.local)
    }

    /// The entries of the last gather, in the order of `from`.
    pub fn last(&self) -> &Vector {
        &self.local
    }
}

impl Drop for Gather {
    fn drop(&mut self) {
        // SAFETY: created by VecScatterCreate, destroyed once.
        unsafe {
            p::VecScatterDestroy(&mut self.ctx);
        }
    }
}

/// The product y = A·x of a fixed matrix whose every row is summed in the mesh's DOF order, so
/// that y is the same bit for bit at any rank count. PETSc's `MatMult` sums a row's diagonal
/// block and then its off-diagonal block, an order that moves with the partition: the inertia
/// and damping forces of a dynamic stage (M·a, K₀·v) then differ in the last bits between 1
/// and 2 ranks, and the plasticity carries that further (10⁻³ of the displacement after the
/// coarse seed quake). The matrix's owned rows are copied at construction (later changes to
/// the matrix are not seen); x's entries in those rows' columns are gathered at every product.
pub struct CanonicalProduct {
    /// Start of each owned row in `position` and `value`, and one past the last.
    row_start: Vec<usize>,
    /// For every entry: its column's place among the gathered entries of x.
    position: Vec<u32>,
    /// For every entry, rows in order, each row's entries in the mesh's DOF order.
    value: Vec<f64>,
    gather: std::cell::RefCell<Gather>,
}

impl CanonicalProduct {
    /// The product with `a` (assembled) for vectors laid out like `like`; `mesh_order[k]` is
    /// the PETSc index of the mesh's DOF k (`Discretization::canonical_dofs`).
    pub fn new(a: &Matrix, like: &Vector, mesh_order: &[i32]) -> Result<CanonicalProduct, PetscError> {
        let mut rank_in_mesh = vec![0u32; mesh_order.len()];
        for (k, &g) in mesh_order.iter().enumerate() {
            rank_in_mesh[g as usize] = k as u32;
        }
        let (lo, hi) = like.ownership_range()?;
        let mut rows: Vec<Vec<(u32, i32, f64)>> = Vec::with_capacity(hi - lo);
        for r in lo..hi {
            let mut row = Self::row(a, r)?;
            for e in &mut row {
                e.0 = rank_in_mesh[e.1 as usize];
            }
            row.sort_unstable_by_key(|e| e.0);
            rows.push(row);
        }
        let mut columns: Vec<i32> = rows.iter().flatten().map(|e| e.1).collect();
        columns.sort_unstable();
        columns.dedup();
        let mut row_start = vec![0];
        let (mut position, mut value) = (Vec::new(), Vec::new());
        for row in &rows {
            for &(_, c, v) in row {
                position.push(columns.binary_search(&c).unwrap_or_default() as u32);
                value.push(v);
            }
            row_start.push(value.len());
        }
        let gather = std::cell::RefCell::new(Gather::new(like, &columns)?);
        Ok(CanonicalProduct {
            row_start,
            position,
            value,
            gather,
        })
    }

    /// Row `r` of `a` as (0, column, value) entries.
    fn row(a: &Matrix, r: usize) -> Result<Vec<(u32, i32, f64)>, PetscError> {
        let (mut ncols, mut cols, mut vals): (i32, *const i32, *const f64) = (0, null(), null());
        call!(MatGetRow(a.raw, r as i32, &mut ncols, &mut cols, &mut vals))?;
        let row = if ncols > 0 {
            // SAFETY: MatGetRow returned `ncols` column indices and values, valid until
            // MatRestoreRow.
            let (c, v) = unsafe {
                (
                    std::slice::from_raw_parts(cols, ncols as usize),
                    std::slice::from_raw_parts(vals, ncols as usize),
                )
            };
            c.iter().zip(v).map(|(&c, &v)| (0, c, v)).collect()
        } else {
            Vec::new()
        };
        call!(MatRestoreRow(a.raw, r as i32, &mut ncols, &mut cols, &mut vals))?;
        Ok(row)
    }

    /// `y ← A x` (collective), every row summed in the mesh's DOF order.
    pub fn mult(&self, x: &Vector, y: &mut Vector) -> Result<(), PetscError> {
        let (starts, position, value) = (&self.row_start, &self.position, &self.value);
        let mut gather = self.gather.borrow_mut();
        let xs = gather.gather(x)?;
        xs.read(|xs| {
            y.write(|ys| {
                for (i, yi) in ys.iter_mut().enumerate() {
                    let entries = starts[i]..starts[i + 1];
                    *yi = entries.map(|k| value[k] * xs[position[k] as usize]).sum();
                }
            })
        })?
    }
}

/// Where the owned rows of an assembled AIJ matrix keep their entries ([`Matrix::csr_layout`]):
/// the diagonal block (the columns this rank owns) and the off-diagonal block, each in
/// compressed rows with increasing global columns.
#[derive(Debug, Clone, Default)]
pub struct CsrLayout {
    /// The diagonal block.
    pub diag: CsrPart,
    /// The off-diagonal block (no entries on one rank).
    pub off: CsrPart,
}

/// One block of a [`CsrLayout`]: entry `k` of local row `r` (`rows[r] <= k < rows[r + 1]`)
/// has global column `cols[k]`.
#[derive(Debug, Clone, Default)]
pub struct CsrPart {
    /// Row starts, one more than the owned rows.
    pub rows: Vec<i32>,
    /// Global column of every entry.
    pub cols: Vec<i32>,
}

impl CsrPart {
    /// The rows of the sequential AIJ matrix `m`, its local columns mapped by `global`.
    fn of(m: p::Mat, global: impl Fn(i32) -> i32) -> Result<CsrPart, PetscError> {
        let mut ij: RowIjOut = (0, null(), null(), p::PETSC_FALSE);
        row_ij(p::MatGetRowIJ, "MatGetRowIJ", m, &mut ij)?;
        let (n, ia, ja, done) = ij;
        if done != p::PETSC_TRUE {
            return Err(PetscError {
                code: 0,
                call: "MatGetRowIJ",
                message: "the matrix gives no compressed rows".into(),
            });
        }
        // SAFETY: PETSc returned n + 1 row starts and rows[n] column indices, valid until
        // MatRestoreRowIJ.
        let part = unsafe {
            let rows = std::slice::from_raw_parts(ia, n as usize + 1).to_vec();
            let nnz = rows[n as usize] as usize;
            let cols = match nnz {
                0 => Vec::new(),
                _ => std::slice::from_raw_parts(ja, nnz)
                    .iter()
                    .map(|&j| global(j))
                    .collect(),
            };
            CsrPart { rows, cols }
        };
        row_ij(p::MatRestoreRowIJ, "MatRestoreRowIJ", m, &mut ij)?;
        Ok(part)
    }
}

/// The outputs of [`RowIj`]: rows, row starts, column indices, whether they were given.
type RowIjOut = (i32, *const i32, *const i32, p::PetscBool);

/// Calls `f` (`MatGetRowIJ` or `MatRestoreRowIJ`) on the sequential AIJ matrix `m` for its
/// compressed rows, unshifted and as stored.
fn row_ij(f: RowIj, name: &'static str, m: p::Mat, out: &mut RowIjOut) -> Result<(), PetscError> {
    let (n, ia, ja, done) = out;
    let no = p::PETSC_FALSE;
    // SAFETY: `m` is a valid sequential AIJ matrix and PETSc writes only the four outputs.
    chk(unsafe { f(m, 0, no, no, n, ia, ja, done) }, name)
}

/// `MatGetRowIJ` and `MatRestoreRowIJ`, which take the same arguments.
type RowIj = unsafe extern "C" fn(
    p::Mat,
    i32,
    p::PetscBool,
    p::PetscBool,
    *mut i32,
    *mut *const i32,
    *mut *const i32,
    *mut p::PetscBool,
) -> p::PetscErrorCode;

/// The values of a sequential AIJ matrix, borrowed from PETSc until [`SeqValues::restore`].
struct SeqValues {
    m: p::Mat,
    ptr: *mut f64,
    len: usize,
}

impl SeqValues {
    fn get(m: p::Mat) -> Result<SeqValues, PetscError> {
        // SAFETY: MatInfo holds only doubles, for which zero bits are a valid value.
        let mut info: p::MatInfo = unsafe { std::mem::zeroed() };
        call!(MatGetInfo(m, p::MAT_LOCAL, &mut info))?;
        let mut ptr: *mut f64 = null_mut();
        call!(MatSeqAIJGetArray(m, &mut ptr))?;
        Ok(SeqValues {
            m,
            ptr,
            len: info.nz_used as usize,
        })
    }

    fn slice(&mut self) -> &mut [f64] {
        if self.len == 0 || self.ptr.is_null() {
            return &mut [];
        }
        // SAFETY: PETSc lent `len` values (the used nonzeros) until MatSeqAIJRestoreArray.
        unsafe { std::slice::from_raw_parts_mut(self.ptr, self.len) }
    }

    fn restore(mut self) -> Result<(), PetscError> {
        call!(MatSeqAIJRestoreArray(self.m, &mut self.ptr))
    }
}

/// The off-diagonal block of an MPIAIJ matrix's owned rows and the global column of each of
/// its local columns.
type OffDiagonal = (p::Mat, *const i32);

/// A distributed sparse matrix (MPIAIJ with block size) with exact preallocation.
pub struct Matrix {
    raw: p::Mat,
}

impl Matrix {
    /// Square AIJ matrix with `n_local` rows on this rank, `d_nnz`/`o_nnz` nonzeros per local
    /// row in the diagonal/off-diagonal blocks. New nonzeros outside the pattern are an error.
    pub fn aij(
        petsc: &Petsc,
        n_local: usize,
        block_size: usize,
        d_nnz: &[i32],
        o_nnz: &[i32],
    ) -> Result<Matrix, PetscError> {
        let mut raw: p::Mat = null_mut();
        call!(MatCreate(petsc.comm, &mut raw))?;
        let m = Matrix { raw };
        let nl = n_local as i32;
        call!(MatSetSizes(m.raw, nl, nl, p::PETSC_DETERMINE, p::PETSC_DETERMINE))?;
        call!(MatSetType(m.raw, p::MATAIJ.as_ptr() as *const c_char))?;
        call!(MatSetBlockSize(m.raw, block_size as i32))?;
        call!(MatSeqAIJSetPreallocation(m.raw, 0, d_nnz.as_ptr()))?;
        call!(MatMPIAIJSetPreallocation(
            m.raw,
            0,
            d_nnz.as_ptr(),
            0,
            o_nnz.as_ptr()
        ))?;
        call!(MatSetOption(
            m.raw,
            p::MAT_NEW_NONZERO_ALLOCATION_ERR,
            p::PETSC_TRUE
        ))?;
        Ok(m)
    }

    /// Sets all stored entries to zero (keeps the pattern).
    pub fn zero(&mut self) -> Result<(), PetscError> {
        call!(MatZeroEntries(self.raw))
    }

    /// Adds a dense **row-major** block `values[i*cols.len()+j]` at (`rows[i]`, `cols[j]`);
    /// negative indices are skipped.
    pub fn add_values(&mut self, rows: &[i32], cols: &[i32], values: &[f64]) -> Result<(), PetscError> {
        assert_eq!(rows.len() * cols.len(), values.len());
        call!(MatSetValues(
            self.raw,
            rows.len() as i32,
            rows.as_ptr(),
            cols.len() as i32,
            cols.as_ptr(),
            values.as_ptr(),
            p::ADD_VALUES
        ))
    }

    /// Final assembly (communicates off-process entries).
    pub fn assemble(&mut self) -> Result<(), PetscError> {
        call!(MatAssemblyBegin(self.raw, p::MAT_FINAL_ASSEMBLY))?;
        call!(MatAssemblyEnd(self.raw, p::MAT_FINAL_ASSEMBLY))
    }

    /// Zeroes the given global rows and columns, puts `diag` on the diagonal and adjusts `b`
    /// so that the solution takes the values of `x` at those rows (Dirichlet conditions).
    pub fn zero_rows_columns(
        &mut self,
        rows: &[i32],
        diag: f64,
        x: &Vector,
        b: &mut Vector,
    ) -> Result<(), PetscError> {
        call!(MatZeroRowsColumns(
            self.raw,
            rows.len() as i32,
            rows.as_ptr(),
            diag,
            x.raw,
            b.raw
        ))
    }

    /// The diagonal and off-diagonal blocks of the owned rows (PETSc's MPIAIJ split; on one
    /// rank the whole matrix is the diagonal block) and the global column of every local
    /// column of the off-diagonal block.
    fn owned_blocks(&self) -> Result<(p::Mat, Option<OffDiagonal>), PetscError> {
        let mut seq = p::PETSC_FALSE;
        call!(PetscObjectTypeCompare(
            self.raw as p::PetscObject,
            p::MATSEQAIJ.as_ptr() as *const c_char,
            &mut seq
        ))?;
        if seq == p::PETSC_TRUE {
            return Ok((self.raw, None));
        }
        let (mut ad, mut ao, mut colmap): (p::Mat, p::Mat, *const i32) = (null_mut(), null_mut(), null());
        call!(MatMPIAIJGetSeqAIJ(self.raw, &mut ad, &mut ao, &mut colmap))?;
        Ok((ad, Some((ao, colmap))))
    }

    /// Where the entries of the owned rows are stored ([`CsrLayout`]). The pattern must be
    /// final (assembled, no new nonzeros allowed), as [`Matrix::aij`] makes it.
    pub fn csr_layout(&self) -> Result<CsrLayout, PetscError> {
        let (mut c_lo, mut c_hi) = (0, 0);
        call!(MatGetOwnershipRangeColumn(self.raw, &mut c_lo, &mut c_hi))?;
        let (ad, off) = self.owned_blocks()?;
        let diag = CsrPart::of(ad, |j| j + c_lo)?;
        let off = match off {
            None => CsrPart {
                rows: vec![0; diag.rows.len()],
                cols: Vec::new(),
            },
            Some((ao, colmap)) => {
                let n = CsrPart::of(ao, |j| j)?;
                let n_cols = n.cols.iter().max().map_or(0, |&m| m as usize + 1);
                // SAFETY: `colmap` maps each of the off-diagonal block's columns (all below
                // n_cols) to its global column while the matrix lives.
                let colmap = unsafe { std::slice::from_raw_parts(colmap, n_cols) };
                CsrPart {
                    cols: n.cols.iter().map(|&j| colmap[j as usize]).collect(),
                    rows: n.rows,
                }
            }
        };
        Ok(CsrLayout { diag, off })
    }

    /// Overwrites the values of the owned rows: `f` gets the values of the diagonal and of the
    /// off-diagonal block in the order of [`Matrix::csr_layout`] (it sees the old values), then
    /// the matrix is assembled. For a pattern that is final and values set on owned rows only,
    /// as the element assembly does; no communication but the assembly's own. Collective.
    pub fn overwrite_values<R>(
        &mut self,
        f: impl FnOnce(&mut [f64], &mut [f64]) -> R,
    ) -> Result<R, PetscError> {
        let (ad, off) = self.owned_blocks()?;
        let mut diag = SeqValues::get(ad)?;
        let mut off = match off {
            Some((ao, _)) => Some(SeqValues::get(ao)?),
            None => None,
        };
        let r = f(diag.slice(), off.as_mut().map_or(&mut [][..], |o| o.slice()));
        diag.restore()?;
        if let Some(o) = off {
            o.restore()?;
        }
        call!(MatSetOption(self.raw, p::MAT_NO_OFF_PROC_ENTRIES, p::PETSC_TRUE))?;
        self.assemble()?;
        Ok(r)
    }

    /// Zeroes the given global rows and columns and puts `diag` on the diagonal (no right-hand
    /// side to adjust: the Jacobian of a residual whose constrained entries are already zero).
    pub fn zero_rows_columns_only(&mut self, rows: &[i32], diag: f64) -> Result<(), PetscError> {
        call!(MatZeroRowsColumns(
            self.raw,
            rows.len() as i32,
            rows.as_ptr(),
            diag,
            null_mut(),
            null_mut()
        ))
    }

    /// Attaches the six rigid-body modes computed from nodal `coords` (a vector with block size
    /// 3 laid out like the DOFs) as the near-null space for algebraic multigrid.
    pub fn set_rigid_body_near_null_space(&mut self, coords: &Vector) -> Result<(), PetscError> {
        let mut ns: p::MatNullSpace = null_mut();
        call!(MatNullSpaceCreateRigidBody(coords.raw, &mut ns))?;
        let r = call!(MatSetNearNullSpace(self.raw, ns));
        // SAFETY: the matrix keeps its own reference.
        unsafe {
            p::MatNullSpaceDestroy(&mut ns);
        }
        r
    }

    /// `y ← A x`.
    pub fn mult(&self, x: &Vector, y: &mut Vector) -> Result<(), PetscError> {
        call!(MatMult(self.raw, x.raw, y.raw))
    }

    /// The raw handle, for the other safe layers of this module's parent (SLEPc).
    pub(super) fn raw(&self) -> p::Mat {
        self.raw
    }

    /// A vector laid out like this matrix's columns (values not set).
    pub fn column_vector(&self) -> Result<Vector, PetscError> {
        let mut raw: p::Vec = null_mut();
        call!(MatCreateVecs(self.raw, &mut raw, null_mut()))?;
        Ok(Vector { raw })
    }

    /// The square submatrix of the global rows and columns `owned` (this rank's owned indices of
    /// the new matrix, ascending; collective). Its rows are distributed as `owned` is: the
    /// i-th owned row of the result is `owned[i]`.
    pub fn submatrix(&self, owned: &[i32]) -> Result<Matrix, PetscError> {
        let mut comm: mpi::ffi::MPI_Comm = unsafe { mpi::ffi::RSMPI_COMM_NULL };
        call!(PetscObjectGetComm(self.raw as p::PetscObject, &mut comm))?;
        let mut is: p::IS = null_mut();
        call!(ISCreateGeneral(
            comm,
            owned.len() as i32,
            owned.as_ptr(),
            p::PETSC_COPY_VALUES,
            &mut is
        ))?;
        let mut raw: p::Mat = null_mut();
        let r = call!(MatCreateSubMatrix(
            self.raw,
            is,
            is,
            p::MAT_INITIAL_MATRIX,
            &mut raw
        ));
        // SAFETY: the index set was created above; the submatrix keeps what it needs.
        unsafe {
            p::ISDestroy(&mut is);
        }
        r?;
        Ok(Matrix { raw })
    }

    /// The symmetric part (A + Aᵀ)/2 of this matrix, a new matrix (collective).
    pub fn symmetric_part(&self) -> Result<Matrix, PetscError> {
        let mut t: p::Mat = null_mut();
        call!(MatTranspose(self.raw, p::MAT_INITIAL_MATRIX, &mut t))?;
        let sym = Matrix { raw: t };
        call!(MatAXPY(sym.raw, 1.0, self.raw, p::DIFFERENT_NONZERO_PATTERN))?;
        call!(MatScale(sym.raw, 0.5))?;
        Ok(sym)
    }

    /// A copy of this matrix, pattern and values.
    pub fn duplicate(&self) -> Result<Matrix, PetscError> {
        let mut raw: p::Mat = null_mut();
        call!(MatDuplicate(self.raw, p::MAT_COPY_VALUES, &mut raw))?;
        Ok(Matrix { raw })
    }

    /// `self ← self + a X` for a matrix `x` of the same nonzero pattern.
    pub fn axpy(&mut self, a: f64, x: &Matrix) -> Result<(), PetscError> {
        call!(MatAXPY(self.raw, a, x.raw, p::SAME_NONZERO_PATTERN))
    }
}

impl Drop for Matrix {
    fn drop(&mut self) {
        // SAFETY: created by MatCreate, destroyed once.
        unsafe {
            p::MatDestroy(&mut self.raw);
        }
    }
}

/// Sets `-name value` in PETSc's options database unless the user has set `-name`.
pub(super) fn default_option(name: &str, value: &str) -> Result<(), PetscError> {
    let (n, v) = (
        CString::new(name).expect("option name without NUL"),
        CString::new(value).expect("option value without NUL"),
    );
    let mut set = p::PETSC_FALSE;
    call!(PetscOptionsHasName(null_mut(), null(), n.as_ptr(), &mut set))?;
    if set == p::PETSC_FALSE {
        call!(PetscOptionsSetValue(null_mut(), n.as_ptr(), v.as_ptr()))?;
    }
    Ok(())
}

/// Marks in `flags` (laid out like the rows of `pmat`) the coupled rows: an entry > 0 where a
/// row has a nonzero entry off the diagonal in its row or its column, 0 where it is decoupled
/// (the constrained DOFs and the nodes of fill not yet placed). Each rank marks its own rows
/// and the columns of their nonzero entries (a count, so the sum is exact in any order).
/// Collective.
pub(super) fn mark_coupled_rows(pmat: p::Mat, flags: p::Vec) -> Result<(), PetscError> {
    let (mut lo, mut hi) = (0, 0);
    call!(VecGetOwnershipRange(flags, &mut lo, &mut hi))?;
    let (lo, hi) = (lo as usize, hi as usize);
    let mut marks = vec![false; hi - lo];
    let mut remote: Vec<i32> = Vec::new();
    for r in lo..hi {
        let (mut ncols, mut cols, mut vals): (i32, *const i32, *const f64) = (0, null(), null());
        call!(MatGetRow(pmat, r as i32, &mut ncols, &mut cols, &mut vals))?;
        if ncols > 0 {
            // SAFETY: MatGetRow returned `ncols` column indices and values, valid until
            // MatRestoreRow.
            let (cols_r, vals_r) = unsafe {
                (
                    std::slice::from_raw_parts(cols, ncols as usize),
                    std::slice::from_raw_parts(vals, ncols as usize),
                )
            };
            for (&c, &v) in cols_r.iter().zip(vals_r) {
                let c = c as usize;
                if c != r && v != 0.0 {
                    marks[r - lo] = true;
                    if (lo..hi).contains(&c) {
                        marks[c - lo] = true;
                    } else {
                        remote.push(c as i32);
                    }
                }
            }
        }
        call!(MatRestoreRow(pmat, r as i32, &mut ncols, &mut cols, &mut vals))?;
    }
    remote.sort_unstable();
    remote.dedup();
    remote.extend((lo..hi).filter(|&r| marks[r - lo]).map(|r| r as i32));
    call!(VecSet(flags, 0.0))?;
    let ones = vec![1.0; remote.len()];
    call!(VecSetValues(
        flags,
        remote.len() as i32,
        remote.as_ptr(),
        ones.as_ptr(),
        p::ADD_VALUES
    ))?;
    call!(VecAssemblyBegin(flags))?;
    call!(VecAssemblyEnd(flags))?;
    Ok(())
}

/// cfrd's Krylov defaults on `ksp`: CG + GAMG for a symmetric operator, GMRES(200) with right
/// preconditioning + GAMG otherwise; relative tolerance `rtol` on the unpreconditioned residual,
/// at most `max_it` iterations; PETSc options (`-ksp_type`, `-pc_type`, ...) override them.
///
/// For a non-symmetric operator the multigrid levels are smoothed by Richardson + SOR instead of
/// GAMG's default Chebyshev + Jacobi: Chebyshev needs a real spectrum and eigenvalue estimates
/// that stay valid as the tangent changes; with the non-associated rockfill tangent it made the
/// preconditioner so far from a fixed linear operator that right-preconditioned GMRES reported
/// convergence (rtol 1e-10) on a wrong Newton correction. Measured on a GP column under gravity
/// and a 10 MPa surcharge (the scene of `tests/step_control.rs` with 10 MPa), relative residual
/// after the first Newton iteration of the second load step: 2.2e-1 with Chebyshev (2.4e-1 even
/// with `-ksp_rtol 1e-14`), 6.34e-2 with Richardson + SOR, 6.34e-2 with LU. It is the likely cause
/// of the GMRES breakdowns (PETSc reason −5) seen earlier on staged dams.
fn configure_ksp(ksp: p::KSP, rtol: f64, max_it: u32, symmetric: bool) -> Result<(), PetscError> {
    if symmetric {
        call!(KSPSetType(ksp, p::KSPCG.as_ptr() as *const c_char))?;
    } else {
        default_option("-mg_levels_ksp_type", "richardson")?;
        default_option("-mg_levels_pc_type", "sor")?;
        call!(KSPSetType(ksp, p::KSPGMRES.as_ptr() as *const c_char))?;
        call!(KSPGMRESSetRestart(ksp, 200))?;
        // GMRES cannot use the unpreconditioned norm with left preconditioning
        call!(KSPSetPCSide(ksp, p::PC_RIGHT))?;
    }
    let mut pc: p::PC = null_mut();
    call!(KSPGetPC(ksp, &mut pc))?;
    call!(PCSetType(pc, p::PCGAMG.as_ptr() as *const c_char))?;
    call!(KSPSetTolerances(ksp, rtol, 1e-300, 1e30, max_it as i32))?;
    call!(KSPSetNormType(ksp, p::KSP_NORM_UNPRECONDITIONED))
}

/// The reduced multigrid's inexact-Newton defaults (`cfrd::linalg::reduced_amg`, "Inexact
/// Newton"): PETSc's Eisenstat–Walker forcing terms, none looser than 0.03.
const EISENSTAT_WALKER: [(&str, &str); 3] = [
    ("-snes_ksp_ew", "true"),
    ("-snes_ksp_ew_rtol0", "0.03"),
    ("-snes_ksp_ew_rtolmax", "0.03"),
];

/// What a nonlinear problem gives PETSc's SNES: the residual F(x), the Jacobian J(x) and the
/// convergence test. Every method is called collectively (on all ranks, in the same order).
pub trait SnesProblem {
    /// Evaluates F(x) into `f`. `Ok(false)` reports a (collectively decided) failure to evaluate
    /// at `x`, e.g. a material update that failed on some rank; SNES then stops with
    /// [`SnesOutcome::DomainError`] (or its line search backs off).
    fn residual(&mut self, x: &Vector, f: &mut Vector) -> Result<bool, PetscError>;
    /// Evaluates J(x) into [`SnesProblem::jacobian_matrix`].
    fn jacobian(&mut self, x: &Vector) -> Result<bool, PetscError>;
    /// The matrix the Jacobian is assembled into (also the preconditioning matrix).
    fn jacobian_matrix(&self) -> &Matrix;
    /// Convergence test after `it` Newton iterations with PETSc's residual norm `fnorm` (the
    /// problem may use its own, rank-count-independent norm of the last residual instead) and
    /// the iterations of the last linear solve: `Some(true)` converged, `Some(false)` diverged,
    /// `None` go on.
    fn converged(&mut self, it: u32, fnorm: f64, linear_iterations: u32) -> Option<bool>;
    /// The line search's merit function at `x`, ‖F(x)‖², or `Ok(None)` when F cannot be
    /// evaluated there. Given to SNES as its objective, so that the `l2` and `bt` line searches
    /// rest on the problem's own (rank-count-independent) norm rather than on `VecNorm`, whose
    /// partial sums depend on the partition.
    fn objective(&mut self, x: &Vector) -> Result<Option<f64>, PetscError>;
    /// The dot product aᵀb of two vectors laid out like x, independent of the rank count
    /// (the residual secant line search's decisions rest on it).
    fn dot(&mut self, a: &Vector, b: &Vector) -> Result<f64, PetscError>;
    /// Whether the last residual evaluated already meets the convergence test (the same on
    /// every rank): [`LineSearch::ResidualSecant`] then keeps the full step rather than
    /// extending it, and Newton ends there. The default: never.
    fn last_residual_converged(&self) -> bool {
        false
    }
}

/// How a SNES solve ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SnesOutcome {
    /// The problem's convergence test was met.
    Converged,
    /// The residual or Jacobian could not be evaluated (material failure).
    DomainError,
    /// The linear solver failed (PETSc's KSP reason).
    LinearSolve(i32),
    /// The line search failed to decrease the residual.
    LineSearch,
    /// The problem's convergence test declared divergence, or the iteration limit was hit.
    Diverged(i32),
}

/// PETSc's nonlinear solver (Newton with a line search, `newtonls` with the `l2` line search by
/// default), driven by a [`SnesProblem`]; `-snes_*` options override the defaults.
pub struct Snes {
    raw: p::SNES,
    comm: mpi::ffi::MPI_Comm,
    settings: (u32, f64, u32, bool),
    /// The linear solver of the Newton corrections.
    method: LinearMethod,
    /// The canonical direct solver's state (the PC shell's context); dropped after the SNES.
    canonical_lu: Option<Box<CanonicalLu>>,
    /// The distributed direct solver's state (the PC shell's context); dropped after the SNES.
    distributed_lu: Option<Box<DistributedLu>>,
    /// The reduced multigrid's state (the PC shell's context); dropped after the SNES.
    reduced_amg: Option<Box<ReducedAmg>>,
    /// Factorizations of canonical solvers already dropped, not yet taken.
    factorizations: u64,
    /// Multigrid set-ups of reduced multigrids already dropped, not yet taken.
    multigrid_builds: u64,
    /// The direct solvers are set for the Jacobians of a dynamic stage ([`Snes::set_time_stepping`]).
    time_stepping: bool,
    /// How a Newton correction is scaled ([`Snes::set_line_search`]).
    line_search: LineSearch,
}

/// How a Newton correction δ is scaled before it is applied (x ← x − λ·δ). Both rest on the
/// problem's own merit function ‖F‖² ([`SnesProblem::objective`], exact sums), so every
/// decision is the same at any rank count.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LineSearch {
    /// PETSc's `l2`: the secant minimum of ‖F(x − λδ)‖² from λ = 1 and ½, at every
    /// iteration (three residual evaluations per iteration).
    Secant,
    /// The full step when it lowers ‖F‖² (one residual evaluation); otherwise the minimum
    /// of the parabola through λ = 0, ½, 1 (two more), halving while F cannot be evaluated.
    FullStepFirst,
    /// The full step, or a longer one, from the secant through F(x) and F(x − δ)
    /// (`residual_secant_step`) when the full step lowers ‖F‖²: one or two residual
    /// evaluations; otherwise `Secant`'s step (three). A full step whose residual already
    /// meets the convergence test ([`SnesProblem::last_residual_converged`]) is kept as it is.
    ResidualSecant,
}

/// The linear solver of the Newton corrections (the scene's `solver.linear_solver`).
#[derive(Debug, Clone)]
pub enum LinearMethod {
    /// cfrd's Krylov defaults (see `configure_ksp`): CG or GMRES with GAMG.
    Krylov,
    /// The same Krylov method preconditioned on the coupled rows only: LU of the structure,
    /// GAMG on the fill ([`ReducedAmg`]).
    ReducedAmg {
        /// The owned DOFs of the stiff structure (slab, interfaces, joints), increasing: the
        /// split factored apart from the fill.
        structure: Vec<i32>,
    },
    /// The canonical direct solver ([`CanonicalLu`]): results independent of the rank count.
    Canonical(CanonicalSettings),
    /// MUMPS's LU on the distributed matrix, factored by all ranks together
    /// ([`DistributedLu`]): each rank holds its share of the factors, so memory and work are
    /// split; results agree between rank counts, and between runs, to the factorization's
    /// rounding only.
    DistributedLu {
        /// Keep the factors of an earlier Jacobian as the preconditioner of GMRES while it
        /// converges quickly (`solver.reuse_factorization`); `false` factors every Jacobian.
        reuse_factorization: bool,
    },
}

/// Settings of the canonical direct solver ([`CanonicalLu`]).
#[derive(Debug, Clone)]
pub struct CanonicalSettings {
    /// The PETSc index of every DOF in the mesh's own order.
    pub dofs: Vec<i32>,
    /// Keep the factors of an earlier Jacobian as the preconditioner of GMRES while it converges
    /// quickly (`solver.reuse_factorization`); `false` factors every Jacobian.
    pub reuse_factorization: bool,
}

impl Snes {
    /// A Newton solver with at most `max_it` iterations and, for the linearized systems, the
    /// linear solver `method` ([`LinearMethod`]); then PETSc options are applied.
    pub fn new(
        petsc: &Petsc,
        max_it: u32,
        rtol: f64,
        ksp_max_it: u32,
        symmetric: bool,
        method: LinearMethod,
    ) -> Result<Snes, PetscError> {
        let mut raw: p::SNES = null_mut();
        call!(SNESCreate(petsc.comm, &mut raw))?;
        let mut s = Snes {
            raw,
            comm: petsc.comm,
            settings: (max_it, rtol, ksp_max_it, symmetric),
            method,
            canonical_lu: None,
            distributed_lu: None,
            reduced_amg: None,
            factorizations: 0,
            multigrid_builds: 0,
            time_stepping: false,
            line_search: LineSearch::Secant,
        };
        s.configure()?;
        Ok(s)
    }

    /// Sets the direct solvers up for the Jacobians of a dynamic stage (`true`) or of a static
    /// one from the next [`Snes::reset`] on (refactoring threshold and tolerance of
    /// [`super::lagged_lu`]).
    pub fn set_time_stepping(&mut self, on: bool) {
        self.time_stepping = on;
    }

    /// The line search of the Newton corrections from the next [`Snes::reset`] on
    /// (`-snes_linesearch_type` still overrides it).
    pub fn set_line_search(&mut self, line_search: LineSearch) {
        self.line_search = line_search;
    }

    /// Replaces the solver by a new one with the same settings: the next solve builds the
    /// preconditioner afresh (smoothed-aggregation GAMG otherwise keeps state from its earlier
    /// set-ups that `KSPReset` does not clear). Called at the start of every stage, so a stage's
    /// solves do not depend on the earlier stages and a restart from a checkpoint repeats them
    /// bitwise.
    pub fn reset(&mut self) -> Result<(), PetscError> {
        let mut raw: p::SNES = null_mut();
        call!(SNESCreate(self.comm, &mut raw))?;
        // SAFETY: created by SNESCreate, destroyed once; replaced by the new solver below.
        unsafe {
            p::SNESDestroy(&mut self.raw);
        }
        self.raw = raw;
        // the old shell context goes only now that no PC refers to it
        self.factorizations = self.take_factorizations();
        self.multigrid_builds = self.take_multigrid_builds();
        self.canonical_lu = None;
        self.distributed_lu = None;
        self.reduced_amg = None;
        self.configure()
    }

    /// cfrd's settings on a new SNES.
    fn configure(&mut self) -> Result<(), PetscError> {
        if let LinearMethod::Canonical(canonical) = &self.method {
            self.canonical_lu = Some(CanonicalLu::new(
                canonical.dofs.clone(),
                canonical.reuse_factorization,
                self.time_stepping,
            )?);
        }
        if let LinearMethod::DistributedLu { reuse_factorization } = &self.method {
            self.distributed_lu = Some(DistributedLu::new(
                self.comm,
                *reuse_factorization,
                self.time_stepping,
            )?);
        }
        let (max_it, rtol, ksp_max_it, symmetric) = self.settings;
        if let LinearMethod::ReducedAmg { structure } = &self.method {
            self.reduced_amg = Some(ReducedAmg::new(self.comm, symmetric, structure.clone())?);
            // inexact Newton (Eisenstat–Walker, reduced_amg module docs): a correction is
            // solved to 0.03, or as much more tightly as Newton converges fast
            for (name, value) in EISENSTAT_WALKER {
                default_option(name, value)?;
            }
        }
        let s = &*self;
        call!(SNESSetType(s.raw, p::SNESNEWTONLS.as_ptr() as *const c_char))?;
        // the problem's convergence test decides; only the iteration limit is SNES's own
        call!(SNESSetTolerances(s.raw, 0.0, 0.0, 0.0, max_it as i32, -1))?;
        // the secant line search minimizing ‖F‖² along the Newton direction: on the GP column
        // of tests/step_control.rs with a 10 MPa surcharge and at most 6 Newton iterations it
        // needs no cut-back ([4]) where the full step (`basic`) needs one ([6, 4]) and
        // backtracking (`bt`) two ([6, 4, 4]); `-snes_linesearch_type` overrides
        // (`LineSearch::FullStepFirst`: a shell whose function `solve` sets)
        let mut ls: p::SNESLineSearch = null_mut();
        call!(SNESGetLineSearch(s.raw, &mut ls))?;
        let kind = match s.line_search {
            LineSearch::Secant => p::SNESLINESEARCHL2.as_ptr(),
            LineSearch::FullStepFirst | LineSearch::ResidualSecant => p::SNESLINESEARCHSHELL.as_ptr(),
        };
        call!(SNESLineSearchSetType(ls, kind as *const c_char))?;
        let mut ksp: p::KSP = null_mut();
        call!(SNESGetKSP(s.raw, &mut ksp))?;
        match (&s.canonical_lu, &s.distributed_lu) {
            (Some(lu), _) => lu.install(ksp)?,
            (None, Some(lu)) => lu.install(ksp)?,
            (None, None) => configure_ksp(ksp, rtol, ksp_max_it, symmetric)?,
        }
        if let Some(amg) = &s.reduced_amg {
            let mut pc: p::PC = null_mut();
            call!(KSPGetPC(ksp, &mut pc))?;
            amg.install(pc)?;
        }
        // options (scene and command line) are applied here, so a bad one is an input error
        call!(SNESSetFromOptions(s.raw))
    }

    /// Set-ups of the reduced multigrid's multigrid since the last call (0 with other solvers).
    pub fn take_multigrid_builds(&mut self) -> u64 {
        let reduced = self
            .reduced_amg
            .as_mut()
            .map_or(0, |amg| amg.take_multigrid_builds());
        std::mem::take(&mut self.multigrid_builds) + reduced
    }

    /// Numeric factorizations of the direct solvers since the last call (0 with the Krylov
    /// defaults; the reduced multigrid's: of its structure).
    pub fn take_factorizations(&mut self) -> u64 {
        let canonical = self
            .canonical_lu
            .as_mut()
            .map_or(0, |lu| lu.inner.take_factorizations());
        let distributed = self
            .distributed_lu
            .as_mut()
            .map_or(0, |lu| lu.take_factorizations());
        let reduced = self.reduced_amg.as_mut().map_or(0, |amg| amg.take_builds());
        std::mem::take(&mut self.factorizations) + canonical + distributed + reduced
    }

    /// Solves F(x) = 0 from the initial guess in `x`, with `r` as the residual work vector.
    /// Returns the outcome and the Newton iterations.
    pub fn solve<P: SnesProblem>(
        &mut self,
        problem: &mut P,
        r: &mut Vector,
        x: &mut Vector,
    ) -> Result<(SnesOutcome, u32), PetscError> {
        let j = problem.jacobian_matrix().raw;
        let ctx = problem as *mut P as *mut std::ffi::c_void;
        call!(SNESSetFunction(self.raw, r.raw, Some(snes_residual::<P>), ctx))?;
        call!(SNESSetJacobian(self.raw, j, j, Some(snes_jacobian::<P>), ctx))?;
        call!(SNESSetConvergenceTest(
            self.raw,
            Some(snes_converged::<P>),
            ctx,
            None
        ))?;
        call!(SNESSetObjective(self.raw, Some(snes_objective::<P>), ctx))?;
        let mut ls: p::SNESLineSearch = null_mut();
        call!(SNESGetLineSearch(self.raw, &mut ls))?;
        // a no-op unless the line search is the shell (options may have chosen another)
        let shell = match self.line_search {
            LineSearch::ResidualSecant => residual_secant::<P>,
            _ => full_step_first::<P>,
        };
        call!(SNESLineSearchShellSetUserFunc(ls, Some(shell), ctx))?;
        call!(SNESSolve(self.raw, null_mut(), x.raw))?;
        let (mut reason, mut its) = (0, 0);
        call!(SNESGetConvergedReason(self.raw, &mut reason))?;
        call!(SNESGetIterationNumber(self.raw, &mut its))?;
        let outcome = match reason {
            r if r > 0 => SnesOutcome::Converged,
            p::SNES_DIVERGED_FUNCTION_DOMAIN => SnesOutcome::DomainError,
            p::SNES_DIVERGED_LINEAR_SOLVE => {
                let mut ksp: p::KSP = null_mut();
                let mut kr = 0;
                call!(SNESGetKSP(self.raw, &mut ksp))?;
                call!(KSPGetConvergedReason(ksp, &mut kr))?;
                SnesOutcome::LinearSolve(kr)
            }
            p::SNES_DIVERGED_LINE_SEARCH => SnesOutcome::LineSearch,
            r => SnesOutcome::Diverged(r),
        };
        Ok((outcome, its as u32))
    }
}

impl Drop for Snes {
    fn drop(&mut self) {
        // SAFETY: created by SNESCreate, destroyed once.
        unsafe {
            p::SNESDestroy(&mut self.raw);
        }
    }
}

unsafe extern "C" fn snes_objective<P: SnesProblem>(
    snes: p::SNES,
    x: p::Vec,
    obj: *mut p::PetscReal,
    ctx: *mut std::ffi::c_void,
) -> p::PetscErrorCode {
    // SAFETY: as in snes_residual; `obj` is a valid out-pointer.
    let problem = unsafe { &mut *(ctx as *mut P) };
    let value = match problem.objective(&borrowed(x)) {
        Ok(Some(v)) => v,
        // an infinite merit value makes the line search back off (or fail)
        Ok(None) => f64::INFINITY,
        Err(e) => return e.code.max(CALLBACK_FAILED),
    };
    let _ = snes;
    unsafe {
        *obj = value;
    }
    0
}

/// [`LineSearch::FullStepFirst`] as PETSc's shell line search: X ← X − λ·Y with F(X) in F.
unsafe extern "C" fn full_step_first<P: SnesProblem>(
    ls: p::SNESLineSearch,
    ctx: *mut std::ffi::c_void,
) -> p::PetscErrorCode {
    // SAFETY: as in snes_residual: ctx is the `&mut P` of the running SNESSolve.
    unsafe { full_step_shell::<P>(ls, ctx, false) }
}

/// [`LineSearch::ResidualSecant`] as PETSc's shell line search.
unsafe extern "C" fn residual_secant<P: SnesProblem>(
    ls: p::SNESLineSearch,
    ctx: *mut std::ffi::c_void,
) -> p::PetscErrorCode {
    // SAFETY: as in snes_residual: ctx is the `&mut P` of the running SNESSolve.
    unsafe { full_step_shell::<P>(ls, ctx, true) }
}

/// The shell line searches; `secant`: [`LineSearch::ResidualSecant`], else
/// [`LineSearch::FullStepFirst`].
///
/// # Safety
/// `ctx` is the `&mut P` of the running SNESSolve.
unsafe fn full_step_shell<P: SnesProblem>(
    ls: p::SNESLineSearch,
    ctx: *mut std::ffi::c_void,
    secant: bool,
) -> p::PetscErrorCode {
    // SAFETY: the caller's contract
    let problem = unsafe { &mut *(ctx as *mut P) };
    match shell_line_search_apply(ls, problem, secant) {
        Ok(()) => 0,
        Err(e) => e.code.max(CALLBACK_FAILED),
    }
}

/// The body of the shell line searches: X ← X − λ·Y with F(X) in F. Without `secant`
/// ([`LineSearch::FullStepFirst`]): λ = 1 when the full step lowers ‖F‖², else
/// [`fallback_step`]'s with the parabola's vertex kept in [0.1, 1]. With `secant`
/// ([`LineSearch::ResidualSecant`]): [`secant_choice`]'s λ, else the vertex as PETSc's `l2`
/// takes it; the full step where its residual meets Newton's tolerance ([`after_full_step`]).
fn shell_line_search_apply<P: SnesProblem>(
    ls: p::SNESLineSearch,
    problem: &mut P,
    secant: bool,
) -> Result<(), PetscError> {
    let (mut x, mut f, mut y, mut w, mut g) = (null_mut(), null_mut(), null_mut(), null_mut(), null_mut());
    call!(SNESLineSearchGetVecs(ls, &mut x, &mut f, &mut y, &mut w, &mut g))?;
    let (x, mut f, y, mut w, mut g) = (borrowed(x), borrowed(f), borrowed(y), borrowed(w), borrowed(g));
    let f0 = problem.objective(&x)?.unwrap_or(f64::INFINITY);
    let g1 = merit(problem, &x, &y, &mut w, 1.0)?;
    let rule = if secant {
        L2_FALLBACK
    } else {
        FULL_STEP_FIRST_FALLBACK
    };
    let chosen = match after_full_step(secant, f0, g1, problem.last_residual_converged()) {
        AfterFullStep::Keep => Some(1.0),
        AfterFullStep::Secant => secant_choice(problem, [&x, &y, &f], &mut w, &mut g, g1)?,
        AfterFullStep::Fallback => None,
    };
    let lambda = match chosen {
        Some(l) => Some(l),
        None => fallback_step(f0, g1, rule, &mut |l| merit(problem, &x, &y, &mut w, l))?,
    };
    let Some(lambda) = lambda else {
        return call!(SNESLineSearchSetReason(ls, p::SNES_LINESEARCH_FAILED_DOMAIN));
    };
    call!(VecWAXPY(w.raw, -lambda, y.raw, x.raw))?;
    // F at the chosen point: known from its merit evaluation unless λ is new
    if !problem.residual(&w, &mut f)? {
        return call!(SNESLineSearchSetReason(ls, p::SNES_LINESEARCH_FAILED_DOMAIN));
    }
    call!(VecCopy(w.raw, x.raw))?;
    let (mut xnorm, mut fnorm, mut ynorm) = (0.0, 0.0, 0.0);
    call!(VecNorm(x.raw, p::NORM_2, &mut xnorm))?;
    call!(VecNorm(f.raw, p::NORM_2, &mut fnorm))?;
    call!(VecNorm(y.raw, p::NORM_2, &mut ynorm))?;
    call!(SNESLineSearchSetNorms(ls, xnorm, fnorm, ynorm))?;
    call!(SNESLineSearchSetReason(ls, p::SNES_LINESEARCH_SUCCEEDED))
}

/// What a shell line search does once it knows φ(1) = `g1` (φ(0) = `f0`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum AfterFullStep {
    /// Take the full step.
    Keep,
    /// Try [`secant_choice`]'s longer step.
    Secant,
    /// The full step does not lower φ: [`fallback_step`].
    Fallback,
}

/// The full step when it lowers φ and either the line search is
/// [`LineSearch::FullStepFirst`] (`secant` false) or its residual already meets Newton's
/// convergence test (`converged`: an extension would only spend an evaluation); the residual
/// secant's step when it lowers φ otherwise; the fallback when it does not lower φ.
fn after_full_step(secant: bool, f0: f64, g1: f64, converged: bool) -> AfterFullStep {
    if g1 < f0 {
        if secant && !converged {
            AfterFullStep::Secant
        } else {
            AfterFullStep::Keep
        }
    } else {
        AfterFullStep::Fallback
    }
}

/// The merit φ(λ) = ‖F(x − λy)‖² (∞ where F cannot be evaluated), with x − λy left in `w`.
fn merit<P: SnesProblem>(
    problem: &mut P,
    x: &Vector,
    y: &Vector,
    w: &mut Vector,
    lambda: f64,
) -> Result<f64, PetscError> {
    call!(VecWAXPY(w.raw, -lambda, y.raw, x.raw))?;
    Ok(problem.objective(w)?.unwrap_or(f64::INFINITY))
}

/// [`LineSearch::ResidualSecant`]'s step when the full step lowered the merit, right after
/// φ(1) = `g1` was evaluated at `w` = x − y (`xyf` = [x, y, F(x)]; `g` is a work vector): 1
/// when [`residual_secant_step`] gives 1; its longer step when φ there is below φ(1), else 1;
/// `None` when it gives a shorter one (the caller takes PETSc's `l2` step instead).
fn secant_choice<P: SnesProblem>(
    problem: &mut P,
    xyf: [&Vector; 3],
    w: &mut Vector,
    g: &mut Vector,
    g1: f64,
) -> Result<Option<f64>, PetscError> {
    let [x, y, f] = xyf;
    // F(x − y) is the problem's last residual: copied, not evaluated again
    if !problem.residual(w, g)? {
        return Ok(None);
    }
    call!(VecAYPX(g.raw, -1.0, f.raw))?;
    let (along, squared) = (problem.dot(f, g)?, problem.dot(g, g)?);
    let lambda = residual_secant_step(along, squared).unwrap_or(0.0);
    if lambda <= 1.0 {
        return Ok((lambda == 1.0).then_some(1.0));
    }
    let gl = merit(problem, x, y, w, lambda)?;
    Ok(Some(if gl < g1 { lambda } else { 1.0 }))
}

/// The full step within `SECANT_SNAP` of [`residual_secant_step`]'s λ, and its largest λ,
/// `SECANT_LAMBDA_MAX`. PETSc's `l2` (the `Secant` line search, whose λ is unbounded) took
/// λ > 1.05 in 349 and λ > 3 in 17 of the 565 Newton iterations of the coarse hyperbolic seed
/// scene: the continuum tangent is stiffer than the consistent one, so Newton's corrections
/// fall short. Shorter steps are left to `l2`'s rule: on interfaces sliding at 100 Pa
/// (`tests/hard_cases.rs`) it took λ = 0.07, 0.008 and 1e-4 in successive iterations, and a
/// residual secant with a floor of 0.1, or of 1e-6, failed the step.
const SECANT_SNAP: f64 = 0.1;
/// See [`SECANT_SNAP`].
const SECANT_LAMBDA_MAX: f64 = 1.0e4;

/// The minimum of ‖F(0) − λ·d‖² over λ for d = F(0) − F(1) (F taken linear along the
/// correction, the secant through the two residual vectors): λ = F(0)ᵀd / ‖d‖² from
/// `along` = F(0)ᵀd and `squared` = ‖d‖², at most 1e4 and snapped to 1 within 0.1; `None`
/// when it is not a positive finite number.
fn residual_secant_step(along: f64, squared: f64) -> Option<f64> {
    let lambda = along / squared;
    if !(lambda.is_finite() && lambda > 0.0) {
        return None;
    }
    if (lambda - 1.0).abs() <= SECANT_SNAP {
        return Some(1.0);
    }
    Some(lambda.min(SECANT_LAMBDA_MAX))
}

/// [`LineSearch::FullStepFirst`]'s step from the merit φ at λ = 0, ½, 1: the vertex of the
/// parabola through them in [0.1, 1], or the smaller of φ(½) and φ(1) where it has none.
fn clamped_vertex(f0: f64, h: f64, g1: f64) -> f64 {
    let c = 2.0 * f0 - 4.0 * h + 2.0 * g1;
    let b = -3.0 * f0 + 4.0 * h - g1;
    if c > 0.0 {
        (-b / (2.0 * c)).clamp(0.1, 1.0)
    } else if h < g1 {
        0.5
    } else {
        1.0
    }
}

/// PETSc's `l2` step (one secant iteration, `-snes_linesearch_max_it 1`) from the merit φ
/// at λ = 0, ½, 1: λ = 1 − φ'(1)/|φ''| with the derivatives of the parabola through them,
/// downhill also where it is concave; ½ below `l2`'s least step 1e-12, 1 where λ is not finite
/// or above its largest step 1e8.
fn l2_vertex(f0: f64, h: f64, g1: f64) -> f64 {
    let slope = 3.0 * g1 - 4.0 * h + f0;
    let curvature = 4.0 * g1 - 8.0 * h + 4.0 * f0;
    let lambda = if curvature > 0.0 {
        1.0 - slope / curvature
    } else {
        1.0 + slope / curvature
    };
    if lambda < 1.0e-12 {
        0.5
    } else if !lambda.is_finite() || lambda > 1.0e8 {
        1.0
    } else {
        lambda
    }
}

/// How [`fallback_step`] picks λ: the vertex rule on φ at 0, ½, 1, the least λ to which it
/// halves where F cannot be evaluated, and whether it then applies the vertex rule on [0, λ].
#[derive(Clone, Copy)]
struct Fallback {
    vertex: fn(f64, f64, f64) -> f64,
    least: f64,
    rescale: bool,
}

/// [`LineSearch::FullStepFirst`]'s fallback: [`clamped_vertex`], halving to 1/64.
const FULL_STEP_FIRST_FALLBACK: Fallback = Fallback {
    vertex: clamped_vertex,
    least: 1.0 / 64.0,
    rescale: false,
};

/// [`LineSearch::ResidualSecant`]'s fallback, PETSc's `l2`: [`l2_vertex`], halving to its
/// least step 1e-12 and the vertex on [0, λ] from there (on a GP column under 30 MPa `l2`
/// found F only at λ = 1/512 of a first correction).
const L2_FALLBACK: Fallback = Fallback {
    vertex: l2_vertex,
    least: 1.0e-12,
    rescale: true,
};

/// The step length when the full step did not lower the merit φ (φ(0) = `f0`, φ(1) = `g1`),
/// or when the residual secant leaves it to the parabola: `rule.vertex(φ(0), φ(½), φ(1))`;
/// where φ is not finite, the first λ = ½, ¼, … ≥ `rule.least` where it is (with
/// `rule.rescale`, λ times the vertex rule on φ(0), φ(λ/2), φ(λ) unless that reaches 0.95 of
/// the last λ where φ was not finite); `None` if there is none.
/// `merit(λ)` evaluates φ.
fn fallback_step(
    f0: f64,
    g1: f64,
    rule: Fallback,
    merit: &mut dyn FnMut(f64) -> Result<f64, PetscError>,
) -> Result<Option<f64>, PetscError> {
    let h = merit(0.5)?;
    if h.is_finite() && g1.is_finite() && f0.is_finite() {
        return Ok(Some((rule.vertex)(f0, h, g1)));
    }
    let mut lambda = 0.5;
    let mut value = h;
    while !value.is_finite() {
        lambda *= 0.5;
        if lambda < rule.least {
            return Ok(None);
        }
        value = merit(lambda)?;
    }
    if rule.rescale && f0.is_finite() {
        let mid = merit(0.5 * lambda)?;
        // as `l2`: never back to 0.95 of the last λ where F failed (2λ)
        let vertex = lambda * (rule.vertex)(f0, mid, value);
        if mid.is_finite() && vertex <= 1.9 * lambda {
            return Ok(Some(vertex));
        }
    }
    Ok(Some(lambda))
}

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
    keep: Vec<i32>,
    /// The PETSc indices of the coupled rows, increasing (what is gathered).
    is_rows: p::IS,
    /// For every coupled row in canonical order: its place among `is_rows`.
    is_perm: p::IS,
    /// The gathered coupled block (array of one, from `MatCreateSubMatrices`).
    sub: *mut p::Mat,
    /// The coupled block in canonical order, the matrix factored (kept while the coupled rows
    /// stay the same, so its symbolic factorization is reused).
    reduced: p::Mat,
    /// For every canonical position: its index among the coupled rows, or -1 when decoupled.
    reduced_index: Vec<i32>,
    /// Diagonal in canonical order (the solution of a decoupled row is b_i / a_ii).
    diagonal: Vec<f64>,
    /// The inner sequential LU (its factors possibly those of an earlier Jacobian).
    inner: LaggedLu,
    rhs: Option<Vector>,
    solution: Option<Vector>,
}

impl CanonicalLu {
    fn new(canonical: Vec<i32>, reuse: bool, time_stepping: bool) -> Result<Box<CanonicalLu>, PetscError> {
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
    fn install(&self, ksp: p::KSP) -> Result<(), PetscError> {
        call!(KSPSetType(ksp, p::KSPPREONLY.as_ptr() as *const c_char))?;
        let mut pc: p::PC = null_mut();
        call!(KSPGetPC(ksp, &mut pc))?;
        call!(PCSetType(pc, p::PCSHELL.as_ptr() as *const c_char))?;
        let ctx = self as *const CanonicalLu as *mut std::ffi::c_void;
        call!(PCShellSetContext(pc, ctx))?;
        call!(PCShellSetSetUp(pc, Some(canonical_lu_setup)))?;
        call!(PCShellSetApply(pc, Some(canonical_lu_apply)))?;
        let name = CString::new("canonical LU (mesh DOF order, rank-count independent)").expect("no NUL");
        call!(PCShellSetName(pc, name.as_ptr()))
    }

    /// Finds the coupled rows of the preconditioning matrix of `pc`, gathers their block on
    /// every rank, permutes it into the canonical order and factors it.
    fn setup(&mut self, pc: p::PC) -> Result<(), PetscError> {
        let (mut a, mut pmat): (p::Mat, p::Mat) = (null_mut(), null_mut());
        call!(PCGetOperators(pc, &mut a, &mut pmat))?;
        let (coupled, diagonal) = self.coupling(pmat)?;
        let n = self.canonical.len();
        let keep: Vec<i32> = (0..n as i32).filter(|&i| coupled[i as usize]).collect();
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
                inverse[g as usize] = i;
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
    fn new_coupled_set(&mut self, keep: Vec<i32>) -> Result<(), PetscError> {
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
        self.reduced_index = vec![-1; n];
        for (k, &i) in keep.iter().enumerate() {
            self.reduced_index[i as usize] = k as i32;
        }
        let mut rows: Vec<i32> = keep.iter().map(|&i| self.canonical[i as usize]).collect();
        rows.sort_unstable();
        let perm: Vec<i32> = keep
            .iter()
            .map(|&i| {
                rows.binary_search(&self.canonical[i as usize])
                    .expect("a gathered row") as i32
            })
            .collect();
        self.keep = keep;
        // SAFETY: a constant handle set by MPI_Init.
        let self_comm = unsafe { mpi::ffi::RSMPI_COMM_SELF };
        call!(ISCreateGeneral(
            self_comm,
            rows.len() as i32,
            rows.as_ptr(),
            p::PETSC_COPY_VALUES,
            &mut self.is_rows
        ))?;
        call!(ISCreateGeneral(
            self_comm,
            perm.len() as i32,
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

    /// y = A⁻¹ x through the canonical factors.
    fn apply(&mut self, pc: p::PC, x: p::Vec, y: p::Vec) -> Result<(), PetscError> {
        let (x, mut y) = (borrowed(x), borrowed(y));
        let (Some(gather), Some(rhs)) = (self.gather.as_mut(), self.rhs.as_mut()) else {
            unreachable!("set up before the first solve");
        };
        let b = gather.gather(&x)?;
        let keep = &self.keep;
        b.read(|full| rhs.write(|r| r.iter_mut().zip(keep).for_each(|(o, &i)| *o = full[i as usize])))??;
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
                        let r = reduced_index[k];
                        *o = if r >= 0 {
                            s[r as usize]
                        } else {
                            full[k] / diagonal[k]
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

/// The shell context of `pc` as the canonical solver.
///
/// # Safety
/// `pc` must be a shell installed by [`CanonicalLu::install`], whose context is alive.
unsafe fn canonical_context<'a>(pc: p::PC) -> Result<&'a mut CanonicalLu, PetscError> {
    let mut ctx: *mut std::ffi::c_void = null_mut();
    call!(PCShellGetContext(
        pc,
        &mut ctx as *mut *mut std::ffi::c_void as *mut std::ffi::c_void
    ))?;
    // SAFETY: the context is the boxed CanonicalLu owned by the Snes (caller's contract).
    Ok(unsafe { &mut *(ctx as *mut CanonicalLu) })
}

unsafe extern "C" fn canonical_lu_setup(pc: p::PC) -> p::PetscErrorCode {
    // SAFETY: installed by CanonicalLu::install with its context.
    match unsafe { canonical_context(pc) }.and_then(|lu| lu.setup(pc)) {
        Ok(()) => 0,
        Err(e) => e.code.max(CALLBACK_FAILED),
    }
}

unsafe extern "C" fn canonical_lu_apply(pc: p::PC, x: p::Vec, y: p::Vec) -> p::PetscErrorCode {
    // SAFETY: installed by CanonicalLu::install with its context.
    match unsafe { canonical_context(pc) }.and_then(|lu| lu.apply(pc, x, y)) {
        Ok(()) => 0,
        Err(e) => e.code.max(CALLBACK_FAILED),
    }
}

/// Krylov iterations of the last solve of one of cfrd's preconditioner shells, told apart by
/// the name they report.
///
/// # Safety
/// `pc` must be a shell installed by [`CanonicalLu::install`] or [`DistributedLu::install`],
/// whose context is alive.
unsafe fn shell_iterations(pc: p::PC) -> Option<u32> {
    let mut name: *const c_char = null();
    unsafe { p::PCShellGetName(pc, &mut name) };
    if name.is_null() {
        return None;
    }
    // SAFETY: the name set by `install`, NUL-terminated while the PC lives.
    let name = unsafe { std::ffi::CStr::from_ptr(name) }.to_bytes_with_nul();
    if name == REDUCED_AMG_NAME {
        // an ordinary preconditioner of the outer Krylov solve, whose iterations count
        None
    } else if name == DISTRIBUTED_LU_NAME {
        // SAFETY: the distributed LU's shell (its name), caller's contract.
        unsafe { distributed_context(pc) }
            .ok()
            .map(|lu| lu.last_iterations())
    } else {
        // SAFETY: the only other shell cfrd installs is the canonical solver.
        unsafe { canonical_context(pc) }
            .ok()
            .map(|lu| lu.inner.last_iterations)
    }
}

/// A vector PETSc owns, seen as a [`Vector`] for the duration of a callback (never destroyed).
fn borrowed(raw: p::Vec) -> std::mem::ManuallyDrop<Vector> {
    std::mem::ManuallyDrop::new(Vector { raw })
}

/// PETSc error code of a failed callback.
pub(super) const CALLBACK_FAILED: p::PetscErrorCode = 1;

unsafe extern "C" fn snes_residual<P: SnesProblem>(
    snes: p::SNES,
    x: p::Vec,
    f: p::Vec,
    ctx: *mut std::ffi::c_void,
) -> p::PetscErrorCode {
    // SAFETY: ctx is the `&mut P` given to Snes::solve, alive for the whole SNESSolve.
    let problem = unsafe { &mut *(ctx as *mut P) };
    let (x, mut f) = (borrowed(x), borrowed(f));
    match problem.residual(&x, &mut f) {
        Ok(true) => 0,
        Ok(false) => unsafe { p::SNESSetFunctionDomainError(snes) },
        Err(e) => e.code.max(CALLBACK_FAILED),
    }
}

unsafe extern "C" fn snes_jacobian<P: SnesProblem>(
    snes: p::SNES,
    x: p::Vec,
    _a: p::Mat,
    _b: p::Mat,
    ctx: *mut std::ffi::c_void,
) -> p::PetscErrorCode {
    // SAFETY: as in snes_residual.
    let problem = unsafe { &mut *(ctx as *mut P) };
    match problem.jacobian(&borrowed(x)) {
        Ok(true) => 0,
        Ok(false) => unsafe { p::SNESSetJacobianDomainError(snes) },
        Err(e) => e.code.max(CALLBACK_FAILED),
    }
}

unsafe extern "C" fn snes_converged<P: SnesProblem>(
    snes: p::SNES,
    it: p::PetscInt,
    _xnorm: p::PetscReal,
    _gnorm: p::PetscReal,
    fnorm: p::PetscReal,
    reason: *mut p::SNESConvergedReason,
    ctx: *mut std::ffi::c_void,
) -> p::PetscErrorCode {
    // SAFETY: as in snes_residual; `reason` is a valid out-pointer.
    let problem = unsafe { &mut *(ctx as *mut P) };
    let mut lin = 0;
    if it > 0 {
        let (mut ksp, mut pc, mut kind): (p::KSP, p::PC, p::PCType) = (null_mut(), null_mut(), null());
        unsafe {
            p::SNESGetKSP(snes, &mut ksp);
            p::KSPGetIterationNumber(ksp, &mut lin);
            p::KSPGetPC(ksp, &mut pc);
            p::PCGetType(pc, &mut kind);
        }
        // SAFETY: PETSc's type name, a NUL-terminated string while the PC lives.
        let shell =
            !kind.is_null() && unsafe { std::ffi::CStr::from_ptr(kind) }.to_bytes_with_nul() == p::PCSHELL;
        // cfrd's shells (the direct solvers): their inner Krylov iterations
        if shell {
            // SAFETY: a shell installed by CanonicalLu::install or DistributedLu::install,
            // alive for the whole SNESSolve; its name tells which.
            if let Some(its) = unsafe { shell_iterations(pc) } {
                lin = its as i32;
            }
        }
    }
    let r = match problem.converged(it as u32, fnorm, lin as u32) {
        Some(true) => p::SNES_CONVERGED_FNORM_ABS,
        Some(false) => p::SNES_DIVERGED_DTOL,
        None => p::SNES_CONVERGED_ITERATING,
    };
    unsafe {
        *reason = r;
    }
    0
}

#[cfg(test)]
mod line_search_tests {
    use super::fallback_step;

    /// The merit values at the fallback's trial points, recorded.
    fn step_of(f0: f64, g1: f64, phi: impl Fn(f64) -> f64) -> (Option<f64>, Vec<f64>) {
        let mut asked = Vec::new();
        let step = fallback_step(f0, g1, super::FULL_STEP_FIRST_FALLBACK, &mut |l| {
            asked.push(l);
            Ok(phi(l))
        })
        .expect("no PETSc call");
        (step, asked)
    }

    #[test]
    fn an_overshooting_step_is_cut_to_the_parabolas_minimum() {
        // φ(λ) = 1 − 2λ + 3λ² (the full step overshoots: φ(1) = 2 > φ(0) = 1), minimum at 1/3
        let phi = |l: f64| 1.0 - 2.0 * l + 3.0 * l * l;
        let (step, asked) = step_of(phi(0.0), phi(1.0), phi);
        assert_eq!(asked, vec![0.5]);
        assert!((step.unwrap() - 1.0 / 3.0).abs() < 1e-15, "{step:?}");
        // a minimum close to zero is kept at 0.1
        let steep = |l: f64| 1.0 - 2.0 * l + 50.0 * l * l;
        assert_eq!(step_of(steep(0.0), steep(1.0), steep).0, Some(0.1));
    }

    #[test]
    fn a_concave_merit_takes_the_lower_of_the_two_trial_points() {
        // φ(λ) = 1 + 2λ − λ²: φ(½) = 1.75 < φ(1) = 2
        let phi = |l: f64| 1.0 + 2.0 * l - l * l;
        assert_eq!(step_of(phi(0.0), phi(1.0), phi).0, Some(0.5));
        // φ(λ) = 1 + 2λ − 1.9λ²: φ(1) = 1.1 < φ(½) = 1.525
        let phi = |l: f64| 1.0 + 2.0 * l - 1.9 * l * l;
        assert_eq!(step_of(phi(0.0), phi(1.0), phi).0, Some(1.0));
    }

    #[test]
    fn the_residual_secant_extrapolates_a_short_correction() {
        use super::residual_secant_step;
        // F linear along the correction, the full step removing 70 % of it: F(λ) = (1 − 0.7λ)F(0)
        // with F(0) = (3, 4): d = 0.7·F(0), λ = 1 / 0.7
        let f0 = [3.0, 4.0];
        let d = [0.7 * 3.0, 0.7 * 4.0];
        let along = f0[0] * d[0] + f0[1] * d[1];
        let squared = d[0] * d[0] + d[1] * d[1];
        let lambda = residual_secant_step(along, squared).unwrap();
        assert!((lambda - 1.0 / 0.7).abs() < 1e-12, "{lambda}");
        // a correction within 10 % of the root is the full step; far ones are clamped
        assert_eq!(residual_secant_step(1.05, 1.0), Some(1.0));
        assert_eq!(residual_secant_step(10.0, 1.0), Some(10.0));
        assert_eq!(residual_secant_step(1.0e6, 1.0), Some(1.0e4));
        assert_eq!(residual_secant_step(0.01, 1.0), Some(0.01));
        // no descent along the correction, or no change of F: no secant step
        assert_eq!(residual_secant_step(-1.0, 1.0), None);
        assert_eq!(residual_secant_step(0.0, 0.0), None);
    }

    #[test]
    fn a_full_step_that_meets_the_tolerance_is_not_extended() {
        use super::{after_full_step, AfterFullStep};
        // the residual secant extends a full step that lowered φ, unless Newton ends there
        assert_eq!(after_full_step(true, 1.0, 0.5, false), AfterFullStep::Secant);
        assert_eq!(after_full_step(true, 1.0, 0.5, true), AfterFullStep::Keep);
        // full_step_first keeps every full step that lowered φ
        assert_eq!(after_full_step(false, 1.0, 0.5, false), AfterFullStep::Keep);
        // a full step that does not lower φ (or where F failed) falls back, converged or not
        for secant in [true, false] {
            assert_eq!(after_full_step(secant, 1.0, 1.0, true), AfterFullStep::Fallback);
            assert_eq!(
                after_full_step(secant, 1.0, f64::INFINITY, false),
                AfterFullStep::Fallback
            );
        }
    }

    #[test]
    fn the_l2_vertex_is_petscs_secant_step() {
        use super::l2_vertex;
        // φ(λ) = 1 − 2λ + 3λ²: minimum at 1/3; a long one (φ = 1 − 2λ + 0.5λ²) at 2, beyond
        // the full step; a steep one at 1e-4, below the clamped vertex's 0.1
        let at = |phi: &dyn Fn(f64) -> f64| l2_vertex(phi(0.0), phi(0.5), phi(1.0));
        assert!((at(&|l| 1.0 - 2.0 * l + 3.0 * l * l) - 1.0 / 3.0).abs() < 1e-15);
        assert!((at(&|l| 1.0 - 2.0 * l + 0.5 * l * l) - 2.0).abs() < 1e-14);
        assert!((at(&|l| 1.0 - 2.0 * l + 1.0e4 * l * l) - 1.0e-4).abs() < 1e-15);
        // concave: downhill past the full step; no decrease from λ = 0: the midpoint
        assert!(at(&|l| 1.0 + 2.0 * l - 1.9 * l * l) > 1.0);
        assert_eq!(at(&|l| 1.0 + 2.0 * l + l * l), 0.5);
    }

    #[test]
    fn points_where_the_residual_fails_are_halved_away_or_reported() {
        // F cannot be evaluated beyond λ = 0.2: the first finite point of ½, ¼, ⅛
        let (step, asked) = step_of(1.0, f64::INFINITY, |l| if l > 0.2 { f64::INFINITY } else { 0.5 });
        assert_eq!(step, Some(0.125));
        assert_eq!(asked, vec![0.5, 0.25, 0.125]);
        // nowhere down to 1/64: no step
        let (step, asked) = step_of(1.0, f64::INFINITY, |_| f64::INFINITY);
        assert_eq!(step, None);
        assert_eq!(asked.last().copied(), Some(1.0 / 64.0));
    }
}
