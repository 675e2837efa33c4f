//! `cfrd export`: one step's node or element fields of a results file as a CSV table, for the
//! whole mesh, a set, or probe points. Serial HDF5; no MPI needed.
//!
//! * **Step**: the last step of the file (default), the last step of a stage (`--stage NAME`)
//!   or a step by its number (`--step N`, 1-based, the `N` of `/steps/00000N`).
//! * **Fields**: one or more fields of the step, all node fields or all element fields
//!   (`displacement`, `reaction`, `stress`, `strain`, `interface_traction`, ...; the layout is
//!   in [`crate::io`]). Interface fields (`interface_*`) are defined on the zero-thickness
//!   elements, the others on the solid elements.
//! * **Rows**: every node or element where the fields are defined; with `--set NAME` those of an
//!   element block of the results file (`*` matches any run of characters: `'slab_*'`), or,
//!   with `--scene SCENE`, of a node set or face set of the scene's mesh (a node field only
//!   for a node set); with `--probe X,Y,Z` (repeatable) the nearest node, or the element whose
//!   centre is nearest, among those rows. Two nodes of an interface share a position: a probe
//!   takes the first in input order, and `--set` chooses the side.
//!
//! Columns: `node_id, x_m, y_m, z_m` (node fields) or `element_id, block, x_m, y_m, z_m` (element
//! fields, at the element centre), then `probe_x_m, probe_y_m, probe_z_m, distance_m` for
//! probes, then one column per component, named `<field>_<component>_<units>` (e.g.
//! `displacement_z_m`, `stress_xx_Pa`; interface fields in their local frame [s, a, n]:
//! `interface_traction_n_Pa` is t_n, tension positive). Values are written with Rust's shortest
//! round-trip formatting, so the CSV holds the stored numbers exactly.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use super::results_reader::{open, results_file, stage_name, step_names};
use crate::mesh::{Block, Element, ElementKind, Mesh};
use crate::scene::blocks::block_pattern_matches;

/// Which step of the results file to export.
#[derive(Debug, Clone, PartialEq)]
pub enum StepChoice {
    /// The last step of the file.
    Last,
    /// The last step of the stage with this name.
    Stage(String),
    /// The step with this number (1-based).
    Number(u64),
}

/// Which rows to export.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct RowChoice {
    /// A block name or pattern of the results file, or a node or face set of `scene`.
    pub set: Option<String>,
    /// The scene whose mesh holds the node and face sets.
    pub scene: Option<PathBuf>,
    /// Probe points (m); none: every row of the set.
    pub probes: Vec<[f64; 3]>,
}

/// What `cfrd export` was asked for.
#[derive(Debug, Clone, PartialEq)]
pub struct ExportRequest {
    /// Results file or run directory.
    pub results: PathBuf,
    /// The step.
    pub step: StepChoice,
    /// Field names, all node fields or all element fields.
    pub fields: Vec<String>,
    /// The rows.
    pub rows: RowChoice,
}

/// The exported table and what it holds.
#[derive(Debug, Clone, PartialEq)]
pub struct ExportTable {
    /// The CSV text, header line first.
    pub csv: String,
    /// Data rows.
    pub rows: usize,
    /// The exported step's group name (e.g. `000014`) and its stage.
    pub step: String,
    /// The step's stage.
    pub stage: String,
}

/// Whether fields live on nodes or on elements.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Center {
    Node,
    Element,
}

/// One field of the step: name, center, units, component labels and values (row-major).
struct Field {
    name: String,
    center: Center,
    units: String,
    components: Vec<String>,
    values: Vec<f64>,
}

/// Runs the export: reads the results file and builds the CSV table.
pub fn export(req: &ExportRequest) -> Result<ExportTable, String> {
    if req.fields.is_empty() {
        return Err("give at least one --field".into());
    }
    let path = results_file(&req.results);
    let file = open(&path)?;
    let mesh = read_mesh(&file, &path)?;
    let (group_name, stage) = choose_step(&file, &path, &req.step)?;
    let group = file
        .group(&format!("/steps/{group_name}"))
        .map_err(|e| format!("{}: /steps/{group_name}: {e}", path.display()))?;
    let fields = req
        .fields
        .iter()
        .map(|f| read_field(&group, f, &group_name, &stage, &path))
        .collect::<Result<Vec<_>, _>>()?;
    let center = common_center(&fields)?;
    let defined = defined_rows(&mesh, center, &fields)?;
    let candidates = select_rows(&mesh, center, defined, &req.rows)?;
    let csv = write_csv(&mesh, center, &fields, &candidates, &req.rows.probes);
    Ok(ExportTable {
        rows: csv.lines().count() - 1,
        csv,
        step: group_name,
        stage,
    })
}

/// Rebuilds the mesh (nodes, elements, blocks; no sets) from a results file's `/mesh` group.
fn read_mesh(file: &hdf5::File, path: &Path) -> Result<Mesh, String> {
    let read_f64 = |name: &str| {
        file.dataset(name)
            .and_then(|d| d.read_raw::<f64>())
            .map_err(|e| format!("{}: {name}: {e}", path.display()))
    };
    let read_i64 = |name: &str| {
        file.dataset(name)
            .and_then(|d| d.read_raw::<i64>())
            .map_err(|e| format!("{}: {name}: {e}", path.display()))
    };
    let coords: Vec<[f64; 3]> = read_f64("/mesh/coordinates")?
        .chunks_exact(3)
        .map(|c| [c[0], c[1], c[2]])
        .collect();
    let node_ids = read_i64("/mesh/node_ids")?
        .into_iter()
        .map(|v| v as u64)
        .collect();
    let topology = read_i64("/mesh/topology")?;
    let ids = read_i64("/mesh/element_ids")?;
    let blocks = read_i64("/mesh/element_block")?;
    let names: String = file
        .group("/mesh")
        .and_then(|g| g.attr("block_names"))
        .and_then(|a| a.read_scalar::<hdf5::types::VarLenUnicode>())
        .map(|s| s.to_string())
        .map_err(|e| format!("{}: /mesh block_names: {e}", path.display()))?;
    let elements = topology
        .chunks_exact(8)
        .zip(ids.iter().zip(&blocks))
        .map(|(t, (&id, &b))| Element {
            id: id as u64,
            kind: ElementKind::Hex8,
            nodes: std::array::from_fn(|k| t[k] as u32),
            block: b as u32,
        })
        .collect();
    let blocks = names
        .split('\n')
        .map(|n| Block {
            name: n.to_string(),
            kind: ElementKind::Hex8,
            orientation: None,
        })
        .collect();
    Ok(Mesh {
        node_ids,
        coords,
        elements,
        blocks,
        ..Mesh::default()
    })
}

/// The group name and stage of the chosen step.
fn choose_step(file: &hdf5::File, path: &Path, choice: &StepChoice) -> Result<(String, String), String> {
    let names = step_names(file, path)?;
    let stage_of = |name: &str| {
        file.group(&format!("/steps/{name}"))
            .ok()
            .and_then(|g| stage_name(&g))
            .unwrap_or_default()
    };
    let found = match choice {
        StepChoice::Last => names.last().cloned(),
        StepChoice::Number(n) => names.iter().find(|s| s.parse::<u64>().ok() == Some(*n)).cloned(),
        StepChoice::Stage(stage) => names.iter().rev().find(|s| &stage_of(s) == stage).cloned(),
    };
    let Some(name) = found else {
        let mut stages: Vec<String> = names.iter().map(|s| stage_of(s)).collect();
        stages.dedup();
        return Err(match choice {
            StepChoice::Last => format!("{}: no step in /steps", path.display()),
            StepChoice::Number(n) => format!(
                "{}: --step {n}: no such step; the file has steps 1 to {}",
                path.display(),
                names.len()
            ),
            StepChoice::Stage(s) => format!(
                "{}: --stage {s}: no such stage; the file has {}",
                path.display(),
                stages.join(", ")
            ),
        });
    };
    let stage = stage_of(&name);
    Ok((name, stage))
}

/// Reads field `name` of the step group with its metadata.
fn read_field(g: &hdf5::Group, name: &str, step: &str, stage: &str, path: &Path) -> Result<Field, String> {
    if !g.link_exists(name) {
        let mut have = g.member_names().unwrap_or_default();
        have.sort();
        return Err(format!(
            "{}: --field {name}: no such field in step {step} (stage {stage}); it has {}",
            path.display(),
            have.join(", ")
        ));
    }
    let where_ = format!("{}: /steps/{step}/{name}", path.display());
    let ds = g.dataset(name).map_err(|e| format!("{where_}: {e}"))?;
    let attr = |key: &str| {
        ds.attr(key)
            .and_then(|a| a.read_scalar::<hdf5::types::VarLenUnicode>())
            .map(|s| s.to_string())
            .map_err(|e| format!("{where_}: attribute {key}: {e}"))
    };
    let center = match attr("center")?.as_str() {
        "node" => Center::Node,
        "element" => Center::Element,
        other => return Err(format!("{where_}: center '{other}' is neither node nor element")),
    };
    Ok(Field {
        name: name.to_string(),
        center,
        units: attr("units")?,
        components: component_names(name, &attr("components")?),
        values: ds.read_raw::<f64>().map_err(|e| format!("{where_}: {e}"))?,
    })
}

/// Component names of field `name` from its stored `components` attribute; the interface
/// fields, stored as `x,y,z`, are in the local frame: (s, a, n) and (s, a) for the slip.
fn component_names(name: &str, stored: &str) -> Vec<String> {
    let stored: Vec<String> = stored.split(',').map(str::to_string).collect();
    if !name.starts_with("interface_") {
        return stored;
    }
    let local = ["s", "a", "n"];
    match stored.len() {
        2 | 3 => local[..stored.len()].iter().map(|c| c.to_string()).collect(),
        _ => stored,
    }
}

/// The center all fields share.
fn common_center(fields: &[Field]) -> Result<Center, String> {
    let center = fields[0].center;
    if let Some(other) = fields.iter().find(|f| f.center != center) {
        return Err(format!(
            "--field {} and --field {}: a node field and an element field cannot share a table; \
             export them one after the other",
            fields[0].name, other.name
        ));
    }
    Ok(center)
}

/// Rows where the fields are defined: every node; for element fields the interface elements
/// (fields `interface_*`) or the solid elements (the others), which one table cannot mix.
fn defined_rows(mesh: &Mesh, center: Center, fields: &[Field]) -> Result<Vec<u32>, String> {
    if center == Center::Node {
        return Ok((0..mesh.num_nodes() as u32).collect());
    }
    let on_interfaces = |f: &Field| f.name.starts_with("interface_");
    let interface = on_interfaces(&fields[0]);
    if let Some(other) = fields.iter().find(|f| on_interfaces(f) != interface) {
        return Err(format!(
            "--field {} and --field {}: interface fields live on the interface elements, the \
             others on the solid elements; export them one after the other",
            fields[0].name, other.name
        ));
    }
    Ok((0..mesh.elements.len() as u32)
        .filter(|&e| mesh.zero_thickness(e as usize) == interface)
        .collect())
}

/// The rows of `defined` that belong to the chosen set (all of them without one).
fn select_rows(mesh: &Mesh, center: Center, defined: Vec<u32>, rows: &RowChoice) -> Result<Vec<u32>, String> {
    let Some(set) = &rows.set else {
        return Ok(defined);
    };
    let in_set = set_members(mesh, center, set, rows.scene.as_deref())?;
    let chosen: Vec<u32> = defined.into_iter().filter(|r| in_set[*r as usize]).collect();
    if chosen.is_empty() {
        return Err(format!(
            "--set {set}: none of its {} carry the field",
            if center == Center::Node {
                "nodes"
            } else {
                "elements"
            }
        ));
    }
    Ok(chosen)
}

/// Membership flags (per node or per element) of the set `set`: a block name or pattern of
/// the results file, else a node or face set of the scene's mesh.
fn set_members(mesh: &Mesh, center: Center, set: &str, scene: Option<&Path>) -> Result<Vec<bool>, String> {
    let blocks: Vec<bool> = mesh
        .blocks
        .iter()
        .map(|b| block_pattern_matches(set, &b.name))
        .collect();
    if blocks.iter().any(|&b| b) {
        let elements = mesh.elements.iter().map(|el| blocks[el.block as usize]);
        return Ok(match center {
            Center::Element => elements.collect(),
            Center::Node => nodes_of(mesh, elements.collect()),
        });
    }
    let Some(scene) = scene else {
        let names: Vec<&str> = mesh.blocks.iter().map(|b| b.name.as_str()).collect();
        return Err(format!(
            "--set {set}: no block of the results file matches; blocks: {}. Node and face sets \
             (e.g. foundation) need the scene: --scene SCENE",
            names.join(", ")
        ));
    };
    scene_set_members(mesh, center, set, scene)
}

/// Nodes of the flagged elements.
fn nodes_of(mesh: &Mesh, elements: Vec<bool>) -> Vec<bool> {
    let mut nodes = vec![false; mesh.num_nodes()];
    for (el, _) in mesh.elements.iter().zip(&elements).filter(|(_, &f)| f) {
        for &n in &el.nodes {
            nodes[n as usize] = true;
        }
    }
    nodes
}

/// Membership flags of a node or face set of the scene's mesh, which must be the results'.
fn scene_set_members(mesh: &Mesh, center: Center, set: &str, scene: &Path) -> Result<Vec<bool>, String> {
    let s = crate::scene::Scene::load(scene).map_err(|e| e.to_string())?;
    let m = &s.mesh;
    if m.num_nodes() != mesh.num_nodes() || m.elements.len() != mesh.elements.len() {
        return Err(format!(
            "{}: its mesh has {} nodes and {} elements, the results {} and {}: results of another scene?",
            scene.display(),
            m.num_nodes(),
            m.elements.len(),
            mesh.num_nodes(),
            mesh.elements.len()
        ));
    }
    if let Some(faces) = m.face_sets.get(set) {
        return Ok(face_set_flags(m, center, faces));
    }
    match (m.node_sets.get(set), center) {
        (Some(nodes), Center::Node) => {
            let mut flags = vec![false; m.num_nodes()];
            nodes.iter().for_each(|&n| flags[n as usize] = true);
            Ok(flags)
        }
        (Some(_), Center::Element) => Err(format!(
            "--set {set}: a node set of {}; element fields take a block or a face set",
            scene.display()
        )),
        (None, _) => Err(format!(
            "--set {set}: no block, node set or face set of {} has this name; it has {}",
            scene.display(),
            set_names(m).join(", ")
        )),
    }
}

/// Flags of the nodes (node fields) or the elements (element fields) of a face set.
fn face_set_flags(m: &Mesh, center: Center, faces: &[crate::mesh::Face]) -> Vec<bool> {
    let mut flags = match center {
        Center::Node => vec![false; m.num_nodes()],
        Center::Element => vec![false; m.elements.len()],
    };
    for f in faces {
        match center {
            Center::Node => f.nodes.iter().for_each(|&n| flags[n as usize] = true),
            Center::Element => flags[f.element as usize] = true,
        }
    }
    flags
}

/// Names of the blocks, node sets and face sets of a mesh, sorted, each once.
fn set_names(m: &Mesh) -> Vec<&str> {
    let mut names: Vec<&str> = m
        .blocks
        .iter()
        .map(|b| b.name.as_str())
        .chain(m.node_sets.keys().map(String::as_str))
        .chain(m.face_sets.keys().map(String::as_str))
        .collect();
    names.sort_unstable();
    names.dedup();
    names
}

/// Position of a row: the node, or the element's centre.
fn position(mesh: &Mesh, center: Center, row: u32) -> [f64; 3] {
    match center {
        Center::Node => mesh.coords[row as usize],
        Center::Element => {
            let x = mesh.element_coords(row as usize);
            std::array::from_fn(|k| x.iter().map(|p| p[k]).sum::<f64>() / 8.0)
        }
    }
}

/// The row of `rows` nearest to `p` (the first in input order on a tie) and its distance.
fn nearest(mesh: &Mesh, center: Center, rows: &[u32], p: [f64; 3]) -> (u32, f64) {
    let mut best = (rows[0], f64::INFINITY);
    for &r in rows {
        let x = position(mesh, center, r);
        let d = ((x[0] - p[0]).powi(2) + (x[1] - p[1]).powi(2) + (x[2] - p[2]).powi(2)).sqrt();
        if d < best.1 {
            best = (r, d);
        }
    }
    best
}

/// A probe point and its distance to the row found for it (m).
type ProbeHit = ([f64; 3], f64);

/// The CSV text: header, then one line per row (or per probe).
fn write_csv(mesh: &Mesh, center: Center, fields: &[Field], rows: &[u32], probes: &[[f64; 3]]) -> String {
    let mut header: Vec<String> = match center {
        Center::Node => vec!["node_id".into()],
        Center::Element => vec!["element_id".into(), "block".into()],
    };
    header.extend(["x_m", "y_m", "z_m"].map(String::from));
    if !probes.is_empty() {
        header.extend(["probe_x_m", "probe_y_m", "probe_z_m", "distance_m"].map(String::from));
    }
    for f in fields {
        header.extend(f.components.iter().map(|c| column_name(f, c)));
    }
    let mut out = header.join(",") + "\n";
    let lines: Vec<(u32, Option<ProbeHit>)> = if probes.is_empty() {
        rows.iter().map(|&r| (r, None)).collect()
    } else {
        probes
            .iter()
            .map(|&p| {
                let (r, d) = nearest(mesh, center, rows, p);
                (r, Some((p, d)))
            })
            .collect()
    };
    for (row, probe) in lines {
        write_line(&mut out, mesh, center, fields, row, probe);
    }
    out
}

/// Column name of one component: `<field>_<component>_<units>` (`<field>_<units>` for a
/// one-component field).
fn column_name(f: &Field, component: &str) -> String {
    let units = if f.units.is_empty() { "1" } else { &f.units };
    if f.components.len() == 1 {
        format!("{}_{units}", f.name)
    } else {
        format!("{}_{component}_{units}", f.name)
    }
}

/// Appends one CSV line for `row` (with its probe point and distance, if any).
fn write_line(
    out: &mut String,
    mesh: &Mesh,
    center: Center,
    fields: &[Field],
    row: u32,
    probe: Option<ProbeHit>,
) {
    let r = row as usize;
    match center {
        Center::Node => write!(out, "{}", mesh.node_ids[r]),
        Center::Element => {
            let el = &mesh.elements[r];
            write!(out, "{},{}", el.id, mesh.blocks[el.block as usize].name)
        }
    }
    .expect("writing to a String");
    let x = position(mesh, center, row);
    let mut values: Vec<f64> = x.to_vec();
    if let Some((p, d)) = probe {
        values.extend(p);
        values.push(d);
    }
    for f in fields {
        let n = f.components.len();
        values.extend(&f.values[r * n..(r + 1) * n]);
    }
    for v in values {
        write!(out, ",{v:?}").expect("writing to a String");
    }
    out.push('\n');
}

/// Parses a probe point `X,Y,Z` (m).
pub fn parse_probe(s: &str) -> Result<[f64; 3], String> {
    let v: Vec<f64> = s
        .split(',')
        .map(|t| t.trim().parse::<f64>())
        .collect::<Result<_, _>>()
        .map_err(|_| format!("'{s}': expected a point X,Y,Z in m, e.g. 0,0,2852"))?;
    match v.as_slice() {
        [x, y, z] if v.iter().all(|c| c.is_finite()) => Ok([*x, *y, *z]),
        _ => Err(format!("'{s}': expected three finite coordinates X,Y,Z in m")),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn probe_points_parse_and_refuse_bad_text() {
        assert_eq!(parse_probe("0, -1.5,2852").unwrap(), [0.0, -1.5, 2852.0]);
        for bad in ["0,0", "0,0,0,0", "a,b,c", "0,0,inf", ""] {
            let e = parse_probe(bad).unwrap_err();
            assert!(e.contains(bad) && e.contains("X,Y,Z"), "{bad}: {e}");
        }
    }
}
