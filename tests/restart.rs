//! Checkpoint and exact restart of staged static runs (issue 4, acceptance 3): a 2-rank run of a
//! generalized-plasticity rockfill column built in 4 layers is stopped (or killed) after a stage
//! and restarted from its last checkpoint; the final displacements and stresses are bitwise
//! those of the uninterrupted run. A restart on 1 rank of a 2-rank checkpoint agrees to the
//! solver tolerances with the iterative solver, and bitwise with the canonical LU. Checkpoints of another scene, truncated files and results files are
//! refused with an input error (exit 2) that names the file.

mod common;
use common::*;
use std::path::Path;
use std::time::Instant;

const STAGES: usize = 4;

/// A 10 × 10 × 40 m rockfill column (2 × 2 × 8 hexahedra, 4 layers), each layer placed by its
/// own stage under gravity in `steps` load steps, with a surcharge on the last stage.
fn scene(density: f64, steps: u32) -> String {
    let mut s = format!(
        "name: gp-column-restart
units: SI
mesh:
  box: {{ size: [10.0, 10.0, 40.0], divisions: [2, 2, 8], layers: {STAGES} }}
materials:
  fill: {{ model: rockfill_gp, density: {density:.1} }}
blocks:
"
    );
    for k in 1..=STAGES {
        s += &format!("  layer_{k}: {{ material: fill }}\n");
    }
    s += &format!(
        "{CONFINED_COLUMN_BOUNDARY}loads:
  gravity: {{ g: [0.0, 0.0, -9.81] }}
solver: {{ load_steps: {steps} }}
stages:
"
    );
    for k in 1..=STAGES {
        s += &format!("  - {{ name: fill_{k}, activate: [layer_{k}] }}\n");
    }
    s
}

/// The fields compared between runs.
const FIELDS: [&str; 4] = ["displacement", "reaction", "stress", "strain"];

fn summary(dir: &Path) -> serde_json::Value {
    let text = std::fs::read_to_string(dir.join("summary.json")).expect("summary");
    serde_json::from_str(&text).expect("json")
}

fn stages_done(checkpoint: &Path) -> u64 {
    let f = hdf5::File::open(checkpoint).expect("open checkpoint");
    f.group("checkpoint")
        .and_then(|g| g.attr("stages_done"))
        .and_then(|a| a.read_scalar::<u64>())
        .expect("stages_done")
}

/// Number of bit-different values and the largest absolute difference.
fn compare(a: &[f64], b: &[f64]) -> (usize, f64) {
    assert_eq!(a.len(), b.len());
    let differing = a
        .iter()
        .zip(b)
        .filter(|(x, y)| x.to_bits() != y.to_bits())
        .count();
    let max = a.iter().zip(b).map(|(x, y)| (x - y).abs()).fold(0.0, f64::max);
    (differing, max)
}

/// Asserts that every field of every step of the restarted run is bitwise the uninterrupted
/// run's step of the same stage, and that it holds the stages after the first `missing` ones:
/// every stage (`missing` = 0) when the results beside its checkpoint were continued, those
/// after the checkpoint when there were none (a checkpoint copied elsewhere).
fn assert_bitwise(full: &Path, restarted: &Path, missing: usize) {
    let steps = |p: &Path| {
        hdf5::File::open(p)
            .unwrap()
            .group("steps")
            .unwrap()
            .member_names()
            .unwrap()
            .len()
    };
    assert_eq!(
        steps(full),
        steps(restarted) + missing,
        "the steps of the two runs"
    );
    for stage in missing + 1..=STAGES {
        for field in FIELDS {
            let a = read_f64(full, &format!("/steps/{stage:06}/{field}"));
            let b = read_f64(restarted, &format!("/steps/{:06}/{field}", stage - missing));
            let (differing, max) = compare(&a, &b);
            println!(
                "stage {stage} {field}: {differing} of {} values differ, max |Δ| = {max:.3e}",
                a.len()
            );
            assert_eq!(
                differing, 0,
                "stage {stage} {field}: not bitwise equal (max |Δ| {max:e})"
            );
        }
    }
    let u = read_f64(&restarted.with_file_name("checkpoint.h5"), "/checkpoint/u");
    let u_full = read_f64(&full.with_file_name("checkpoint.h5"), "/checkpoint/u");
    assert_eq!(compare(&u, &u_full).0, 0, "final checkpoint displacements");
}

fn run_ok(np: usize, dir: &Path, args: &[&str]) {
    let o = cfrd_mpi(np, dir, args);
    assert!(o.status.success(), "{args:?}: {}", text(&o));
}

/// The column scene run uninterrupted on 2 ranks (`full/`) and stopped after stage 2 (`part/`).
fn full_and_stopped_after_stage_two() -> tempfile::TempDir {
    full_and_stopped_with(&scene(2150.0, 2))
}

/// [`full_and_stopped_after_stage_two`] for the scene text `yaml`.
fn full_and_stopped_with(yaml: &str) -> tempfile::TempDir {
    let dir = tempdir();
    let d = dir.path();
    std::fs::write(d.join("col.yaml"), yaml).unwrap();
    run_ok(2, d, &["run", "col.yaml", "-o", "full", "-q"]);
    run_ok(
        2,
        d,
        &["run", "col.yaml", "-o", "part", "-q", "--stop-after-stage", "2"],
    );
    dir
}

#[test]
fn restart_after_stage_two_is_bitwise_exact() {
    let dir = full_and_stopped_after_stage_two();
    let d = dir.path();
    let ckpt = d.join("part/checkpoint.h5");
    assert_eq!(stages_done(&ckpt), 2);
    let size = std::fs::metadata(&ckpt).unwrap().len();
    println!(
        "checkpoint: {size} bytes, written in {:.4} s (2 checkpoints)",
        summary(&d.join("part"))["checkpoint_seconds"].as_f64().unwrap()
    );
    std::fs::copy(&ckpt, d.join("stage2.h5")).unwrap();
    let o = cfrd_mpi(2, d, &["run", "col.yaml", "-o", "rest", "--restart", "stage2.h5"]);
    assert!(o.status.success(), "{}", text(&o));
    assert!(
        text(&o).contains("restarted from stage2.h5 after stage 2 'fill_2'"),
        "{}",
        text(&o)
    );
    // no terminal: a progress line per converged load step (at least 2 per stage, one of them
    // at the stage's end)
    let lines = |prefix: &str| text(&o).lines().filter(|l| l.starts_with(prefix)).count();
    assert!(lines("  λ = ") >= 2 * (STAGES - 2), "{}", text(&o));
    assert_eq!(lines("  λ = 1.000 after"), STAGES - 2, "{}", text(&o));
    // a checkpoint copied away from its results: the restart says so, and its results hold
    // its own stages only
    assert!(
        text(&o).contains("no results beside the checkpoint"),
        "{}",
        text(&o)
    );
    assert_bitwise(&d.join("full/results.h5"), &d.join("rest/results.h5"), 2);
    // the restarted run holds the later stages only: `cfrd compare` names the steps the full
    // run holds beyond them and fails, and with `--common` it compares the common ones,
    // matched by stage and time, and says how many
    let o = cfrd(d, &["compare", "full", "rest", "--tolerance", "0"]);
    assert_eq!(o.status.code(), Some(1), "{}", text(&o));
    for stage in 1..=2 {
        let missing = format!("step {stage:06} (fill_{stage}) only in full/results.h5");
        assert!(text(&o).contains(&missing), "no '{missing}' in\n{}", text(&o));
    }
    let o = cfrd(d, &["compare", "full", "rest", "--tolerance", "0", "--common"]);
    assert!(o.status.success(), "{}", text(&o));
    let out = text(&o);
    let compared = format!("compared {} step(s) held by both runs", STAGES - 2);
    assert!(out.contains(&compared), "no '{compared}' in\n{out}");
    for stage in 3..=STAGES {
        let row = format!("| {stage:06} = {:06} (fill_{stage}) | displacement |", stage - 2);
        assert!(out.contains(&row), "no row '{row}' in\n{out}");
    }
    assert!(out.contains("largest relative difference: 0.000e0"), "{out}");
    // the restarted results hold the remaining stages, at their stage times
    let steps: Vec<_> = layout(&d.join("rest/results.h5"))
        .into_iter()
        .filter(|(n, _)| n.ends_with("/displacement"))
        .collect();
    assert_eq!(steps.len(), STAGES - 2, "{steps:?}");
    let f = hdf5::File::open(d.join("rest/results.h5")).unwrap();
    let time: f64 = f
        .group("steps/000001")
        .unwrap()
        .attr("time")
        .unwrap()
        .read_scalar()
        .unwrap();
    assert_eq!(time, 3.0);
    // the counters continue from the checkpoint: the same totals as the uninterrupted run
    let (s_full, s_rest) = (summary(&d.join("full")), summary(&d.join("rest")));
    assert_eq!(s_rest["restarted_after_stage"], 2);
    for key in ["steps", "newton_iterations", "ksp_iterations", "newton_per_step"] {
        assert_eq!(s_full[key], s_rest[key], "{key}");
    }
    assert!(s_full.get("restarted_after_stage").is_none());
    // the stopped part says so (scripts/run_in_parts.sh continues it); the finished runs do not
    assert_eq!(summary(&d.join("part"))["stopped_after_stage"], 2);
    assert!(s_full.get("stopped_after_stage").is_none());
    assert!(s_rest.get("stopped_after_stage").is_none());
    // so do the stage times: the restarted run lists the stages of both parts
    let stage_times = |s: &serde_json::Value| -> Vec<(String, f64)> {
        s["stage_seconds"]
            .as_array()
            .expect("stage_seconds")
            .iter()
            .map(|e| {
                (
                    e["stage"].as_str().unwrap().to_string(),
                    e["seconds"].as_f64().unwrap(),
                )
            })
            .collect()
    };
    let (t_full, t_rest) = (stage_times(&s_full), stage_times(&s_rest));
    let names = |t: &[(String, f64)]| t.iter().map(|(n, _)| n.clone()).collect::<Vec<_>>();
    assert_eq!(
        names(&t_full),
        (1..=STAGES).map(|k| format!("fill_{k}")).collect::<Vec<_>>()
    );
    assert_eq!(names(&t_rest), names(&t_full));
    assert!(t_rest.iter().all(|(_, s)| *s > 0.0), "{t_rest:?}");
}

/// Runs `col.yaml` on 2 ranks into `killed/` and kills it as soon as its first checkpoint
/// appears; returns the exit status and the start time.
fn run_until_first_checkpoint(d: &Path) -> (std::process::ExitStatus, Instant) {
    let args = ["run", "col.yaml", "-o", "killed", "-q"];
    let (mut child, t0) = cfrd_mpi_until(2, d, &args, "killed/checkpoint.h5");
    (kill_tree(&mut child), t0)
}

#[test]
fn a_killed_run_restarts_from_its_last_checkpoint() {
    let dir = tempdir();
    let d = dir.path();
    // more load steps per stage, so that the kill comes well before the end of the run
    std::fs::write(d.join("col.yaml"), scene(2150.0, 6)).unwrap();
    run_ok(2, d, &["run", "col.yaml", "-o", "full", "-q"]);
    let ckpt = d.join("killed/checkpoint.h5");
    let (status, t0) = run_until_first_checkpoint(d);
    let done = stages_done(&ckpt) as usize;
    println!(
        "killed after {:.2} s ({status}), checkpoint after stage {done}",
        t0.elapsed().as_secs_f64()
    );
    assert!(!status.success(), "the run was killed, not finished");
    assert!((1..STAGES).contains(&done), "checkpoint after stage {done}");
    // the killed run published the results of the stages before its checkpoint (and perhaps
    // of the next one, if killed between its results and its checkpoint), bitwise the full run's
    let published = layout(&d.join("killed/results.h5"))
        .into_iter()
        .filter(|(n, _)| n.ends_with("/displacement"))
        .count();
    assert!(
        published == done || published == done + 1,
        "{published} published, {done} done"
    );
    for stage in 1..=published {
        for field in FIELDS {
            let name = format!("/steps/{stage:06}/{field}");
            let a = read_f64(&d.join("full/results.h5"), &name);
            let b = read_f64(&d.join("killed/results.h5"), &name);
            assert_eq!(compare(&a, &b).0, 0, "{name}");
        }
    }
    assert!(d.join("killed/results.xdmf").exists());
    run_ok(
        2,
        d,
        &[
            "run",
            "col.yaml",
            "-o",
            "killed",
            "-q",
            "--overwrite",
            "--restart",
            "killed/checkpoint.h5",
        ],
    );
    assert_bitwise(&d.join("full/results.h5"), &d.join("killed/results.h5"), 0);
}

/// A step checkpoint (`output.checkpoint: step`, written after every converged load step): a
/// 2-rank run killed as soon as its first checkpoint appears (inside the first stage's 6 load
/// steps) and restarted from it (with `--monitor`) continues inside that stage and ends bitwise where the
/// uninterrupted run with step checkpoints ends, with the same solver counters. A step
/// checkpoint has the stage's load path; a stage checkpoint has none.
#[test]
fn a_run_killed_inside_a_stage_restarts_from_its_step_checkpoint() {
    let dir = tempdir();
    let d = dir.path();
    let yaml = scene(2150.0, 6).replace("units: SI", "units: SI\noutput: { checkpoint: step }");
    assert!(yaml.contains("checkpoint: step"));
    std::fs::write(d.join("col.yaml"), yaml).unwrap();
    run_ok(2, d, &["run", "col.yaml", "-o", "full", "-q"]);
    let ckpt = d.join("killed/checkpoint.h5");
    let (status, t0) = run_until_first_checkpoint(d);
    assert!(!status.success(), "the run was killed, not finished");
    let done = stages_done(&ckpt) as usize;
    let path = read_f64(&ckpt, "/checkpoint/load_path");
    println!(
        "killed after {:.2} s, checkpoint in stage {} at λ = {}",
        t0.elapsed().as_secs_f64(),
        done + 1,
        path[0]
    );
    assert_eq!(done, 0, "the first checkpoint is inside the first stage");
    assert!(path[0] > 0.0 && path[0] < 1.0, "{path:?}");
    let o = cfrd_mpi(
        2,
        d,
        &[
            "run",
            "col.yaml",
            "-o",
            "rest",
            "--restart",
            "killed/checkpoint.h5",
            "--monitor",
        ],
    );
    assert!(o.status.success(), "{}", text(&o));
    let expected = format!("in stage 1 'fill_1' at λ = {:.3}", path[0]);
    assert!(text(&o).contains(&expected), "{}", text(&o));
    // `--monitor` prints the Newton iterations and leaves the scene's hash (the restart is
    // accepted) and the numbers (checked below) as they are
    assert!(
        text(&o).contains("iteration 1: relative residual"),
        "{}",
        text(&o)
    );
    assert_bitwise(&d.join("full/results.h5"), &d.join("rest/results.h5"), 0);
    let (s_full, s_rest) = (summary(&d.join("full")), summary(&d.join("rest")));
    for key in [
        "steps",
        "newton_iterations",
        "ksp_iterations",
        "newton_per_step",
        "cutbacks",
    ] {
        assert_eq!(s_full[key], s_rest[key], "{key}");
    }
    // the last checkpoint of a finished run is its last stage's: no load path
    let f = hdf5::File::open(d.join("full/checkpoint.h5")).unwrap();
    assert!(f.dataset("checkpoint/load_path").is_err());
    // `--checkpoint step` on the scene without the key does the same, bit for bit
    std::fs::write(d.join("plain.yaml"), scene(2150.0, 6)).unwrap();
    run_ok(
        2,
        d,
        &["run", "plain.yaml", "-o", "over", "-q", "--checkpoint", "step"],
    );
    assert_bitwise(&d.join("full/results.h5"), &d.join("over/results.h5"), 0);
}

/// Restarts the stopped run of [`full_and_stopped_after_stage_two`] on 1 rank into `one/`.
fn restart_on_one_rank(d: &Path) {
    run_ok(
        1,
        d,
        &[
            "run",
            "col.yaml",
            "-o",
            "one",
            "-q",
            "--restart",
            "part/checkpoint.h5",
        ],
    );
}

#[test]
fn restart_on_one_rank_from_a_two_rank_checkpoint() {
    let dir = full_and_stopped_after_stage_two();
    let d = dir.path();
    restart_on_one_rank(d);
    // the parallel sums are ordered differently on 1 rank; both runs converge Newton to a
    // relative residual of 1e-8 (the default newton_tol), so they agree to that fraction
    for field in ["displacement", "stress"] {
        let a = read_f64(&d.join("full/results.h5"), &format!("/steps/{STAGES:06}/{field}"));
        // the restart continued the 2-rank results beside its checkpoint: the same numbering
        let b = read_f64(&d.join("one/results.h5"), &format!("/steps/{STAGES:06}/{field}"));
        let scale = a.iter().map(|v| v.abs()).fold(0.0, f64::max);
        let (_, max) = compare(&a, &b);
        println!("1-rank restart {field}: max |Δ| = {max:.3e} of max |value| {scale:.3e}");
        assert!(max <= 1e-8 * scale, "{field}: max |Δ| {max:e} of {scale:e}");
    }
}

/// With the canonical LU (`linear_solver: canonical_lu`) the results do not depend on the rank
/// count, so a 1-rank restart of a 2-rank checkpoint ends bitwise where the uninterrupted 2-rank
/// run ends.
#[test]
fn canonical_restart_on_one_rank_is_bitwise_exact() {
    let yaml = scene(2150.0, 2).replace(
        "solver: { load_steps: 2 }",
        "solver: { load_steps: 2, linear_solver: canonical_lu }",
    );
    assert!(yaml.contains("canonical_lu"));
    let dir = full_and_stopped_with(&yaml);
    let d = dir.path();
    restart_on_one_rank(d);
    assert_bitwise(&d.join("full/results.h5"), &d.join("one/results.h5"), 0);
}

#[test]
fn restart_refuses_other_scenes_and_bad_files() {
    let dir = tempdir();
    let d = dir.path();
    std::fs::write(d.join("col.yaml"), scene(2150.0, 1)).unwrap();
    std::fs::write(d.join("other.yaml"), scene(2100.0, 1)).unwrap();
    run_ok(
        2,
        d,
        &["run", "col.yaml", "-o", "part", "-q", "--stop-after-stage", "1"],
    );
    let bytes = std::fs::read(d.join("part/checkpoint.h5")).unwrap();
    std::fs::write(d.join("truncated.h5"), &bytes[..bytes.len() / 2]).unwrap();
    let cases = [
        ("other.yaml", "part/checkpoint.h5", "written for another scene"),
        ("col.yaml", "truncated.h5", "truncated.h5"),
        ("col.yaml", "part/results.h5", "not a cfrd checkpoint"),
        ("col.yaml", "missing.h5", "missing.h5"),
    ];
    for (scene, file, expected) in cases {
        let o = cfrd_mpi(2, d, &["run", scene, "-o", "bad", "-q", "--restart", file]);
        let t = text(&o);
        assert_eq!(o.status.code(), Some(2), "{scene} {file}: {t}");
        assert!(t.contains(&format!("restart from {file}")), "{file}: {t}");
        assert!(t.contains(expected), "{file}: {t}");
        assert!(!t.contains("panicked"), "{file}: {t}");
    }
    // no checkpoint with `output.checkpoint: none`
    let none = scene(2150.0, 1).replace("units: SI", "units: SI\noutput: { checkpoint: none }");
    std::fs::write(d.join("none.yaml"), none).unwrap();
    run_ok(2, d, &["run", "none.yaml", "-o", "none", "-q"]);
    assert!(d.join("none/results.h5").exists());
    assert!(!d.join("none/checkpoint.h5").exists());
    // --stop-after-stage: only a stage this run runs, and only with checkpoints
    let cases: [(&str, &[&str], &str); 5] = [
        (
            "col.yaml",
            &["--stop-after-stage", "5"],
            "not one of the stages this run runs (1 to 4)",
        ),
        (
            "col.yaml",
            &["--stop-after-stage", "0"],
            "not one of the stages this run runs (1 to 4)",
        ),
        (
            "col.yaml",
            &["--stop-after-stage", "1", "--restart", "part/checkpoint.h5"],
            "not one of the stages this run runs (2 to 4)",
        ),
        (
            "col.yaml",
            &["--stop-after-stage", "+0", "--restart", "part/checkpoint.h5"],
            "--stop-after-stage 1: not one of the stages this run runs (2 to 4)",
        ),
        (
            "none.yaml",
            &["--stop-after-stage", "2"],
            "the run writes no checkpoints",
        ),
    ];
    for (scene, extra, expected) in cases {
        let mut args = vec!["run", scene, "-o", "bad_stop", "-q"];
        args.extend_from_slice(extra);
        let o = cfrd_mpi(2, d, &args);
        let t = text(&o);
        assert_eq!(o.status.code(), Some(2), "{extra:?}: {t}");
        assert!(t.contains(expected), "{extra:?}: {t}");
        assert!(!t.contains("panicked"), "{extra:?}: {t}");
    }
}

/// The column of [`scene`] with a 3-s quake after its stages (300 time steps, fields every 10):
/// under the default checkpoints it writes a step checkpoint every 100 time steps.
fn quake_scene() -> String {
    let mut s = scene(2150.0, 2);
    s += "  - name: shake\n    dynamic: { record: record.csv, output_every: 10, hht_alpha: -0.1, \
          damping: { ratio: 0.05, frequencies: [1.0, 5.0] } }\n";
    s
}

/// Where a checkpoint left the run: completed stages and, inside the stage in progress, its
/// converged steps (`None` for a stage checkpoint).
fn checkpoint_point(ckpt: &Path) -> Option<(u64, Option<f64>)> {
    let f = hdf5::File::open(ckpt).ok()?;
    let done = f
        .group("checkpoint")
        .ok()?
        .attr("stages_done")
        .ok()?
        .read_scalar::<u64>()
        .ok()?;
    let steps = match f.dataset("checkpoint/load_path") {
        Ok(ds) => Some(ds.read_raw::<f64>().ok()?[3]),
        Err(_) => None,
    };
    Some((done, steps))
}

/// A point of a run, as [`checkpoint_point`] gives it.
type Point = (u64, Option<f64>);

/// Starts `col.yaml` on 2 ranks into `out` and SIGKILLs one of its ranks as soon as it has
/// written a checkpoint that `reached` accepts (checked at every new checkpoint file); returns
/// that checkpoint's point once the run has ended.
fn kill_one_rank_at(d: &Path, out: &str, reached: &dyn Fn(Point) -> bool) -> Point {
    let mut child = cfrd_mpi_spawn(2, d, &["run", "col.yaml", "-o", out, "-q"]);
    let ckpt = d.join(out).join("checkpoint.h5");
    let t0 = Instant::now();
    let mut last = None;
    let point = loop {
        assert!(child.try_wait().unwrap().is_none(), "{out}: the run ended first");
        assert!(
            t0.elapsed().as_secs() < 240,
            "{out}: no such checkpoint after 240 s"
        );
        let inode = std::fs::metadata(&ckpt)
            .ok()
            .map(|m| std::os::unix::fs::MetadataExt::ino(&m));
        if inode.is_some() && inode != last {
            last = inode;
            if let Some(p) = checkpoint_point(&ckpt).filter(|&p| reached(p)) {
                break p;
            }
        }
        std::thread::sleep(std::time::Duration::from_millis(1));
    };
    let rank = *process_tree(child.id()).last().expect("a rank");
    let killed = std::process::Command::new("kill")
        .args(["-KILL", &rank.to_string()])
        .status();
    assert!(killed.unwrap().success());
    assert!(
        !child.wait().unwrap().success(),
        "{out}: the run was killed, not finished"
    );
    point
}

/// A 2-rank quake killed (SIGKILL of one rank) after a stage checkpoint of its static stages
/// and after its step checkpoints at 100 and 200 time steps, each restarted into its own directory:
/// every restarted run holds the steps of the uninterrupted run, numbered and timed alike, and
/// `cfrd compare --tolerance 0` (without `--common`) finds them bitwise equal; the killed runs'
/// own results, which lack the steps after their checkpoints, fail the comparison (exit 1).
#[test]
fn a_quake_killed_anywhere_restarts_to_the_same_steps_bit_for_bit() {
    let dir = tempdir();
    let d = dir.path();
    std::fs::write(d.join("col.yaml"), quake_scene()).unwrap();
    let mut csv = String::from("t,a_x,a_y,a_z\n");
    for i in 0..=300 {
        let t = f64::from(i) * 0.01;
        let a = 2.0 * (2.0 * std::f64::consts::PI * 2.0 * t).sin();
        csv += &format!("{t},{a},0,{}\n", 0.5 * a);
    }
    std::fs::write(d.join("record.csv"), csv).unwrap();
    run_ok(2, d, &["run", "col.yaml", "-o", "full", "-q"]);
    let n_steps = |p: &str| {
        let f = hdf5::File::open(d.join(p).join("results.h5")).unwrap();
        f.group("steps").unwrap().member_names().unwrap().len()
    };
    // the 4 stages and the quake's fields every 10 of its 300 steps (its end among them)
    assert_eq!(n_steps("full"), STAGES + 30);
    let quake = STAGES as u64;
    let points: [(&str, &dyn Fn(Point) -> bool); 3] = [
        ("in the static stages", &|(done, steps)| {
            done < quake && steps.is_none()
        }),
        ("after 100 quake steps", &|(done, steps)| {
            done == quake && steps >= Some(100.0)
        }),
        ("after 200 quake steps", &|(done, steps)| {
            done == quake && steps >= Some(200.0)
        }),
    ];
    for (k, (where_, reached)) in points.into_iter().enumerate() {
        let (killed, rest) = (format!("killed_{k}"), format!("rest_{k}"));
        let point = kill_one_rank_at(d, &killed, reached);
        println!("{killed}: killed {where_}: checkpoint at {point:?}");
        let ckpt = d.join(&killed).join("checkpoint.h5");
        let restart = ckpt.to_str().unwrap().to_string();
        run_ok(
            2,
            d,
            &["run", "col.yaml", "-o", &rest, "-q", "--restart", &restart],
        );
        assert_eq!(n_steps(&rest), n_steps("full"), "{rest}");
        let o = cfrd(d, &["compare", "full", &rest, "--tolerance", "0"]);
        assert!(o.status.success(), "{rest}: {}", text(&o));
        assert!(
            text(&o).contains(&format!("compared {} step(s) held by both runs", n_steps("full"))),
            "{}",
            text(&o)
        );
        let o = cfrd(d, &["compare", "full", &killed]);
        assert_eq!(o.status.code(), Some(1), "{killed}: {}", text(&o));
    }
}

/// A restart into its own checkpoint's directory is refused without `--overwrite` (exit 2,
/// nothing there touched); with it the run continues the results in place and keeps the
/// stages before the checkpoint.
#[test]
fn a_restart_into_its_own_directory_needs_overwrite_and_keeps_the_earlier_results() {
    let dir = full_and_stopped_after_stage_two();
    let d = dir.path();
    let before = std::fs::read(d.join("part/results.h5")).unwrap();
    let args = [
        "run",
        "col.yaml",
        "-o",
        "part",
        "-q",
        "--restart",
        "part/checkpoint.h5",
    ];
    let o = cfrd_mpi(2, d, &args);
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(text(&o).contains("pass --overwrite"), "{}", text(&o));
    assert_eq!(std::fs::read(d.join("part/results.h5")).unwrap(), before);
    run_ok(2, d, &[&args[..], &["--overwrite"]].concat());
    assert_bitwise(&d.join("full/results.h5"), &d.join("part/results.h5"), 0);
}

/// A restart whose record or partition file changed since the checkpoint was written is
/// refused (exit 2, naming the scene key and the file); with `--accept-changed FILE` it goes
/// on, says so, and `summary.json` lists the file.
#[test]
fn a_changed_record_or_partition_is_refused_at_restart() {
    let dir = tempdir();
    let d = dir.path();
    std::fs::write(d.join("plain.yaml"), quake_scene()).unwrap();
    std::fs::write(d.join("record.csv"), "t,a_x,a_y,a_z\n0,0,0,0\n3,1,0,0\n").unwrap();
    let o = cfrd(d, &["partition", "plain.yaml", "-n", "2", "-o", "parts.json"]);
    assert!(o.status.success(), "{}", text(&o));
    let yaml = quake_scene().replace("units: SI\n", "units: SI\npartition: parts.json\n");
    std::fs::write(d.join("col.yaml"), &yaml).unwrap();
    run_ok(
        2,
        d,
        &["run", "col.yaml", "-o", "part", "-q", "--stop-after-stage", "2"],
    );
    let restart = [
        "run",
        "col.yaml",
        "-o",
        "rest",
        "--restart",
        "part/checkpoint.h5",
        "--stop-after-stage",
        "3",
    ];
    for (file, key) in [
        ("record.csv", "stages[4].dynamic.record"),
        ("parts.json", "partition"),
    ] {
        let original = std::fs::read(d.join(file)).unwrap();
        std::fs::write(d.join(file), [&original[..], b"\n"].concat()).unwrap();
        let o = cfrd_mpi(2, d, &restart);
        assert_eq!(o.status.code(), Some(2), "{file}: {}", text(&o));
        let named = format!("{key} ({file}): its content changed");
        assert!(
            text(&o).contains(&named) && text(&o).contains("--accept-changed"),
            "{file}: {}",
            text(&o)
        );
        std::fs::write(d.join(file), original).unwrap();
    }
    std::fs::write(d.join("record.csv"), "t,a_x,a_y,a_z\n0,0,0,0\n3,2,0,0\n").unwrap();
    let o = cfrd_mpi(
        2,
        d,
        &[&restart[..], &["--accept-changed", "record.csv"]].concat(),
    );
    assert!(o.status.success(), "{}", text(&o));
    assert!(
        text(&o).contains("going on with the changed input stages[4].dynamic.record"),
        "{}",
        text(&o)
    );
    let accepted = summary(&d.join("rest"))["accepted_changed_inputs"].clone();
    assert_eq!(accepted.as_array().map(Vec::len), Some(1), "{accepted}");
}
