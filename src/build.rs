//! Generates the PETSc and SLEPc FFI bindings with bindgen from Debian's PETSc 3.18 and SLEPc 3.18
//! (see `spec/stack.md` §3; SLEPc serves the modal analysis of spec seismic §4 items 4 and 9).
//!
//! Only runs when the `native` feature is on. Refuses to build against a PETSc with 64-bit indices or
//! non-double scalars, because the safe layer in `src/linalg/petsc/` assumes `PetscInt = i32` and
//! `PetscScalar = f64`.

use std::env;
use std::path::PathBuf;

fn main() {
    println!("cargo:rerun-if-changed=src/build.rs");
    if env::var_os("CARGO_FEATURE_NATIVE").is_none() {
        return;
    }
    let petsc = pkg_config::Config::new()
        .atleast_version("3.18")
        .probe("PETSc")
        .unwrap_or_else(|e| {
            panic!(
                "PETSc >= 3.18 not found by pkg-config ({e}). Install it with\n  \
                 apt-get install libpetsc-real-dev libopenmpi-dev openmpi-bin libhdf5-openmpi-dev libmetis-dev libclang-dev pkg-config\n\
                 or build without the native stack: cargo build --no-default-features"
            )
        });
    let slepc = pkg_config::Config::new()
        .atleast_version("3.18")
        .probe("SLEPc")
        .unwrap_or_else(|e| {
            panic!(
                "SLEPc >= 3.18 not found by pkg-config ({e}). Install it with\n  \
                 apt-get install libslepc-real-dev\n\
                 or build without the native stack: cargo build --no-default-features"
            )
        });
    let mpi = pkg_config::Config::new()
        .cargo_metadata(false)
        .probe("ompi-c")
        .expect("OpenMPI's pkg-config file ompi-c not found (apt-get install libopenmpi-dev)");

    let mut includes: Vec<PathBuf> = slepc.include_paths.clone();
    includes.extend(petsc.include_paths.iter().cloned());
    includes.extend(mpi.include_paths.iter().cloned());

    check_petscconf(&includes);

    let out = PathBuf::from(env::var("OUT_DIR").expect("OUT_DIR"));
    let header = out.join("petsc_wrapper.h");
    // bindgen makes cargo watch this header: rewriting it (a newer mtime) would rebuild the crate
    // at every cargo command, so it is written only when missing or different
    let wrapper = "#include <petscsnes.h>\n#include <slepceps.h>\n";
    if std::fs::read_to_string(&header).ok().as_deref() != Some(wrapper) {
        std::fs::write(&header, wrapper).expect("write wrapper header");
    }

    let mut builder = bindgen::Builder::default()
        .header(header.to_string_lossy())
        .allowlist_function("^(Petsc|Vec|Mat|KSP|PC|SNES|IS|ISLocalToGlobalMapping)[A-Za-z0-9_]*")
        .allowlist_function("^(Slepc|EPS|ST)[A-Za-z0-9_]*")
        .allowlist_type("^(Petsc|Vec|Mat|KSP|PC|SNES|IS|InsertMode|NormType|ScatterMode)[A-Za-z0-9_]*")
        .allowlist_type("^(EPS|ST)[A-Za-z0-9_]*")
        .allowlist_var("^(PETSC_|KSP|PC|MAT|VEC|SNES)[A-Za-z0-9_]*")
        .allowlist_var("^(EPS|ST)[A-Z0-9_]*")
        .blocklist_type("^(MPI_|ompi_).*")
        .raw_line("#[allow(unused_imports)] use mpi::ffi::*;")
        .prepend_enum_name(false)
        .layout_tests(false)
        .generate_comments(false)
        .parse_callbacks(Box::new(bindgen::CargoCallbacks::new()));
    for dir in &includes {
        builder = builder.clang_arg(format!("-I{}", dir.display()));
    }
    builder
        .generate()
        .expect("bindgen failed on petscsnes.h and slepceps.h")
        .write_to_file(out.join("petsc_bindings.rs"))
        .expect("write petsc_bindings.rs");
}

/// Reads `petscconf.h` and refuses 64-bit indices or non-double scalars.
fn check_petscconf(includes: &[PathBuf]) {
    for dir in includes {
        let conf = dir.join("petscconf.h");
        if let Ok(text) = std::fs::read_to_string(&conf) {
            println!("cargo:rerun-if-changed={}", conf.display());
            if text.contains("#define PETSC_USE_64BIT_INDICES") {
                panic!(
                    "{}: PETSc built with 64-bit indices; cfrd needs 32-bit PetscInt",
                    conf.display()
                );
            }
            if !text.contains("#define PETSC_USE_REAL_DOUBLE") {
                panic!("{}: PETSc must use real double scalars", conf.display());
            }
            return;
        }
    }
    panic!("petscconf.h not found in the PETSc include paths {includes:?}");
}
