//! Helpers for integration tests that run the `cfrd` binary, alone or under `mpirun`.
#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};

/// Path of the built `cfrd` binary.
pub fn cfrd_bin() -> PathBuf {
    PathBuf::from(env!("CARGO_BIN_EXE_cfrd"))
}

/// `mpirun -n np` as the tests start it, with a 300-s limit ([`cfrd::parallel::mpirun_command`]).
fn mpi_command(np: usize) -> Command {
    cfrd::parallel::mpirun_command(np, 300)
}

/// Runs `cfrd ARGS` under `mpirun -n np` in `dir`.
pub fn cfrd_mpi(np: usize, dir: &Path, args: &[&str]) -> Output {
    let mut cmd = mpi_command(np);
    cmd.arg(cfrd_bin()).args(args).current_dir(dir);
    cmd.output().expect("mpirun starts")
}

/// [`cfrd_mpi`] with extra environment variables (passed on to every rank).
pub fn cfrd_mpi_env(np: usize, dir: &Path, args: &[&str], env: &[(&str, &str)]) -> Output {
    let mut cmd = mpi_command(np);
    for (k, v) in env {
        cmd.env(k, v).args(["-x", k]);
    }
    cmd.arg(cfrd_bin()).args(args).current_dir(dir);
    cmd.output().expect("mpirun starts")
}

/// Starts `cfrd ARGS` under `mpirun -n np` in `dir` without waiting (output discarded).
pub fn cfrd_mpi_spawn(np: usize, dir: &Path, args: &[&str]) -> std::process::Child {
    let mut cmd = mpi_command(np);
    cmd.arg(cfrd_bin())
        .args(args)
        .current_dir(dir)
        .stdout(Stdio::null())
        .stderr(Stdio::null());
    cmd.spawn().expect("mpirun starts")
}

/// Starts `cfrd ARGS` under `mpirun -n np` in `dir` and waits until `file` (relative to `dir`)
/// exists; panics if the run ends first or after 120 s. Returns the run and its start time.
pub fn cfrd_mpi_until(
    np: usize,
    dir: &Path,
    args: &[&str],
    file: &str,
) -> (std::process::Child, std::time::Instant) {
    let mut child = cfrd_mpi_spawn(np, dir, args);
    let t0 = std::time::Instant::now();
    while !dir.join(file).exists() {
        assert!(
            child.try_wait().unwrap().is_none(),
            "the run ended before {file} appeared"
        );
        assert!(
            t0.elapsed() < std::time::Duration::from_secs(120),
            "no {file} after 120 s"
        );
        std::thread::sleep(std::time::Duration::from_millis(2));
    }
    (child, t0)
}

/// The process `pid` and all its descendants (from `/proc`), parents first.
pub fn process_tree(pid: u32) -> Vec<u32> {
    let mut parent_of = Vec::new();
    for entry in std::fs::read_dir("/proc").into_iter().flatten().flatten() {
        let Ok(p) = entry.file_name().to_string_lossy().parse::<u32>() else {
            continue;
        };
        let Ok(stat) = std::fs::read_to_string(entry.path().join("stat")) else {
            continue;
        };
        // "pid (comm) state ppid ...": the command may hold spaces, so split after ')'
        if let Some(ppid) = stat
            .rsplit_once(')')
            .and_then(|(_, rest)| rest.split_whitespace().nth(1))
            .and_then(|v| v.parse::<u32>().ok())
        {
            parent_of.push((p, ppid));
        }
    }
    let mut tree = vec![pid];
    let mut i = 0;
    while i < tree.len() {
        let parent = tree[i];
        tree.extend(parent_of.iter().filter(|&&(_, pp)| pp == parent).map(|&(p, _)| p));
        i += 1;
    }
    tree
}

/// Sends SIGKILL to `child` and all its descendants (the MPI ranks run in their own process
/// groups, so killing mpirun's group would not reach them), then reaps it.
pub fn kill_tree(child: &mut std::process::Child) -> std::process::ExitStatus {
    let tree = process_tree(child.id());
    // the ranks first, so that none is re-parented before it is found
    for pid in tree.iter().rev() {
        let _ = Command::new("kill")
            .args(["-KILL", &pid.to_string()])
            .stderr(Stdio::null())
            .status();
    }
    child.wait().expect("wait for mpirun")
}

/// Runs `cfrd ARGS` as a plain process (an MPI singleton) in `dir`.
pub fn cfrd(dir: &Path, args: &[&str]) -> Output {
    Command::new(cfrd_bin())
        .args(args)
        .current_dir(dir)
        .stdin(Stdio::null())
        .output()
        .expect("cfrd starts")
}

/// stdout + stderr as text.
pub fn text(o: &Output) -> String {
    format!(
        "{}{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    )
}

/// A fresh temporary directory.
pub fn tempdir() -> tempfile::TempDir {
    tempfile::tempdir().expect("tempdir")
}

/// Reads a whole f64 dataset of a results file (serial HDF5, no MPI needed).
pub fn read_f64(path: &Path, dataset: &str) -> Vec<f64> {
    let f = hdf5::File::open(path).expect("open results");
    f.dataset(dataset)
        .expect("dataset")
        .read_raw::<f64>()
        .expect("read")
}

/// Reads a whole i64 dataset of a results file.
pub fn read_i64(path: &Path, dataset: &str) -> Vec<i64> {
    let f = hdf5::File::open(path).expect("open results");
    f.dataset(dataset)
        .expect("dataset")
        .read_raw::<i64>()
        .expect("read")
}

/// Names of all datasets under a group, sorted, with their shapes.
pub fn layout(path: &Path) -> Vec<(String, Vec<usize>)> {
    let f = hdf5::File::open(path).expect("open results");
    let mut out = Vec::new();
    fn walk(g: &hdf5::Group, prefix: &str, out: &mut Vec<(String, Vec<usize>)>) {
        for name in g.member_names().expect("members") {
            let path = format!("{prefix}/{name}");
            if let Ok(ds) = g.dataset(&name) {
                out.push((path, ds.shape()));
            } else if let Ok(sub) = g.group(&name) {
                walk(&sub, &path, out);
            }
        }
    }
    walk(&f, "", &mut out);
    out.sort();
    out
}

/// Boundary of a laterally confined box column (oedometric conditions): base fixed, the four
/// sides on rollers. A complete `boundary:` section of a scene, ending with a newline.
pub const CONFINED_COLUMN_BOUNDARY: &str = "boundary:
  - { set: zmin, fix: [x, y, z] }
  - { set: xmin, fix: [x] }
  - { set: xmax, fix: [x] }
  - { set: ymin, fix: [y] }
  - { set: ymax, fix: [y] }
";

/// The mesh of [`small_dam`]: the generated seed-shaped dam at its smallest useful size.
pub const SMALL_DAM_MESH: &str = "{ fill_layers: 4, panel_width: 60.0, elements_per_panel: 1, rockfill_elements: 2, impoundment_stages: 2 }";

/// Elastic rockfill of [`small_dam`] (the tests' usual fill).
pub const ELASTIC_FILL: &str = "{ model: elastic, young: 3.0e8, poisson: 0.3, density: 2150.0 }";

/// The seed figures' outputs (Figs. 7–11) with the probe I-A, a last line for [`small_dam`].
pub const SEED_FIGURES: &str = "output: { profiles: { probes: [ { name: I-A, elevation: 2711.0 } ] } }";

/// The small generated CFRD (its whole schedule: fill, slab stages, impoundment) with the fill
/// material `fill`, the slab-cushion interface model `interface`, slab density `rho_slab`,
/// extra `mesh.cfrd` keys `mesh_extra` (", key: value"), solver settings `solver` and an extra
/// last line `tail` (YAML flow mappings).
pub fn small_dam(
    fill: &str,
    interface: &str,
    rho_slab: f64,
    mesh_extra: &str,
    solver: &str,
    tail: &str,
) -> String {
    let mesh = SMALL_DAM_MESH.replace(" }", &format!("{mesh_extra} }}"));
    format!(
        "name: cfrd-small
units: SI
mesh:
  cfrd: {mesh}
materials:
  fill: {fill}
  slab: {{ model: elastic, young: 25.5e9, poisson: 0.167, density: {rho_slab:.1} }}
  interface: {{ model: {interface} }}
  joint: {{ model: joint }}
blocks:
  'fill_*': {{ material: fill }}
  'slab_*': {{ material: slab }}
  'interface_*': {{ material: interface }}
  'joint_*': {{ material: joint }}
boundary:
  - {{ set: foundation, fix: [x, y, z] }}
  - {{ set: plinth, fix: [x, y, z] }}
loads:
  gravity: {{ g: [0.0, 0.0, -9.81] }}
solver: {solver}
{tail}
"
    )
}

/// The stage time of a step checkpoint inside a run's second stage (after one stage done),
/// `None` before it (or while the file is being replaced).
pub fn time_in_second_stage(ckpt: &Path) -> Option<f64> {
    let f = hdf5::File::open(ckpt).ok()?;
    let done: u64 = f
        .group("checkpoint")
        .ok()?
        .attr("stages_done")
        .ok()?
        .read_scalar()
        .ok()?;
    let path = f.dataset("checkpoint/load_path").ok()?.read_raw::<f64>().ok()?;
    (done == 1).then(|| path[0])
}

/// The time reached in a dynamic stage by the step checkpoint `ckpt` (`None` before there is
/// one).
pub fn time_in_dynamic_stage(ckpt: &Path) -> Option<f64> {
    let f = hdf5::File::open(ckpt).ok()?;
    f.dataset("checkpoint/velocity").ok()?;
    let path = f.dataset("checkpoint/load_path").ok()?.read_raw::<f64>().ok()?;
    path.first().copied()
}

/// Runs `scene` on 2 ranks in `dir` into `out` (restarting from `restart` if given) and kills
/// it once its step checkpoint is past `t_kill` s of its dynamic stage.
pub fn run_and_kill(dir: &Path, scene: &str, out: &str, restart: Option<&str>, t_kill: f64) {
    run_and_kill_with(dir, scene, out, restart, t_kill, &[]);
}

/// [`run_and_kill`] with the extra command-line arguments `extra`.
pub fn run_and_kill_with(
    dir: &Path,
    scene: &str,
    out: &str,
    restart: Option<&str>,
    t_kill: f64,
    extra: &[&str],
) {
    let mut args = vec!["run", scene, "-o", out, "-q"];
    args.extend(extra);
    if let Some(r) = restart {
        args.extend(["--restart", r]);
    }
    let mut child = cfrd_mpi_spawn(2, dir, &args);
    let ckpt = dir.join(out).join("checkpoint.h5");
    let t0 = std::time::Instant::now();
    while time_in_dynamic_stage(&ckpt).is_none_or(|t| t < t_kill) {
        assert!(
            child.try_wait().unwrap().is_none(),
            "{out}: the run ended before t = {t_kill} s"
        );
        assert!(
            t0.elapsed().as_secs() < 240,
            "{out}: no checkpoint past t = {t_kill} s"
        );
        std::thread::sleep(std::time::Duration::from_millis(5));
    }
    assert!(!kill_tree(&mut child).success(), "{out}: killed, not finished");
}

/// Restarts `scene` in `dir` on 2 ranks from `checkpoint` into `out` and asserts that its
/// results equal those of the uninterrupted run in `full` bit for bit (`cfrd compare
/// --tolerance 0`).
pub fn restart_matches_bitwise(dir: &Path, scene: &str, checkpoint: &str, out: &str, full: &str) {
    restart_matches_bitwise_with(dir, scene, checkpoint, out, full, &[]);
}

/// [`restart_matches_bitwise`] with the extra command-line arguments `extra` for the restart.
pub fn restart_matches_bitwise_with(
    dir: &Path,
    scene: &str,
    checkpoint: &str,
    out: &str,
    full: &str,
    extra: &[&str],
) {
    let mut args = vec!["run", scene, "-o", out, "-q", "--restart", checkpoint];
    args.extend(extra);
    let o = cfrd_mpi(2, dir, &args);
    assert!(o.status.success(), "{}", text(&o));
    let (a, b) = (format!("{full}/results.h5"), format!("{out}/results.h5"));
    // the restarted run holds the stages from its checkpoint on
    let o = cfrd(dir, &["compare", &a, &b, "--tolerance", "0", "--common"]);
    assert!(
        o.status.success(),
        "restarted run differs from {full}: {}",
        text(&o)
    );
}

/// Asserts that every step field of results file `a` equals that of `b` bit for bit; returns the
/// field names.
pub fn assert_bitwise_equal(a: &Path, b: &Path) -> Vec<String> {
    let fields: Vec<String> = layout(a)
        .into_iter()
        .map(|(n, _)| n)
        .filter(|n| n.starts_with("/steps/"))
        .collect();
    assert!(!fields.is_empty(), "{} has step fields", a.display());
    for name in &fields {
        let (x, y) = (read_f64(a, name), read_f64(b, name));
        let differ = x
            .iter()
            .zip(&y)
            .filter(|(u, v)| u.to_bits() != v.to_bits())
            .count();
        assert!(
            x.len() == y.len() && differ == 0,
            "{name}: {differ} of {} values differ",
            x.len()
        );
    }
    fields
}

/// The crest node of the quake run in `out` (`crest_node_id` of its `quake_summary.json`) as
/// an index of its results file's mesh, with the mesh's node coordinates (x, y, z per node).
pub fn crest_node(out: &Path) -> (usize, Vec<f64>) {
    let text = std::fs::read_to_string(out.join("quake_summary.json")).unwrap();
    let summary: serde_json::Value = serde_json::from_str(&text).unwrap();
    let id = summary["crest_node_id"].as_i64().expect("crest_node_id");
    let h5 = out.join("results.h5");
    let ids = read_i64(&h5, "/mesh/node_ids");
    let n = ids
        .iter()
        .position(|&i| i == id)
        .expect("the crest node in the mesh");
    (n, read_f64(&h5, "/mesh/coordinates"))
}

/// A count of the run in the output directory `out` (its `summary.json`).
pub fn summary_count(out: &Path, key: &str) -> u64 {
    let text = std::fs::read_to_string(out.join("summary.json")).unwrap();
    let s: serde_json::Value = serde_json::from_str(&text).unwrap();
    s[key]
        .as_u64()
        .unwrap_or_else(|| panic!("summary.json has {key}"))
}
