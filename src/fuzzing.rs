//! One input in, one reader run: the entry points of the fuzz targets (`tests/fuzz`) and of the
//! corpus replay test (`tests/fuzz_corpus.rs`), so both exercise the functions the program uses
//! on a file's bytes.
//!
//! Each function takes the raw bytes of one input and runs one reader as the program does after
//! reading the file. An `Err` of the reader is a correct answer to bad input
//! ([`Outcome::Rejected`]); a panic, an abort (out of memory, capacity overflow) or a run that
//! does not end is a bug. The user guide's section on fuzzing ([`crate::guide`]) tells how the
//! campaign runs and what it found.
//!
//! | function | reader | as in |
//! |---|---|---|
//! | [`scene`] | [`Scene::from_str`]: parse, validation, mesh, cross-references | `cfrd check` |
//! | [`gmsh`] | [`crate::mesh::gmsh::parse_gmsh`] (MSH 2.2 and 4.1 detected from the header) | `mesh.file` |
//! | [`accel_csv`] | [`Accelerogram::from_csv_str`] | `stages[k].dynamic.record` |
//! | [`accel_at2`] | [`crate::seismic::at2::parse_at2`], then [`Accelerogram::from_components`] | `stages[k].dynamic.record: { x, y, z }` |
//! | [`state_codec()`] | [`crate::solver::state_codec`] decoders of every model | a checkpoint's `states` rows |
//! | [`lock_file`] | [`crate::dir_lock::RunLock::acquire`] over whatever stands at the lock's path | `cfrd run -o OUT` |
//! | [`checkpoint_inputs`] | [`crate::scene::inputs::changed`] on a checkpoint's `input_files` text | `cfrd run --restart` |

use crate::material::elastic::ElasticParams;
use crate::material::{InterfaceParams, SolidParams};
use crate::scene::schema::MeshSource;
use crate::scene::Scene;
use crate::seismic::Accelerogram;
use crate::solver::interface::InterfaceElements;
use crate::solver::solid::SolidBlock;
use crate::solver::state_codec;
use std::path::{Path, PathBuf};

/// What one input did.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Outcome {
    /// The reader accepted the input.
    Accepted,
    /// The reader returned an error (the right answer to bad input).
    Rejected,
    /// Not run: a scene whose generated mesh exceeds [`SCENE_MAX_NODES`] (valid input whose
    /// cost grows with the size asked for, not a reader defect).
    Skipped,
}

impl Outcome {
    fn of<T, E>(result: Result<T, E>) -> Outcome {
        match result {
            Ok(_) => Outcome::Accepted,
            Err(_) => Outcome::Rejected,
        }
    }
}

/// Most nodes of a generated mesh (`mesh.box`, `mesh.dam`, `mesh.cfrd`) that [`scene`] builds:
/// each input then runs in milliseconds. Larger meshes are legal up to
/// [`crate::mesh::generate::MAX_GENERATED_NODES`].
pub const SCENE_MAX_NODES: u128 = 20_000;

/// Folder that relative paths of a fuzzed scene are taken from: `inputs/scenes` of the source
/// tree, so `../meshes/…` and `../accel/…` reach the real mesh and record files.
pub fn scene_base() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("inputs")
        .join("scenes")
}

/// A scene file's bytes through [`Scene::from_str`] as `cfrd check` runs it (after the UTF-8
/// check of [`Scene::load`]), relative paths from [`scene_base`].
pub fn scene(bytes: &[u8]) -> Outcome {
    let Ok(text) = std::str::from_utf8(bytes) else {
        return Outcome::Rejected;
    };
    if asks_for_large_mesh(text) {
        return Outcome::Skipped;
    }
    Outcome::of(Scene::from_str(text, "<fuzz>", &scene_base()))
}

/// Whether the scene text passes the checks [`Scene::from_str`] runs before parsing, parses,
/// and asks a generator for more than [`SCENE_MAX_NODES`] nodes.
fn asks_for_large_mesh(text: &str) -> bool {
    let text = crate::scene::text::strip_bom(text);
    if crate::scene::text::check_depth(text, "<fuzz>").is_err() {
        return false;
    }
    crate::scene::parse::parse(text, "<fuzz>").is_ok_and(|f| generated_nodes(&f.mesh) > SCENE_MAX_NODES)
}

/// Nodes of the mesh a scene's generator would build (0 for a mesh file, or when the spec is
/// invalid: the generator then refuses it before building anything).
fn generated_nodes(src: &MeshSource) -> u128 {
    let grid = |d: [usize; 3]| d.iter().map(|&n| n as u128 + 1).product::<u128>();
    if let Some(b) = &src.box_ {
        grid(b.divisions)
    } else if let Some(d) = &src.dam {
        grid(d.divisions)
    } else if let Some(c) = &src.cfrd {
        c.approximate_nodes().unwrap_or(0)
    } else {
        0
    }
}

/// A Gmsh file's bytes through [`crate::mesh::gmsh::parse_gmsh`], decoded as
/// [`crate::mesh::gmsh::read_gmsh`] does (invalid UTF-8 replaced).
pub fn gmsh(bytes: &[u8]) -> Outcome {
    let text = String::from_utf8_lossy(bytes);
    Outcome::of(crate::mesh::gmsh::parse_gmsh(&text, "<fuzz>"))
}

/// A record CSV's bytes through [`Accelerogram::from_csv_str`] (UTF-8 required, as
/// [`Accelerogram::read_csv`] does).
pub fn accel_csv(bytes: &[u8]) -> Outcome {
    let Ok(text) = std::str::from_utf8(bytes) else {
        return Outcome::Rejected;
    };
    Outcome::of(Accelerogram::from_csv_str(text, Path::new("<fuzz>")))
}

/// A PEER AT2 file's bytes through [`crate::seismic::at2::parse_at2`]; an accepted component
/// then becomes the x component of a three-component record.
pub fn accel_at2(bytes: &[u8]) -> Outcome {
    let Ok(text) = std::str::from_utf8(bytes) else {
        return Outcome::Rejected;
    };
    let component = crate::seismic::at2::parse_at2(text, Path::new("<fuzz>")).map_err(|e| e.to_string());
    Outcome::of(component.and_then(|c| Accelerogram::from_components([Some(c), None, None])))
}

/// Elements in each block of [`state_codec()`]: a decoded element index beyond them is refused.
const CODEC_ELEMENTS: usize = 2;

/// An encoded element state through the checkpoint decoders. The first byte picks the model
/// (its value modulo 6: elastic, rockfill GP, hyperbolic, Mohr–Coulomb, joint, GP interface),
/// the second the block-local element (modulo 3, one past the block's 2 elements), the rest is
/// the encoded states. Accepted bytes must survive a re-encoding: encoding the decoded states
/// and decoding those bytes again gives the same bytes (a failure panics, as a bug).
pub fn state_codec(bytes: &[u8]) -> Outcome {
    let [model, element, encoded @ ..] = bytes else {
        return Outcome::Rejected;
    };
    let e = usize::from(*element) % (CODEC_ELEMENTS + 1);
    match model % 6 {
        m @ 0..=1 => solid_codec(m, e, encoded),
        m => interface_codec(m - 2, e, encoded),
    }
}

/// Valid inputs of [`state_codec()`]: the initial states of element 0 of every model, encoded
/// as a checkpoint stores them, behind the two selector bytes (seeds of the campaign).
pub fn state_codec_examples() -> Vec<Vec<u8>> {
    let mut out = Vec::new();
    for (m, params) in [
        (0u8, SolidParams::Elastic(ElasticParams::seed_slab())),
        (1, rockfill()),
    ] {
        let block = SolidBlock::new(&params, CODEC_ELEMENTS).expect("a solid block");
        out.push(
            [
                vec![m, 0],
                state_codec::encode_solid(&block, 0).expect("encoding"),
            ]
            .concat(),
        );
    }
    for m in 0..4 {
        let block = InterfaceElements::new(&interface(m), CODEC_ELEMENTS, 1.0e5).expect("an interface block");
        out.push(
            [
                vec![m + 2, 0],
                state_codec::encode_interface(&block, 0).expect("encoding"),
            ]
            .concat(),
        );
    }
    out
}

fn rockfill() -> SolidParams {
    SolidParams::RockfillGp(Default::default())
}

/// The parameters of interface model `m` (0 to 3: hyperbolic, Mohr–Coulomb, joint, GP).
fn interface(m: u8) -> InterfaceParams {
    match m {
        0 => InterfaceParams::Hyperbolic(Default::default()),
        1 => InterfaceParams::MohrCoulomb(Default::default()),
        2 => InterfaceParams::Joint(Default::default()),
        _ => InterfaceParams::GpInterface(Default::default()),
    }
}

fn solid_codec(model: u8, e: usize, encoded: &[u8]) -> Outcome {
    let params = match model {
        0 => SolidParams::Elastic(ElasticParams::seed_slab()),
        _ => rockfill(),
    };
    let Ok(mut block) = SolidBlock::new(&params, CODEC_ELEMENTS) else {
        return Outcome::Rejected;
    };
    if state_codec::decode_solid(&mut block, e, encoded).is_err() {
        return Outcome::Rejected;
    }
    let once = state_codec::encode_solid(&block, e).expect("re-encoding decoded solid states");
    state_codec::decode_solid(&mut block, e, &once).expect("decoding re-encoded solid states");
    let twice = state_codec::encode_solid(&block, e).expect("re-encoding solid states twice");
    assert_eq!(once, twice, "solid states change on a second round trip");
    Outcome::Accepted
}

fn interface_codec(model: u8, e: usize, encoded: &[u8]) -> Outcome {
    let Ok(mut block) = InterfaceElements::new(&interface(model), CODEC_ELEMENTS, 1.0e5) else {
        return Outcome::Rejected;
    };
    if state_codec::decode_interface(&mut block, e, encoded).is_err() {
        return Outcome::Rejected;
    }
    let once = state_codec::encode_interface(&block, e).expect("re-encoding decoded interface states");
    state_codec::decode_interface(&mut block, e, &once).expect("decoding re-encoded interface states");
    let twice = state_codec::encode_interface(&block, e).expect("re-encoding interface states twice");
    assert_eq!(once, twice, "interface states change on a second round trip");
    Outcome::Accepted
}

/// The output directory's lock ([`crate::dir_lock::RunLock::acquire`]) with what stands at the
/// lock file's path made from the bytes: the first byte picks it (modulo 5: nothing, a regular
/// file holding the other bytes, a directory, a symbolic link to a file holding them, a
/// dangling symbolic link), in a fresh directory under the system's temporary folder.
/// Accepted when the lock is taken. What was there must be left as it was: a file's bytes, a
/// link's target, and no file made where a dangling link points (a failure panics, as a bug).
pub fn lock_file(bytes: &[u8]) -> Outcome {
    static NEXT: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(0);
    let [kind, content @ ..] = bytes else {
        return Outcome::Rejected;
    };
    let n = NEXT.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let root = std::env::temp_dir().join(format!("cfrd-fuzz-lock-{}-{n}", std::process::id()));
    let (out, target) = (root.join("out"), root.join("target"));
    let lock = out.join(crate::dir_lock::LOCK_FILE);
    std::fs::create_dir_all(&out).expect("a fresh directory");
    let made = match kind % 5 {
        0 => Ok(()),
        1 => std::fs::write(&lock, content),
        2 => std::fs::create_dir(&lock),
        3 => std::fs::write(&target, content).and_then(|()| std::os::unix::fs::symlink(&target, &lock)),
        _ => std::os::unix::fs::symlink(&target, &lock),
    };
    made.expect("the lock path prepared");
    let outcome = Outcome::of(crate::dir_lock::RunLock::acquire(&out));
    match kind % 5 {
        1 => assert_eq!(
            std::fs::read(&lock).expect("the file kept"),
            content,
            "the lock file's bytes changed"
        ),
        3 => assert_eq!(
            std::fs::read(&target).expect("the target kept"),
            content,
            "a link's target changed"
        ),
        4 => assert!(!target.exists(), "a file was made where a dangling link points"),
        _ => {}
    }
    let _ = std::fs::remove_dir_all(&root);
    outcome
}

/// A checkpoint's `input_files` text ([`crate::scene::inputs::to_text`]) from the bytes
/// (invalid UTF-8 replaced) through [`crate::scene::inputs::changed`] against the input files of
/// a scene with a mesh file and a record, one of them accepted. Accepted when nothing changed.
/// Every change named must be a key of the text (a failure panics, as a bug).
pub fn checkpoint_inputs(bytes: &[u8]) -> Outcome {
    use crate::scene::inputs::{changed, InputFile};
    let stored = String::from_utf8_lossy(bytes);
    let base = scene_base();
    let now = [
        InputFile {
            key: "mesh.file".into(),
            path: base.join("../meshes/two_hex_v41.msh"),
            hash: "00000000000000aa".into(),
        },
        InputFile {
            key: "stages[1].dynamic.record".into(),
            path: base.join("../accel/seed_quake.csv"),
            hash: "00000000000000bb".into(),
        },
    ];
    let accepted = [base.join("../accel/seed_quake.csv")];
    let found = changed(&stored, &now, &accepted);
    let keys: Vec<&str> = stored
        .lines()
        .map(|l| l.split('\t').next().unwrap_or(""))
        .collect();
    for (key, _, _) in &found {
        assert!(
            keys.contains(&key.as_str()),
            "a change named for a key the text lacks: {key}"
        );
    }
    match found.is_empty() {
        true => Outcome::Accepted,
        false => Outcome::Rejected,
    }
}

/// The entry function of a fuzz target: one input's bytes in, what the reader did out.
pub type Entry = fn(&[u8]) -> Outcome;

/// The fuzz targets by name (the folder names of `tests/fuzz/corpus`), each with its entry
/// function.
pub const TARGETS: [(&str, Entry); 7] = [
    ("scene", scene),
    ("gmsh", gmsh),
    ("accel_csv", accel_csv),
    ("accel_at2", accel_at2),
    ("state_codec", state_codec),
    ("lock_file", lock_file),
    ("checkpoint_inputs", checkpoint_inputs),
];
