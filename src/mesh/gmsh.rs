//! Reader of Gmsh meshes, ASCII MSH 4.1 and MSH 2.2, into a [`Mesh`].
//!
//! What is read:
//! - **Volume elements**: 8-node hexahedra (Gmsh type 5). Each must belong to exactly one
//!   named physical volume; physical volumes become element blocks, in order of first
//!   appearance, and elements stay in input order. Any other volume element type is rejected.
//! - **Node sets**: every named physical point, curve and surface gives the sorted, unique set of
//!   the nodes of its elements (a name shared by groups of different dimensions merges them).
//! - **Face sets**: every named physical surface, whose elements must be 4-node quadrangles
//!   (type 3). Each quad is matched to the hexahedron face with the same 4 nodes; the face's
//!   nodes are stored in the hex's outward order. On a face shared by two hexahedra (an internal
//!   surface) the quad's own orientation picks the hex: the one whose outward normal is the
//!   quad's right-hand normal.
//! - Lower-dimensional elements in no physical group are ignored; unknown sections are skipped.
//!
//! After reading, every hexahedron is checked ([`crate::mesh::validate::check_element_geometry`]):
//! distinct nodes, non-zero volume, positive Jacobian at corners and Gauss points.
//! Errors name the file, the line and the element or node id ([`MeshError`]).
//!
//! MSH 2.2 writes an element once per physical group it belongs to, with the same id; such
//! repeated lines (same type and nodes) add a group membership, anything else with an id seen
//! before is a duplicate.

use crate::element::hex8::HEX8_FACES;
use crate::mesh::error::{Location, MeshError};
use crate::mesh::validate::check_all_elements;
use crate::mesh::{Block, Element, ElementKind, Face, Mesh};
use std::collections::{BTreeMap, HashMap};
use std::path::Path;
use std::str::FromStr;

/// Gmsh type number of the 8-node hexahedron.
pub const GMSH_HEX8: u32 = 5;
/// Gmsh type number of the 4-node quadrangle.
pub const GMSH_QUAD4: u32 = 3;

/// Dimension, node count and name of the Gmsh element types this reader can parse.
pub fn gmsh_element_type(gmsh_type: u32) -> Option<(u8, usize, &'static str)> {
    Some(match gmsh_type {
        1 => (1, 2, "2-node line"),
        2 => (2, 3, "3-node triangle"),
        3 => (2, 4, "4-node quadrangle"),
        4 => (3, 4, "4-node tetrahedron"),
        5 => (3, 8, "8-node hexahedron"),
        6 => (3, 6, "6-node prism"),
        7 => (3, 5, "5-node pyramid"),
        8 => (1, 3, "3-node line"),
        9 => (2, 6, "6-node triangle"),
        10 => (2, 9, "9-node quadrangle"),
        11 => (3, 10, "10-node tetrahedron"),
        12 => (3, 27, "27-node hexahedron"),
        13 => (3, 18, "18-node prism"),
        14 => (3, 14, "14-node pyramid"),
        15 => (0, 1, "1-node point"),
        16 => (2, 8, "8-node quadrangle"),
        17 => (3, 20, "20-node hexahedron"),
        18 => (3, 15, "15-node prism"),
        19 => (3, 13, "13-node pyramid"),
        _ => return None,
    })
}

/// Reads a Gmsh ASCII mesh file (MSH 4.1 or 2.2). Only a regular file of at most
/// [`crate::input::MAX_MESH_BYTES`] is read.
pub fn read_gmsh(path: &Path) -> Result<Mesh, MeshError> {
    let file = path.display().to_string();
    let bytes = crate::input::read_bounded(path, crate::input::MAX_MESH_BYTES).map_err(|reason| {
        MeshError::Unreadable {
            file: file.clone(),
            reason,
        }
    })?;
    parse_gmsh(&String::from_utf8_lossy(&bytes), &file)
}

/// Parses the text of a Gmsh ASCII mesh; `file` names it in error messages.
pub fn parse_gmsh(text: &str, file: &str) -> Result<Mesh, MeshError> {
    let mut reader = Reader {
        cursor: Cursor {
            lines: text.lines(),
            line_no: 0,
            file,
            size: text.len(),
        },
        version: None,
        names: HashMap::new(),
        entities: HashMap::new(),
        node_index: HashMap::new(),
        mesh: Mesh::default(),
        element_lines: Vec::new(),
        seen_elements: HashMap::new(),
        node_set_members: BTreeMap::new(),
        face_set_names: Vec::new(),
        quads: Vec::new(),
        have_nodes: false,
        have_elements: false,
    };
    reader.read_sections()?;
    reader.finish()
}

/// Lines of the file with their numbers.
struct Cursor<'a> {
    lines: std::str::Lines<'a>,
    line_no: usize,
    file: &'a str,
    /// Length of the whole text (bytes): the bound of every count the file announces.
    size: usize,
}

/// Fewest bytes of one node in either format (`1 0 0 0` and a line end; MSH 4.1: `1`, `0 0 0`).
const MIN_NODE_BYTES: usize = 8;
/// Fewest bytes of one element line (MSH 4.1: `1 1` and a line end).
const MIN_ELEMENT_BYTES: usize = 4;
/// Fewest bytes of an MSH 2.2 element line (`1 15 0 1`), a block header, an entity or a physical
/// name line (`1 1 "a"`), with the line end.
const MIN_RECORD_BYTES: usize = 8;

impl<'a> Cursor<'a> {
    /// The next non-blank line, or `None` at the end of the file.
    fn next_opt(&mut self) -> Option<&'a str> {
        for line in self.lines.by_ref() {
            self.line_no += 1;
            let t = line.trim();
            if !t.is_empty() {
                return Some(t);
            }
        }
        None
    }

    /// The next non-blank line inside section `section`.
    fn next(&mut self, section: &str) -> Result<&'a str, MeshError> {
        self.next_opt()
            .ok_or_else(|| self.malformed(format!("end of file inside section ${section}")))
    }

    fn at(&self) -> Location {
        Location::file_line(self.file, self.line_no)
    }

    fn malformed(&self, reason: String) -> MeshError {
        MeshError::Malformed {
            at: self.at(),
            reason,
        }
    }

    /// Parses every token of `line` as `T`.
    fn numbers<T: FromStr>(&self, line: &str, what: &str) -> Result<Vec<T>, MeshError> {
        line.split_ascii_whitespace()
            .map(|tok| {
                tok.parse::<T>()
                    .map_err(|_| self.malformed(format!("{what}: cannot read '{tok}' as a number")))
            })
            .collect()
    }

    /// Parses the first `N` tokens of `line` as `T` (more tokens are allowed).
    fn fixed<T: FromStr + Copy + Default, const N: usize>(
        &self,
        line: &str,
        what: &str,
    ) -> Result<[T; N], MeshError> {
        let mut out = [T::default(); N];
        let mut toks = line.split_ascii_whitespace();
        for slot in out.iter_mut() {
            let tok = toks
                .next()
                .ok_or_else(|| self.malformed(format!("{what}: expected {N} numbers in '{line}'")))?;
            *slot = tok
                .parse()
                .map_err(|_| self.malformed(format!("{what}: cannot read '{tok}' as a number")))?;
        }
        Ok(out)
    }

    /// `count` (announced by the current line for `what`) as a `usize`, if the file can hold
    /// that many items of at least `min_bytes` each; checked before any memory is reserved.
    fn count<T: TryInto<usize> + Copy + std::fmt::Display>(
        &self,
        count: T,
        min_bytes: usize,
        what: &str,
    ) -> Result<usize, MeshError> {
        let most = self.size / min_bytes;
        match count.try_into() {
            Ok(n) if n <= most => Ok(n),
            _ => Err(self.malformed(format!(
                "{what}: the count {count} is negative or more than a file of {} bytes can hold \
                 (at most {most})",
                self.size
            ))),
        }
    }

    /// Coordinates of node `id` on `line`, each finite.
    fn coordinates(&self, line: &str, skip: usize, id: u64) -> Result<[f64; 3], MeshError> {
        let mut out = [0.0; 3];
        let mut toks = line.split_ascii_whitespace().skip(skip);
        for (axis, slot) in ["x", "y", "z"].iter().zip(out.iter_mut()) {
            let tok = toks
                .next()
                .ok_or_else(|| self.malformed(format!("node {id}: expected 3 coordinates in '{line}'")))?;
            *slot = match tok.parse::<f64>() {
                Ok(v) if v.is_finite() => v,
                Ok(_) => {
                    return Err(self.malformed(format!(
                        "node {id}: coordinate {axis} = '{tok}' is not a finite number"
                    )))
                }
                Err(_) => {
                    return Err(self.malformed(format!(
                        "node {id}: cannot read coordinate {axis} '{tok}' as a number"
                    )))
                }
            };
        }
        Ok(out)
    }

    /// Expects the closing line `$End<section>`.
    fn end(&mut self, section: &str) -> Result<(), MeshError> {
        let line = self.next(section)?;
        if line == format!("$End{section}") {
            Ok(())
        } else {
            Err(self.malformed(format!("expected $End{section}, found '{line}'")))
        }
    }
}

/// Format version of the file.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Version {
    V2,
    V4,
}

/// A quadrangle of one or more physical surfaces, to be matched to a hex face.
struct QuadRecord {
    id: u64,
    line: usize,
    nodes: [u32; 4],
    sets: Vec<usize>,
}

/// What is remembered of an element id, to detect duplicates (and MSH 2.2 repeated lines).
struct SeenElement {
    gmsh_type: u32,
    nodes_hash: u64,
    hex: Option<u32>,
}

/// One element line as [`Reader::element`] resolved it.
struct ElementLine<'g> {
    /// Element id.
    id: u64,
    /// Gmsh element type.
    gmsh_type: u32,
    /// Dimension of the element.
    dim: u8,
    /// Node indices.
    nodes: Vec<u32>,
    /// Hash of the type and the node tags (a repeated MSH 2.2 line has the same).
    nodes_hash: u64,
    /// Names of its physical groups.
    groups: &'g [String],
    /// For a repeated MSH 2.2 line, the hexahedron of the first line (if it made one).
    repeated: Option<Option<u32>>,
}

struct Reader<'a> {
    cursor: Cursor<'a>,
    version: Option<Version>,
    /// Physical group names by (dimension, tag).
    names: HashMap<(u8, i64), String>,
    /// Physical group names of each MSH 4 entity, by (dimension, entity tag).
    entities: HashMap<(u8, i64), Vec<String>>,
    node_index: HashMap<u64, u32>,
    mesh: Mesh,
    element_lines: Vec<usize>,
    seen_elements: HashMap<u64, SeenElement>,
    node_set_members: BTreeMap<String, Vec<u32>>,
    face_set_names: Vec<String>,
    quads: Vec<QuadRecord>,
    have_nodes: bool,
    have_elements: bool,
}

impl<'a> Reader<'a> {
    fn read_sections(&mut self) -> Result<(), MeshError> {
        while let Some(line) = self.cursor.next_opt() {
            let Some(section) = line.strip_prefix('$') else {
                return Err(self
                    .cursor
                    .malformed(format!("expected a section header, found '{line}'")));
            };
            if self.version.is_none() && section != "MeshFormat" && section != "Comments" {
                return Err(self.cursor.malformed(format!(
                    "expected $MeshFormat first, found '{line}' (is this a Gmsh .msh file?)"
                )));
            }
            match section {
                "MeshFormat" => self.mesh_format()?,
                "PhysicalNames" => self.physical_names()?,
                "Entities" => self.entities()?,
                "Nodes" => self.nodes()?,
                "Elements" => self.elements()?,
                other if other.starts_with("End") => {
                    return Err(self.cursor.malformed(format!("'{line}' closes no open section")))
                }
                other => self.skip_section(other)?,
            }
        }
        let present = [
            (self.version.is_some(), "MeshFormat"),
            (self.have_nodes, "Nodes"),
            (self.have_elements, "Elements"),
        ];
        match present.iter().find(|(have, _)| !have) {
            Some((_, name)) => Err(MeshError::Malformed {
                at: Location::file_line(self.cursor.file, self.cursor.line_no),
                reason: format!("no ${name} section"),
            }),
            None => Ok(()),
        }
    }

    fn skip_section(&mut self, section: &str) -> Result<(), MeshError> {
        let end = format!("$End{section}");
        loop {
            if self.cursor.next(section)? == end {
                return Ok(());
            }
        }
    }

    fn mesh_format(&mut self) -> Result<(), MeshError> {
        let line = self.cursor.next("MeshFormat")?;
        let toks: Vec<&str> = line.split_ascii_whitespace().collect();
        if toks.len() < 3 {
            return Err(self.cursor.malformed(format!(
                "$MeshFormat: expected 'version file-type data-size', found '{line}'"
            )));
        }
        if toks[1] != "0" {
            return Err(MeshError::Binary { at: self.cursor.at() });
        }
        self.version = Some(match toks[0] {
            "4.1" => Version::V4,
            "2.2" => Version::V2,
            v => {
                return Err(MeshError::UnsupportedVersion {
                    at: self.cursor.at(),
                    version: v.to_string(),
                })
            }
        });
        self.cursor.end("MeshFormat")
    }

    fn physical_names(&mut self) -> Result<(), MeshError> {
        let line = self.cursor.next("PhysicalNames")?;
        let [count] = self.cursor.fixed::<u64, 1>(line, "$PhysicalNames count")?;
        let count = self
            .cursor
            .count(count, MIN_RECORD_BYTES, "$PhysicalNames count")?;
        for _ in 0..count {
            let line = self.cursor.next("PhysicalNames")?;
            let [dim, tag] = self.cursor.fixed::<i64, 2>(line, "$PhysicalNames entry")?;
            let name = line
                .split_once('"')
                .and_then(|(_, rest)| rest.rsplit_once('"'))
                .map(|(name, _)| name)
                .ok_or_else(|| {
                    self.cursor
                        .malformed(format!("physical name not in quotes: '{line}'"))
                })?;
            if !(0..=3).contains(&dim) {
                return Err(self.cursor.malformed(format!("physical group dimension {dim}")));
            }
            if name.is_empty() {
                return Err(MeshError::UnnamedPhysical {
                    at: self.cursor.at(),
                    dim: dim as u8,
                    tag,
                });
            }
            self.names.insert((dim as u8, tag), name.to_string());
            if dim < 3 {
                self.node_set_members.entry(name.to_string()).or_default();
            }
            if dim == 2 && !self.face_set_names.iter().any(|n| n == name) {
                self.face_set_names.push(name.to_string());
            }
        }
        self.cursor.end("PhysicalNames")
    }

    /// Name of physical group `(dim, tag)`, or an error at the current line.
    fn physical_name(&self, dim: u8, tag: i64) -> Result<String, MeshError> {
        self.names
            .get(&(dim, tag))
            .cloned()
            .ok_or(MeshError::UnnamedPhysical {
                at: self.cursor.at(),
                dim,
                tag,
            })
    }

    fn entities(&mut self) -> Result<(), MeshError> {
        if self.version == Some(Version::V2) {
            return self.skip_section("Entities");
        }
        let line = self.cursor.next("Entities")?;
        let counts = self.cursor.fixed::<u64, 4>(line, "$Entities counts")?;
        let mut checked = [0usize; 4];
        for (c, &count) in checked.iter_mut().zip(&counts) {
            *c = self.cursor.count(count, MIN_RECORD_BYTES, "$Entities counts")?;
        }
        for (dim, &count) in checked.iter().enumerate() {
            // Points: tag x y z nPhys phys…; others: tag 6 bounds nPhys phys… nBound bound…
            let skip = if dim == 0 { 4 } else { 7 };
            for _ in 0..count {
                let line = self.cursor.next("Entities")?;
                let v: Vec<f64> = self.cursor.numbers(line, "entity")?;
                let room = v.len().saturating_sub(skip + 1);
                let n_phys = v.get(skip).copied().filter(|n| *n >= 0.0 && n.fract() == 0.0);
                let n_phys = match n_phys {
                    Some(n) if n <= room as f64 => n as usize,
                    Some(n) => {
                        return Err(self.cursor.malformed(format!(
                            "entity {}: {n} physical tags announced, the line holds {room} more numbers",
                            v[0]
                        )))
                    }
                    None => return Err(self.cursor.malformed(format!("entity line too short: '{line}'"))),
                };
                let mut groups = Vec::with_capacity(n_phys);
                for &t in &v[skip + 1..skip + 1 + n_phys] {
                    let name = self.physical_name(dim as u8, t as i64)?;
                    if !groups.contains(&name) {
                        groups.push(name);
                    }
                }
                self.entities.insert((dim as u8, v[0] as i64), groups);
            }
        }
        self.cursor.end("Entities")
    }

    fn add_node(&mut self, id: u64, xyz: [f64; 3]) -> Result<(), MeshError> {
        let index = self.mesh.coords.len() as u32;
        if self.node_index.insert(id, index).is_some() {
            return Err(MeshError::DuplicateNode {
                at: self.cursor.at(),
                node_id: id,
            });
        }
        self.mesh.node_ids.push(id);
        self.mesh.coords.push(xyz);
        Ok(())
    }

    fn nodes(&mut self) -> Result<(), MeshError> {
        if self.have_nodes {
            return Err(self.cursor.malformed("a second $Nodes section".into()));
        }
        self.have_nodes = true;
        let line = self.cursor.next("Nodes")?;
        match self.version {
            Some(Version::V2) => {
                let [count] = self.cursor.fixed::<u64, 1>(line, "$Nodes count")?;
                let count = self.cursor.count(count, MIN_NODE_BYTES, "$Nodes count")?;
                self.reserve_nodes(count);
                for _ in 0..count {
                    let line = self.cursor.next("Nodes")?;
                    let [id] = self.cursor.fixed::<u64, 1>(line, "node id")?;
                    let xyz = self.cursor.coordinates(line, 1, id)?;
                    self.add_node(id, xyz)?;
                }
            }
            _ => {
                let [blocks, count] = self.cursor.fixed::<u64, 2>(line, "$Nodes header")?;
                let blocks = self
                    .cursor
                    .count(blocks, MIN_RECORD_BYTES, "$Nodes header: entity blocks")?;
                let count = self.cursor.count(count, MIN_NODE_BYTES, "$Nodes header: nodes")?;
                self.reserve_nodes(count);
                for _ in 0..blocks {
                    let line = self.cursor.next("Nodes")?;
                    let [_, _, _, in_block] = self.cursor.fixed::<i64, 4>(line, "node block header")?;
                    let in_block = self
                        .cursor
                        .count(in_block, MIN_NODE_BYTES, "node block header: nodes")?;
                    let mut tags = Vec::with_capacity(in_block);
                    for _ in 0..in_block {
                        let line = self.cursor.next("Nodes")?;
                        let [id] = self.cursor.fixed::<u64, 1>(line, "node tag")?;
                        tags.push((id, self.cursor.line_no));
                    }
                    let mut coords = Vec::with_capacity(tags.len());
                    for &(id, _) in &tags {
                        let line = self.cursor.next("Nodes")?;
                        coords.push(self.cursor.coordinates(line, 0, id)?);
                    }
                    let end_line = self.cursor.line_no;
                    for ((id, line_no), xyz) in tags.into_iter().zip(coords) {
                        self.cursor.line_no = line_no;
                        self.add_node(id, xyz)?;
                    }
                    self.cursor.line_no = end_line;
                }
                if self.mesh.coords.len() != count {
                    return Err(self.cursor.malformed(format!(
                        "$Nodes header announces {count} nodes, the blocks hold {}",
                        self.mesh.coords.len()
                    )));
                }
            }
        }
        self.cursor.end("Nodes")
    }

    /// Reserves room for `count` nodes (bounded by the file size, [`Cursor::count`]).
    fn reserve_nodes(&mut self, count: usize) {
        self.mesh.coords.reserve(count);
        self.mesh.node_ids.reserve(count);
        self.node_index.reserve(count);
    }

    /// Reads the `$Elements` section (MSH 2.2 or 4.1).
    fn elements(&mut self) -> Result<(), MeshError> {
        if !self.have_nodes {
            return Err(self.cursor.malformed("$Elements before $Nodes".into()));
        }
        if self.have_elements {
            return Err(self.cursor.malformed("a second $Elements section".into()));
        }
        self.have_elements = true;
        let line = self.cursor.next("Elements")?;
        match self.version {
            Some(Version::V2) => self.elements_v2(line)?,
            _ => self.elements_v4(line)?,
        }
        self.cursor.end("Elements")
    }

    /// Reads the element lines of MSH 2.2 after the count line `line`.
    fn elements_v2(&mut self, line: &str) -> Result<(), MeshError> {
        let [count] = self.cursor.fixed::<u64, 1>(line, "$Elements count")?;
        let count = self.cursor.count(count, MIN_RECORD_BYTES, "$Elements count")?;
        for _ in 0..count {
            let line = self.cursor.next("Elements")?;
            let v: Vec<i64> = self.cursor.numbers(line, "element")?;
            if v.len() < 3 || v[0] < 0 || !(0..=i64::from(u32::MAX)).contains(&v[1]) || v[2] < 0 {
                return Err(self.cursor.malformed(format!("element line: '{line}'")));
            }
            let (id, gmsh_type, n_tags) = (v[0] as u64, v[1] as u32, v[2] as usize);
            let (dim, n_nodes, _) = self.type_info(gmsh_type, id)?;
            if v.len() != 3 + n_tags + n_nodes {
                return Err(self.cursor.malformed(format!(
                    "element {id}: expected {n_tags} tags and {n_nodes} nodes in '{line}'"
                )));
            }
            let physical = if n_tags > 0 { v[3] } else { 0 };
            let groups = if physical != 0 {
                vec![self.physical_name(dim, physical)?]
            } else {
                Vec::new()
            };
            if let Some(t) = v[3 + n_tags..].iter().find(|&&t| t <= 0) {
                return Err(self.cursor.malformed(format!(
                    "element {id}: node id {t} is not positive (node ids are 1, 2, ...)"
                )));
            }
            let node_tags: Vec<u64> = v[3 + n_tags..].iter().map(|&t| t as u64).collect();
            self.element(id, gmsh_type, dim, &node_tags, &groups)?;
        }
        Ok(())
    }

    /// Reads the entity blocks of elements of MSH 4.1 after the header line `line`.
    fn elements_v4(&mut self, line: &str) -> Result<(), MeshError> {
        let [blocks] = self.cursor.fixed::<u64, 1>(line, "$Elements header")?;
        let blocks = self
            .cursor
            .count(blocks, MIN_RECORD_BYTES, "$Elements header: entity blocks")?;
        for _ in 0..blocks {
            let line = self.cursor.next("Elements")?;
            let [dim, tag, gmsh_type, in_block] =
                self.cursor.fixed::<i64, 4>(line, "element block header")?;
            if !(0..=3).contains(&dim) || !(0..=i64::from(u32::MAX)).contains(&gmsh_type) {
                return Err(self.cursor.malformed(format!("element block header '{line}'")));
            }
            let in_block =
                self.cursor
                    .count(in_block, MIN_ELEMENT_BYTES, "element block header: elements")?;
            let groups = self.entities.get(&(dim as u8, tag)).cloned().unwrap_or_default();
            for _ in 0..in_block {
                let line = self.cursor.next("Elements")?;
                let v: Vec<u64> = self.cursor.numbers(line, "element")?;
                let id = *v
                    .first()
                    .ok_or_else(|| self.cursor.malformed("empty element line".into()))?;
                let (_, n_nodes, _) = self.type_info(gmsh_type as u32, id)?;
                if v.len() != 1 + n_nodes {
                    return Err(self
                        .cursor
                        .malformed(format!("element {id}: expected {n_nodes} node tags in '{line}'")));
                }
                self.element(id, gmsh_type as u32, dim as u8, &v[1..], &groups)?;
            }
        }
        Ok(())
    }

    fn type_info(&self, gmsh_type: u32, id: u64) -> Result<(u8, usize, &'static str), MeshError> {
        gmsh_element_type(gmsh_type).ok_or_else(|| MeshError::UnsupportedElementType {
            at: self.cursor.at(),
            gmsh_type,
            type_name: "unknown to this reader".into(),
            element_id: id,
            context: "(its node count is not known)".into(),
        })
    }

    /// Handles one element line: `groups` are the names of its physical groups.
    fn element(
        &mut self,
        id: u64,
        gmsh_type: u32,
        dim: u8,
        node_tags: &[u64],
        groups: &[String],
    ) -> Result<(), MeshError> {
        let mut nodes = Vec::with_capacity(node_tags.len());
        for &tag in node_tags {
            let index = self.node_index.get(&tag).ok_or(MeshError::UnknownNode {
                at: self.cursor.at(),
                element_id: id,
                node_id: tag,
            })?;
            nodes.push(*index);
        }
        let nodes_hash = node_tags.iter().fold(gmsh_type as u64, |h, &t| {
            h.wrapping_mul(0x0000_0100_0000_01B3).wrapping_add(t)
        });
        let repeated = match self.seen_elements.get(&id) {
            None => None,
            Some(seen)
                if self.version == Some(Version::V2)
                    && seen.gmsh_type == gmsh_type
                    && seen.nodes_hash == nodes_hash =>
            {
                Some(seen.hex)
            }
            Some(_) => {
                return Err(MeshError::DuplicateElement {
                    at: self.cursor.at(),
                    element_id: id,
                })
            }
        };
        let line = ElementLine {
            id,
            gmsh_type,
            dim,
            nodes,
            nodes_hash,
            groups,
            repeated,
        };
        match dim {
            3 => self.volume_element(&line),
            _ => self.lower_element(&line),
        }
    }

    /// The error of an element of a type or in a group this reader does not take.
    fn unsupported(&self, el: &ElementLine, context: String) -> MeshError {
        let (_, _, type_name) = gmsh_element_type(el.gmsh_type).unwrap_or((el.dim, 0, "unknown"));
        MeshError::UnsupportedElementType {
            at: self.cursor.at(),
            gmsh_type: el.gmsh_type,
            type_name: type_name.to_string(),
            element_id: el.id,
            context,
        }
    }

    /// Handles a 3D element: a hexahedron of one physical volume (its block); a repeated MSH 2.2
    /// line must name the same volume.
    fn volume_element(&mut self, el: &ElementLine) -> Result<(), MeshError> {
        let (id, gmsh_type) = (el.id, el.gmsh_type);
        let name = match el.groups {
            [] if el.repeated.is_some() => return Ok(()),
            [] if gmsh_type == GMSH_HEX8 => {
                return Err(MeshError::ElementWithoutBlock {
                    at: self.cursor.at(),
                    element_id: id,
                })
            }
            [] => return Err(self.unsupported(el, "(in no physical volume)".into())),
            [name] => name,
            [first, second, ..] => {
                return Err(MeshError::AmbiguousBlock {
                    at: self.cursor.at(),
                    element_id: id,
                    first: first.clone(),
                    second: second.clone(),
                })
            }
        };
        if gmsh_type != GMSH_HEX8 {
            return Err(self.unsupported(
                el,
                format!("in physical volume '{name}' (only type 5, 8-node hexahedra, is supported)"),
            ));
        }
        let block = match self.mesh.block_index(name) {
            Some(b) => b,
            None => {
                self.mesh.blocks.push(Block {
                    name: name.clone(),
                    kind: ElementKind::Hex8,
                    orientation: None,
                });
                (self.mesh.blocks.len() - 1) as u32
            }
        };
        match el.repeated {
            Some(Some(hex)) => {
                let first = &self.mesh.blocks[self.mesh.elements[hex as usize].block as usize].name;
                if *first != *name {
                    return Err(MeshError::AmbiguousBlock {
                        at: self.cursor.at(),
                        element_id: id,
                        first: first.clone(),
                        second: name.clone(),
                    });
                }
            }
            _ => self.push_hex(el, block),
        }
        Ok(())
    }

    /// Adds the hexahedron `el` to `block` and remembers its id.
    fn push_hex(&mut self, el: &ElementLine, block: u32) {
        let hex = self.mesh.elements.len() as u32;
        let mut conn = [0u32; 8];
        conn.copy_from_slice(&el.nodes);
        self.mesh.elements.push(Element {
            id: el.id,
            kind: ElementKind::Hex8,
            nodes: conn,
            block,
        });
        self.element_lines.push(self.cursor.line_no);
        self.seen_elements.insert(
            el.id,
            SeenElement {
                gmsh_type: el.gmsh_type,
                nodes_hash: el.nodes_hash,
                hex: Some(hex),
            },
        );
    }

    /// Handles an element of dimension 0 to 2: its nodes join the node sets of its groups, and
    /// a quadrangle of a physical surface is kept for the face sets.
    fn lower_element(&mut self, el: &ElementLine) -> Result<(), MeshError> {
        let (groups, nodes) = (el.groups, &el.nodes);
        if el.repeated.is_none() {
            self.seen_elements.insert(
                el.id,
                SeenElement {
                    gmsh_type: el.gmsh_type,
                    nodes_hash: el.nodes_hash,
                    hex: None,
                },
            );
        }
        if groups.is_empty() {
            return Ok(());
        }
        if el.dim == 2 && el.gmsh_type != GMSH_QUAD4 {
            return Err(self.unsupported(
                el,
                format!(
                    "in physical surface '{}' (face sets need type 3, 4-node quadrangles)",
                    groups[0]
                ),
            ));
        }
        for name in groups {
            self.node_set_members
                .entry(name.clone())
                .or_default()
                .extend_from_slice(nodes);
        }
        if el.dim == 2 {
            let sets: Vec<usize> = groups
                .iter()
                .filter_map(|name| self.face_set_names.iter().position(|n| n == name))
                .collect();
            let mut quad = [0u32; 4];
            quad.copy_from_slice(nodes);
            self.quads.push(QuadRecord {
                id: el.id,
                line: self.cursor.line_no,
                nodes: quad,
                sets,
            });
        }
        Ok(())
    }

    fn finish(mut self) -> Result<Mesh, MeshError> {
        let file = self.cursor.file;
        if self.mesh.elements.is_empty() {
            return Err(MeshError::Malformed {
                at: Location::in_memory(file),
                reason: "no 8-node hexahedron in any physical volume".into(),
            });
        }
        let lines = std::mem::take(&mut self.element_lines);
        if let Err((block, element_id)) = self.mesh.classify_zero_thickness() {
            let e = self
                .mesh
                .elements
                .iter()
                .position(|el| el.id == element_id)
                .unwrap_or(0);
            return Err(MeshError::Malformed {
                at: Location::file_line(file, lines[e]),
                reason: format!(
                    "physical volume '{block}' mixes zero-thickness (interface) and solid hexahedra \
                     (element {element_id} differs from the block's first element)"
                ),
            });
        }
        check_all_elements(&self.mesh, &|e| Location::file_line(file, lines[e]))?;
        for (name, mut members) in std::mem::take(&mut self.node_set_members) {
            members.sort_unstable();
            members.dedup();
            self.mesh.node_sets.insert(name, members);
        }
        self.match_faces()?;
        Ok(self.mesh)
    }

    /// Matches every quad of a physical surface to the hex face with the same nodes.
    fn match_faces(&mut self) -> Result<(), MeshError> {
        let mut face_sets: Vec<Vec<Face>> = vec![Vec::new(); self.face_set_names.len()];
        let sorted = |mut k: [u32; 4]| {
            k.sort_unstable();
            k
        };
        let mut by_key: HashMap<[u32; 4], Vec<usize>> = HashMap::with_capacity(self.quads.len());
        for (q, quad) in self.quads.iter().enumerate() {
            by_key.entry(sorted(quad.nodes)).or_default().push(q);
        }
        let mut candidates: Vec<Vec<Face>> = vec![Vec::new(); self.quads.len()];
        if !by_key.is_empty() {
            for (e, el) in self.mesh.elements.iter().enumerate() {
                for (f, local) in HEX8_FACES.iter().enumerate() {
                    let nodes = local.map(|a| el.nodes[a]);
                    if let Some(qs) = by_key.get(&sorted(nodes)) {
                        for &q in qs {
                            candidates[q].push(Face {
                                element: e as u32,
                                local_face: f as u8,
                                nodes,
                            });
                        }
                    }
                }
            }
        }
        for (quad, cands) in self.quads.iter().zip(candidates) {
            let same_orientation =
                |face: &Face| (0..4).any(|r| (0..4).all(|k| face.nodes[(k + r) % 4] == quad.nodes[k]));
            let chosen = cands
                .iter()
                .find(|f| same_orientation(f))
                .or_else(|| cands.first())
                .copied()
                .ok_or_else(|| MeshError::UnmatchedFace {
                    at: Location::file_line(self.cursor.file, quad.line),
                    element_id: quad.id,
                    set: quad
                        .sets
                        .first()
                        .map(|&s| self.face_set_names[s].clone())
                        .unwrap_or_default(),
                })?;
            for &s in &quad.sets {
                face_sets[s].push(chosen);
            }
        }
        for (name, faces) in self.face_set_names.iter().zip(face_sets) {
            self.mesh.face_sets.insert(name.clone(), faces);
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::element::hex8::{face_coords, quad_area_vector};

    const V41: &str = include_str!("../../inputs/meshes/two_hex_v41.msh");
    const V22: &str = include_str!("../../inputs/meshes/two_hex_v22.msh");

    fn meshes_dir() -> std::path::PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR")).join("inputs/meshes")
    }

    /// 1-based number of the (unique) line equal to `needle`.
    fn line_of(text: &str, needle: &str) -> usize {
        let hits: Vec<usize> = text
            .lines()
            .enumerate()
            .filter(|(_, l)| l.trim() == needle)
            .map(|(i, _)| i + 1)
            .collect();
        assert_eq!(hits.len(), 1, "line '{needle}' is not unique");
        hits[0]
    }

    /// `text` with the (unique) line `old` replaced by `new`.
    fn replace_line(text: &str, old: &str, new: &str) -> String {
        line_of(text, old);
        text.lines()
            .map(|l| if l.trim() == old { new } else { l })
            .collect::<Vec<_>>()
            .join("\n")
    }

    fn error_of(text: &str, file: &str) -> String {
        let err = parse_gmsh(text, file).expect_err("the mesh must be rejected");
        err.to_string()
    }

    fn assert_names(msg: &str, parts: &[&str]) {
        for p in parts {
            assert!(msg.contains(p), "message '{msg}' does not contain '{p}'");
        }
    }

    #[test]
    fn both_formats_give_the_same_mesh() {
        let m41 = read_gmsh(&meshes_dir().join("two_hex_v41.msh")).expect("MSH 4.1");
        let m22 = read_gmsh(&meshes_dir().join("two_hex_v22.msh")).expect("MSH 2.2");
        assert_eq!(m41, m22);
        let m = m41;
        m.validate().expect("valid");
        assert_eq!(m.node_ids, (1..=12).collect::<Vec<u64>>());
        assert_eq!(m.coords[10], [1.0, 1.0, 1.0]);
        let blocks: Vec<&str> = m.blocks.iter().map(|b| b.name.as_str()).collect();
        assert_eq!(blocks, ["left", "right"]);
        assert_eq!(m.elements.len(), 2);
        assert_eq!((m.elements[0].id, m.elements[0].block), (8, 0));
        assert_eq!((m.elements[1].id, m.elements[1].block), (9, 1));
        assert_eq!(m.elements[1].nodes, [1, 2, 5, 4, 7, 8, 11, 10]);
        let sets: Vec<(&str, Vec<u32>)> = vec![
            ("base", vec![0, 1, 2, 3, 4, 5]),
            ("corner", vec![0]),
            ("interface", vec![1, 4, 7, 10]),
            ("top_edge", vec![9, 10, 11]),
            ("xmax", vec![2, 5, 8, 11]),
        ];
        assert_eq!(m.node_sets.len(), sets.len());
        for (name, nodes) in sets {
            assert_eq!(m.node_sets[name], nodes, "node set {name}");
        }
        let face = |element, local_face, nodes| Face {
            element,
            local_face,
            nodes,
        };
        assert_eq!(m.face_sets.len(), 3);
        assert_eq!(
            m.face_sets["base"],
            [face(0, 0, [0, 3, 4, 1]), face(1, 0, [1, 4, 5, 2])]
        );
        assert_eq!(m.face_sets["xmax"], [face(1, 3, [2, 5, 11, 8])]);
        // The internal quad's right-hand normal is +x: it is the x = 1 face of `left`.
        assert_eq!(m.face_sets["interface"], [face(0, 3, [1, 4, 10, 7])]);
    }

    /// Files written by Gmsh 4.15 itself (`inputs/meshes/gmsh_box.py`): two glued boxes.
    #[test]
    fn files_written_by_gmsh_are_read_identically_in_both_formats() {
        let m41 = read_gmsh(&meshes_dir().join("gmsh_box_v41.msh")).expect("MSH 4.1");
        let m22 = read_gmsh(&meshes_dir().join("gmsh_box_v22.msh")).expect("MSH 2.2");
        assert_eq!(m41, m22);
        let m = m41;
        m.validate().expect("valid");
        assert_eq!(m.num_nodes(), 63);
        let blocks: Vec<&str> = m.blocks.iter().map(|b| b.name.as_str()).collect();
        assert_eq!(blocks, ["fill", "toe"]);
        let in_block = |b: u32| m.elements.iter().filter(|e| e.block == b).count();
        assert_eq!((in_block(0), in_block(1)), (16, 8));
        let volume: f64 = (0..m.elements.len())
            .map(|e| crate::element::hex8::volume(&m.element_coords(e)))
            .sum();
        assert!((volume - 3.0).abs() < 1e-12, "volume {volume}");
        assert_eq!(m.node_sets["origin"].len(), 1);
        assert_eq!(m.coords[m.node_sets["origin"][0] as usize], [0.0, 0.0, 0.0]);
        assert_eq!(m.node_sets["crest_line"].len(), 3);
        assert_eq!(m.node_sets["base"].len(), 7 * 3);
        for (name, count, normal) in [("base", 12, [0.0, 0.0, -1.0]), ("upstream", 4, [-1.0, 0.0, 0.0])] {
            let faces = &m.face_sets[name];
            assert_eq!(faces.len(), count, "{name}");
            for f in faces {
                let a = quad_area_vector(&f.nodes.map(|n| m.coords[n as usize]));
                let n = a.map(|v| v / 0.25);
                assert!((0..3).all(|i| (n[i] - normal[i]).abs() < 1e-12), "{name}: {a:?}");
            }
        }
        // The internal surface: every quad goes to the same side, consistently oriented.
        let joint = &m.face_sets["joint"];
        assert_eq!(joint.len(), 4);
        let side = m.elements[joint[0].element as usize].block;
        for f in joint {
            assert_eq!(m.elements[f.element as usize].block, side);
            let a = quad_area_vector(&f.nodes.map(|n| m.coords[n as usize]));
            assert!((a[0].abs() - 0.25).abs() < 1e-12 && a[0].signum() == if side == 0 { 1.0 } else { -1.0 });
        }
    }

    #[test]
    fn face_sets_have_outward_normals() {
        let m = parse_gmsh(V41, "two_hex_v41.msh").expect("mesh");
        for (name, normal) in [("base", [0.0, 0.0, -1.0]), ("xmax", [1.0, 0.0, 0.0])] {
            for f in &m.face_sets[name] {
                let x = m.element_coords(f.element as usize);
                let a = quad_area_vector(&face_coords(&x, f.local_face as usize));
                assert_eq!(a, normal, "{name}");
                let direct = quad_area_vector(&f.nodes.map(|n| m.coords[n as usize]));
                assert_eq!(direct, normal, "{name}: stored node order");
            }
        }
    }

    #[test]
    fn repeated_msh2_lines_add_group_memberships_and_unused_elements_are_ignored() {
        let text = V22.replace("$Elements\n9\n", "$Elements\n11\n").replace(
            "$EndElements",
            "6 3 2 3 2 3 6 12 9\n10 1 2 0 1 1 2\n$EndElements\n$Comments\nanything\n$EndComments",
        );
        let m = parse_gmsh(&text, "repeat.msh").expect("mesh");
        assert_eq!(m.face_sets["base"].len(), 3);
        assert_eq!(m.face_sets["base"][2], m.face_sets["xmax"][0]);
        assert_eq!(m.node_sets["base"], [0, 1, 2, 3, 4, 5, 8, 11]);
    }

    #[test]
    fn missing_file_is_named() {
        let path = meshes_dir().join("no_such_mesh.msh");
        let msg = read_gmsh(&path).expect_err("missing").to_string();
        assert_names(&msg, &["no_such_mesh.msh", "cannot read"]);
    }

    #[test]
    fn malformed_number_and_truncated_section_are_located() {
        let text = replace_line(V22, "5 1 1 0", "5 1 abc 0");
        let msg = error_of(&text, "bad.msh");
        assert_names(&msg, &[&format!("bad.msh:{}", line_of(V22, "5 1 1 0")), "'abc'"]);
        let cut = &V41[..V41.find("3 2 5 1").expect("block")];
        let msg = error_of(cut, "cut.msh");
        assert_names(&msg, &["cut.msh:", "end of file inside section $Elements"]);
        let no_elements = &V22[..V22.find("$Elements").expect("section")];
        let msg = error_of(no_elements, "noel.msh");
        assert_names(&msg, &["noel.msh:", "no $Elements section"]);
        let msg = error_of("solid box\n", "notmsh.msh");
        assert_names(&msg, &["notmsh.msh:1", "expected a section header"]);
    }

    #[test]
    fn unsupported_version_is_rejected() {
        let text = replace_line(V41, "4.1 0 8", "4.0 0 8");
        let msg = error_of(&text, "old.msh");
        assert_names(&msg, &["old.msh:2", "version 4.0"]);
    }

    #[test]
    fn binary_file_is_rejected() {
        let text = replace_line(V41, "4.1 0 8", "4.1 1 8");
        let msg = error_of(&text, "bin.msh");
        assert_names(&msg, &["bin.msh:2", "binary"]);
    }

    #[test]
    fn unsupported_element_type_in_physical_volume_is_named() {
        let old = "9 5 2 7 2 2 3 6 5 8 9 12 11";
        let text = replace_line(V22, old, "9 6 2 7 2 2 3 6 8 9 12");
        let msg = error_of(&text, "prism.msh");
        assert_names(
            &msg,
            &[
                &format!("prism.msh:{}", line_of(V22, old)),
                "type 6",
                "element 9",
                "'right'",
            ],
        );
    }

    #[test]
    fn triangle_in_physical_surface_is_rejected() {
        let old = "6 3 2 4 2 3 6 12 9";
        let text = replace_line(V22, old, "6 2 2 4 2 3 6 12");
        let msg = error_of(&text, "tri.msh");
        assert_names(
            &msg,
            &[
                &format!("tri.msh:{}", line_of(V22, old)),
                "type 2",
                "element 6",
                "'xmax'",
            ],
        );
    }

    #[test]
    fn duplicate_node_id_is_located() {
        let text = replace_line(V41, "12", "11");
        let msg = error_of(&text, "dup.msh");
        assert_names(
            &msg,
            &[&format!("dup.msh:{}", line_of(V41, "12")), "duplicate node id 11"],
        );
    }

    #[test]
    fn duplicate_element_id_is_located() {
        let old = "9 5 2 7 2 2 3 6 5 8 9 12 11";
        let text = replace_line(V22, old, "8 5 2 7 2 2 3 6 5 8 9 12 11");
        let msg = error_of(&text, "dup.msh");
        assert_names(
            &msg,
            &[
                &format!("dup.msh:{}", line_of(V22, old)),
                "duplicate element id 8",
            ],
        );
    }

    #[test]
    fn unknown_node_is_named() {
        let old = "9 2 3 6 5 8 9 12 11";
        let text = replace_line(V41, old, "9 2 3 6 5 8 9 13 11");
        let msg = error_of(&text, "unknown.msh");
        assert_names(
            &msg,
            &[
                &format!("unknown.msh:{}", line_of(V41, old)),
                "element 9",
                "unknown node 13",
            ],
        );
    }

    #[test]
    fn inverted_element_is_located() {
        let old = "9 5 2 7 2 2 3 6 5 8 9 12 11";
        let text = replace_line(V22, old, "9 5 2 7 2 8 9 12 11 2 3 6 5");
        let msg = error_of(&text, "inv.msh");
        assert_names(
            &msg,
            &[&format!("inv.msh:{}", line_of(V22, old)), "element 9 is inverted"],
        );
        // Only one corner folded over: caught at that corner.
        let text = replace_line(V22, "9 2 0 1", "9 0.4 0 0.2");
        let msg = error_of(&text, "fold.msh");
        assert_names(
            &msg,
            &[
                &format!("fold.msh:{}", line_of(V22, old)),
                "element 9 is inverted",
                "corner node",
            ],
        );
    }

    #[test]
    fn degenerate_elements_are_located() {
        let old = "9 5 2 7 2 2 3 6 5 8 9 12 11";
        let text = replace_line(V22, old, "9 5 2 7 2 2 3 6 5 8 9 12 12");
        let msg = error_of(&text, "rep.msh");
        assert_names(
            &msg,
            &[
                &format!("rep.msh:{}", line_of(V22, old)),
                "element 9 is degenerate",
                "node 12 appears twice",
            ],
        );
        // A flat element: all nodes within 1e-12 m of the plane x = 0 (its node pairs a, a + 4
        // stay apart, so it is not a zero-thickness interface element).
        let mut flat = V22.to_string();
        for (id, yz) in [(2, "0 0"), (5, "1 0"), (8, "0 1"), (11, "1 1")] {
            flat = replace_line(&flat, &format!("{id} 1 {yz}"), &format!("{id} 1e-12 {yz}"));
        }
        let msg = error_of(&flat, "flat.msh");
        assert_names(
            &msg,
            &[
                &format!("flat.msh:{}", line_of(V22, "8 5 2 6 1 1 2 5 4 7 8 11 10")),
                "element 8 is degenerate",
                "volume",
            ],
        );
    }

    #[test]
    fn zero_thickness_blocks_become_interface_blocks() {
        // element 8 (block 'left') with its top face moved onto its bottom face: nodes 5-8 of
        // the hexahedron pair with nodes 1-4, a zero-thickness interface element
        let mut text = V22.replace("8 5 2 6 1 1 2 5 4 7 8 11 10", "8 5 2 6 1 1 2 5 4 13 14 15 16");
        text = text.replace("$Nodes\n12\n", "$Nodes\n16\n");
        text = text.replace(
            "12 2 1 1\n$EndNodes",
            "12 2 1 1\n13 0 0 0\n14 1 0 0\n15 1 1 0\n16 0 1 0\n$EndNodes",
        );
        let m = parse_gmsh(&text, "iface.msh").expect("a zero-thickness block is valid");
        let left = m.block_index("left").unwrap() as usize;
        let right = m.block_index("right").unwrap() as usize;
        assert_eq!(m.blocks[left].kind, ElementKind::Interface8);
        assert_eq!(m.blocks[right].kind, ElementKind::Hex8);
        assert!(m.is_interface(0) && !m.is_interface(1));
        // the same block mixing a solid hexahedron is refused, naming the block and element
        let mixed = text.replace("9 5 2 7 2 2 3 6 5 8 9 12 11", "9 5 2 6 2 2 3 6 5 8 9 12 11");
        let msg = error_of(&mixed, "mixed.msh");
        assert_names(&msg, &["mixed.msh:", "'left' mixes zero-thickness", "element 9"]);
    }

    #[test]
    fn unnamed_physical_group_is_located_in_both_formats() {
        let text = replace_line(V22, "3 7 \"right\"", "").replace("$PhysicalNames\n7", "$PhysicalNames\n6");
        let msg = error_of(&text, "un22.msh");
        let line = line_of(V22, "9 5 2 7 2 2 3 6 5 8 9 12 11");
        assert_names(
            &msg,
            &[&format!("un22.msh:{line}"), "dimension 3, tag 7", "no name"],
        );
        let text = replace_line(V41, "3 7 \"right\"", "").replace("$PhysicalNames\n7", "$PhysicalNames\n6");
        let msg = error_of(&text, "un41.msh");
        let line = line_of(V41, "2 1 0 0 2 1 1 1 7 0");
        assert_names(&msg, &[&format!("un41.msh:{line}"), "dimension 3, tag 7"]);
    }

    #[test]
    fn hexahedron_without_physical_volume_is_named() {
        let old = "9 5 2 7 2 2 3 6 5 8 9 12 11";
        let text = replace_line(V22, old, "9 5 2 0 2 2 3 6 5 8 9 12 11");
        let msg = error_of(&text, "nophys.msh");
        assert_names(
            &msg,
            &[
                &format!("nophys.msh:{}", line_of(V22, old)),
                "hexahedron 9",
                "no physical volume",
            ],
        );
        let text = replace_line(V41, "2 1 0 0 2 1 1 1 7 0", "2 1 0 0 2 1 1 0 0");
        let msg = error_of(&text, "nophys41.msh");
        let line = line_of(V41, "9 2 3 6 5 8 9 12 11");
        assert_names(&msg, &[&format!("nophys41.msh:{line}"), "hexahedron 9"]);
    }

    #[test]
    fn element_in_two_physical_volumes_is_rejected() {
        let text = replace_line(V41, "2 1 0 0 2 1 1 1 7 0", "2 1 0 0 2 1 1 2 7 6 0");
        let msg = error_of(&text, "two.msh");
        let line = line_of(V41, "9 2 3 6 5 8 9 12 11");
        assert_names(
            &msg,
            &[&format!("two.msh:{line}"), "element 9", "'right'", "'left'"],
        );
    }

    #[test]
    fn quad_that_bounds_no_hexahedron_is_named() {
        let old = "6 3 2 4 2 3 6 12 9";
        let text = replace_line(V22, old, "6 3 2 4 2 3 6 12 11");
        let msg = error_of(&text, "face.msh");
        assert_names(
            &msg,
            &[
                &format!("face.msh:{}", line_of(V22, old)),
                "quadrangle 6",
                "'xmax'",
            ],
        );
    }

    /// Issue defect 3: a physical-tag count of 2^64 − 1 on an entity line reached
    /// `Vec::with_capacity` (capacity overflow).
    #[test]
    fn huge_physical_tag_count_of_an_entity_is_located() {
        let old = "2 1 0 0 2 1 1 1 7 0";
        let text = replace_line(V41, old, "2 1 0 0 2 1 1 18446744073709551615 7 0");
        let msg = error_of(&text, "tags.msh");
        assert_names(
            &msg,
            &[
                &format!("tags.msh:{}", line_of(V41, old)),
                "entity 2",
                "physical tags",
            ],
        );
    }

    /// Issue defect 4: counts of 10^12 are refused before memory is reserved, naming the line
    /// and the count.
    #[test]
    fn counts_larger_than_the_file_are_located() {
        let big = "1000000000000";
        let cases = [
            (V41, "3 1 0 12", format!("3 1 0 {big}"), "node block header"),
            (V41, "1 12 1 12", format!("1 {big} 1 12"), "$Nodes header"),
            (V41, "1 1 3 2", format!("1 1 3 {big}"), "$Entities counts"),
            (V22, "12", big.to_string(), "$Nodes count"),
            (V22, "9", big.to_string(), "$Elements count"),
            (V22, "7", big.to_string(), "$PhysicalNames count"),
        ];
        for (text, old, new, what) in cases {
            let msg = error_of(&replace_line(text, old, &new), "big.msh");
            assert_names(
                &msg,
                &[
                    &format!("big.msh:{}", line_of(text, old)),
                    what,
                    big,
                    "bytes can hold",
                ],
            );
        }
        let text = V41.replace("$Elements\n7 ", &format!("$Elements\n{big} "));
        let msg = error_of(&text, "big.msh");
        assert_names(&msg, &["$Elements header", big]);
        let old = "3 2 5 1";
        let msg = error_of(&replace_line(V41, old, &format!("3 2 5 {big}")), "big.msh");
        assert_names(
            &msg,
            &[
                &format!("big.msh:{}", line_of(V41, old)),
                "element block header",
                big,
            ],
        );
    }

    /// Issue item 7: a non-finite coordinate is named with its node and line (it was reported
    /// later as a face area of NaN).
    #[test]
    fn non_finite_coordinates_are_located() {
        let msg = error_of(&replace_line(V22, "5 1 1 0", "5 1 inf 0"), "inf.msh");
        assert_names(
            &msg,
            &[
                &format!("inf.msh:{}", line_of(V22, "5 1 1 0")),
                "node 5",
                "y = 'inf'",
                "finite",
            ],
        );
        let msg = error_of(&replace_line(V41, "2 1 1", "2 nan 1"), "nan.msh");
        assert_names(
            &msg,
            &[&format!("nan.msh:{}", line_of(V41, "2 1 1")), "node 12", "'nan'"],
        );
    }

    /// Issue item 7: a negative node id in an MSH 2.2 element is reported as written.
    #[test]
    fn negative_node_id_of_an_element_is_reported_as_written() {
        let old = "9 5 2 7 2 2 3 6 5 8 9 12 11";
        let msg = error_of(&replace_line(V22, old, "9 5 2 7 2 2 3 6 5 8 -3 12 11"), "neg.msh");
        assert_names(
            &msg,
            &[
                &format!("neg.msh:{}", line_of(V22, old)),
                "element 9",
                "node id -3",
            ],
        );
        assert!(!msg.contains("node 0"), "{msg}");
    }

    #[test]
    fn a_device_is_not_read_as_a_mesh() {
        let msg = read_gmsh(Path::new("/dev/zero"))
            .expect_err("a device")
            .to_string();
        assert_names(&msg, &["/dev/zero", "not a regular file"]);
    }
}
