//! The commands that need no MPI: each reads its files, prints what it made and returns the
//! process's exit code (2 for bad input, with the message on standard error).

use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// Prints `error: e` and returns exit code `code`.
pub fn fail(e: impl std::fmt::Display, code: u8) -> ExitCode {
    eprintln!("error: {e}");
    ExitCode::from(code)
}

/// `cfrd schema`: the JSON Schema of the scene format.
pub fn schema() -> ExitCode {
    let schema = schemars::schema_for!(cfrd::scene::SceneFile);
    println!(
        "{}",
        serde_json::to_string_pretty(&schema).expect("schema serializes")
    );
    ExitCode::SUCCESS
}

/// `cfrd point`: a material-point test.
pub fn point(test: &Path, out: &Path) -> ExitCode {
    match cfrd::point::run_file(test, out) {
        Ok(summary) => {
            println!("{summary}");
            ExitCode::SUCCESS
        }
        Err(e) => fail(&e, e.exit_code()),
    }
}

/// `cfrd accel`: a spectrum-compatible record; exit code 1 when it misses the acceptance.
pub fn accel(spec: &Path, out: &Path) -> ExitCode {
    match cfrd::seismic::run_file(spec, out) {
        Ok(summary) => {
            print!("{summary}");
            if summary.accepted() {
                ExitCode::SUCCESS
            } else {
                ExitCode::from(1)
            }
        }
        Err(e) => fail(&e, e.exit_code()),
    }
}

/// `cfrd compare`: the field differences of two runs and how many steps were compared; exit
/// code 1 above `tolerance`, or when one run holds a step or field the other lacks (unless
/// `common`).
pub fn compare(a: &Path, b: &Path, tolerance: Option<f64>, common: bool) -> ExitCode {
    match cfrd::io::compare::compare_results(a, b) {
        Ok(c) => {
            use std::io::Write as _;
            let worst = c.diffs.iter().map(|d| d.relative()).fold(0.0, f64::max);
            // a closed pipe (`cfrd compare a b | head`) is not an error of the comparison
            let mut out = std::io::stdout().lock();
            let _ = write!(out, "{}", cfrd::io::compare::DiffTable(&c.diffs))
                .and_then(|()| writeln!(out, "compared {} step(s) held by both runs", c.compared_steps))
                .and_then(|()| writeln!(out, "largest relative difference: {worst:.3e}"));
            for u in &c.unmatched {
                eprintln!("{}: {u}", if common { "note" } else { "error" });
            }
            let missing = !c.unmatched.is_empty() && !common;
            if missing {
                eprintln!("error: the runs do not hold the same steps and fields (--common compares those both hold)");
            }
            match tolerance {
                _ if missing => ExitCode::from(1),
                Some(t) if worst > t => ExitCode::from(1),
                _ => ExitCode::SUCCESS,
            }
        }
        Err(e) => fail(e, 2),
    }
}

/// `cfrd export`: one step's fields as CSV.
pub fn export(req: &cfrd::io::export::ExportRequest, out: Option<&Path>) -> ExitCode {
    match export_fields(req, out) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => fail(e, 2),
    }
}

/// `cfrd accuracy`: runs' slab tables against a reference run's.
pub fn accuracy(reference: &Path, quake: bool, runs: &[String], out: &Path) -> ExitCode {
    let study = match quake {
        true => cfrd::post::accuracy::Study::Quake,
        false => cfrd::post::accuracy::Study::Static,
    };
    match label_pairs(runs).and_then(|p| cfrd::post::accuracy::write_study(study, reference, &p, out)) {
        Ok(files) => {
            for f in files {
                println!("{}", f.display());
            }
            ExitCode::SUCCESS
        }
        Err(e) => fail(e, 2),
    }
}

/// `cfrd overlay`: the slab tables of several runs in one figure.
pub fn overlay(runs: &[String], out: &Path, quake: bool) -> ExitCode {
    let table = if quake {
        cfrd::post::profiles::SlabTable::Quake
    } else {
        cfrd::post::profiles::SlabTable::Static
    };
    let overlaid = label_pairs(runs)
        .and_then(|p| cfrd::post::profiles::overlay_slab_profiles(&p, table, out).map_err(|e| e.to_string()));
    match overlaid {
        Ok(n) => {
            println!("{n} rows from {} run(s): {}", runs.len(), out.display());
            ExitCode::SUCCESS
        }
        Err(e) => fail(e, 2),
    }
}

/// `cfrd profiles`: the static figures of a run in parts.
pub fn profiles(scene: &Path, runs: &[PathBuf], out: &Path) -> ExitCode {
    match profiles_of_parts(scene, runs, out) {
        Ok(n) => {
            println!("{n} file(s) from {} run(s) in {}", runs.len(), out.display());
            ExitCode::SUCCESS
        }
        Err(e) => fail(e, 2),
    }
}

/// `cfrd partition`: METIS ahead of a run.
pub fn partition(scene: &Path, parts: usize, out: &Path) -> ExitCode {
    match partition_ahead(scene, parts, out) {
        Ok(msg) => {
            println!("{msg}");
            ExitCode::SUCCESS
        }
        Err(e) => fail(e, 2),
    }
}

/// `cfrd bench materials`: material updates per second; exit code 3 when a model failed.
pub fn bench_materials(quick: bool) -> ExitCode {
    let rows = cfrd::material::bench::run(quick);
    println!("{}", cfrd::material::bench::BenchTable(&rows));
    if rows.iter().any(|r| r.error.is_some()) {
        ExitCode::from(3)
    } else {
        ExitCode::SUCCESS
    }
}

/// `cfrd profiles`: the profile tables and plots of the runs `runs` (results files or run
/// directories, in order) of `scene`, written into `out`; returns the number of files.
fn profiles_of_parts(
    scene: &std::path::Path,
    runs: &[PathBuf],
    out: &std::path::Path,
) -> Result<usize, String> {
    let s = cfrd::scene::Scene::load(scene).map_err(|e| e.to_string())?;
    let spec = s.file.output.profiles.as_ref().ok_or_else(|| {
        format!(
            "{}: output.profiles: not set, so there is nothing to draw",
            scene.display()
        )
    })?;
    let files: Vec<PathBuf> = runs
        .iter()
        .map(|r| cfrd::io::results_reader::results_file(r))
        .collect();
    std::fs::create_dir_all(out).map_err(|e| format!("{}: {e}", out.display()))?;
    let statics = cfrd::post::profiles_from_results::write_profiles_from_results(&s, spec, &files, out)?;
    let quake = cfrd::post::quake_figures::write_quake_figures(&s, spec, &files, &[], out)?;
    Ok(statics.len() + quake.len())
}

/// `cfrd export`: the table of `req`, into `out` (with a line saying what was written) or to
/// standard output.
fn export_fields(req: &cfrd::io::export::ExportRequest, out: Option<&std::path::Path>) -> Result<(), String> {
    use std::io::Write as _;
    let table = cfrd::io::export::export(req)?;
    match out {
        Some(path) => {
            std::fs::write(path, &table.csv).map_err(|e| format!("{}: {e}", path.display()))?;
            println!(
                "{}: {} row(s) of step {} (stage {})",
                path.display(),
                table.rows,
                table.step,
                table.stage
            );
        }
        // a closed pipe (`cfrd export ... | head`) is not an error of the export
        None => {
            let _ = std::io::stdout().lock().write_all(table.csv.as_bytes());
        }
    }
    Ok(())
}

/// `cfrd partition`: METIS on the scene's mesh (each construction band balanced and the
/// evaluated elements evened out, as `cfrd run` does), written to a partition file.
fn partition_ahead(scene: &std::path::Path, parts: usize, out: &std::path::Path) -> Result<String, String> {
    if parts == 0 {
        return Err("--parts must be at least 1".into());
    }
    let s = cfrd::scene::Scene::load(scene).map_err(|e| e.to_string())?;
    let cells = cfrd::solver::mesh_cells(&s.mesh);
    let n = s.mesh.num_nodes();
    let (band, n_bands) = cfrd::run::construction_bands(&s);
    let started = std::time::Instant::now();
    let part = partition::partition_for_assembly(&cells, n, parts, &band, n_bands)
        .map_err(|e| format!("{}: {e}", scene.display()))?;
    let seconds = started.elapsed().as_secs_f64();
    let p = partition::Partition::new(&cells, n, parts, part.clone());
    let by_count =
        partition::partition_elements_by_band(&cells, n, parts, &band, n_bands).map_err(|e| e.to_string())?;
    let by_count = partition::Partition::new(&cells, n, parts, by_count);
    partition::PartitionFile::new(&cells, n, parts, part)
        .write(out)
        .map_err(|e| e.to_string())?;
    Ok(format!(
        "{}: {} elements, {} nodes in {parts} parts ({seconds:.2} s)\n{}\n  elements evaluated per \
         part with the partition balanced by owned elements alone: max {}",
        out.display(),
        cells.len(),
        n,
        partition_statistics(&p, &cells),
        by_count.evaluated_cells(&cells).into_iter().max().unwrap_or(0)
    ))
}

/// What a partition costs a run in balance and communication: elements, owned nodes and ghost
/// nodes per part (min / mean / max) and the elements on part boundaries. A ghost node is
/// received at every update of the ghosted displacement (3 values) and sends its element
/// forces back once per assembly.
fn partition_statistics(p: &partition::Partition, cells: &partition::Cells) -> String {
    let parts = p.nparts;
    let spread = |v: Vec<usize>| {
        let (min, max) = (
            v.iter().min().copied().unwrap_or(0),
            v.iter().max().copied().unwrap_or(0),
        );
        let total: usize = v.iter().sum();
        (min, total as f64 / parts as f64, max, total)
    };
    let line = |what: &str, (min, mean, max, total): (usize, f64, usize, usize)| {
        format!("  {what} per part: min {min}, mean {mean:.1}, max {max} (total {total})\n")
    };
    let owned: Vec<usize> = (0..parts)
        .map(|r| p.node_offsets[r + 1] - p.node_offsets[r])
        .collect();
    let ghosts: Vec<usize> = (0..parts).map(|r| p.ghost_nodes(cells, r).len()).collect();
    let ratio = owned
        .iter()
        .zip(&ghosts)
        .map(|(&o, &g)| g as f64 / o.max(1) as f64)
        .fold(0.0, f64::max);
    format!(
        "{}{}{}{}  elements on part boundaries: {}; largest ghost / owned nodes of a part: {ratio:.3}",
        line(
            "elements",
            spread((0..parts).map(|r| p.owned_cells(r).len()).collect())
        ),
        line(
            "elements evaluated (own and neighbours' around owned nodes)",
            spread(p.evaluated_cells(cells))
        ),
        line("owned nodes", spread(owned)),
        line("ghost nodes", spread(ghosts)),
        p.boundary_cells(cells),
    )
}

/// `LABEL=DIR` arguments as (label, directory) pairs.
fn label_pairs(runs: &[String]) -> Result<Vec<(String, PathBuf)>, String> {
    runs.iter()
        .map(|r| match r.split_once('=') {
            Some((l, d)) if !l.is_empty() && !d.is_empty() => Ok((l.to_string(), PathBuf::from(d))),
            _ => Err(format!("'{r}': expected LABEL=DIR")),
        })
        .collect()
}
