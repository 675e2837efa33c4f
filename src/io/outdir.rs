//! The output directory of `cfrd run`, checked before the run starts: a directory holding
//! another run's results is not written over without `--overwrite` (a restart from that
//! directory's own checkpoint included), so no run's data is lost by accident and no run leaves
//! a checkpoint of another scene beside its results; temporary files of killed runs are named
//! and removed.

use crate::parallel::any_error;
use mpi::topology::{Communicator, SimpleCommunicator};
use std::path::{Path, PathBuf};

/// The files of a finished (or stopped) run whose presence makes a directory another run's.
pub const RUN_FILES: [&str; 3] = ["results.h5", "checkpoint.h5", "summary.json"];

/// Files written under a temporary name `.<name>.partial-<pid>` (or `.<name>.publish`).
const TEMP_OF: [&str; 4] = ["results.h5", "checkpoint.h5", "summary.json", "results.xdmf"];

/// The output directory of `cfrd run`: `-o` if given, else the scene's `output.dir` (the
/// embedded default scene's without a scene). `None` if the scene cannot be read or parsed;
/// the run then fails on the scene with its own message.
pub fn run_output_dir(out: Option<&Path>, scene: Option<&Path>) -> Option<PathBuf> {
    if let Some(dir) = out {
        return Some(dir.to_path_buf());
    }
    let text = match scene {
        Some(p) => {
            let bytes = crate::input::read_bounded(p, crate::input::MAX_SCENE_BYTES).ok()?;
            String::from_utf8(bytes).ok()?
        }
        None => crate::scene::DEFAULT_SCENE.to_string(),
    };
    let file = crate::scene::parse::parse(crate::scene::text::strip_bom(&text), "").ok()?;
    Some(file.output.dir)
}

/// Decides on rank 0 whether the run may write into `dir` (see [`prepare_output_dir`]) and
/// shares the decision, so every rank returns the same; rank 0 prints the notes unless `quiet`.
/// Collective.
pub fn prepare_output_dir_collective(
    world: &SimpleCommunicator,
    dir: &Path,
    restart: Option<&Path>,
    overwrite: bool,
    quiet: bool,
) -> Result<(), String> {
    let local = if world.rank() == 0 {
        prepare_output_dir(dir, restart, overwrite)
    } else {
        Ok(Vec::new())
    };
    for note in any_error(world, local)? {
        if !quiet {
            eprintln!("note: {note}");
        }
    }
    Ok(())
}

/// Checks the output directory `dir` of a run (restarting from `restart`, if any) and returns
/// notes of what was removed:
/// - a directory holding [`RUN_FILES`] is refused, naming them, unless `overwrite` (the old
///   `checkpoint.h5` is then removed first, so that it cannot outlive the new results, unless
///   the run restarts from it);
/// - a restart from `dir`'s own `checkpoint.h5` is refused without `overwrite` (with it, the
///   run continues the results there: `run::results::continue_results`);
/// - a temporary file of a run whose process is alive is refused (another run writes there);
///   those of runs that no longer exist are removed.
pub fn prepare_output_dir(
    dir: &Path,
    restart: Option<&Path>,
    overwrite: bool,
) -> Result<Vec<String>, String> {
    let shown = dir.display();
    match std::fs::metadata(dir) {
        Err(_) => return Ok(Vec::new()),
        Ok(m) if !m.is_dir() => return Err(format!("output directory {shown}: not a directory")),
        Ok(_) => {}
    }
    let stale = stale_temporaries(dir)?;
    let present: Vec<&str> = RUN_FILES.into_iter().filter(|f| dir.join(f).exists()).collect();
    let ckpt = dir.join("checkpoint.h5");
    let restart_here = restart.is_some_and(|r| same_file(r, &ckpt));
    if restart_here && !overwrite {
        return Err(format!(
            "--restart {}: the run would continue in the directory of its own checkpoint, \
             replacing its results with the continued ones; pass --overwrite to do so (the \
             steps before the checkpoint are kept), or choose another directory with -o",
            ckpt.display()
        ));
    }
    if !present.is_empty() && !overwrite {
        let resume = if ckpt.exists() {
            format!(
                ", or continue that run into another directory with --restart {}",
                ckpt.display()
            )
        } else {
            String::new()
        };
        return Err(format!(
            "output directory {shown} holds the files of another run ({}); pass --overwrite to \
             replace them or choose another directory with -o{resume}",
            present.join(", ")
        ));
    }
    let mut notes = Vec::new();
    if overwrite && !restart_here && ckpt.exists() {
        remove(&ckpt)?;
        notes.push(format!(
            "--overwrite: removed {} of the previous run",
            ckpt.display()
        ));
    }
    for (path, why) in stale {
        remove(&path)?;
        notes.push(format!("removed {}, left by {why}", path.display()));
    }
    Ok(notes)
}

/// Temporary files in `dir` left by killed runs, with why each is stale; an error if one belongs
/// to a live process.
fn stale_temporaries(dir: &Path) -> Result<Vec<(PathBuf, String)>, String> {
    let entries = std::fs::read_dir(dir).map_err(|e| format!("output directory {}: {e}", dir.display()))?;
    let mut out = Vec::new();
    let mut live = None;
    for entry in entries.flatten() {
        let name = entry.file_name().to_string_lossy().into_owned();
        match temporary_owner(&name) {
            Some(Some(pid)) if pid != std::process::id() && process_alive(pid) => {
                live = Some((name, pid));
            }
            Some(Some(pid)) => out.push((entry.path(), format!("a run that ended (process {pid})"))),
            Some(None) => out.push((entry.path(), "an interrupted publish of the results".into())),
            None => {}
        }
    }
    if let Some((name, pid)) = live {
        return Err(format!(
            "output directory {}: process {pid} is writing into it ({name}); wait for that run \
             or choose another directory with -o (if no run is writing there, remove {name})",
            dir.display()
        ));
    }
    Ok(out)
}

/// Whether `name` is a temporary file of a run: `Some(Some(pid))` for `.<file>.partial-<pid>`
/// (any file written whole, [`crate::input::write_replacing`]) and `.<stem>.partial-<pid>.png`
/// (a figure, [`crate::plot::Figure::save_png`]), `Some(None)` for `.<file>.publish` of
/// [`TEMP_OF`], `None` otherwise.
fn temporary_owner(name: &str) -> Option<Option<u32>> {
    let rest = name.strip_prefix('.')?;
    if TEMP_OF
        .iter()
        .any(|file| rest.strip_prefix(file) == Some(".publish"))
    {
        return Some(None);
    }
    let (file, pid) = rest.rsplit_once(".partial-")?;
    let pid = pid.strip_suffix(".png").unwrap_or(pid);
    match file.is_empty() || !pid.bytes().all(|b| b.is_ascii_digit()) {
        true => None,
        false => pid.parse().ok().map(Some),
    }
}

/// Whether a process with id `pid` runs (Linux `/proc`; a zombie, a killed process not yet
/// reaped, does not).
fn process_alive(pid: u32) -> bool {
    let Ok(stat) = std::fs::read_to_string(format!("/proc/{pid}/stat")) else {
        return false;
    };
    // "pid (comm) state ...": the name may hold spaces, so the state follows the last ')'
    let state = stat
        .rsplit_once(')')
        .and_then(|(_, rest)| rest.split_whitespace().next());
    !matches!(state, Some("Z" | "X") | None)
}

/// Whether `a` and `b` name the same existing file.
fn same_file(a: &Path, b: &Path) -> bool {
    match (a.canonicalize(), b.canonicalize()) {
        (Ok(a), Ok(b)) => a == b,
        _ => false,
    }
}

fn remove(path: &Path) -> Result<(), String> {
    std::fs::remove_file(path).map_err(|e| format!("{}: cannot remove: {e}", path.display()))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn dir_with(files: &[&str]) -> tempfile::TempDir {
        let dir = tempfile::tempdir().unwrap();
        for f in files {
            std::fs::write(dir.path().join(f), b"x").unwrap();
        }
        dir
    }

    #[test]
    fn another_runs_files_are_refused_unless_overwritten_or_restarted_from() {
        let dir = dir_with(&["results.h5", "checkpoint.h5", "summary.json"]);
        let d = dir.path();
        let msg = prepare_output_dir(d, None, false).expect_err("another run's files");
        assert!(
            msg.contains("results.h5, checkpoint.h5, summary.json") && msg.contains("--overwrite"),
            "{msg}"
        );
        let msg =
            prepare_output_dir(d, Some(&d.join("checkpoint.h5")), false).expect_err("into its own directory");
        assert!(msg.contains("pass --overwrite"), "{msg}");
        prepare_output_dir(d, Some(&d.join("checkpoint.h5")), true).expect("restart from its checkpoint");
        assert!(
            d.join("checkpoint.h5").exists(),
            "a restart keeps the checkpoint it reads"
        );
        let other = dir_with(&["checkpoint.h5"]);
        prepare_output_dir(d, Some(&other.path().join("checkpoint.h5")), false)
            .expect_err("another checkpoint");
        let notes = prepare_output_dir(d, None, true).expect("--overwrite");
        assert!(
            !d.join("checkpoint.h5").exists(),
            "the old checkpoint is removed first"
        );
        assert!(notes[0].contains("checkpoint.h5"), "{notes:?}");
        prepare_output_dir(&d.join("new"), None, false).expect("a new directory");
    }

    #[test]
    fn stale_temporaries_are_named_and_removed_live_ones_refused() {
        let dead = u32::MAX - 1;
        let stale = format!(".results.h5.partial-{dead}");
        let figure = format!(".fig08_slab_stress.partial-{dead}.png");
        let table = format!(".fig08_slab_stress.csv.partial-{dead}");
        let dir = dir_with(&[
            &stale,
            &figure,
            &table,
            ".checkpoint.h5.publish",
            ".results.h5.partialx",
            ".fig.partial-12x.png",
            "notes.txt",
        ]);
        let d = dir.path();
        let notes = prepare_output_dir(d, None, false).expect("stale files only");
        assert_eq!(notes.len(), 4, "{notes:?}");
        assert!(notes.iter().any(|n| n.contains(&stale)), "{notes:?}");
        assert!(!d.join(&stale).exists() && !d.join(".checkpoint.h5.publish").exists());
        assert!(!d.join(&figure).exists() && !d.join(&table).exists());
        assert!(d.join(".fig.partial-12x.png").exists());
        assert!(d.join(".results.h5.partialx").exists() && d.join("notes.txt").exists());
        let live = format!(".checkpoint.h5.partial-{}", std::os::unix::process::parent_id());
        std::fs::write(d.join(&live), b"x").unwrap();
        let msg = prepare_output_dir(d, None, false).expect_err("a live writer");
        assert!(msg.contains(&live) && msg.contains("is writing"), "{msg}");
    }
}
