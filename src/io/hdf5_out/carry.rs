//! Continuing the results of an earlier run: a run restarted from a checkpoint starts its
//! results file as a copy of the results published beside that checkpoint, keeps the steps
//! written before the checkpoint's point and writes its own after them, so its results hold
//! every step the uninterrupted run writes, numbered as it numbers them.

use std::path::Path;

use hdf5::types::VarLenUnicode;
use hdf5::File;
use mpi::raw::AsRaw;
use mpi::topology::SimpleCommunicator;
use mpi::traits::Communicator;

use super::attrs::read_attr;
use super::step::FieldRecord;
use super::{OwnedMesh, ResultsFile, StepInfo, StepRecord};
use crate::io::error::{agree, IoError};
use crate::io::guard;
use crate::io::redistribute::Redistribution;
use crate::io::xdmf::Center;

impl ResultsFile {
    /// A results file for `path` (as [`ResultsFile::create`]) that starts as a copy of the
    /// closed results file `prior` of the same scene and mesh, holding its steps up to the
    /// last one `keep` accepts (the later ones are removed); new steps follow them. Fails,
    /// naming `prior`, when it is not a results file of this scene and mesh (checked before
    /// anything is copied). Collective.
    pub fn continuing(
        comm: &SimpleCommunicator,
        path: &Path,
        scene: &str,
        prior: &Path,
        mesh: &OwnedMesh,
        keep: &dyn Fn(&StepInfo) -> bool,
    ) -> Result<Self, IoError> {
        let checked = match comm.rank() {
            0 => check_prior(prior, scene, mesh),
            _ => Ok(()),
        };
        agree(comm, checked)?;
        let mut out = Self::create(comm, path, scene)?;
        out.close_temp()?;
        let copied = match out.comm.rank() {
            0 => copy_file(prior, &out.temp_path),
            _ => Ok(()),
        };
        out.agreed(copied)?;
        let reopened = File::with_options()
            .with_fapl(|f| f.mpio(out.comm.as_raw(), None).libver_v18())
            .open_rw(&out.temp_path)
            .map_err(|e| IoError::hdf5(format!("opening a copy of {}", prior.display()), e));
        out.file = Some(out.agreed(reopened)?);
        out.node_plan = Some(Redistribution::new(
            &out.comm,
            "nodes",
            mesh.n_nodes,
            &mesh.nodes,
        )?);
        let elements = Redistribution::new(&out.comm, "elements", mesh.n_elements, &mesh.elements)?;
        out.element_plan = Some(elements);
        out.n_nodes = Some(mesh.n_nodes);
        out.n_elements = Some(mesh.n_elements);
        out.adopt_steps(prior, keep)?;
        Ok(out)
    }

    /// Takes the copied file's steps up to the last one `keep` accepts and removes the others
    /// (every rank alike: the removal is collective). Collective.
    fn adopt_steps(&mut self, prior: &Path, keep: &dyn Fn(&StepInfo) -> bool) -> Result<(), IoError> {
        let read = read_steps(self.file()?, prior);
        let steps = self.agreed(read)?;
        let kept = steps.iter().take_while(|s| keep(&s.info)).count();
        if kept < steps.len() {
            let removed = self.file()?.group("/steps").and_then(|g| {
                steps[kept..]
                    .iter()
                    .try_for_each(|s| g.unlink(&format!("{:06}", s.number)))
            });
            let context = format!("removing the steps of {} after the checkpoint", prior.display());
            self.agreed(removed.map_err(|e| IoError::hdf5(context, e)))?;
        }
        self.steps = steps.into_iter().take(kept).collect();
        Ok(())
    }
}

/// Checks on one rank that `prior` is a closed results file of `scene` on `mesh`.
fn check_prior(prior: &Path, scene: &str, mesh: &OwnedMesh) -> Result<(), IoError> {
    let not = |what: String| IoError::Layout(format!("{}: {what}", prior.display()));
    let file = crate::io::results_reader::open(prior).map_err(IoError::Layout)?;
    let format: VarLenUnicode = read_attr(&file, "/", "format")?;
    let named: VarLenUnicode = read_attr(&file, "/", "scene")?;
    if format.as_str() != super::FORMAT_NAME || named.as_str() != scene {
        return Err(not(format!("not a results file of scene '{scene}'")));
    }
    let nn: u64 = read_attr(&file, "/mesh", "n_nodes")?;
    let ne: u64 = read_attr(&file, "/mesh", "n_elements")?;
    if nn != mesh.n_nodes || ne != mesh.n_elements {
        return Err(not(format!(
            "its mesh has {nn} nodes and {ne} elements, this scene's {} and {}",
            mesh.n_nodes, mesh.n_elements
        )));
    }
    Ok(())
}

/// The steps of a results file in order, with their fields; an error when they are not
/// numbered 1, 2, … in order.
fn read_steps(file: &File, prior: &Path) -> Result<Vec<StepRecord>, IoError> {
    let Ok(group) = file.group("/steps") else {
        return Ok(Vec::new());
    };
    let h5 = |e: hdf5::Error| IoError::hdf5(format!("reading the steps of {}", prior.display()), e);
    let mut names = group.member_names().map_err(h5)?;
    names.sort();
    let mut steps = Vec::with_capacity(names.len());
    for (i, name) in names.iter().enumerate() {
        let at = format!("/steps/{name}");
        let number: u64 = read_attr(file, &at, "step")?;
        if number != i as u64 + 1 || *name != format!("{number:06}") {
            return Err(IoError::Layout(format!(
                "{}: step {at} is not step {} of the file",
                prior.display(),
                i + 1
            )));
        }
        let text = |k: &str| read_attr::<VarLenUnicode>(file, &at, k).map(|v| v.as_str().to_string());
        let info = StepInfo {
            time: read_attr(file, &at, "time")?,
            stage: text("stage")?,
            label: text("label")?,
        };
        let fields = read_fields(file, &at).map_err(h5)?;
        steps.push(StepRecord {
            number,
            group: at,
            info,
            fields,
        });
    }
    Ok(steps)
}

/// The fields of a step in the order a run writes them.
const WRITING_ORDER: [&str; 10] = [
    "displacement",
    "reaction",
    "velocity",
    "acceleration",
    "stress",
    "strain",
    "interface_traction",
    "interface_jump",
    "interface_slip",
    "interface_opening",
];

/// The fields of the step group `at`, in writing order, as [`ResultsFile::write_field`] records
/// them.
fn read_fields(file: &File, at: &str) -> hdf5::Result<Vec<FieldRecord>> {
    let group = file.group(at)?;
    let mut names = group.member_names()?;
    // the order the run writes them in (`run::results`), so that the XDMF lists them alike
    let rank = |n: &str| {
        WRITING_ORDER
            .iter()
            .position(|w| *w == n)
            .unwrap_or(WRITING_ORDER.len())
    };
    names.sort_by(|a, b| rank(a).cmp(&rank(b)).then(a.cmp(b)));
    let mut fields = Vec::with_capacity(names.len());
    for name in names {
        let ds = group.dataset(&name)?;
        let center: VarLenUnicode = ds.attr("center")?.read_scalar()?;
        let center = match center.as_str() {
            "node" => Center::Node,
            _ => Center::Element,
        };
        let ncomp = ds.shape().get(1).copied().unwrap_or(1);
        fields.push(FieldRecord {
            name: name.clone(),
            center,
            ncomp,
            dataset: format!("{at}/{name}"),
        });
    }
    Ok(fields)
}

/// Copies the file `from` to `to` after checking the free space (rank 0).
fn copy_file(from: &Path, to: &Path) -> Result<(), IoError> {
    let size = std::fs::metadata(from).map_or(0, |m| m.len());
    guard::ensure_space(to, size)?;
    std::fs::copy(from, to).map(drop).map_err(|source| IoError::File {
        path: from.to_path_buf(),
        source,
    })
}
