//! [`ResultsFile`]: creating the file and writing the mesh, steps, fields, tables and attributes.

use std::path::{Path, PathBuf};

use hdf5::{File, Group};
use mpi::raw::AsRaw;
use mpi::topology::SimpleCommunicator;
use mpi::traits::{Communicator, Root};

use super::attrs::{write_attr, write_attr_str};
use super::checksum::sum_over_ranks;
use super::names::{agree_text, check_name, split_path};
use super::raw;
use super::{
    component_labels, rows_checksum, FieldRecord, OwnedMesh, StepInfo, StepRecord, TableValue, CHECKSUM_ATTR,
    COORDINATES, ELEMENT_BLOCK, ELEMENT_IDS, FORMAT_NAME, FORMAT_VERSION, NODE_IDS, TOPOLOGY,
};
use crate::io::error::{agree, IoError};
use crate::io::guard;
use crate::io::redistribute::{BlockDistribution, Redistribution};
use crate::io::xdmf::Center;

/// A results file being written collectively. See the module docs.
pub struct ResultsFile {
    pub(super) comm: SimpleCommunicator,
    pub(super) file: Option<File>,
    pub(super) final_path: PathBuf,
    pub(super) temp_path: PathBuf,
    pub(super) n_nodes: Option<u64>,
    pub(super) n_elements: Option<u64>,
    pub(super) node_plan: Option<Redistribution>,
    pub(super) element_plan: Option<Redistribution>,
    pub(super) steps: Vec<StepRecord>,
    pub(super) published: bool,
    /// Steps at the target path after the last [`ResultsFile::publish`] (`None` before one).
    pub(super) published_steps: Option<usize>,
    /// A collective HDF5 operation failed: the file is not closed but abandoned
    /// ([`guard::abandon`]), since its close could hang.
    pub(super) failed: std::cell::Cell<bool>,
    /// Data ranges (dataset, offset, bytes) of the tables written, for the integrity record.
    pub(super) regions: Vec<(String, u64, u64)>,
    /// Append the integrity record at close ([`ResultsFile::seal_on_close`]).
    pub(super) seal: bool,
}

impl ResultsFile {
    /// Creates a new results file that will appear at `path` when [`ResultsFile::close`]
    /// succeeds (an existing file there is left untouched until then). Writes the root
    /// attributes `format`, `format_version`, `units` = `"SI"`, `n_ranks` (informational),
    /// `scene` and `cfrd_version`. Collective over `comm` (which is duplicated).
    pub fn create(comm: &SimpleCommunicator, path: impl AsRef<Path>, scene: &str) -> Result<Self, IoError> {
        let comm = comm.duplicate();
        let final_path = path.as_ref().to_path_buf();
        let mut pid = std::process::id();
        comm.process_at_rank(0).broadcast_into(&mut pid);
        agree_text(&comm, "results file path", &final_path.to_string_lossy())?;
        agree_text(&comm, "scene name", scene)?;
        let temp_path = match final_path.file_name() {
            Some(name) => Ok(final_path.with_file_name(format!(".{}.partial-{pid}", name.to_string_lossy()))),
            None => Err(IoError::Usage(format!(
                "{}: not a file path",
                final_path.display()
            ))),
        };
        let temp_path = agree(&comm, temp_path)?;
        let _watch = guard::watch(&format!("creating {}", temp_path.display()));
        let room = match comm.rank() {
            0 => guard::ensure_space(&temp_path, 0),
            _ => Ok(()),
        };
        agree(&comm, room).inspect_err(|_| guard::abandon())?;
        let created = File::with_options()
            .with_fapl(|f| f.mpio(comm.as_raw(), None).libver_v18())
            .create(&temp_path)
            .map_err(|e| IoError::hdf5(format!("creating {}", temp_path.display()), e));
        let file = agree(&comm, created)?;
        let out = ResultsFile {
            comm,
            file: Some(file),
            final_path,
            temp_path,
            n_nodes: None,
            n_elements: None,
            node_plan: None,
            element_plan: None,
            steps: Vec::new(),
            published: false,
            published_steps: None,
            failed: std::cell::Cell::new(false),
            regions: Vec::new(),
            seal: false,
        };
        let n_ranks = out.comm.size() as u32;
        let root = out.file()?;
        let written = (|| -> hdf5::Result<()> {
            write_attr_str(root, "format", FORMAT_NAME)?;
            write_attr(root, "format_version", FORMAT_VERSION)?;
            write_attr_str(root, "units", "SI")?;
            write_attr(root, "n_ranks", n_ranks)?;
            write_attr_str(root, "scene", scene)?;
            write_attr_str(root, "cfrd_version", env!("CARGO_PKG_VERSION"))?;
            Ok(())
        })()
        .map_err(|e| IoError::hdf5("writing the root attributes", e));
        out.agreed(written)?;
        Ok(out)
    }

    /// Has [`ResultsFile::close_checked`] append the integrity record
    /// ([`crate::io::integrity`]) before the file takes its place (checkpoints).
    pub fn seal_on_close(&mut self) {
        self.seal = true;
    }

    /// The (duplicated) communicator of the file.
    pub fn comm(&self) -> &SimpleCommunicator {
        &self.comm
    }

    /// The path the file will have after [`ResultsFile::close`].
    pub fn path(&self) -> &Path {
        &self.final_path
    }

    /// The temporary path the file is written to until it is closed.
    pub fn temp_path(&self) -> &Path {
        &self.temp_path
    }

    /// Steps written so far.
    pub fn steps(&self) -> &[StepRecord] {
        &self.steps
    }

    /// The node ownership plan set by [`ResultsFile::write_mesh`].
    pub fn node_plan(&self) -> Option<&Redistribution> {
        self.node_plan.as_ref()
    }

    /// The element ownership plan set by [`ResultsFile::write_mesh`].
    pub fn element_plan(&self) -> Option<&Redistribution> {
        self.element_plan.as_ref()
    }

    pub(super) fn file(&self) -> Result<&File, IoError> {
        self.file
            .as_ref()
            .ok_or_else(|| IoError::Usage("results file already closed".to_string()))
    }

    /// Writes the mesh group: coordinates, node ids, connectivity, element ids, block index and
    /// the attribute `block_names`. Remembers the node and element ownership for the fields.
    /// Collective; fails unless every node and element is owned by exactly one rank.
    pub fn write_mesh(&mut self, mesh: &OwnedMesh) -> Result<(), IoError> {
        agree(
            &self.comm,
            if self.n_nodes.is_some() {
                Err(IoError::Usage("the mesh was already written".to_string()))
            } else {
                mesh.check()
            },
        )?;
        agree_text(&self.comm, "block names", &mesh.block_names.join("\n"))?;
        let node_plan = Redistribution::new(&self.comm, "nodes", mesh.n_nodes, &mesh.nodes)?;
        let element_plan = Redistribution::new(&self.comm, "elements", mesh.n_elements, &mesh.elements)?;

        let coords: Vec<f64> = mesh.coords.iter().flatten().copied().collect();
        self.write_table(COORDINATES, &node_plan, 3, &coords)?;
        let ids: Vec<i64> = mesh.node_ids.iter().map(|&i| i as i64).collect();
        self.write_table(NODE_IDS, &node_plan, 1, &ids)?;
        let conn: Vec<i64> = mesh
            .connectivity
            .iter()
            .flatten()
            .map(|&v| i64::from(v))
            .collect();
        self.write_table(TOPOLOGY, &element_plan, 8, &conn)?;
        let ids: Vec<i64> = mesh.element_ids.iter().map(|&i| i as i64).collect();
        self.write_table(ELEMENT_IDS, &element_plan, 1, &ids)?;
        let blocks: Vec<i64> = mesh.element_blocks.iter().map(|&b| i64::from(b)).collect();
        self.write_table(ELEMENT_BLOCK, &element_plan, 1, &blocks)?;

        let group = self.open_group("/mesh")?;
        let written = (|| -> hdf5::Result<()> {
            write_attr(&group, "n_nodes", mesh.n_nodes)?;
            write_attr(&group, "n_elements", mesh.n_elements)?;
            write_attr_str(&group, "cell_type", "hex8")?;
            write_attr_str(&group, "node_order", "gmsh")?;
            write_attr_str(&group, "block_names", &mesh.block_names.join("\n"))?;
            let coords = self.file()?.dataset(COORDINATES)?;
            write_attr_str(&coords, "units", "m")?;
            Ok(())
        })()
        .map_err(|e| IoError::hdf5("writing the mesh attributes", e));
        self.agreed(written)?;
        self.n_nodes = Some(mesh.n_nodes);
        self.n_elements = Some(mesh.n_elements);
        self.node_plan = Some(node_plan);
        self.element_plan = Some(element_plan);
        Ok(())
    }

    /// Starts a new output step (group `/steps/NNNNNN` with attributes `step`, `time`, `stage`,
    /// `label`) and returns its number. Fields go to the latest step. Collective.
    pub fn begin_step(&mut self, info: StepInfo) -> Result<u64, IoError> {
        agree_text(
            &self.comm,
            "step metadata",
            &format!("{:x}\n{}\n{}", info.time.to_bits(), info.stage, info.label),
        )?;
        let number = self.steps.len() as u64 + 1;
        let path = format!("/steps/{number:06}");
        let group = self.create_group(&path)?;
        let written = (|| -> hdf5::Result<()> {
            write_attr(&group, "step", number)?;
            write_attr(&group, "time", info.time)?;
            write_attr_str(&group, "stage", &info.stage)?;
            write_attr_str(&group, "label", &info.label)?;
            Ok(())
        })()
        .map_err(|e| IoError::hdf5(format!("writing the attributes of {path}"), e));
        self.agreed(written)?;
        self.steps.push(StepRecord {
            number,
            group: path,
            info,
            fields: Vec::new(),
        });
        Ok(number)
    }

    /// Writes a node field of the current step: `values` holds `ncomp` values per owned node, in
    /// the order of [`OwnedMesh::nodes`]. `units` is stored as the dataset attribute `units`.
    /// Collective.
    pub fn write_node_field(
        &mut self,
        name: &str,
        units: &str,
        ncomp: usize,
        values: &[f64],
    ) -> Result<(), IoError> {
        self.write_field(name, units, Center::Node, ncomp, values)
    }

    /// Writes an element field of the current step (`ncomp` values per owned element, in the
    /// order of [`OwnedMesh::elements`]), e.g. stress at the element centre. Collective.
    pub fn write_element_field(
        &mut self,
        name: &str,
        units: &str,
        ncomp: usize,
        values: &[f64],
    ) -> Result<(), IoError> {
        self.write_field(name, units, Center::Element, ncomp, values)
    }

    pub(super) fn write_field(
        &mut self,
        name: &str,
        units: &str,
        center: Center,
        ncomp: usize,
        values: &[f64],
    ) -> Result<(), IoError> {
        let state = match (self.steps.last(), &self.node_plan, &self.element_plan) {
            (None, _, _) => Err(IoError::Usage(format!("field '{name}': no step begun"))),
            (_, None, _) | (_, _, None) => Err(IoError::Usage(format!(
                "field '{name}': the mesh is not written yet"
            ))),
            (Some(step), _, _) => check_name(name).map(|_| format!("{}/{name}", step.group)),
        };
        let dataset = agree(&self.comm, state)?;
        agree_text(&self.comm, "field units", units)?;
        let plan = match center {
            Center::Node => self.node_plan.take(),
            Center::Element => self.element_plan.take(),
        }
        .ok_or_else(|| IoError::Usage("missing ownership plan".to_string()))?;
        let result = self.write_table(&dataset, &plan, ncomp, values);
        match center {
            Center::Node => self.node_plan = Some(plan),
            Center::Element => self.element_plan = Some(plan),
        }
        result?;
        let written = (|| -> hdf5::Result<()> {
            let ds = self.file()?.dataset(&dataset)?;
            write_attr_str(&ds, "center", center.file_name())?;
            write_attr_str(&ds, "units", units)?;
            write_attr_str(&ds, "components", &component_labels(ncomp))?;
            Ok(())
        })()
        .map_err(|e| IoError::hdf5(format!("writing the attributes of {dataset}"), e));
        self.agreed(written)?;
        if let Some(step) = self.steps.last_mut() {
            step.fields.push(FieldRecord {
                name: name.to_string(),
                center,
                ncomp,
                dataset,
            });
        }
        Ok(())
    }

    /// Writes a table (`n_global` rows × `ncomp` columns, one-dimensional if `ncomp` is 1) in
    /// global row order from distributed rows: `values` holds `ncomp` values per item of the
    /// plan's ownership, in the plan's order. The generic entry point for fields and checkpoint
    /// data (integration-point states, Newmark vectors). Groups on the path are created.
    /// Collective.
    pub fn write_table<T: TableValue>(
        &mut self,
        dataset: &str,
        plan: &Redistribution,
        ncomp: usize,
        values: &[T],
    ) -> Result<(), IoError> {
        let block = plan.to_block(&self.comm, ncomp, values)?;
        self.write_table_block(dataset, plan.distribution().n_global(), ncomp, &block)
    }

    /// Writes a table from blocks that are already in place: this rank passes the rows
    /// `BlockDistribution::new(n_global, size).range(rank)` (`ncomp` values per row). Collective.
    pub fn write_table_block<T: TableValue>(
        &mut self,
        dataset: &str,
        n_global: u64,
        ncomp: usize,
        block: &[T],
    ) -> Result<(), IoError> {
        let rows =
            BlockDistribution::new(n_global, self.comm.size() as usize).range(self.comm.rank() as usize);
        let local = if ncomp == 0 {
            Err(IoError::Usage(format!("{dataset}: ncomp must be at least 1")))
        } else if block.len() as u64 != (rows.end - rows.start) * ncomp as u64 {
            Err(IoError::Usage(format!(
                "{dataset}: block of {} values, expected {} rows × {ncomp}",
                block.len(),
                rows.end - rows.start
            )))
        } else {
            Ok(())
        };
        agree(&self.comm, local)?;
        let bytes = n_global * ncomp as u64 * std::mem::size_of::<T>() as u64;
        let _watch = guard::watch_sized(
            &format!("writing {dataset} to {}", self.temp_path.display()),
            bytes,
        );
        self.ensure_space(bytes)?;
        agree_text(
            &self.comm,
            "table layout",
            &format!("{dataset}\n{n_global}\n{ncomp}\n{}", std::any::type_name::<T>()),
        )?;
        let (parent, leaf) = split_path(dataset);
        let parent_group = self.create_group(parent)?;
        let created = if parent_group.link_exists(leaf) {
            Err(IoError::Layout(format!("{dataset} already exists")))
        } else {
            let shape: Vec<usize> = if ncomp == 1 {
                vec![n_global as usize]
            } else {
                vec![n_global as usize, ncomp]
            };
            parent_group
                .new_dataset::<T>()
                .shape(shape)
                .create(leaf)
                .map_err(|e| IoError::hdf5(format!("creating {dataset}"), e))
        };
        let ds = self.agreed(created)?;
        if let Some(offset) = ds.offset() {
            self.regions.push((dataset.to_string(), offset, bytes));
        }
        let first = rows.start;
        let written = raw::transfer_rows::<T>(&ds, rows, ncomp, raw::Buffer::Write(block))
            .map_err(|e| IoError::Layout(format!("collective write of {dataset}: {e}")));
        self.agreed(written)?;
        let checksum = sum_over_ranks(&self.comm, rows_checksum(first, ncomp, block));
        let stamped = write_attr(&ds, CHECKSUM_ATTR, checksum)
            .map_err(|e| IoError::hdf5(format!("writing the checksum of {dataset}"), e));
        self.agreed(stamped)
    }

    /// Writes scalar attributes of the group at `group` (created if needed): unsigned integers
    /// (`u64`) and strings. Used for checkpoint metadata. Collective; every rank passes the same
    /// values (checked).
    pub fn write_group_attrs(
        &mut self,
        group: &str,
        numbers: &[(&str, u64)],
        strings: &[(&str, &str)],
    ) -> Result<(), IoError> {
        let all: Vec<String> = numbers
            .iter()
            .map(|(k, v)| format!("{k}={v}"))
            .chain(strings.iter().map(|(k, v)| format!("{k}={v}")))
            .collect();
        agree_text(
            &self.comm,
            "group attributes",
            &format!("{group}\n{}", all.join("\n")),
        )?;
        let g = self.create_group(group)?;
        let written = (|| -> hdf5::Result<()> {
            for &(k, v) in numbers {
                write_attr(&g, k, v)?;
            }
            for &(k, v) in strings {
                write_attr_str(&g, k, v)?;
            }
            Ok(())
        })()
        .map_err(|e| IoError::hdf5(format!("writing the attributes of {group}"), e));
        self.agreed(written)
    }
}

impl ResultsFile {
    /// [`agree`] for an outcome of HDF5 calls on the open file: a failure marks the file as
    /// failed, and every open file as abandoned rather than closed ([`guard::abandon`]).
    pub(super) fn agreed<T>(&self, local: Result<T, IoError>) -> Result<T, IoError> {
        let outcome = agree(&self.comm, local);
        if outcome.is_err() {
            self.failed.set(true);
            guard::abandon();
        }
        outcome
    }

    /// Refuses, on every rank, a write of `bytes` that would leave less than the reserve free
    /// on the file's file system ([`guard::ensure_space`]). Collective.
    pub(super) fn ensure_space(&self, bytes: u64) -> Result<(), IoError> {
        let room = match self.comm.rank() {
            0 => guard::ensure_space(&self.temp_path, bytes),
            _ => Ok(()),
        };
        self.agreed(room)
    }
}

impl ResultsFile {
    /// Opens the group at `path`, creating it and its parents if needed. Collective.
    pub(super) fn create_group(&self, path: &str) -> Result<Group, IoError> {
        let made = (|| -> hdf5::Result<Group> {
            let mut group: Group = (**self.file()?).clone();
            for part in path.split('/').filter(|p| !p.is_empty()) {
                group = if group.link_exists(part) {
                    group.group(part)?
                } else {
                    group.create_group(part)?
                };
            }
            Ok(group)
        })()
        .map_err(|e| IoError::hdf5(format!("creating group {path}"), e));
        agree(&self.comm, made)
    }

    pub(super) fn open_group(&self, path: &str) -> Result<Group, IoError> {
        let opened = self.file().and_then(|f| {
            f.group(path)
                .map_err(|e| IoError::hdf5(format!("opening {path}"), e))
        });
        agree(&self.comm, opened)
    }
}
