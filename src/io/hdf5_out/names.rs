//! Dataset paths, field names and texts that every rank must agree on.

use mpi::topology::SimpleCommunicator;
use mpi::traits::CommunicatorCollectives;

use crate::io::error::IoError;

/// Splits `/a/b/c` into (`/a/b`, `c`).
pub(super) fn split_path(path: &str) -> (&str, &str) {
    match path.rfind('/') {
        Some(i) => (&path[..i], &path[i + 1..]),
        None => ("", path),
    }
}

/// A field name must be a single, non-empty path component.
pub(super) fn check_name(name: &str) -> Result<(), IoError> {
    if name.is_empty() || name.contains('/') || name == "." || name == ".." {
        Err(IoError::Usage(format!("'{name}' is not a valid field name")))
    } else {
        Ok(())
    }
}

/// 64-bit FNV-1a hash (to compare texts across ranks).
pub(super) fn fnv1a(text: &str) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for b in text.bytes() {
        h ^= u64::from(b);
        h = h.wrapping_mul(0x0100_0000_01b3);
    }
    h
}

/// Fails on every rank unless `text` is the same on every rank (compared by hash).
pub(super) fn agree_text(comm: &SimpleCommunicator, what: &str, text: &str) -> Result<(), IoError> {
    let h = fnv1a(text);
    let (mut lo, mut hi) = (0u64, 0u64);
    comm.all_reduce_into(&h, &mut lo, mpi::collective::SystemOperation::min());
    comm.all_reduce_into(&h, &mut hi, mpi::collective::SystemOperation::max());
    if lo == hi {
        Ok(())
    } else {
        Err(IoError::Usage(format!(
            "ranks disagree on the {what} (this rank: '{text}'); collective calls need the same arguments"
        )))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn paths_and_names() {
        assert_eq!(split_path("/steps/000001/u"), ("/steps/000001", "u"));
        assert_eq!(split_path("/u"), ("", "u"));
        assert!(check_name("stress").is_ok());
        for bad in ["", "a/b", ".", ".."] {
            assert!(check_name(bad).is_err(), "{bad}");
        }
        assert_ne!(fnv1a("abc"), fnv1a("abd"));
        assert_eq!(fnv1a(""), 0xcbf2_9ce4_8422_2325);
    }
}
