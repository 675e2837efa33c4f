//! The PETSc library guard [`Petsc`]: start-up on a communicator, the options database as a
//! whole, and shutdown.
#![allow(unsafe_code)]

use super::error::{call, to_usize, PetscError};
use crate::linalg::ffi as p;
use mpi::raw::AsRaw;
use mpi::topology::SimpleCommunicator;
use std::ffi::{c_char, CStr, CString};
use std::ptr::{null, null_mut};

/// One OpenMP thread per MPI rank, unless `OMP_NUM_THREADS` says otherwise: SuperLU_DIST (the
/// reduced multigrid's structure factorization, the `reduced_amg` module) is built with
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

    /// Inserts `options` as [`Petsc::insert_options`] does, and starts PETSc's performance
    /// log when they ask for it (`-log_view` and its kin) and it was not running: PETSc starts
    /// it in `PetscInitialize` only, for options given to it there, so `-log_view` inserted
    /// later would print nothing.
    pub fn insert_run_options(&self, options: &str) -> Result<(), PetscError> {
        let before = self.has_option("-log_view")?;
        self.insert_options(options)?;
        if !before && self.has_option("-log_view")? {
            call!(PetscLogDefaultBegin())?;
        }
        Ok(())
    }

    /// Whether the options database holds `name` (with or without a value).
    fn has_option(&self, name: &str) -> Result<bool, PetscError> {
        let c = CString::new(name).map_err(|_| PetscError {
            code: -1,
            call: "PetscOptionsHasName",
            message: "option name contains a NUL byte".into(),
        })?;
        let mut set = p::PETSC_FALSE;
        call!(PetscOptionsHasName(null_mut(), null(), c.as_ptr(), &mut set))?;
        Ok(set == p::PETSC_TRUE)
    }

    /// Options set (in the scene or on the command line) that no PETSc object has read so far,
    /// as `-name value` (PETSc's own unused-option record, `PetscOptionsLeftGet`): at the end of
    /// a run, misspelled options or options of a solver the run did not use.
    pub fn unused_options(&self) -> Result<Vec<String>, PetscError> {
        let lists = LeftOptions::get()?;
        let left = lists.text()?;
        lists.restore()?;
        Ok(left)
    }

    /// The communicator PETSc runs on.
    pub fn comm(&self) -> mpi::ffi::MPI_Comm {
        self.comm
    }
}

/// PETSc's lists of unused options (`PetscOptionsLeftGet`), given back by
/// [`LeftOptions::restore`] or, on an early return, on drop.
struct LeftOptions {
    n: p::PetscInt,
    names: *mut *mut c_char,
    values: *mut *mut c_char,
    lent: bool,
}

impl LeftOptions {
    /// The options of the database that no PETSc object has read.
    fn get() -> Result<LeftOptions, PetscError> {
        let mut lists = LeftOptions {
            n: 0,
            names: null_mut(),
            values: null_mut(),
            lent: false,
        };
        call!(PetscOptionsLeftGet(
            null_mut(),
            &mut lists.n,
            &mut lists.names,
            &mut lists.values
        ))?;
        lists.lent = true;
        Ok(lists)
    }

    /// The options as `-name value`.
    fn text(&self) -> Result<Vec<String>, PetscError> {
        let entry = |list: *mut *mut c_char, i: usize| -> String {
            // SAFETY: PETSc returned `n` entries in each list (`i < n`), valid until
            // PetscOptionsLeftRestore; an entry may be NULL (no value).
            unsafe {
                let s = *list.add(i);
                if s.is_null() {
                    String::new()
                } else {
                    CStr::from_ptr(s).to_string_lossy().into_owned()
                }
            }
        };
        let left = (0..to_usize(self.n.max(0), "unused options")?)
            .map(|i| {
                let (name, value) = (entry(self.names, i), entry(self.values, i));
                match value.is_empty() {
                    true => format!("-{name}"),
                    false => format!("-{name} {value}"),
                }
            })
            .collect();
        Ok(left)
    }

    fn give_back(&mut self) -> Result<(), PetscError> {
        self.lent = false;
        call!(PetscOptionsLeftRestore(
            null_mut(),
            &mut self.n,
            &mut self.names,
            &mut self.values
        ))
    }

    /// Gives the lists back to PETSc.
    fn restore(mut self) -> Result<(), PetscError> {
        self.give_back()
    }
}

impl Drop for LeftOptions {
    fn drop(&mut self) {
        if self.lent {
            // an error is already on its way out; this one would only hide it
            let _ = self.give_back();
        }
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
