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

/// Reads the whole of the regular file `path`, at most `cap` bytes. A directory, device, FIFO
/// or socket, and a file larger than `cap`, are refused with a message saying so (the caller
/// adds the file name).
pub fn read_bounded(path: &Path, cap: u64) -> Result<Vec<u8>, String> {
    let file = std::fs::File::open(path).map_err(|e| e.to_string())?;
    let meta = file.metadata().map_err(|e| e.to_string())?;
    if !meta.is_file() {
        return Err(format!(
            "not a regular file ({}); give the path of a file",
            file_kind(&meta)
        ));
    }
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
    fn files_over_the_cap_are_refused_and_others_read() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("f.txt");
        std::fs::write(&path, "0123456789").unwrap();
        assert_eq!(read_bounded(&path, 10).unwrap(), b"0123456789");
        let msg = read_bounded(&path, 9).expect_err("over the cap");
        assert!(msg.contains("10 bytes") && msg.contains("9 bytes"), "{msg}");
    }
}
