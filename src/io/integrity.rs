//! The integrity record of a checkpoint: checksums of every byte of the file, checked before
//! HDF5 reads any of it.
//!
//! A checkpoint travels between machines and lies on disks for weeks; a changed byte must not
//! restart a run with wrong values, and HDF5 itself must never parse a damaged file (a damaged
//! object header can crash the library). So after a checkpoint is written, closed and read back
//! ([`super::ResultsReader::verify_tables`]), rank 0 appends this record behind the HDF5 data
//! (HDF5 ignores bytes past its end of file), and on restart rank 0 checks it before the file
//! is opened:
//!
//! ```text
//! [HDF5 file, hdf5_len bytes][record: JSON][record length: u64 LE][magic "CFRDSUM1"]
//! ```
//!
//! The record lists the byte range of every dataset's data with the XXH3-64 of those bytes, and
//! covers the rest of the HDF5 file (its metadata) in pieces of at most [`PIECE`] bytes, so a
//! mismatch names the dataset or the metadata bytes that changed. The record's own bytes are
//! covered by a checksum in it.

use super::IoError;
use serde::{Deserialize, Serialize};
use std::io::{Read, Seek, SeekFrom, Write};
use std::path::Path;
use xxhash_rust::xxh3::{xxh3_64, Xxh3};

/// Last bytes of a sealed file.
pub const MAGIC: &[u8; 8] = b"CFRDSUM1";

/// Largest piece of HDF5 metadata covered by one checksum.
pub const PIECE: u64 = 4096;

/// Largest record accepted (a record lists a few entries per dataset and per metadata piece).
const MAX_RECORD: u64 = 64 << 20;

/// A byte range of the file with its checksum.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
struct Region {
    /// Dataset path, or empty for HDF5 metadata.
    name: String,
    offset: u64,
    len: u64,
    xxh3: u64,
}

/// The record appended to a sealed file.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
struct Record {
    /// Length of the HDF5 part of the file.
    hdf5_len: u64,
    regions: Vec<Region>,
    /// XXH3-64 of the JSON of `hdf5_len` and `regions`.
    check: u64,
}

fn record_check(hdf5_len: u64, regions: &[Region]) -> u64 {
    let text = serde_json::to_string(&(hdf5_len, regions)).unwrap_or_default();
    xxh3_64(text.as_bytes())
}

fn file_err(path: &Path) -> impl Fn(std::io::Error) -> IoError + '_ {
    move |source| IoError::File {
        path: path.to_path_buf(),
        source,
    }
}

/// XXH3-64 of `len` bytes of `file` from `offset`, read in 1 MiB pieces.
fn hash_range(file: &mut std::fs::File, offset: u64, len: u64) -> std::io::Result<u64> {
    file.seek(SeekFrom::Start(offset))?;
    let mut hasher = Xxh3::new();
    let mut buf = vec![0u8; 1 << 20];
    let mut left = len;
    while left > 0 {
        let n = left.min(buf.len() as u64) as usize;
        file.read_exact(&mut buf[..n])?;
        hasher.update(&buf[..n]);
        left -= n as u64;
    }
    Ok(hasher.digest())
}

/// The regions of a file of `hdf5_len` bytes: the datasets' data ranges (`name`, offset,
/// length; those outside the file or overlapping an earlier one are left to the metadata
/// pieces) and the gaps between them in pieces of at most [`PIECE`] bytes.
fn plan_regions(hdf5_len: u64, datasets: &[(String, u64, u64)]) -> Vec<(String, u64, u64)> {
    let mut data: Vec<&(String, u64, u64)> = datasets
        .iter()
        .filter(|(_, o, l)| *l > 0 && o.checked_add(*l).is_some_and(|end| end <= hdf5_len))
        .collect();
    data.sort_by_key(|(_, o, _)| *o);
    let mut out = Vec::new();
    let mut at = 0u64;
    let gap = |from: u64, to: u64, out: &mut Vec<(String, u64, u64)>| {
        let mut p = from;
        while p < to {
            let n = PIECE.min(to - p);
            out.push((String::new(), p, n));
            p += n;
        }
    };
    for (name, o, l) in data {
        if *o < at {
            continue;
        }
        gap(at, *o, &mut out);
        out.push((name.clone(), *o, *l));
        at = o + l;
    }
    gap(at, hdf5_len, &mut out);
    out
}

/// Appends the integrity record to the closed HDF5 file at `path` (call on one rank).
/// `datasets`: (path, offset, length) of every dataset's data in the file.
pub fn seal(path: &Path, datasets: &[(String, u64, u64)]) -> Result<(), IoError> {
    let err = file_err(path);
    let mut file = std::fs::OpenOptions::new()
        .read(true)
        .write(true)
        .open(path)
        .map_err(&err)?;
    let hdf5_len = file.metadata().map_err(&err)?.len();
    let mut regions = Vec::new();
    for (name, offset, len) in plan_regions(hdf5_len, datasets) {
        let xxh3 = hash_range(&mut file, offset, len).map_err(&err)?;
        regions.push(Region {
            name,
            offset,
            len,
            xxh3,
        });
    }
    let check = record_check(hdf5_len, &regions);
    let json = serde_json::to_vec(&Record {
        hdf5_len,
        regions,
        check,
    })
    .map_err(|e| IoError::Usage(format!("encoding the integrity record: {e}")))?;
    file.seek(SeekFrom::End(0)).map_err(&err)?;
    file.write_all(&json).map_err(&err)?;
    file.write_all(&(json.len() as u64).to_le_bytes()).map_err(&err)?;
    file.write_all(MAGIC).map_err(&err)?;
    file.sync_all().map_err(&err)
}

/// Reads the integrity record at the end of `file` (of `size` bytes).
fn read_record(file: &mut std::fs::File, size: u64, path: &Path) -> Result<Record, IoError> {
    let corrupt = |m: &str| IoError::Layout(format!("{}: {m}", path.display()));
    let err = file_err(path);
    if size < 16 {
        return Err(corrupt("too short for a cfrd checkpoint"));
    }
    let mut tail = [0u8; 16];
    file.seek(SeekFrom::Start(size - 16)).map_err(&err)?;
    file.read_exact(&mut tail).map_err(&err)?;
    if &tail[8..] != MAGIC {
        return Err(corrupt(
            "not a cfrd checkpoint, or not a complete one (no integrity record at its end: \
             truncated, damaged, or written by an older cfrd)",
        ));
    }
    let len = u64::from_le_bytes(tail[..8].try_into().unwrap_or_default());
    if len > MAX_RECORD || len > size - 16 {
        return Err(corrupt("the integrity record's length is damaged"));
    }
    let mut json = vec![0u8; len as usize];
    file.seek(SeekFrom::Start(size - 16 - len)).map_err(&err)?;
    file.read_exact(&mut json).map_err(&err)?;
    let record: Record =
        serde_json::from_slice(&json).map_err(|_| corrupt("the integrity record is damaged"))?;
    if record.check != record_check(record.hdf5_len, &record.regions) {
        return Err(corrupt("the integrity record does not match its checksum"));
    }
    if record.hdf5_len != size - 16 - len {
        return Err(corrupt("the file's length does not match its integrity record"));
    }
    Ok(record)
}

/// Checks the integrity record of the file at `path`: an error names the dataset (or the
/// metadata bytes) whose bytes changed (call on one rank, before HDF5 opens the file).
pub fn verify(path: &Path) -> Result<(), IoError> {
    let err = file_err(path);
    let mut file = crate::input::open_regular(path).map_err(|m| err(std::io::Error::other(m)))?;
    let size = file.metadata().map_err(&err)?.len();
    let record = read_record(&mut file, size, path)?;
    let mut at = 0u64;
    for r in &record.regions {
        let fits = r.offset == at && r.offset.checked_add(r.len).is_some_and(|e| e <= record.hdf5_len);
        if !fits {
            return Err(IoError::Layout(format!(
                "{}: the integrity record's regions do not cover the file",
                path.display()
            )));
        }
        if hash_range(&mut file, r.offset, r.len).map_err(&err)? != r.xxh3 {
            let what = match r.name.as_str() {
                "" => "HDF5 metadata".to_string(),
                name => format!("dataset {name}"),
            };
            return Err(IoError::Layout(format!(
                "{}: {what} (bytes {}..{}) does not match its checksum: the file is corrupted",
                path.display(),
                r.offset,
                r.offset + r.len
            )));
        }
        at = r.offset + r.len;
    }
    if at != record.hdf5_len {
        return Err(IoError::Layout(format!(
            "{}: the integrity record's regions do not cover the file",
            path.display()
        )));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sealed_file(dir: &Path) -> std::path::PathBuf {
        let p = dir.join("c.h5");
        let bytes: Vec<u8> = (0..20_000u32).map(|i| (i * 7 % 251) as u8).collect();
        std::fs::write(&p, &bytes).unwrap();
        seal(
            &p,
            &[
                ("/checkpoint/u".into(), 5000, 8000),
                ("/bad".into(), 19_000, 5000),
            ],
        )
        .unwrap();
        p
    }

    #[test]
    fn regions_cover_the_file_and_name_the_datasets() {
        let plan = plan_regions(20_000, &[("/a".into(), 5000, 8000), ("/b".into(), 19_000, 5000)]);
        let total: u64 = plan.iter().map(|r| r.2).sum();
        assert_eq!(total, 20_000);
        assert!(plan.iter().any(|r| r.0 == "/a" && r.1 == 5000));
        assert!(
            plan.iter().all(|r| r.0 != "/b"),
            "a range past the end is metadata"
        );
        assert!(plan.iter().all(|r| r.0 == "/a" || r.2 <= PIECE));
    }

    #[test]
    fn every_flipped_byte_is_found_and_named() {
        let dir = tempfile::tempdir().unwrap();
        let p = sealed_file(dir.path());
        verify(&p).unwrap();
        let good = std::fs::read(&p).unwrap();
        for at in (0..good.len()).step_by(97).chain([good.len() - 1, 5000, 12_999]) {
            let mut bad = good.clone();
            bad[at] ^= 0x01;
            std::fs::write(&p, &bad).unwrap();
            let e = verify(&p).expect_err("a flipped byte").to_string();
            if (5000..13_000).contains(&at) {
                assert!(e.contains("dataset /checkpoint/u"), "byte {at}: {e}");
            }
        }
        std::fs::write(&p, &good[..good.len() - 3]).unwrap();
        assert!(verify(&p)
            .unwrap_err()
            .to_string()
            .contains("no integrity record"));
    }
}
