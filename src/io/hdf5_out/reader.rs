//! [`ResultsReader`]: reading results and checkpoint files back collectively.

use std::ops::Range;
use std::path::{Path, PathBuf};

use hdf5::types::VarLenUnicode;
use hdf5::{Dataset, File, Group, H5Type};
use mpi::raw::AsRaw;
use mpi::topology::SimpleCommunicator;
use mpi::traits::Communicator;

use super::attrs::read_attr;
use super::checksum::sum_over_ranks;
use super::names::agree_text;
use super::raw;
use super::{rows_checksum, StepInfo, TableValue, CHECKSUM_ATTR, FORMAT_NAME, FORMAT_VERSION};
use crate::io::error::{agree, IoError};
use crate::io::redistribute::{BlockDistribution, Redistribution};

/// This rank's rows of a table read back.
#[derive(Debug, Clone, PartialEq)]
pub struct TableBlock<T> {
    /// Global rows `[lo, hi)` held.
    pub rows: Range<u64>,
    /// Number of rows of the whole table.
    pub n_global: u64,
    /// Components per row.
    pub ncomp: usize,
    /// `ncomp` values per row.
    pub values: Vec<T>,
}

/// A results or checkpoint file opened read-only on every rank of a communicator.
pub struct ResultsReader {
    comm: SimpleCommunicator,
    file: File,
    path: PathBuf,
    /// Refuse tables without a checksum ([`ResultsReader::requiring_checksums`]).
    require_checksums: bool,
}

impl ResultsReader {
    /// Opens `path` collectively (MPI-IO, read-only) and checks the `format` attribute and that
    /// `format_version` is not newer than this code's. Collective.
    pub fn open(comm: &SimpleCommunicator, path: impl AsRef<Path>) -> Result<Self, IoError> {
        let comm = comm.duplicate();
        let path = path.as_ref().to_path_buf();
        agree_text(&comm, "results file path", &path.to_string_lossy())?;
        let opened = File::with_options()
            .with_fapl(|f| f.mpio(comm.as_raw(), None))
            .open(&path)
            .map_err(|e| IoError::hdf5(format!("opening {}", path.display()), e));
        let file = agree(&comm, opened)?;
        let reader = ResultsReader {
            comm,
            file,
            path,
            require_checksums: false,
        };
        let checked = (|| {
            let format = reader.attr_string("/", "format")?;
            let version: u32 = read_attr(&reader.file, "/", "format_version")?;
            if format != FORMAT_NAME || version > FORMAT_VERSION {
                return Err(IoError::Layout(format!(
                    "{}: format '{format}' version {version}, this cfrd reads '{FORMAT_NAME}' up to version {FORMAT_VERSION}",
                    reader.path.display()
                )));
            }
            Ok(())
        })();
        agree(&reader.comm, checked)?;
        Ok(reader)
    }

    /// The communicator of the reader.
    pub fn comm(&self) -> &SimpleCommunicator {
        &self.comm
    }

    /// From now on every table read must carry its checksum attribute (checkpoints); without
    /// this, a table without one (a file of an older cfrd) is read unchecked.
    pub fn requiring_checksums(mut self) -> Self {
        self.require_checksums = true;
        self
    }

    /// The checksum stored with `dataset` (`None`: none stored and none required).
    pub(super) fn stored_checksum(&self, ds: &Dataset, dataset: &str) -> Result<Option<u64>, IoError> {
        let corrupt = |what: &str| {
            IoError::Layout(format!(
                "{}: dataset {dataset} {what}: the file is corrupted or was not written by this cfrd",
                self.path.display()
            ))
        };
        match ds.attr(CHECKSUM_ATTR) {
            Ok(a) => a
                .read_scalar::<u64>()
                .map(Some)
                .map_err(|_| corrupt("has an unreadable checksum")),
            Err(_) if self.require_checksums => Err(corrupt("has no checksum")),
            Err(_) => Ok(None),
        }
    }

    /// Reads every table of the file once, collectively, checking its checksum (which must be
    /// there); returns the number of tables. Tables of `f64`, `i64`, `u64` and `u8`.
    pub fn verify_tables(&self) -> Result<usize, IoError> {
        use hdf5::types::{FloatSize, IntSize, TypeDescriptor as T};
        let paths = self.dataset_paths();
        let paths = agree(&self.comm, paths)?;
        for p in &paths {
            let kind = self.dataset(p).and_then(|d| {
                d.dtype()
                    .and_then(|t| t.to_descriptor())
                    .map_err(|e| IoError::hdf5(p.clone(), e))
            });
            match agree(&self.comm, kind)? {
                T::Float(FloatSize::U8) => self.read_block::<f64>(p).map(|_| ())?,
                T::Integer(IntSize::U8) => self.read_block::<i64>(p).map(|_| ())?,
                T::Unsigned(IntSize::U8) => self.read_block::<u64>(p).map(|_| ())?,
                T::Unsigned(IntSize::U1) => self.read_block::<u8>(p).map(|_| ())?,
                other => {
                    return Err(IoError::Layout(format!(
                        "{}: dataset {p} has the unexpected type {other:?}",
                        self.path.display()
                    )))
                }
            }
        }
        Ok(paths.len())
    }

    /// Compares a table's stored checksum with the one of the values read.
    pub(super) fn check_sum(&self, dataset: &str, stored: Option<u64>, computed: u64) -> Result<(), IoError> {
        match stored {
            Some(s) if s != computed => Err(IoError::Layout(format!(
                "{}: dataset {dataset} does not match its checksum (stored {s:016x}, computed \
                 {computed:016x}): the file is corrupted",
                self.path.display()
            ))),
            _ => Ok(()),
        }
    }

    /// Shape of a dataset (`[rows]` or `[rows, ncomp]`).
    pub fn shape(&self, dataset: &str) -> Result<Vec<usize>, IoError> {
        let ds = self.dataset(dataset)?;
        Ok(ds.shape())
    }

    pub(super) fn dataset(&self, dataset: &str) -> Result<Dataset, IoError> {
        self.file
            .dataset(dataset)
            .map_err(|e| IoError::Layout(format!("{}: no dataset {dataset} ({e})", self.path.display())))
    }

    pub(super) fn rows_ncomp(&self, dataset: &str) -> Result<(Dataset, u64, usize), IoError> {
        let ds = self.dataset(dataset)?;
        match ds.shape().as_slice() {
            [n] => Ok((ds, *n as u64, 1)),
            [n, c] => Ok((ds, *n as u64, *c)),
            other => Err(IoError::Layout(format!("{dataset}: unexpected shape {other:?}"))),
        }
    }

    /// Reads this rank's block of a table (rows of `BlockDistribution::new(n, size)`) with one
    /// collective transfer. Collective.
    pub fn read_block<T: TableValue>(&self, dataset: &str) -> Result<TableBlock<T>, IoError> {
        let found = self.rows_ncomp(dataset);
        let (ds, n_global, ncomp) = agree(&self.comm, found)?;
        let rows =
            BlockDistribution::new(n_global, self.comm.size() as usize).range(self.comm.rank() as usize);
        let mut values = vec![T::default(); (rows.end - rows.start) as usize * ncomp];
        let read = raw::transfer_rows::<T>(&ds, rows.clone(), ncomp, raw::Buffer::Read(&mut values))
            .map_err(|e| IoError::Layout(format!("collective read of {dataset}: {e}")));
        agree(&self.comm, read)?;
        let stored = self.stored_checksum(&ds, dataset);
        let stored = agree(&self.comm, stored)?;
        let computed = sum_over_ranks(&self.comm, rows_checksum(rows.start, ncomp, &values));
        agree(&self.comm, self.check_sum(dataset, stored, computed))?;
        Ok(TableBlock {
            rows,
            n_global,
            ncomp,
            values,
        })
    }

    /// Reads the rows of a table for the items of `plan` (owned items, or any wanted items for a
    /// [`Redistribution::for_reading`] plan), `ncomp` values per item in the plan's order.
    /// Collective; the plan's item count must match the table's rows.
    pub fn read_owned<T: TableValue>(&self, dataset: &str, plan: &Redistribution) -> Result<Vec<T>, IoError> {
        let block = self.read_block::<T>(dataset)?;
        let local = if block.n_global != plan.distribution().n_global() {
            Err(IoError::Layout(format!(
                "{dataset}: {} rows in the file, {} items in the ownership plan",
                block.n_global,
                plan.distribution().n_global()
            )))
        } else {
            Ok(())
        };
        agree(&self.comm, local)?;
        plan.from_block(&self.comm, block.ncomp, &block.values)
    }

    /// Reads a whole table on this rank (independent I/O; not collective). Returns the values
    /// row by row and the number of components.
    pub fn read_all<T: TableValue>(&self, dataset: &str) -> Result<(Vec<T>, usize), IoError> {
        let (ds, _, ncomp) = self.rows_ncomp(dataset)?;
        let values = ds
            .read_raw::<T>()
            .map_err(|e| IoError::hdf5(format!("reading {dataset}"), e))?;
        let stored = self.stored_checksum(&ds, dataset)?;
        self.check_sum(dataset, stored, rows_checksum(0, ncomp, &values))?;
        Ok((values, ncomp))
    }

    /// Absolute paths of every dataset in the file, sorted.
    pub fn dataset_paths(&self) -> Result<Vec<String>, IoError> {
        fn visit(g: &Group, out: &mut Vec<String>) -> hdf5::Result<()> {
            for d in g.datasets()? {
                out.push(d.name());
            }
            for sub in g.groups()? {
                visit(&sub, out)?;
            }
            Ok(())
        }
        let mut out = Vec::new();
        visit(&self.file, &mut out).map_err(|e| IoError::hdf5("listing datasets", e))?;
        out.sort();
        Ok(out)
    }

    /// A string attribute of the object (group or dataset) at `object`.
    pub fn attr_string(&self, object: &str, name: &str) -> Result<String, IoError> {
        let value: VarLenUnicode = read_attr(&self.file, object, name)?;
        Ok(value.as_str().to_string())
    }

    /// A numeric attribute of the object at `object`.
    pub fn attr<T: H5Type>(&self, object: &str, name: &str) -> Result<T, IoError> {
        read_attr(&self.file, object, name)
    }

    /// The steps in the file, in order: group path and metadata.
    pub fn steps(&self) -> Result<Vec<(String, StepInfo)>, IoError> {
        let mut names = match self.file.group("/steps") {
            Ok(g) => g.member_names().map_err(|e| IoError::hdf5("listing /steps", e))?,
            Err(_) => Vec::new(),
        };
        names.sort();
        names
            .into_iter()
            .map(|n| {
                let path = format!("/steps/{n}");
                let info = StepInfo {
                    time: self.attr(&path, "time")?,
                    stage: self.attr_string(&path, "stage")?,
                    label: self.attr_string(&path, "label")?,
                };
                Ok((path, info))
            })
            .collect()
    }
}
