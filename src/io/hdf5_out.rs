//! The results file: one HDF5 file written collectively by every rank through MPI-IO.
//!
//! [`ResultsFile`] creates the file on all ranks of a communicator (the `mpio` driver), writes the
//! mesh, then one group per output step with node and element fields. Every dataset is in global
//! input order, whatever the rank count: each rank moves its owned rows to its contiguous block
//! ([`super::redistribute`]) and the blocks are written with one **collective** MPI-IO transfer
//! (`H5Pset_dxpl_mpio(COLLECTIVE)`). The layout is documented in [`crate::io`].
//!
//! The file is written under a temporary name in the target directory and renamed over the
//! target only by [`ResultsFile::close`], after the HDF5 file was closed successfully; the XDMF
//! file is written then. [`ResultsFile::publish`] (called by a staged run at every stage
//! checkpoint) puts a complete copy of the steps written so far at the target and continues
//! writing the temporary file, so a run killed later leaves the results of its completed stages.
//! A writer dropped without `close` (an error, a failed step) deletes its temporary file, so an
//! existing results file is never lost or left half-written.
//!
//! [`ResultsReader`] opens a results or checkpoint file collectively and reads datasets back:
//! each rank its block, every row, or the rows of a given ownership (for restarts).
//!
//! All methods that take or hold a communicator are collective: every rank calls them in the
//! same order with the same names, sizes and metadata (this is checked), and every rank gets the
//! same `Ok`/`Err` outcome ([`super::error::agree`]).

use std::ops::Range;
use std::path::{Path, PathBuf};

use hdf5::types::VarLenUnicode;
use hdf5::{Dataset, File, Group, H5Type, Location};
use mpi::raw::AsRaw;
use mpi::topology::SimpleCommunicator;
use mpi::traits::{Communicator, CommunicatorCollectives, Equivalence, Root};

use super::error::{agree, IoError};
use super::guard;
use super::redistribute::{BlockDistribution, Redistribution};
use super::xdmf::{self, Center, NumberType, XdmfAttribute, XdmfDocument, XdmfMesh, XdmfStep};
use crate::mesh::Mesh;
use crate::tensor::Strain6;

/// Value of the root attribute `format`.
pub const FORMAT_NAME: &str = "cfrd-results";
/// Value of the root attribute `format_version`; raised when the layout changes incompatibly.
pub const FORMAT_VERSION: u32 = 1;

/// Types that can be stored in a table: plain numbers with an HDF5 and an MPI type
/// (`f64`, `i64`, `u64`, `i32`, `u32`, ...).
pub trait TableValue: H5Type + Equivalence + Copy + Default {}
impl<T: H5Type + Equivalence + Copy + Default> TableValue for T {}

/// Name of the attribute that every table carries: [`rows_checksum`] of its values.
pub const CHECKSUM_ATTR: &str = "checksum";

/// Checksum of the rows `first_row, first_row + 1, ...` of a table (`ncomp` values each):
/// the wrapping sum over the rows of XXH3-64 of the row's bytes seeded with its global row
/// index. Sums of the blocks of any partition of the rows add up to the whole table's, so
/// every rank hashes only its own rows whatever the rank count; a changed byte changes its
/// row's hash and so the sum (up to a 2^-64 chance), and rows swapped are caught by the seeds.
pub fn rows_checksum<T: TableValue>(first_row: u64, ncomp: usize, values: &[T]) -> u64 {
    values
        .chunks(ncomp.max(1))
        .zip(first_row..)
        .fold(0u64, |sum, (row, i)| {
            sum.wrapping_add(xxhash_rust::xxh3::xxh3_64_with_seed(raw::as_bytes(row), i))
        })
}

/// The sum of every rank's partial [`rows_checksum`]. Collective.
fn sum_over_ranks(comm: &SimpleCommunicator, partial: u64) -> u64 {
    let mut all = vec![0u64; comm.size() as usize];
    comm.all_gather_into(&partial, &mut all[..]);
    all.iter().fold(0u64, |s, &x| s.wrapping_add(x))
}

/// The part of the mesh one rank owns, in global input-order indices.
///
/// Every node and every element must be owned by exactly one rank. Connectivity uses global
/// 0-based node indices.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct OwnedMesh {
    /// Number of nodes of the whole mesh.
    pub n_nodes: u64,
    /// Number of elements of the whole mesh.
    pub n_elements: u64,
    /// Global indices of the owned nodes; node fields are given in this order.
    pub nodes: Vec<u32>,
    /// Coordinates (m) of the owned nodes.
    pub coords: Vec<[f64; 3]>,
    /// Input ids of the owned nodes.
    pub node_ids: Vec<u64>,
    /// Global indices of the owned elements; element fields are given in this order.
    pub elements: Vec<u32>,
    /// Hex8 connectivity of the owned elements (global node indices, Gmsh node order).
    pub connectivity: Vec<[u32; 8]>,
    /// Input ids of the owned elements.
    pub element_ids: Vec<u64>,
    /// Block index of each owned element.
    pub element_blocks: Vec<u32>,
    /// Names of all blocks (the same on every rank).
    pub block_names: Vec<String>,
}

impl OwnedMesh {
    /// Extracts the owned part of a global mesh held by this rank.
    pub fn from_mesh(mesh: &Mesh, nodes: Vec<u32>, elements: Vec<u32>) -> Self {
        OwnedMesh {
            n_nodes: mesh.num_nodes() as u64,
            n_elements: mesh.elements.len() as u64,
            coords: nodes.iter().map(|&n| mesh.coords[n as usize]).collect(),
            node_ids: nodes.iter().map(|&n| mesh.node_ids[n as usize]).collect(),
            connectivity: elements
                .iter()
                .map(|&e| mesh.elements[e as usize].nodes)
                .collect(),
            element_ids: elements.iter().map(|&e| mesh.elements[e as usize].id).collect(),
            element_blocks: elements
                .iter()
                .map(|&e| mesh.elements[e as usize].block)
                .collect(),
            block_names: mesh.blocks.iter().map(|b| b.name.clone()).collect(),
            nodes,
            elements,
        }
    }

    /// The whole mesh owned by one rank.
    pub fn whole(mesh: &Mesh) -> Self {
        let nodes = (0..mesh.num_nodes() as u32).collect();
        let elements = (0..mesh.elements.len() as u32).collect();
        Self::from_mesh(mesh, nodes, elements)
    }

    fn check(&self) -> Result<(), IoError> {
        let n = self.nodes.len();
        let e = self.elements.len();
        let lens = [
            ("coords", self.coords.len(), n),
            ("node_ids", self.node_ids.len(), n),
            ("connectivity", self.connectivity.len(), e),
            ("element_ids", self.element_ids.len(), e),
            ("element_blocks", self.element_blocks.len(), e),
        ];
        for (name, got, want) in lens {
            if got != want {
                return Err(IoError::Usage(format!(
                    "owned mesh: {name} has {got} rows, expected {want}"
                )));
            }
        }
        for (k, conn) in self.connectivity.iter().enumerate() {
            if let Some(bad) = conn.iter().find(|&&v| u64::from(v) >= self.n_nodes) {
                return Err(IoError::Usage(format!(
                    "owned mesh: element {} refers to node index {bad} of {}",
                    self.element_ids[k], self.n_nodes
                )));
            }
        }
        if let Some(b) = self
            .element_blocks
            .iter()
            .find(|&&b| b as usize >= self.block_names.len())
        {
            return Err(IoError::Usage(format!(
                "owned mesh: block index {b} but only {} block names",
                self.block_names.len()
            )));
        }
        Ok(())
    }
}

/// Metadata of one output step.
#[derive(Debug, Clone, PartialEq)]
pub struct StepInfo {
    /// Time (s) of a dynamic step, or the pseudo-time (load factor) of a static stage; shown by
    /// ParaView, so it should increase from step to step.
    pub time: f64,
    /// Name of the stage (e.g. `impoundment`).
    pub stage: String,
    /// Free label (e.g. `increment 3/10`).
    pub label: String,
}

/// A field written in a step.
#[derive(Debug, Clone, PartialEq)]
pub struct FieldRecord {
    /// Field name (the dataset's name in the step group).
    pub name: String,
    /// Node or element field.
    pub center: Center,
    /// Components per row.
    pub ncomp: usize,
    /// Absolute dataset path.
    pub dataset: String,
}

/// A step written to the file.
#[derive(Debug, Clone, PartialEq)]
pub struct StepRecord {
    /// Step number, 1-based, in writing order.
    pub number: u64,
    /// Absolute group path, e.g. `/steps/000001`.
    pub group: String,
    /// The step's metadata.
    pub info: StepInfo,
    /// Fields written so far.
    pub fields: Vec<FieldRecord>,
}

/// Component labels stored in a field's `components` attribute.
pub fn component_labels(ncomp: usize) -> String {
    match ncomp {
        1 => "value".to_string(),
        3 => "x,y,z".to_string(),
        6 => "xx,yy,zz,xy,yz,zx".to_string(),
        n => (0..n).map(|i| format!("c{i}")).collect::<Vec<_>>().join(","),
    }
}

/// Strain as written to results files: Voigt order with **tensor** shear components
/// ε_xy = γ_xy / 2, so that ParaView's tensor filters (eigenvalues, invariants) are right.
pub fn strain_output_components(strain: &Strain6) -> [f64; 6] {
    let v = &strain.0;
    [v[0], v[1], v[2], 0.5 * v[3], 0.5 * v[4], 0.5 * v[5]]
}

/// Dataset path of the node coordinates.
pub const COORDINATES: &str = "/mesh/coordinates";
/// Dataset path of the connectivity.
pub const TOPOLOGY: &str = "/mesh/topology";
/// Dataset path of the node input ids.
pub const NODE_IDS: &str = "/mesh/node_ids";
/// Dataset path of the element input ids.
pub const ELEMENT_IDS: &str = "/mesh/element_ids";
/// Dataset path of the element block indices.
pub const ELEMENT_BLOCK: &str = "/mesh/element_block";

/// A results file being written collectively. See the module docs.
pub struct ResultsFile {
    comm: SimpleCommunicator,
    file: Option<File>,
    final_path: PathBuf,
    temp_path: PathBuf,
    n_nodes: Option<u64>,
    n_elements: Option<u64>,
    node_plan: Option<Redistribution>,
    element_plan: Option<Redistribution>,
    steps: Vec<StepRecord>,
    published: bool,
    /// A collective HDF5 operation failed: the file is not closed but abandoned
    /// ([`guard::abandon`]), since its close could hang.
    failed: std::cell::Cell<bool>,
    /// Data ranges (dataset, offset, bytes) of the tables written, for the integrity record.
    regions: Vec<(String, u64, u64)>,
    /// Append the integrity record at close ([`ResultsFile::seal_on_close`]).
    seal: bool,
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
    /// ([`super::integrity`]) before the file takes its place (checkpoints).
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

    fn file(&self) -> Result<&File, IoError> {
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

    fn write_field(
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
    fn close_temp(&mut self) -> Result<(), IoError> {
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
    /// publish. Collective.
    pub fn publish(&mut self) -> Result<(), IoError> {
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
        Ok(())
    }

    /// Closes the HDF5 file, renames it over the target path and (if the mesh was written) has
    /// rank 0 write the XDMF file next to it. Collective; on error the temporary file is removed
    /// and an existing file at the target path is left as it was.
    pub fn close(self) -> Result<(), IoError> {
        self.close_checked(|_| Ok(()))
    }

    /// [`ResultsFile::close`] with a check of the closed file before it replaces the target:
    /// `verify` gets the temporary path (collective, e.g. [`ResultsReader::verify_tables`]); if
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
            (true, 0) => super::integrity::seal(&self.temp_path, &self.regions),
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
    /// [`agree`] for an outcome of HDF5 calls on the open file: a failure marks the file as
    /// failed, and every open file as abandoned rather than closed ([`guard::abandon`]).
    fn agreed<T>(&self, local: Result<T, IoError>) -> Result<T, IoError> {
        let outcome = agree(&self.comm, local);
        if outcome.is_err() {
            self.failed.set(true);
            guard::abandon();
        }
        outcome
    }

    /// Refuses, on every rank, a write of `bytes` that would leave less than the reserve free
    /// on the file's file system ([`guard::ensure_space`]). Collective.
    fn ensure_space(&self, bytes: u64) -> Result<(), IoError> {
        let room = match self.comm.rank() {
            0 => guard::ensure_space(&self.temp_path, bytes),
            _ => Ok(()),
        };
        self.agreed(room)
    }

    /// Copies the closed temporary file over the target path through a second temporary name
    /// (removed again if the copy fails), after checking the free space (rank 0).
    fn copy_to_target(&self) -> Result<(), IoError> {
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
    fn stored_checksum(&self, ds: &Dataset, dataset: &str) -> Result<Option<u64>, IoError> {
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
    fn check_sum(&self, dataset: &str, stored: Option<u64>, computed: u64) -> Result<(), IoError> {
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

    fn dataset(&self, dataset: &str) -> Result<Dataset, IoError> {
        self.file
            .dataset(dataset)
            .map_err(|e| IoError::Layout(format!("{}: no dataset {dataset} ({e})", self.path.display())))
    }

    fn rows_ncomp(&self, dataset: &str) -> Result<(Dataset, u64, usize), IoError> {
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

/// Reads a scalar attribute of the group or dataset at `object`.
fn read_attr<T: H5Type>(file: &File, object: &str, name: &str) -> Result<T, IoError> {
    let context = || format!("reading attribute {name} of {object}");
    let attr = match file.group(object) {
        Ok(g) => g.attr(name),
        Err(_) => file.dataset(object).and_then(|d| d.attr(name)),
    };
    attr.and_then(|a| a.read_scalar::<T>())
        .map_err(|e| IoError::hdf5(context(), e))
}

fn write_attr<T: H5Type>(location: &Location, name: &str, value: T) -> hdf5::Result<()> {
    location.new_attr::<T>().create(name)?.write_scalar(&value)
}

fn write_attr_str(location: &Location, name: &str, value: &str) -> hdf5::Result<()> {
    let value: VarLenUnicode = value
        .parse()
        .map_err(|e| hdf5::Error::from(format!("attribute {name}: {e}")))?;
    location
        .new_attr::<VarLenUnicode>()
        .create(name)?
        .write_scalar(&value)
}

impl ResultsFile {
    /// Opens the group at `path`, creating it and its parents if needed. Collective.
    fn create_group(&self, path: &str) -> Result<Group, IoError> {
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

    fn open_group(&self, path: &str) -> Result<Group, IoError> {
        let opened = self.file().and_then(|f| {
            f.group(path)
                .map_err(|e| IoError::hdf5(format!("opening {path}"), e))
        });
        agree(&self.comm, opened)
    }
}

impl From<IoError> for hdf5::Error {
    fn from(e: IoError) -> Self {
        hdf5::Error::from(e.to_string())
    }
}

/// Splits `/a/b/c` into (`/a/b`, `c`).
fn split_path(path: &str) -> (&str, &str) {
    match path.rfind('/') {
        Some(i) => (&path[..i], &path[i + 1..]),
        None => ("", path),
    }
}

/// A field name must be a single, non-empty path component.
fn check_name(name: &str) -> Result<(), IoError> {
    if name.is_empty() || name.contains('/') || name == "." || name == ".." {
        Err(IoError::Usage(format!("'{name}' is not a valid field name")))
    } else {
        Ok(())
    }
}

/// 64-bit FNV-1a hash (to compare texts across ranks).
fn fnv1a(text: &str) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for b in text.bytes() {
        h ^= u64::from(b);
        h = h.wrapping_mul(0x0100_0000_01b3);
    }
    h
}

/// Fails on every rank unless `text` is the same on every rank (compared by hash).
fn agree_text(comm: &SimpleCommunicator, what: &str, text: &str) -> Result<(), IoError> {
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

/// The one place with raw HDF5 calls: collective transfer of a block of rows.
#[allow(unsafe_code)]
mod raw {
    use std::ops::Range;
    use std::ptr;

    use hdf5::{Dataset, Datatype, H5Type};
    use hdf5_sys::h5::hsize_t;
    use hdf5_sys::h5d::{H5Dget_space, H5Dread, H5Dwrite};
    use hdf5_sys::h5i::hid_t;
    use hdf5_sys::h5p::{H5FD_mpio_xfer_t, H5Pclose, H5Pcreate, H5Pset_dxpl_mpio};
    use hdf5_sys::h5s::{H5S_seloper_t, H5Sclose, H5Screate_simple, H5Sselect_hyperslab, H5Sselect_none};

    /// The bytes of a slice of plain numbers (the values as they are in memory).
    pub(super) fn as_bytes<T: H5Type + Copy>(values: &[T]) -> &[u8] {
        // SAFETY: table values are plain numbers (no padding, any bit pattern readable as
        // bytes); the byte slice covers exactly the memory of `values` and borrows it.
        unsafe { std::slice::from_raw_parts(values.as_ptr().cast::<u8>(), std::mem::size_of_val(values)) }
    }

    /// The buffer of a transfer.
    pub(super) enum Buffer<'a, T> {
        /// Values to write.
        Write(&'a [T]),
        /// Space to read into.
        Read(&'a mut [T]),
    }

    /// Closes an HDF5 id when dropped.
    struct Id(hid_t, unsafe extern "C" fn(hid_t) -> hdf5_sys::h5::herr_t);
    impl Drop for Id {
        fn drop(&mut self) {
            if self.0 >= 0 {
                // SAFETY: the id was returned by the matching create call and is closed once.
                unsafe {
                    (self.1)(self.0);
                }
            }
        }
    }

    /// Writes or reads the rows `rows` (`ncomp` values each) of `ds` with a collective MPI-IO
    /// transfer. Every rank of the file's communicator must call this, with an empty range if it
    /// holds no rows. The buffer length must be `rows.len() * ncomp`.
    pub(super) fn transfer_rows<T: H5Type>(
        ds: &Dataset,
        rows: Range<u64>,
        ncomp: usize,
        buffer: Buffer<'_, T>,
    ) -> Result<(), String> {
        let count = rows.end - rows.start;
        let len = match &buffer {
            Buffer::Write(b) => b.len(),
            Buffer::Read(b) => b.len(),
        };
        if len as u64 != count * ncomp as u64 {
            return Err(format!("buffer of {len} values for {count} rows × {ncomp}"));
        }
        let one_d = ds.ndim() == 1;
        if one_d != (ncomp == 1) {
            return Err(format!(
                "dataset rank {} does not fit {ncomp} components",
                ds.ndim()
            ));
        }
        let dtype = Datatype::from_type::<T>().map_err(|e| e.to_string())?;
        hdf5::sync::sync(|| {
            // SAFETY: all ids are checked before use and closed by `Id`; the buffer holds exactly
            // `count * ncomp` values of the memory type `dtype` (checked above).
            unsafe {
                let fspace = Id(H5Dget_space(ds.id()), H5Sclose);
                if fspace.0 < 0 {
                    return Err("H5Dget_space failed".to_string());
                }
                let start: [hsize_t; 2] = [rows.start, 0];
                let block: [hsize_t; 2] = [count, ncomp as hsize_t];
                let rank = if one_d { 1 } else { 2 };
                let status = if count == 0 {
                    H5Sselect_none(fspace.0)
                } else {
                    H5Sselect_hyperslab(
                        fspace.0,
                        H5S_seloper_t::H5S_SELECT_SET,
                        start.as_ptr(),
                        ptr::null(),
                        block.as_ptr(),
                        ptr::null(),
                    )
                };
                if status < 0 {
                    return Err("selecting the file rows failed".to_string());
                }
                let mspace = Id(H5Screate_simple(rank, block.as_ptr(), ptr::null()), H5Sclose);
                if mspace.0 < 0 {
                    return Err("H5Screate_simple failed".to_string());
                }
                if count == 0 && H5Sselect_none(mspace.0) < 0 {
                    return Err("H5Sselect_none failed".to_string());
                }
                let dxpl = Id(H5Pcreate(*hdf5::globals::H5P_DATASET_XFER), H5Pclose);
                if dxpl.0 < 0 || H5Pset_dxpl_mpio(dxpl.0, H5FD_mpio_xfer_t::H5FD_MPIO_COLLECTIVE) < 0 {
                    return Err("setting up the collective transfer failed".to_string());
                }
                let status = match buffer {
                    Buffer::Write(b) => {
                        H5Dwrite(ds.id(), dtype.id(), mspace.0, fspace.0, dxpl.0, b.as_ptr().cast())
                    }
                    Buffer::Read(b) => H5Dread(
                        ds.id(),
                        dtype.id(),
                        mspace.0,
                        fspace.0,
                        dxpl.0,
                        b.as_mut_ptr().cast(),
                    ),
                };
                if status < 0 {
                    return Err("H5Dwrite/H5Dread failed".to_string());
                }
                Ok(())
            }
        })
    }
}

/// Size of the file at `path` in bytes (0 when it cannot be read): the bytes a publish copies
/// and a checked close reads back, for the watchdog's limit ([`guard::watch_sized`]).
fn file_size(path: &Path) -> u64 {
    std::fs::metadata(path).map_or(0, |m| m.len())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn component_labels_follow_the_voigt_order() {
        assert_eq!(component_labels(6), "xx,yy,zz,xy,yz,zx");
        assert_eq!(component_labels(3), "x,y,z");
        assert_eq!(component_labels(1), "value");
        assert_eq!(component_labels(2), "c0,c1");
    }

    #[test]
    fn strain_output_halves_the_engineering_shear() {
        let e = Strain6(crate::tensor::Vector6::from_column_slice(&[
            1.0, 2.0, 3.0, 4.0, 6.0, 8.0,
        ]));
        assert_eq!(strain_output_components(&e), [1.0, 2.0, 3.0, 2.0, 3.0, 4.0]);
    }

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

    #[test]
    fn owned_mesh_checks_lengths_and_references() {
        let mut m = OwnedMesh {
            n_nodes: 8,
            n_elements: 1,
            nodes: (0..8).collect(),
            coords: vec![[0.0; 3]; 8],
            node_ids: (1..=8).collect(),
            elements: vec![0],
            connectivity: vec![[0, 1, 2, 3, 4, 5, 6, 7]],
            element_ids: vec![1],
            element_blocks: vec![0],
            block_names: vec!["fill".to_string()],
        };
        assert!(m.check().is_ok());
        m.connectivity[0][3] = 8;
        assert!(m.check().unwrap_err().to_string().contains("node index 8"));
        m.connectivity[0][3] = 3;
        m.coords.pop();
        assert!(m.check().unwrap_err().to_string().contains("coords"));
        m.coords.push([0.0; 3]);
        m.element_blocks[0] = 1;
        assert!(m.check().is_err());
    }
}
