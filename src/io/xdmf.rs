//! The XDMF 3 description of a results file, which ParaView (`Xdmf3ReaderT`) and VisIt open
//! directly.
//!
//! The XML file (e.g. `results.xdmf`) sits next to the HDF5 file (`results.h5`) and names it by
//! its bare file name, so the pair can be moved together. It holds one temporal collection; each
//! output step is a `Uniform` grid with its `<Time Value=…/>`, the shared mesh (topology and
//! geometry point at the same `/mesh/...` datasets in every step, so they are stored once) and
//! the step's fields. A file without steps is a single `Uniform` grid with the mesh only.
//!
//! Attribute types: 1 component → `Scalar`, 3 → `Vector`, 6 → `Tensor6`, anything else →
//! `Matrix`. ParaView reads a `Tensor6` array as six components in the file's order, which for
//! cfrd is the Voigt order `[xx, yy, zz, xy, yz, zx]`: the same order as VTK's symmetric tensors
//! (XX, YY, ZZ, XY, YZ, XZ), so component names and tensor filters in ParaView are right.
//!
//! The layout of the HDF5 datasets themselves (shapes, units, signs) is documented in
//! [`crate::io`].
//!
//! The XML is written by rank 0 only, through a temporary file renamed into place.

use std::fmt::Write as _;
use std::path::Path;

use super::error::IoError;

/// Where a field's values live.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Center {
    /// One row per mesh node (input order).
    Node,
    /// One row per element (input order), e.g. stress at the element centre.
    Element,
}

impl Center {
    /// The XDMF `Center` attribute value.
    pub fn xdmf_name(self) -> &'static str {
        match self {
            Center::Node => "Node",
            Center::Element => "Cell",
        }
    }

    /// The value of the `center` attribute of a field dataset in the HDF5 file.
    pub fn file_name(self) -> &'static str {
        match self {
            Center::Node => "node",
            Center::Element => "element",
        }
    }
}

/// Number type of a dataset as XDMF names it (all cfrd datasets are 8 bytes wide).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum NumberType {
    /// 64-bit IEEE float.
    Float,
    /// 64-bit signed integer.
    Int,
}

impl NumberType {
    fn xdmf_name(self) -> &'static str {
        match self {
            NumberType::Float => "Float",
            NumberType::Int => "Int",
        }
    }
}

/// One attribute (field) of a grid.
#[derive(Debug, Clone, PartialEq)]
pub struct XdmfAttribute {
    /// Name shown in ParaView.
    pub name: String,
    /// Node or cell data.
    pub center: Center,
    /// Components per row (1, 3, 6 or other).
    pub ncomp: usize,
    /// Absolute path of the dataset inside the HDF5 file, e.g. `/steps/000001/displacement`.
    pub dataset: String,
    /// Number type of the dataset.
    pub number_type: NumberType,
}

impl XdmfAttribute {
    /// The XDMF `AttributeType` for the component count.
    pub fn attribute_type(&self) -> &'static str {
        match self.ncomp {
            1 => "Scalar",
            3 => "Vector",
            6 => "Tensor6",
            _ => "Matrix",
        }
    }
}

/// The mesh part of every grid.
#[derive(Debug, Clone, PartialEq)]
pub struct XdmfMesh {
    /// Number of nodes.
    pub n_nodes: u64,
    /// Number of hexahedra.
    pub n_elements: u64,
    /// Dataset of node coordinates, `n_nodes × 3` floats.
    pub coordinates: String,
    /// Dataset of the connectivity, `n_elements × 8` integers (0-based node rows).
    pub topology: String,
    /// Mesh attributes repeated in every grid (node ids, element ids, block index).
    pub attributes: Vec<XdmfAttribute>,
}

/// One output step: a grid at one time.
#[derive(Debug, Clone, PartialEq)]
pub struct XdmfStep {
    /// Grid name (e.g. `step_000001`).
    pub name: String,
    /// Time value shown by ParaView (s, or the stage's pseudo-time).
    pub time: f64,
    /// The step's fields.
    pub attributes: Vec<XdmfAttribute>,
}

/// Everything the XML needs.
#[derive(Debug, Clone, PartialEq)]
pub struct XdmfDocument {
    /// File name of the HDF5 file relative to the XML file (normally the bare file name).
    pub h5_file: String,
    /// The mesh.
    pub mesh: XdmfMesh,
    /// Output steps in order.
    pub steps: Vec<XdmfStep>,
}

/// Escapes the five XML special characters.
fn escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&apos;"),
            _ => out.push(c),
        }
    }
    out
}

/// The `Dimensions` string of a dataset with `rows` rows of `ncomp` components (1-component
/// datasets are one-dimensional).
fn dims(rows: u64, ncomp: usize) -> String {
    if ncomp == 1 {
        format!("{rows}")
    } else {
        format!("{rows} {ncomp}")
    }
}

/// Writes one `DataItem` pointing at an HDF5 dataset.
fn data_item(out: &mut String, indent: &str, h5: &str, dataset: &str, dims: &str, ty: NumberType) {
    let _ = writeln!(
        out,
        "{indent}<DataItem Dimensions=\"{dims}\" NumberType=\"{}\" Precision=\"8\" Format=\"HDF\">{}:{}</DataItem>",
        ty.xdmf_name(),
        escape(h5),
        escape(dataset)
    );
}

fn attribute(out: &mut String, indent: &str, h5: &str, rows: u64, a: &XdmfAttribute) {
    let _ = writeln!(
        out,
        "{indent}<Attribute Name=\"{}\" AttributeType=\"{}\" Center=\"{}\">",
        escape(&a.name),
        a.attribute_type(),
        a.center.xdmf_name()
    );
    data_item(
        out,
        &format!("{indent}  "),
        h5,
        &a.dataset,
        &dims(rows, a.ncomp),
        a.number_type,
    );
    let _ = writeln!(out, "{indent}</Attribute>");
}

/// Writes one `Uniform` grid: mesh, mesh attributes, then `fields`.
fn grid(
    out: &mut String,
    indent: &str,
    doc: &XdmfDocument,
    name: &str,
    time: Option<f64>,
    fields: &[XdmfAttribute],
) {
    let m = &doc.mesh;
    let h5 = &doc.h5_file;
    let inner = format!("{indent}  ");
    let item = format!("{indent}    ");
    let _ = writeln!(
        out,
        "{indent}<Grid Name=\"{}\" GridType=\"Uniform\">",
        escape(name)
    );
    if let Some(t) = time {
        let _ = writeln!(out, "{inner}<Time Value=\"{t:?}\"/>");
    }
    let _ = writeln!(
        out,
        "{inner}<Topology TopologyType=\"Hexahedron\" NumberOfElements=\"{}\" NodesPerElement=\"8\">",
        m.n_elements
    );
    data_item(
        out,
        &item,
        h5,
        &m.topology,
        &dims(m.n_elements, 8),
        NumberType::Int,
    );
    let _ = writeln!(out, "{inner}</Topology>");
    let _ = writeln!(out, "{inner}<Geometry GeometryType=\"XYZ\">");
    data_item(
        out,
        &item,
        h5,
        &m.coordinates,
        &dims(m.n_nodes, 3),
        NumberType::Float,
    );
    let _ = writeln!(out, "{inner}</Geometry>");
    for a in m.attributes.iter().chain(fields) {
        let rows = match a.center {
            Center::Node => m.n_nodes,
            Center::Element => m.n_elements,
        };
        attribute(out, &inner, h5, rows, a);
    }
    let _ = writeln!(out, "{indent}</Grid>");
}

/// Renders the XDMF 3 document.
pub fn render(doc: &XdmfDocument) -> String {
    let mut out = String::new();
    out.push_str("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
    out.push_str("<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n");
    out.push_str("<Xdmf Version=\"3.0\" xmlns:xi=\"http://www.w3.org/2001/XInclude\">\n");
    out.push_str("  <Domain>\n");
    if doc.steps.is_empty() {
        grid(&mut out, "    ", doc, "mesh", None, &[]);
    } else {
        out.push_str("    <Grid Name=\"results\" GridType=\"Collection\" CollectionType=\"Temporal\">\n");
        for s in &doc.steps {
            grid(&mut out, "      ", doc, &s.name, Some(s.time), &s.attributes);
        }
        out.push_str("    </Grid>\n");
    }
    out.push_str("  </Domain>\n");
    out.push_str("</Xdmf>\n");
    out
}

/// Writes the document to `path` through a temporary file in the same directory, renamed into
/// place, so an existing XDMF file is replaced only by a complete one. Call on one rank only.
pub fn write(doc: &XdmfDocument, path: &Path) -> Result<(), IoError> {
    super::error::write_atomic(path, render(doc).as_bytes())
}

/// An element found by [`parse_for_tests`].
#[cfg(test)]
#[derive(Debug, Clone)]
pub(crate) struct XmlElement {
    /// Tag name.
    pub name: String,
    /// Attributes in order.
    pub attrs: Vec<(String, String)>,
    /// Text content (trimmed, concatenated).
    pub text: String,
}

#[cfg(test)]
impl XmlElement {
    /// Value of attribute `key`.
    pub fn attr(&self, key: &str) -> Option<&str> {
        self.attrs.iter().find(|(k, _)| k == key).map(|(_, v)| v.as_str())
    }
}

/// A minimal XML well-formedness check used by the tests: balanced, properly nested tags,
/// quoted attribute values, and no stray `<`/`>`. Returns every element in document order.
#[cfg(test)]
pub(crate) fn parse_for_tests(xml: &str) -> Result<Vec<XmlElement>, String> {
    let mut elements: Vec<XmlElement> = Vec::new();
    let mut stack: Vec<(String, usize)> = Vec::new();
    let mut rest = xml;
    let mut roots = 0;
    while let Some(lt) = rest.find('<') {
        let text = &rest[..lt];
        if let Some(&(_, idx)) = stack.last() {
            elements[idx].text.push_str(text.trim());
        } else if !text.trim().is_empty() {
            return Err(format!("text outside the root: {text:?}"));
        }
        if text.contains('>') {
            return Err(format!("stray '>' in {text:?}"));
        }
        rest = &rest[lt..];
        let gt = rest.find('>').ok_or("unterminated tag")?;
        let tag = &rest[1..gt];
        rest = &rest[gt + 1..];
        if tag.starts_with('?') || tag.starts_with('!') {
            continue;
        }
        if let Some(name) = tag.strip_prefix('/') {
            let (open, _) = stack.pop().ok_or(format!("closing </{name}> without opening"))?;
            if open != name.trim() {
                return Err(format!("<{open}> closed by </{name}>"));
            }
            continue;
        }
        let self_closing = tag.ends_with('/');
        let body = tag.trim_end_matches('/');
        let mut parts = body.splitn(2, char::is_whitespace);
        let name = parts.next().ok_or("empty tag")?.to_string();
        let mut attrs = Vec::new();
        let mut a = parts.next().unwrap_or("").trim();
        while !a.is_empty() {
            let eq = a
                .find('=')
                .ok_or(format!("attribute without value in <{name}>"))?;
            let key = a[..eq].trim().to_string();
            let after = a[eq + 1..].trim_start();
            if !after.starts_with('"') {
                return Err(format!("unquoted attribute {key} in <{name}>"));
            }
            let close = after[1..].find('"').ok_or("unterminated attribute value")?;
            let value = after[1..1 + close].to_string();
            if value.contains('<') {
                return Err(format!("'<' in attribute {key}"));
            }
            attrs.push((key, value));
            a = after[close + 2..].trim_start();
        }
        if stack.is_empty() {
            roots += 1;
        }
        elements.push(XmlElement {
            name: name.clone(),
            attrs,
            text: String::new(),
        });
        if !self_closing {
            stack.push((name, elements.len() - 1));
        }
    }
    if !rest.trim().is_empty() {
        return Err(format!("trailing text {rest:?}"));
    }
    if let Some((open, _)) = stack.pop() {
        return Err(format!("<{open}> never closed"));
    }
    if roots != 1 {
        return Err(format!("{roots} root elements"));
    }
    Ok(elements)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn doc(steps: usize) -> XdmfDocument {
        let field = |name: &str, center, ncomp, step: usize| XdmfAttribute {
            name: name.to_string(),
            center,
            ncomp,
            dataset: format!("/steps/{step:06}/{name}"),
            number_type: NumberType::Float,
        };
        XdmfDocument {
            h5_file: "dam & co.h5".to_string(),
            mesh: XdmfMesh {
                n_nodes: 12,
                n_elements: 2,
                coordinates: "/mesh/coordinates".to_string(),
                topology: "/mesh/topology".to_string(),
                attributes: vec![XdmfAttribute {
                    name: "block".to_string(),
                    center: Center::Element,
                    ncomp: 1,
                    dataset: "/mesh/element_block".to_string(),
                    number_type: NumberType::Int,
                }],
            },
            steps: (1..=steps)
                .map(|s| XdmfStep {
                    name: format!("step_{s:06}"),
                    time: s as f64 * 0.5,
                    attributes: vec![
                        field("displacement", Center::Node, 3, s),
                        field("stress", Center::Element, 6, s),
                        field("plastic", Center::Element, 1, s),
                        field("state", Center::Element, 4, s),
                    ],
                })
                .collect(),
        }
    }

    #[test]
    fn temporal_collection_is_well_formed_and_typed() {
        let xml = render(&doc(2));
        let elements = parse_for_tests(&xml).unwrap_or_else(|e| panic!("{e}\n{xml}"));
        let count = |n: &str| elements.iter().filter(|e| e.name == n).count();
        assert_eq!(count("Xdmf"), 1);
        assert_eq!(count("Grid"), 3, "collection + 2 steps");
        assert_eq!(count("Time"), 2);
        assert_eq!(count("Topology"), 2);
        let attr = |e: &XmlElement, k: &str| e.attr(k).map(str::to_string);
        let times: Vec<String> = elements
            .iter()
            .filter(|e| e.name == "Time")
            .filter_map(|e| attr(e, "Value"))
            .collect();
        assert_eq!(times, vec!["0.5", "1.0"]);
        let types: Vec<(String, String, String)> = elements
            .iter()
            .filter(|e| e.name == "Attribute")
            .take(5)
            .map(|e| {
                (
                    attr(e, "Name").unwrap(),
                    attr(e, "AttributeType").unwrap(),
                    attr(e, "Center").unwrap(),
                )
            })
            .collect();
        let expect = [
            ("block", "Scalar", "Cell"),
            ("displacement", "Vector", "Node"),
            ("stress", "Tensor6", "Cell"),
            ("plastic", "Scalar", "Cell"),
            ("state", "Matrix", "Cell"),
        ];
        for (got, want) in types.iter().zip(expect) {
            assert_eq!((got.0.as_str(), got.1.as_str(), got.2.as_str()), want);
        }
        let items: Vec<&XmlElement> = elements.iter().filter(|e| e.name == "DataItem").collect();
        assert!(
            items.iter().all(|e| e.text.starts_with("dam &amp; co.h5:/")),
            "escaped file name"
        );
        let topo = items.iter().find(|e| e.text.ends_with("/mesh/topology")).unwrap();
        assert_eq!(attr(topo, "Dimensions").unwrap(), "2 8");
        assert_eq!(attr(topo, "NumberType").unwrap(), "Int");
        let stress = items.iter().find(|e| e.text.ends_with("000002/stress")).unwrap();
        assert_eq!(attr(stress, "Dimensions").unwrap(), "2 6");
        let disp = items
            .iter()
            .find(|e| e.text.ends_with("000001/displacement"))
            .unwrap();
        assert_eq!(attr(disp, "Dimensions").unwrap(), "12 3");
    }

    #[test]
    fn mesh_only_document_is_a_single_uniform_grid() {
        let xml = render(&doc(0));
        let elements = parse_for_tests(&xml).unwrap();
        assert_eq!(elements.iter().filter(|e| e.name == "Grid").count(), 1);
        assert!(!xml.contains("Temporal"));
        assert!(!xml.contains("<Time"));
    }

    #[test]
    fn checker_rejects_malformed_xml() {
        assert!(parse_for_tests("<a><b></a></b>").is_err());
        assert!(parse_for_tests("<a x=1></a>").is_err());
        assert!(parse_for_tests("<a></a><b/>").is_err());
        assert!(parse_for_tests("<a>").is_err());
        assert!(parse_for_tests("<a x=\"1\"><b/>text</a>").is_ok());
    }

    #[test]
    fn write_replaces_the_file_atomically() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("r.xdmf");
        std::fs::write(&path, "old").unwrap();
        write(&doc(1), &path).unwrap();
        let text = std::fs::read_to_string(&path).unwrap();
        assert!(text.starts_with("<?xml") && text.contains("step_000001"));
        let leftovers: Vec<_> = std::fs::read_dir(dir.path()).unwrap().collect();
        assert_eq!(leftovers.len(), 1, "no temporary file left behind");
    }
}
