//! One run per output directory at a time: `cfrd run` holds an exclusive lock on the file
//! `.cfrd.lock` in its output directory from before it looks at the directory's files until it
//! ends. A second run started into the same directory meanwhile is refused at once (exit code
//! 2) instead of racing the first for its files. The lock is the kernel's (`flock`, through `File::try_lock`), so a killed
//! run holds it no longer: its directory can be restarted from or overwritten at once.

use std::path::{Path, PathBuf};

/// The lock file's name in the output directory.
pub const LOCK_FILE: &str = ".cfrd.lock";

/// The held lock of an output directory (rank 0 holds it; released when dropped or when the
/// process ends). A directory the lock created and that holds nothing else when the lock is
/// released (a run refused before it wrote anything) is removed again.
#[derive(Debug)]
pub struct RunLock {
    /// The locked file, held open for the run: closing it releases the lock.
    _file: std::fs::File,
    dir: PathBuf,
    created_dir: bool,
}

impl RunLock {
    /// Creates `dir` if needed and takes the exclusive lock of its [`LOCK_FILE`]; an error
    /// names the directory when another process holds it. A refused attempt removes nothing.
    pub fn acquire(dir: &Path) -> Result<RunLock, String> {
        let shown = dir.display();
        let created_dir = match std::fs::metadata(dir) {
            Ok(m) if !m.is_dir() => return Err(format!("output directory {shown}: not a directory")),
            Ok(_) => false,
            Err(_) => true,
        };
        let path = dir.join(LOCK_FILE);
        // a run that ends removes the lock file (and the directory) it created when it wrote
        // nothing else; one that opened the file before that holds the lock of an unlinked
        // file, so it checks and tries again
        for _ in 0..100 {
            std::fs::create_dir_all(dir).map_err(|e| format!("output directory {shown}: {e}"))?;
            let file = lock_file(&path, dir)?;
            if still_at(&file, &path) {
                return Ok(RunLock {
                    _file: file,
                    dir: dir.to_path_buf(),
                    created_dir,
                });
            }
        }
        Err(format!(
            "output directory {shown}: {} keeps being replaced while it is locked",
            path.display()
        ))
    }
}

/// Opens (creating) and locks the lock file `path` of `dir`: a regular file, never followed
/// through a symbolic link nor blocking on a FIFO, its content left as it is.
fn lock_file(path: &Path, dir: &Path) -> Result<std::fs::File, String> {
    use std::os::unix::fs::OpenOptionsExt;
    let shown = dir.display();
    let file = std::fs::OpenOptions::new()
        .read(true)
        .write(true)
        .create(true)
        .truncate(false)
        .custom_flags(libc::O_NOFOLLOW | libc::O_NONBLOCK)
        .open(path)
        .map_err(|e| format!("output directory {shown}: cannot open {}: {e}", path.display()))?;
    match file.metadata() {
        Ok(m) if m.is_file() => {}
        Ok(m) => {
            return Err(format!(
                "output directory {shown}: {} is {}, not a regular file; remove it",
                path.display(),
                crate::input::file_kind(&m)
            ))
        }
        Err(e) => return Err(format!("output directory {shown}: {}: {e}", path.display())),
    }
    match file.try_lock() {
        Ok(()) => Ok(file),
        Err(std::fs::TryLockError::WouldBlock) => Err(format!(
            "output directory {shown}: another cfrd run is writing into it (it holds {}); \
             wait until it ends, or choose another directory with -o",
            path.display()
        )),
        Err(std::fs::TryLockError::Error(e)) => Err(format!(
            "output directory {shown}: cannot lock {}: {e}",
            path.display()
        )),
    }
}

/// Whether the open `file` is still the file at `path` (not unlinked or replaced meanwhile).
fn still_at(file: &std::fs::File, path: &Path) -> bool {
    use std::os::unix::fs::MetadataExt;
    match (file.metadata(), std::fs::metadata(path)) {
        (Ok(a), Ok(b)) => a.dev() == b.dev() && a.ino() == b.ino(),
        _ => false,
    }
}

impl Drop for RunLock {
    fn drop(&mut self) {
        if !self.created_dir {
            return;
        }
        let only_lock = std::fs::read_dir(&self.dir).is_ok_and(|entries| {
            entries
                .flatten()
                .all(|e| e.file_name() == std::ffi::OsStr::new(LOCK_FILE))
        });
        if only_lock {
            let _ = std::fs::remove_file(self.dir.join(LOCK_FILE));
            let _ = std::fs::remove_dir(&self.dir);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_second_lock_of_one_directory_is_refused_until_the_first_is_dropped() {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("out");
        let first = RunLock::acquire(&out).expect("first");
        let msg = RunLock::acquire(&out).expect_err("held");
        assert!(msg.contains("another cfrd run is writing into it"), "{msg}");
        assert!(out.join(LOCK_FILE).exists(), "a refused attempt removes nothing");
        drop(first);
        assert!(
            !out.exists(),
            "a directory holding only the lock is removed again"
        );
        let again = RunLock::acquire(&out).expect("free again");
        std::fs::write(out.join("results.h5"), b"x").unwrap();
        drop(again);
        assert!(out.join("results.h5").exists() && out.join(LOCK_FILE).exists());
    }

    #[test]
    fn a_lock_of_a_file_unlinked_meanwhile_is_told_apart() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join(LOCK_FILE);
        let file = lock_file(&path, dir.path()).expect("locked");
        assert!(still_at(&file, &path));
        std::fs::remove_file(&path).unwrap();
        assert!(!still_at(&file, &path), "unlinked");
        std::fs::write(&path, b"").unwrap();
        assert!(!still_at(&file, &path), "replaced by another file");
    }
}
