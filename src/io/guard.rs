//! I/O failures that end every rank: free-space checks before collective writes, a watchdog on
//! every collective file operation, and the exit without MPI finalization once an HDF5 file had
//! to be abandoned.
//!
//! Under MPI-IO an HDF5 file is closed collectively, and closing flushes its metadata. After a
//! write failed (a full disk, a quota, a failing device), the ranks' views of the file differ and
//! that flush can enter different collective calls on different ranks: the job hangs until the
//! wall-time limit. So cfrd
//!
//! 1. checks the free space of the output file system before every collective write and refuses
//!    the write, on every rank, when less than its size plus [`RESERVE_BYTES`] is free
//!    ([`ensure_space`]): a full disk is in almost every case found here, and the files already
//!    open are closed normally;
//! 2. never closes a file after a write failed or was refused: [`abandon`] marks every open
//!    results and checkpoint file, whose HDF5 handles are then leaked, rank 0 removes their
//!    temporary files, and the process ends with the I/O exit code without finalizing MPI
//!    ([`exit_now`]), so HDF5's shutdown does not flush them;
//! 3. runs every collective file operation under a watchdog ([`watch`], [`watch_sized`]): a
//!    rank that is still inside one after [`io_timeout`] seconds prints what it was doing and
//!    ends with the I/O exit code, and `mpirun` then ends the other ranks. The limit is
//!    `CFRD_IO_TIMEOUT` seconds if set; by default [`BASE_TIMEOUT_S`] plus the operation's bytes
//!    at [`SLOWEST_BYTES_PER_S`], so a hung small write ends the job within a minute while a
//!    large file on a slow parallel file system still has time to be written.
//!
//! The exit code of every I/O and environment failure is [`EXIT_IO`] (4), distinct from input
//! errors (2) and solver failures (3).
#![allow(unsafe_code)]

use std::path::Path;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Mutex, Once};
use std::time::{Duration, SystemTime, UNIX_EPOCH};

pub use crate::parallel::EXIT_IO;

/// Bytes that must stay free after every collective write: room for the HDF5 metadata that the
/// parallel metadata cache holds dirty (at most 256 KiB before it flushes) and for the file's
/// final flush at close.
pub const RESERVE_BYTES: u64 = 512 * 1024;

/// Seconds any collective file operation may take by default, whatever its size.
pub const BASE_TIMEOUT_S: u64 = 45;

/// The slowest rate (bytes per second) at which a file operation is still taken as progressing
/// when no `CFRD_IO_TIMEOUT` is set: 4 MiB/s, far below a local disk or a parallel file system.
pub const SLOWEST_BYTES_PER_S: u64 = 4 << 20;

static ABANDONED: AtomicBool = AtomicBool::new(false);
/// Deadline of the collective operation in progress (milliseconds since the epoch; 0: none).
static DEADLINE_MS: AtomicU64 = AtomicU64::new(0);
static WHAT: Mutex<String> = Mutex::new(String::new());
/// The limit of the operation in progress, seconds (for the message).
static LIMIT_S: AtomicU64 = AtomicU64::new(0);
static WATCHDOG: Once = Once::new();

/// Seconds a rank may spend inside one collective file operation on `bytes` bytes:
/// `CFRD_IO_TIMEOUT` if it is a positive integer, else [`BASE_TIMEOUT_S`] plus `bytes` at
/// [`SLOWEST_BYTES_PER_S`].
pub fn io_timeout(bytes: u64) -> u64 {
    std::env::var("CFRD_IO_TIMEOUT")
        .ok()
        .and_then(|v| v.trim().parse::<u64>().ok())
        .filter(|&s| s > 0)
        .unwrap_or(BASE_TIMEOUT_S + bytes / SLOWEST_BYTES_PER_S)
}

fn now_ms() -> u64 {
    SystemTime::now()
        .duration_since(UNIX_EPOCH)
        .map_or(0, |d| d.as_millis() as u64)
}

/// A collective file operation under the watchdog; dropping it ends the watch.
pub struct Watch {
    outer: bool,
}

/// Starts watching the collective file operation `what` on a few bytes (metadata): a
/// [`watch_sized`] of 0 bytes.
pub fn watch(what: &str) -> Watch {
    watch_sized(what, 0)
}

/// Starts watching the collective file operation `what` that moves `bytes` bytes (a nested
/// call runs under the outer one's watch). See the module docs.
pub fn watch_sized(what: &str, bytes: u64) -> Watch {
    WATCHDOG.call_once(|| {
        std::thread::spawn(watchdog);
    });
    let limit = io_timeout(bytes);
    let deadline = now_ms() + 1000 * limit;
    let outer = DEADLINE_MS
        .compare_exchange(0, deadline, Ordering::SeqCst, Ordering::SeqCst)
        .is_ok();
    if outer {
        LIMIT_S.store(limit, Ordering::SeqCst);
        if let Ok(mut w) = WHAT.lock() {
            *w = what.to_string();
        }
    }
    Watch { outer }
}

impl Drop for Watch {
    fn drop(&mut self) {
        if self.outer {
            DEADLINE_MS.store(0, Ordering::SeqCst);
        }
    }
}

fn watchdog() {
    loop {
        std::thread::sleep(Duration::from_millis(500));
        let deadline = DEADLINE_MS.load(Ordering::SeqCst);
        if deadline != 0 && now_ms() > deadline {
            let what = WHAT.lock().map(|w| w.clone()).unwrap_or_default();
            eprintln!(
                "error: {what} did not finish within {} s on this rank (a full or failing file \
                 system?); the job ends with exit code {EXIT_IO}; the last checkpoint is intact \
                 (CFRD_IO_TIMEOUT sets the limit)",
                LIMIT_S.load(Ordering::SeqCst)
            );
            exit_now(EXIT_IO);
        }
    }
}

/// Marks that a collective write failed or was refused: every results or checkpoint file still
/// open is left open, the process must not finalize MPI (HDF5 would flush those files on the
/// way) and ends through [`exit_now`].
pub fn abandon() {
    ABANDONED.store(true, Ordering::SeqCst);
}

/// Whether an HDF5 file was abandoned ([`abandon`]).
pub fn abandoned() -> bool {
    ABANDONED.load(Ordering::SeqCst)
}

/// Ends the process at once with `code`, without running exit handlers or finalizing MPI
/// (standard output and error are flushed first).
pub fn exit_now(code: i32) -> ! {
    use std::io::Write;
    let _ = std::io::stdout().flush();
    let _ = std::io::stderr().flush();
    // SAFETY: _exit takes no pointers and never returns.
    unsafe { libc::_exit(code) }
}

/// Bytes available to an unprivileged writer on the file system holding `dir`, or `None` when
/// the file system does not say.
pub fn free_bytes(dir: &Path) -> Option<u64> {
    use std::os::unix::ffi::OsStrExt;
    let c = std::ffi::CString::new(dir.as_os_str().as_bytes()).ok()?;
    let mut st = std::mem::MaybeUninit::<libc::statvfs>::uninit();
    // SAFETY: `c` is a NUL-terminated path and `st` a writable statvfs; read only on success.
    let st = unsafe {
        if libc::statvfs(c.as_ptr(), st.as_mut_ptr()) != 0 {
            return None;
        }
        st.assume_init()
    };
    Some((st.f_bavail as u64).saturating_mul(st.f_frsize as u64))
}

/// Checks that `bytes` more can be written to the file system of `file` with
/// [`RESERVE_BYTES`] to spare (`CFRD_IO_RESERVE` overrides the reserve, in bytes). Call on one
/// rank and agree on the outcome.
pub fn ensure_space(file: &Path, bytes: u64) -> Result<(), super::IoError> {
    let dir = match file.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    let reserve = std::env::var("CFRD_IO_RESERVE")
        .ok()
        .and_then(|v| v.trim().parse::<u64>().ok())
        .unwrap_or(RESERVE_BYTES);
    let need = bytes.saturating_add(reserve);
    match free_bytes(dir) {
        Some(free) if free < need => Err(super::IoError::NoSpace {
            path: file.to_path_buf(),
            free,
            need,
        }),
        _ => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn free_space_is_reported_and_checked() {
        let dir = tempfile::tempdir().unwrap();
        let free = free_bytes(dir.path()).expect("statvfs of a temporary directory");
        assert!(free > 0);
        let file = dir.path().join("results.h5");
        assert!(ensure_space(&file, 0).is_ok() || free < RESERVE_BYTES);
        let err = ensure_space(&file, u64::MAX / 2).unwrap_err().to_string();
        assert!(
            err.contains("no space left") && err.contains("results.h5"),
            "{err}"
        );
        assert!(free_bytes(Path::new("/no/such/dir")).is_none());
    }
}
