//! Reading input files (scenes, meshes) with bounds: only regular files are read, and only up to
//! a documented size, so a device such as `/dev/zero` or a FIFO is refused instead of being read
//! without end. Output files that are written whole (tables, summaries) are replaced only by
//! complete ones ([`write_replacing`]).

use std::io::Read;
use std::path::Path;

/// Largest scene file read (bytes): 16 MiB, far above any hand-written or generated scene.
pub const MAX_SCENE_BYTES: u64 = 16 << 20;

/// Largest mesh file read (bytes): 4 GiB. The reader holds the text and the mesh in memory; the
/// seed dam at the paper's resolution is some 10 MB as MSH text.
pub const MAX_MESH_BYTES: u64 = 4 << 30;

/// Largest ground-motion record file read (bytes): 1 GiB, above a CSV of the 10^7 time steps a
/// dynamic stage may have.
pub const MAX_RECORD_BYTES: u64 = 1 << 30;

/// Opens the regular file `path` for reading without ever blocking on it: the file is opened
/// non-blocking (so a FIFO with no writer does not hang the reader) and its kind checked on
/// the open descriptor; a directory, device, FIFO or socket is refused with a message saying
/// so (the caller adds the file name). Every reader of a user's file opens it through here.
pub fn open_regular(path: &Path) -> Result<std::fs::File, String> {
    use std::os::unix::fs::OpenOptionsExt;
    let file = std::fs::OpenOptions::new()
        .read(true)
        .custom_flags(libc::O_NONBLOCK)
        .open(path)
        .map_err(|e| e.to_string())?;
    let meta = file.metadata().map_err(|e| e.to_string())?;
    if !meta.is_file() {
        return Err(format!(
            "not a regular file ({}); give the path of a file",
            file_kind(&meta)
        ));
    }
    Ok(file)
}

/// Checks that `path` is a regular file, without opening it for data, before a library (HDF5)
/// that would block on a FIFO opens it; the message names the kind, as [`open_regular`]'s.
pub fn require_regular(path: &Path) -> Result<(), String> {
    open_regular(path).map(drop)
}

/// Reads the whole of the regular file `path` ([`open_regular`]), at most `cap` bytes. A
/// directory, device, FIFO or socket, and a file larger than `cap`, are refused with a message
/// saying so (the caller adds the file name).
pub fn read_bounded(path: &Path, cap: u64) -> Result<Vec<u8>, String> {
    let file = open_regular(path)?;
    let meta = file.metadata().map_err(|e| e.to_string())?;
    if meta.len() > cap {
        return Err(too_large(meta.len(), cap));
    }
    let mut bytes = Vec::with_capacity(meta.len() as usize);
    file.take(cap + 1)
        .read_to_end(&mut bytes)
        .map_err(|e| e.to_string())?;
    if bytes.len() as u64 > cap {
        return Err(too_large(bytes.len() as u64, cap));
    }
    Ok(bytes)
}

/// The UTF-8 text of the regular file `path` ([`read_bounded`], at most `cap` bytes), the
/// reason of a refusal as an I/O error, for readers whose errors carry one.
pub fn read_text(path: &Path, cap: u64) -> std::io::Result<String> {
    let bytes = read_bounded(path, cap).map_err(std::io::Error::other)?;
    String::from_utf8(bytes)
        .map_err(|e| std::io::Error::new(std::io::ErrorKind::InvalidData, format!("not UTF-8 text: {e}")))
}

fn too_large(len: u64, cap: u64) -> String {
    format!("{len} bytes is larger than the limit of {cap} bytes for this kind of input")
}

/// What kind of file system object `meta` describes, in words.
pub fn file_kind(meta: &std::fs::Metadata) -> &'static str {
    use std::os::unix::fs::FileTypeExt;
    let t = meta.file_type();
    if t.is_dir() {
        "a directory"
    } else if t.is_char_device() || t.is_block_device() {
        "a device"
    } else if t.is_fifo() {
        "a FIFO"
    } else if t.is_socket() {
        "a socket"
    } else {
        "of another kind"
    }
}

/// Writes `bytes` to `path` through the temporary file `.<name>.partial-<pid>` in the same
/// directory, renamed into place once complete: an existing file is replaced only by a complete
/// one, and a failed write (a full disk) removes the temporary file and leaves no truncated
/// output. Call on one rank only.
pub fn write_replacing(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    let name = path
        .file_name()
        .ok_or_else(|| std::io::Error::new(std::io::ErrorKind::InvalidInput, "not a file path"))?;
    let temp = path.with_file_name(format!(
        ".{}.partial-{}",
        name.to_string_lossy(),
        std::process::id()
    ));
    let written = std::fs::write(&temp, bytes).and_then(|()| std::fs::rename(&temp, path));
    if written.is_err() {
        let _ = std::fs::remove_file(&temp);
    }
    written
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn devices_and_directories_are_refused() {
        let msg = read_bounded(Path::new("/dev/zero"), 1 << 20).expect_err("a device");
        assert!(msg.contains("not a regular file (a device)"), "{msg}");
        let msg = read_bounded(Path::new("/"), 1 << 20).expect_err("a directory");
        assert!(msg.contains("a directory"), "{msg}");
    }

    #[test]
    fn a_fifo_without_a_writer_is_refused_at_once() {
        let dir = tempfile::tempdir().unwrap();
        let fifo = dir.path().join("f.yaml");
        let made = std::process::Command::new("mkfifo").arg(&fifo).status();
        assert!(made.unwrap().success(), "mkfifo");
        let msg = read_bounded(&fifo, 1 << 20).expect_err("a FIFO");
        assert!(msg.contains("not a regular file (a FIFO)"), "{msg}");
        let msg = require_regular(&fifo).expect_err("a FIFO");
        assert!(msg.contains("a FIFO"), "{msg}");
    }

    #[test]
    fn files_over_the_cap_are_refused_and_others_read() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("f.txt");
        std::fs::write(&path, "0123456789").unwrap();
        assert_eq!(read_bounded(&path, 10).unwrap(), b"0123456789");
        let msg = read_bounded(&path, 9).expect_err("over the cap");
        assert!(msg.contains("10 bytes") && msg.contains("9 bytes"), "{msg}");
    }
}
