//! Closing and publishing a [`ResultsFile`]: the XDMF description, the rename over the target,
//! copies of the steps written so far, and the discard of an unfinished file.

use std::path::{Path, PathBuf};

use hdf5::File;
use mpi::raw::AsRaw;
use mpi::traits::{Communicator, CommunicatorCollectives};

use super::{ResultsFile, COORDINATES, ELEMENT_BLOCK, ELEMENT_IDS, NODE_IDS, TOPOLOGY};
use crate::io::error::{agree, IoError};
use crate::io::guard;
use crate::io::xdmf::{self, Center, NumberType, XdmfAttribute, XdmfDocument, XdmfMesh, XdmfStep};

impl ResultsFile {
    /// The XDMF description of what was written so far (for the file name of `path`).
    pub fn xdmf_document(&self) -> XdmfDocument {
        let h5_file = self
            .final_path
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default();
        let int_attr = |name: &str, center, dataset: &str| XdmfAttribute {
            name: name.to_string(),
            center,
            ncomp: 1,
            dataset: dataset.to_string(),
            number_type: NumberType::Int,
        };
        XdmfDocument {
            h5_file,
            mesh: XdmfMesh {
                n_nodes: self.n_nodes.unwrap_or(0),
                n_elements: self.n_elements.unwrap_or(0),
                coordinates: COORDINATES.to_string(),
                topology: TOPOLOGY.to_string(),
                attributes: vec![
                    int_attr("node_id", Center::Node, NODE_IDS),
                    int_attr("element_id", Center::Element, ELEMENT_IDS),
                    int_attr("block", Center::Element, ELEMENT_BLOCK),
                ],
            },
            steps: self
                .steps
                .iter()
                .map(|s| XdmfStep {
                    name: format!("step_{:06}", s.number),
                    time: s.info.time,
                    attributes: s
                        .fields
                        .iter()
                        .map(|f| XdmfAttribute {
                            name: f.name.clone(),
                            center: f.center,
                            ncomp: f.ncomp,
                            dataset: f.dataset.clone(),
                            number_type: NumberType::Float,
                        })
                        .collect(),
                })
                .collect(),
        }
    }

    /// The XDMF path written by [`ResultsFile::close`]: the results path with extension `xdmf`.
    pub fn xdmf_path(&self) -> PathBuf {
        self.final_path.with_extension("xdmf")
    }

    /// Closes the HDF5 file of the temporary path (if open). Collective.
    pub(super) fn close_temp(&mut self) -> Result<(), IoError> {
        let _watch = guard::watch(&format!("closing {}", self.temp_path.display()));
        let closed = match self.file.take() {
            Some(f) => f
                .close()
                .map_err(|e| IoError::hdf5(format!("closing {}", self.temp_path.display()), e)),
            None => Ok(()),
        };
        // on failure HDF5 may still hold the file: it must not be flushed at MPI finalization
        self.agreed(closed)
    }

    /// Publishes the steps written so far: closes the HDF5 file, copies it to the target path
    /// (under a second temporary name that is renamed over the target, so the target is always
    /// a complete file), has rank 0 write the XDMF file, and reopens the temporary file to
    /// continue writing. A run killed later leaves at the target the steps up to the last
    /// publish. Nothing is done when no step was written since the last publish (the target
    /// holds them all already). Collective.
    pub fn publish(&mut self) -> Result<(), IoError> {
        if self.published_steps == Some(self.steps.len()) {
            return Ok(());
        }
        let _watch = guard::watch_sized(
            &format!("publishing {}", self.final_path.display()),
            file_size(&self.temp_path),
        );
        self.close_temp()?;
        let copied = if self.comm.rank() == 0 {
            self.copy_to_target()
        } else {
            Ok(())
        };
        self.agreed(copied)?;
        let described = if self.comm.rank() == 0 && self.n_nodes.is_some() {
            xdmf::write(&self.xdmf_document(), &self.xdmf_path())
        } else {
            Ok(())
        };
        agree(&self.comm, described)?;
        let reopened = File::with_options()
            .with_fapl(|f| f.mpio(self.comm.as_raw(), None).libver_v18())
            .open_rw(&self.temp_path)
            .map_err(|e| IoError::hdf5(format!("reopening {}", self.temp_path.display()), e));
        self.file = Some(agree(&self.comm, reopened)?);
        self.published_steps = Some(self.steps.len());
        Ok(())
    }

    /// Closes the HDF5 file, renames it over the target path and (if the mesh was written) has
    /// rank 0 write the XDMF file next to it. Collective; on error the temporary file is removed
    /// and an existing file at the target path is left as it was.
    pub fn close(self) -> Result<(), IoError> {
        self.close_checked(|_| Ok(()))
    }

    /// [`ResultsFile::close`] with a check of the closed file before it replaces the target:
    /// `verify` gets the temporary path (collective, e.g. [`super::ResultsReader::verify_tables`]); if
    /// it fails, the temporary file is removed and the target left as it was.
    pub fn close_checked(mut self, verify: impl FnOnce(&Path) -> Result<(), IoError>) -> Result<(), IoError> {
        let _watch = guard::watch_sized(
            &format!("closing {}", self.final_path.display()),
            file_size(&self.temp_path),
        );
        self.close_temp()?;
        let verified = verify(&self.temp_path);
        self.agreed(verified)?;
        let sealed = match (self.seal, self.comm.rank()) {
            (true, 0) => crate::io::integrity::seal(&self.temp_path, &self.regions),
            _ => Ok(()),
        };
        self.agreed(sealed)?;
        let renamed = if self.comm.rank() == 0 {
            std::fs::rename(&self.temp_path, &self.final_path).map_err(|source| IoError::File {
                path: self.final_path.clone(),
                source,
            })
        } else {
            Ok(())
        };
        agree(&self.comm, renamed)?;
        self.published = true;
        let described = if self.comm.rank() == 0 && self.n_nodes.is_some() {
            xdmf::write(&self.xdmf_document(), &self.xdmf_path())
        } else {
            Ok(())
        };
        agree(&self.comm, described)
    }
}

impl ResultsFile {
    /// Copies the closed temporary file over the target path through a second temporary name
    /// (removed again if the copy fails), after checking the free space (rank 0).
    pub(super) fn copy_to_target(&self) -> Result<(), IoError> {
        let size = std::fs::metadata(&self.temp_path).map_or(0, |m| m.len());
        guard::ensure_space(&self.final_path, size)?;
        let copy = self.temp_path.with_extension("publish");
        std::fs::copy(&self.temp_path, &copy)
            .and_then(|_| std::fs::rename(&copy, &self.final_path))
            .map_err(|source| {
                let _ = std::fs::remove_file(&copy);
                IoError::File {
                    path: self.final_path.clone(),
                    source,
                }
            })
    }
}

impl Drop for ResultsFile {
    /// A writer that was not published discards its temporary file (closing the HDF5 file is
    /// collective, like every HDF5 close under MPI-IO).
    fn drop(&mut self) {
        if let Some(file) = self.file.take() {
            if self.failed.get() || guard::abandoned() {
                std::mem::forget(file);
                guard::abandon();
            } else {
                let _watch = guard::watch(&format!("closing {}", self.temp_path.display()));
                drop(file);
                self.comm.barrier();
            }
        }
        if !self.published && self.comm.rank() == 0 {
            let _ = std::fs::remove_file(&self.temp_path);
        }
    }
}

/// Size of the file at `path` in bytes (0 when it cannot be read): the bytes a publish copies
/// and a checked close reads back, for the watchdog's limit ([`guard::watch_sized`]).
pub(super) fn file_size(path: &Path) -> u64 {
    std::fs::metadata(path).map_or(0, |m| m.len())
}
