//! Golden results of the coarse seed dam (issue 21, acceptance 3): for each interface model
//! (`inputs/scenes/seed_coarse_{gp_interface,hyperbolic,mohr_coulomb}.yaml`) the slab table
//! (seed Figs. 8 and 9, `fig08_slab_stress.csv`: σ_s, σ_a and deflection at the central
//! section, end of construction and after impoundment), the crest settlement (the top of
//! `fig07_dam_displacement.csv`), the open and slipping interface points and the Newton counts
//! (`summary.json`) are kept in `tests/goldens/seed_coarse_<model>.json` with their provenance
//! (commit, command, date, reason) and compared with a fresh run. A change that moves them
//! fails here; its author regenerates the goldens and states why.
//!
//! **Ranks.** The three scenes run on 2 ranks; the GP-interface scene (the main job's) also on
//! 1 rank. The 1-rank runs of the other two are in the slow lane
//! (`cargo test --release --test goldens -- --ignored`): with `linear_solver: canonical_lu` the
//! seed scenes give the same results bit for bit at any rank count (`cfrd::verification`), so
//! the one 1-rank run guards that property here and the others would repeat it.
//!
//! **Tolerance.** Real numbers agree when |run − golden| ≤ 1e-6 · the largest magnitude of the
//! same quantity in the golden (a column of the slab table, the crest settlement of both
//! states), as `cfrd compare` measures. The runs are deterministic and rank-count independent
//! bit for bit, so on this build any difference is a change; 1e-6 leaves room for the last bits
//! a different compiler or libm may move, and is far below what a physical change moves: the
//! GP-interface scene with the slab's Young's modulus 1 % higher (a scratch run at commit
//! cc028bd) moved the slab stresses by 5.2e-3, the slab deflection by 3.8e-4 and the crest
//! settlement by 5.2e-4 of their magnitudes, the Newton iterations by one and the open and
//! slipping interface points by 1 and 3, and fails the comparison on each of them
//! (`the_comparison_fails_on_a_moved_value_and_names_it` checks the comparison itself).
//! **BLAS kernels.** The last bits do depend on OpenBLAS's kernels (the GMRES sums with lagged
//! factors), and the GP rockfill's loading path carries them far: on a virtual CPU that
//! OpenBLAS did not recognise, its generic `Prescott` kernels moved the slab stresses by
//! 1.4e-3 and the Newton iterations of several steps. The goldens are made with its AVX2
//! kernels (`Haswell`; `Zen` gives the same bits, the AVX-512 `SkylakeX` others), which
//! `ci/env.sh` selects on any CPU with AVX2 and FMA (`OPENBLAS_CORETYPE`).
//! Counts (Newton iterations per step, steps, cut-backs, open and slipping interface points)
//! must be equal: a count that moves is a changed path. Iteration counts are fragile
//! goldens (style guide G.8); they are here because the issue asks for them, and a change of
//! the solver that moves them is exactly what a reviewer should see.
//!
//! **Regenerating.** Run the 2-rank tests with the reason in the environment; they rewrite the
//! three files from their runs, with the current commit, command and date:
//!
//! ```sh
//! CFRD_UPDATE_GOLDENS=1 CFRD_GOLDEN_REASON="why the results moved" \
//!     cargo test --release --test goldens -- 2_ranks
//! cargo test --release --test goldens        # then check both rank counts against them
//! ```
//!
//! Commit the goldens with the change that moved them and say why in the commit message.

mod common;
use common::*;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// Largest accepted difference of a real number, relative to its quantity's magnitude.
const RELATIVE_TOLERANCE: f64 = 1e-6;

/// Where a golden came from.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
struct Provenance {
    /// Commit of the build that made the run (`+ uncommitted changes` when the tree differed).
    commit: String,
    /// The command of the run.
    command: String,
    /// UTC date and time of the run.
    date: String,
    /// Why the golden was (re)made.
    reason: String,
}

/// One number per state of the dam (`end of construction`, `after impoundment`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
struct StateValue {
    state: String,
    value: f64,
}

/// One row of the slab table (seed Figs. 8 and 9).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
struct SlabRow {
    state: String,
    z_m: f64,
    sigma_slope_pa: f64,
    sigma_axis_pa: f64,
    deflection_m: f64,
}

/// Counts of the run summary.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
struct Counts {
    interface_points: u64,
    interface_open: u64,
    interface_slipping: u64,
    newton_iterations: u64,
    steps: u64,
    cutbacks: u64,
    newton_per_step: Vec<u64>,
}

/// A golden file: the values of one coarse seed run and where they came from.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
struct Golden {
    /// The scene, relative to the repository.
    scene: String,
    /// FNV-1a hash of the scene text (a changed scene explains changed values).
    scene_fnv1a: String,
    provenance: Provenance,
    /// The tolerance the test applies (documentation; the test uses its own constant).
    relative_tolerance: f64,
    /// Settlement of the crest centre, −u_z (m, downwards positive), per state.
    crest_settlement_m: Vec<StateValue>,
    counts: Counts,
    slab: Vec<SlabRow>,
}

fn repo() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn scene_path(model: &str) -> String {
    format!("inputs/scenes/seed_coarse_{model}.yaml")
}

fn golden_path(model: &str) -> PathBuf {
    repo().join(format!("tests/goldens/seed_coarse_{model}.json"))
}

/// The rows of a CSV table of a run (header skipped).
fn csv_rows(path: &Path) -> Vec<Vec<String>> {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    text.lines()
        .skip(1)
        .map(|l| l.split(',').map(str::to_string).collect())
        .collect()
}

fn number(s: &str) -> f64 {
    s.parse().unwrap_or_else(|_| panic!("'{s}' is not a number"))
}

/// The slab table of a run's `fig08_slab_stress.csv`.
fn slab_table(out: &Path) -> Vec<SlabRow> {
    csv_rows(&out.join("fig08_slab_stress.csv"))
        .iter()
        .map(|r| SlabRow {
            state: r[0].clone(),
            z_m: number(&r[1]),
            sigma_slope_pa: number(&r[2]),
            sigma_axis_pa: number(&r[3]),
            deflection_m: number(&r[4]),
        })
        .collect()
}

/// −u_z at the highest point of each state's crest vertical (`fig07_dam_displacement.csv`).
fn crest_settlement(out: &Path) -> Vec<StateValue> {
    let rows = csv_rows(&out.join("fig07_dam_displacement.csv"));
    let mut states: Vec<String> = rows.iter().map(|r| r[0].clone()).collect();
    states.dedup();
    states
        .into_iter()
        .map(|state| {
            let top = rows
                .iter()
                .filter(|r| r[0] == state)
                .max_by(|a, b| number(&a[1]).total_cmp(&number(&b[1])))
                .expect("a row per state");
            StateValue {
                value: -number(&top[3]),
                state,
            }
        })
        .collect()
}

/// The counts of a run's `summary.json`.
fn counts(out: &Path) -> Counts {
    let text = std::fs::read_to_string(out.join("summary.json")).expect("summary.json");
    let s: serde_json::Value = serde_json::from_str(&text).expect("summary is JSON");
    let n = |k: &str| s[k].as_u64().unwrap_or_else(|| panic!("summary has {k}"));
    Counts {
        interface_points: n("interface_points"),
        interface_open: n("interface_open"),
        interface_slipping: n("interface_slipping"),
        newton_iterations: n("newton_iterations"),
        steps: n("steps"),
        cutbacks: n("cutbacks"),
        newton_per_step: s["newton_per_step"]
            .as_array()
            .expect("newton_per_step")
            .iter()
            .map(|v| v.as_u64().expect("a count"))
            .collect(),
    }
}

fn git(args: &[&str]) -> String {
    let o = std::process::Command::new("git")
        .args(args)
        .current_dir(repo())
        .output()
        .expect("git runs");
    String::from_utf8_lossy(&o.stdout).trim().to_string()
}

/// The commit of this build's sources, marked when the sources differ from it.
fn commit() -> String {
    let head = git(&["rev-parse", "HEAD"]);
    let dirty = git(&[
        "status",
        "--porcelain",
        "--",
        "src",
        "partition",
        "inputs",
        "Cargo.toml",
        "Cargo.lock",
    ]);
    if dirty.is_empty() {
        head
    } else {
        format!("{head} + uncommitted changes")
    }
}

fn utc_now() -> String {
    let o = std::process::Command::new("date")
        .args(["-u", "+%Y-%m-%dT%H:%M:%SZ"])
        .output()
        .expect("date runs");
    String::from_utf8_lossy(&o.stdout).trim().to_string()
}

fn scene_hash(model: &str) -> String {
    let text = std::fs::read(repo().join(scene_path(model))).expect("scene");
    cfrd::scene::resolved::fnv1a(&text)
}

/// The coarse runs take the 2-core machine one at a time: the tests of a binary run in parallel
/// threads, and two coarse runs at once (3 or 4 ranks on 2 cores) went past mpirun's 300 s
/// limit on the loaded machine (measured: the GP and hyperbolic 2-rank runs were aborted while
/// the 1-rank run beside them took 136 s; alone they take 66-170 s).
static ONE_RUN_AT_A_TIME: std::sync::Mutex<()> = std::sync::Mutex::new(());

/// Runs the coarse seed scene of `model` on `np` ranks into a temporary directory and returns
/// the values a golden holds (provenance of this run).
fn run_and_extract(model: &str, np: usize) -> Golden {
    let dir = tempdir();
    let scene = repo().join(scene_path(model));
    let scene = scene.to_str().expect("UTF-8 path");
    let turn = ONE_RUN_AT_A_TIME.lock().unwrap_or_else(|e| e.into_inner());
    let t = std::time::Instant::now();
    let o = cfrd_mpi(np, dir.path(), &["run", scene, "-o", "out", "-q"]);
    drop(turn);
    assert!(o.status.success(), "{model} on {np} rank(s): {}", text(&o));
    println!("{model} on {np} rank(s): {:.1} s", t.elapsed().as_secs_f64());
    let out = dir.path().join("out");
    Golden {
        scene: scene_path(model),
        scene_fnv1a: scene_hash(model),
        provenance: Provenance {
            commit: commit(),
            command: format!(
                "mpirun -n {np} cfrd run {} -o out -q (tests/goldens.rs, release build)",
                scene_path(model)
            ),
            date: utc_now(),
            reason: std::env::var("CFRD_GOLDEN_REASON").unwrap_or_default(),
        },
        relative_tolerance: RELATIVE_TOLERANCE,
        crest_settlement_m: crest_settlement(&out),
        counts: counts(&out),
        slab: slab_table(&out),
    }
}

/// Checks `|a − g| ≤ tol · scale` for every pair; a line per difference found.
fn compare_numbers(what: &str, golden: &[f64], actual: &[f64], tol: f64, diffs: &mut Vec<String>) {
    if golden.len() != actual.len() {
        diffs.push(format!(
            "{what}: {} values, golden {}",
            actual.len(),
            golden.len()
        ));
        return;
    }
    let scale = golden.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    for (i, (g, a)) in golden.iter().zip(actual).enumerate() {
        let d = (a - g).abs();
        if d.is_nan() || d > tol * scale {
            diffs.push(format!(
                "{what}[{i}]: {a:e}, golden {g:e} (difference {:.2e} of the largest {scale:.4e})",
                d / scale
            ));
        }
    }
}

/// Every difference of `actual` from `golden` beyond the relative tolerance `tol` (reals) or
/// at all (counts, states, the scene); empty when they agree.
fn compare(golden: &Golden, actual: &Golden, tol: f64) -> Vec<String> {
    let mut diffs = Vec::new();
    if golden.scene_fnv1a != actual.scene_fnv1a {
        diffs.push(format!(
            "{}: the scene changed since the golden was made (hash {} → {})",
            golden.scene, golden.scene_fnv1a, actual.scene_fnv1a
        ));
    }
    if golden.counts != actual.counts {
        diffs.push(format!("counts: {:?}, golden {:?}", actual.counts, golden.counts));
    }
    let states = |rows: &[SlabRow]| rows.iter().map(|r| r.state.clone()).collect::<Vec<_>>();
    let crest_states = |v: &[StateValue]| v.iter().map(|s| s.state.clone()).collect::<Vec<_>>();
    if states(&golden.slab) != states(&actual.slab)
        || crest_states(&golden.crest_settlement_m) != crest_states(&actual.crest_settlement_m)
    {
        diffs.push("the states of the slab or crest table differ from the golden's".into());
    }
    let crest = |g: &Golden| g.crest_settlement_m.iter().map(|s| s.value).collect::<Vec<_>>();
    compare_numbers(
        "crest settlement (m)",
        &crest(golden),
        &crest(actual),
        tol,
        &mut diffs,
    );
    type Column = (&'static str, fn(&SlabRow) -> f64);
    let columns: [Column; 4] = [
        ("slab z (m)", |r| r.z_m),
        ("slab sigma_s (Pa)", |r| r.sigma_slope_pa),
        ("slab sigma_a (Pa)", |r| r.sigma_axis_pa),
        ("slab deflection (m)", |r| r.deflection_m),
    ];
    for (what, f) in columns {
        let (g, a): (Vec<f64>, Vec<f64>) = (
            golden.slab.iter().map(f).collect(),
            actual.slab.iter().map(f).collect(),
        );
        compare_numbers(what, &g, &a, tol, &mut diffs);
    }
    diffs
}

fn read_golden(model: &str) -> Golden {
    let path = golden_path(model);
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| {
        panic!(
            "{}: {e}; make it with CFRD_UPDATE_GOLDENS=1 (see tests/goldens.rs)",
            path.display()
        )
    });
    serde_json::from_str(&text).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// Writes the golden of `model` (through a temporary file, so a reader never sees half of it).
fn write_golden(model: &str, g: &Golden) {
    assert!(
        !g.provenance.reason.trim().is_empty(),
        "state why the goldens change: CFRD_GOLDEN_REASON=\"...\""
    );
    let path = golden_path(model);
    std::fs::create_dir_all(path.parent().expect("tests/goldens")).expect("mkdir");
    let tmp = path.with_extension("json.tmp");
    let text = serde_json::to_string_pretty(g).expect("golden serializes") + "\n";
    std::fs::write(&tmp, text).expect("write golden");
    std::fs::rename(&tmp, &path).expect("rename golden");
    println!("{}: rewritten ({})", path.display(), g.provenance.reason);
}

/// Runs `model` on `np` ranks and checks it against its golden; with `CFRD_UPDATE_GOLDENS=1`
/// (2 ranks only) rewrites the golden instead.
fn check(model: &str, np: usize) {
    let actual = run_and_extract(model, np);
    if np == 2 && std::env::var("CFRD_UPDATE_GOLDENS").is_ok_and(|v| v == "1") {
        write_golden(model, &actual);
        return;
    }
    let golden = read_golden(model);
    let diffs = compare(&golden, &actual, RELATIVE_TOLERANCE);
    println!(
        "{model} on {np} rank(s): crest settlement {:?} m, counts {} Newton / {} steps / {} cut-backs, \
         interface {} open {} slipping of {}; golden of {} ({}): {} difference(s)",
        actual
            .crest_settlement_m
            .iter()
            .map(|s| s.value)
            .collect::<Vec<_>>(),
        actual.counts.newton_iterations,
        actual.counts.steps,
        actual.counts.cutbacks,
        actual.counts.interface_open,
        actual.counts.interface_slipping,
        actual.counts.interface_points,
        golden.provenance.commit,
        golden.provenance.date,
        diffs.len()
    );
    assert!(
        diffs.is_empty(),
        "{model} on {np} rank(s) differs from {} (tolerance {RELATIVE_TOLERANCE:e} relative):\n{}\n\
         If the change is intended, regenerate the goldens with a reason (see tests/goldens.rs).",
        golden_path(model).display(),
        diffs.join("\n")
    );
}

#[test]
fn seed_coarse_gp_interface_2_ranks() {
    check("gp_interface", 2);
}

#[test]
fn seed_coarse_hyperbolic_2_ranks() {
    check("hyperbolic", 2);
}

#[test]
fn seed_coarse_mohr_coulomb_2_ranks() {
    check("mohr_coulomb", 2);
}

#[test]
fn seed_coarse_gp_interface_1_rank() {
    check("gp_interface", 1);
}

#[test]
#[ignore = "slow lane: repeats the rank-count independence the GP-interface 1-rank run checks"]
fn seed_coarse_hyperbolic_1_rank() {
    check("hyperbolic", 1);
}

#[test]
#[ignore = "slow lane: repeats the rank-count independence the GP-interface 1-rank run checks"]
fn seed_coarse_mohr_coulomb_1_rank() {
    check("mohr_coulomb", 1);
}

/// The comparison itself, on the committed GP-interface golden: it agrees with itself, a slab
/// stress moved by 10× the tolerance or a Newton count moved by one fails and is named, a
/// move of a tenth of the tolerance passes, and a changed scene is named.
#[test]
fn the_comparison_fails_on_a_moved_value_and_names_it() {
    let golden = read_golden("gp_interface");
    assert!(compare(&golden, &golden, RELATIVE_TOLERANCE).is_empty());
    let scale = golden
        .slab
        .iter()
        .fold(0.0f64, |m, r| m.max(r.sigma_slope_pa.abs()));
    let mut moved = golden.clone();
    moved.slab[3].sigma_slope_pa += 10.0 * RELATIVE_TOLERANCE * scale;
    let diffs = compare(&golden, &moved, RELATIVE_TOLERANCE);
    assert_eq!(diffs.len(), 1, "{diffs:?}");
    assert!(diffs[0].starts_with("slab sigma_s (Pa)[3]"), "{diffs:?}");
    let mut within = golden.clone();
    within.slab[3].sigma_slope_pa += 0.1 * RELATIVE_TOLERANCE * scale;
    assert!(compare(&golden, &within, RELATIVE_TOLERANCE).is_empty());
    let mut newton = golden.clone();
    newton.counts.newton_per_step[0] += 1;
    let diffs = compare(&golden, &newton, RELATIVE_TOLERANCE);
    assert!(diffs.len() == 1 && diffs[0].starts_with("counts"), "{diffs:?}");
    let mut nan = golden.clone();
    nan.crest_settlement_m[1].value = f64::NAN;
    let diffs = compare(&golden, &nan, RELATIVE_TOLERANCE);
    assert!(
        diffs.len() == 1 && diffs[0].starts_with("crest settlement"),
        "{diffs:?}"
    );
    let mut scene = golden.clone();
    scene.scene_fnv1a = "0".repeat(16);
    assert!(compare(&golden, &scene, RELATIVE_TOLERANCE)[0].contains("the scene changed"));
}
