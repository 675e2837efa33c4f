//! The files a scene reads besides its own text (a Gmsh mesh, a partition, the ground-motion
//! records of its dynamic stages), each identified by the hash of its content when the scene is
//! loaded. A checkpoint stores them, and a restart with a file whose content changed is
//! refused, so another record or mesh cannot be spliced into a run halfway.

use super::record::RecordSpec;
use super::schema::SceneFile;
use std::path::{Path, PathBuf};

/// One input file of a scene: the scene key naming it, the path as resolved, and the XXH3-64
/// hash of its bytes (hex).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct InputFile {
    /// The scene key, e.g. `mesh.file` or `stages[95].dynamic.record.x`.
    pub key: String,
    /// The file, resolved against the scene's folder.
    pub path: PathBuf,
    /// XXH3-64 of the file's bytes, 16 hex digits.
    pub hash: String,
}

/// The input files the scene `file` names (relative paths taken from `base`), hashed; a file
/// that cannot be read (it was read a moment before) is an error naming its key.
pub fn input_files(file: &SceneFile, base: &Path) -> Result<Vec<InputFile>, (String, String)> {
    let resolve = |p: &Path| {
        if p.is_absolute() {
            p.to_path_buf()
        } else {
            base.join(p)
        }
    };
    let mut named: Vec<(String, PathBuf)> = Vec::new();
    if let Some(mesh) = &file.mesh.file {
        named.push(("mesh.file".into(), resolve(mesh)));
    }
    if let Some(partition) = &file.partition {
        named.push(("partition".into(), resolve(partition)));
    }
    for (k, stage) in file.stages.iter().enumerate() {
        let Some(dynamic) = &stage.dynamic else { continue };
        let key = format!("stages[{k}].dynamic.record");
        match &dynamic.record {
            RecordSpec::Csv(p) => named.push((key, resolve(p))),
            RecordSpec::At2(files) => {
                for (axis, p) in [("x", &files.x), ("y", &files.y), ("z", &files.z)] {
                    if let Some(p) = p {
                        named.push((format!("{key}.{axis}"), resolve(p)));
                    }
                }
            }
        }
    }
    named
        .into_iter()
        .map(|(key, path)| match hash_file(&path) {
            Ok(hash) => Ok(InputFile { key, path, hash }),
            Err(reason) => Err((key, format!("{}: {reason}", path.display()))),
        })
        .collect()
}

/// XXH3-64 of the bytes of the regular file `path` (hex).
fn hash_file(path: &Path) -> Result<String, String> {
    let bytes = crate::input::read_bounded(path, crate::input::MAX_MESH_BYTES)?;
    Ok(format!("{:016x}", xxhash_rust::xxh3::xxh3_64(&bytes)))
}

/// The input files as one text, a line `key<TAB>hash<TAB>path` each (a checkpoint attribute).
pub fn to_text(files: &[InputFile]) -> String {
    files
        .iter()
        .map(|f| format!("{}\t{}\t{}", f.key, f.hash, f.path.display()))
        .collect::<Vec<_>>()
        .join("\n")
}

/// The files of `stored` (a checkpoint's [`to_text`]) whose content differs from `now`'s, or
/// that `now` lacks, as `(key, path, why)`; those whose stored or current path is in `accepted`
/// are left out.
pub fn changed(stored: &str, now: &[InputFile], accepted: &[PathBuf]) -> Vec<(String, String, String)> {
    let is_accepted = |p: &Path| accepted.iter().any(|a| same_path(a, p));
    let mut out = Vec::new();
    for line in stored.lines().filter(|l| !l.is_empty()) {
        let mut parts = line.splitn(3, '\t');
        let (key, hash, path) = (
            parts.next().unwrap_or(""),
            parts.next().unwrap_or(""),
            parts.next().unwrap_or(""),
        );
        let current = now.iter().find(|f| f.key == key);
        let why = match current {
            None => "the scene reads it no more".to_string(),
            Some(f) if f.hash == hash => continue,
            Some(f) => format!(
                "its content changed (hash {hash} in the checkpoint, {} now)",
                f.hash
            ),
        };
        if is_accepted(Path::new(path)) || current.is_some_and(|f| is_accepted(&f.path)) {
            continue;
        }
        out.push((key.to_string(), path.to_string(), why));
    }
    out
}

/// Whether two paths name the same file (or are equal as written when either cannot be
/// resolved).
fn same_path(a: &Path, b: &Path) -> bool {
    match (a.canonicalize(), b.canonicalize()) {
        (Ok(x), Ok(y)) => x == y,
        _ => a == b,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_changed_file_is_named_unless_accepted() {
        let dir = tempfile::tempdir().unwrap();
        let record = dir.path().join("record.csv");
        std::fs::write(&record, "t,a_x,a_y,a_z\n0,0,0,0\n").unwrap();
        let file = |hash: &str| InputFile {
            key: "stages[1].dynamic.record".into(),
            path: record.clone(),
            hash: hash.into(),
        };
        let stored = to_text(&[file("00000000000000aa")]);
        assert!(changed(&stored, &[file("00000000000000aa")], &[]).is_empty());
        let found = changed(&stored, &[file("00000000000000bb")], &[]);
        assert_eq!(found.len(), 1);
        assert!(
            found[0].2.contains("hash 00000000000000aa in the checkpoint"),
            "{found:?}"
        );
        assert!(changed(
            &stored,
            &[file("00000000000000bb")],
            std::slice::from_ref(&record)
        )
        .is_empty());
        assert_eq!(changed(&stored, &[], &[])[0].2, "the scene reads it no more");
    }
}
