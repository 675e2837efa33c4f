//! MPI start-up, the abort-on-panic hook, and collective decisions.
//!
//! Rules (`spec/stack.md` §4): MPI is initialized first (rsmpi), PETSc second, and finalized in
//! the reverse order. A panic on one rank must not leave the others waiting in a collective: the
//! hook installed by [`install_panic_hook`] prints the panic and calls `MPI_Abort`, ending the
//! whole job. Input errors are decided collectively with [`any_error`], so that every rank
//! takes the same branch and exits with the same code.
#![allow(unsafe_code)]

use mpi::collective::{CommunicatorCollectives, Root, SystemOperation};
use mpi::topology::{Communicator, SimpleCommunicator};

/// Exit code for input errors (bad YAML, mesh, parameters, options).
pub const EXIT_INPUT: i32 = 2;
/// Exit code for solver failures.
pub const EXIT_SOLVER: i32 = 3;
/// Exit code of I/O and environment failures: a full disk, a failing file system, an output
/// directory that cannot be created ([`crate::io::guard`]).
pub const EXIT_IO: i32 = 4;
/// Exit code used by the panic hook's `MPI_Abort`.
pub const EXIT_PANIC: i32 = 101;

/// Installs a panic hook that prints the panic (default hook) and aborts the whole MPI job.
pub fn install_panic_hook() {
    let default = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        default(info);
        // SAFETY: MPI_Abort may be called at any time after MPI_Init; it does not return.
        unsafe {
            mpi::ffi::MPI_Abort(mpi::ffi::RSMPI_COMM_WORLD, EXIT_PANIC);
        }
    }));
}

/// True on every rank if `local` is true on any rank (collective).
pub fn any(world: &SimpleCommunicator, local: bool) -> bool {
    let mut out = 0i32;
    world.all_reduce_into(&(local as i32), &mut out, SystemOperation::max());
    out != 0
}

/// Decides a fallible step collectively: if any rank failed, every rank gets `Err` with the
/// message of the lowest failing rank (broadcast), so all ranks report and exit the same way.
pub fn any_error<T, E: std::fmt::Display>(
    world: &SimpleCommunicator,
    local: Result<T, E>,
) -> Result<T, String> {
    let my_fail = if local.is_err() { world.rank() } else { i32::MAX };
    let mut first = i32::MAX;
    world.all_reduce_into(&my_fail, &mut first, SystemOperation::min());
    if first == i32::MAX {
        return local.map_err(|_| unreachable!("no rank failed"));
    }
    let mut msg: Vec<u8> = match &local {
        Err(e) if world.rank() == first => e.to_string().into_bytes(),
        _ => Vec::new(),
    };
    broadcast_vec(world, first, &mut msg);
    Err(String::from_utf8_lossy(&msg).into_owned())
}

/// Broadcasts a vector of any length from `root` (the other ranks' contents are replaced).
pub fn broadcast_vec<T: mpi::datatype::Equivalence + Default + Clone>(
    world: &SimpleCommunicator,
    root: i32,
    data: &mut Vec<T>,
) {
    let proc = world.process_at_rank(root);
    let mut len = data.len() as u64;
    proc.broadcast_into(&mut len);
    data.resize(len as usize, T::default());
    if len > 0 {
        proc.broadcast_into(&mut data[..]);
    }
}

/// Sum over ranks.
pub fn sum_f64(world: &SimpleCommunicator, v: f64) -> f64 {
    let mut out = 0.0;
    world.all_reduce_into(&v, &mut out, SystemOperation::sum());
    out
}

/// Sum over ranks, entry by entry (every rank passes the same length).
pub fn sum_f64_slice(world: &SimpleCommunicator, v: &[f64]) -> Vec<f64> {
    let mut out = vec![0.0; v.len()];
    world.all_reduce_into(v, &mut out[..], SystemOperation::sum());
    out
}

/// Whether `v` is true on any rank (collective).
pub fn any_true(world: &SimpleCommunicator, v: bool) -> bool {
    sum_u64(world, u64::from(v)) > 0
}

/// Sum over ranks.
pub fn sum_u64(world: &SimpleCommunicator, v: u64) -> u64 {
    let mut out = 0u64;
    world.all_reduce_into(&v, &mut out, SystemOperation::sum());
    out
}

/// Maximum over ranks.
pub fn max_f64(world: &SimpleCommunicator, v: f64) -> f64 {
    let mut out = 0.0;
    world.all_reduce_into(&v, &mut out, SystemOperation::max());
    out
}

/// Sum of `local` over all ranks, bit for bit independent of the rank count, of how the terms
/// are spread over the ranks and of their order ([`crate::solver::exact_sum`]: exact fixed-point
/// accumulation on a grid set by the largest magnitude). NaN if any term is not finite.
/// Collective.
pub fn exact_sum(world: &SimpleCommunicator, local: impl Iterator<Item = f64> + Clone) -> f64 {
    use crate::solver::exact_sum::{max_abs, ExactGrid};
    let m = max_abs(local.clone());
    // NaN (a non-finite term somewhere) is carried as +inf through the max
    let m = max_f64(world, if m.is_nan() { f64::INFINITY } else { m });
    if !m.is_finite() {
        return f64::NAN;
    }
    let grid = ExactGrid::new(m);
    let part = grid.partial(local);
    let words = [part as u64, (part >> 64) as u64];
    let mut all = vec![0u64; 2 * world.size() as usize];
    world.all_gather_into(&words[..], &mut all[..]);
    let total = all
        .chunks(2)
        .map(|w| ((w[1] as i128) << 64) | w[0] as i128)
        .fold(0i128, i128::wrapping_add);
    grid.to_f64(total)
}

/// Euclidean norm of a distributed vector from this rank's entries, independent of the rank
/// count ([`exact_sum`] of the squares). Collective.
pub fn exact_norm2(world: &SimpleCommunicator, local: &[f64]) -> f64 {
    exact_sum(world, local.iter().map(|v| v * v)).sqrt()
}

/// An `mpirun -n np` command for a child job on a small shared machine, as the tests start
/// theirs (`spec/stack.md` §8 pattern B): as root, oversubscribed, unbound, with a time limit
/// of `timeout_seconds`, without the variables of an MPI singleton parent (a child `mpirun`
/// that inherits them fails), and with the ranks yielding while they wait. Tests run side by
/// side, so two 2-rank jobs share 2 cores; Open MPI does not see that and spins while a rank
/// waits, and SuperLU_DIST (the structure of `reduced_amg`) waits often: the embedded default
/// dam to stage 5, two jobs at once, took 231, 191 and 42 s each in three pairs spinning and
/// 15 s yielding (7 s alone). The caller adds the program and its arguments.
pub fn mpirun_command(np: usize, timeout_seconds: u32) -> std::process::Command {
    let mut cmd = std::process::Command::new("mpirun");
    for (key, _) in std::env::vars_os() {
        let key = key.to_string_lossy();
        if ["OMPI_", "PMIX_", "OPAL_", "ORTE_"]
            .iter()
            .any(|p| key.starts_with(p))
        {
            cmd.env_remove(&*key);
        }
    }
    cmd.args(["-n", &np.to_string(), "--oversubscribe", "--bind-to", "none"])
        .args(["--timeout", &timeout_seconds.to_string()])
        .env("OMPI_ALLOW_RUN_AS_ROOT", "1")
        .env("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1")
        .env("OMPI_MCA_btl_vader_single_copy_mechanism", "none")
        .env("OMPI_MCA_mpi_yield_when_idle", "1")
        .stdin(std::process::Stdio::null());
    cmd
}
