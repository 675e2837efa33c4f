//! Issue 23, acceptance 4: the fuzz corpus (`tests/fuzz/corpus/<target>/`, the inputs the
//! coverage-guided campaign kept and every crasher it found) replays on stable through the same
//! entry functions as the fuzz targets ([`cfrd::fuzzing`]). Every file must finish within
//! [`BOUND`] without a panic; the reader may accept or reject it.

use cfrd::fuzzing::{Entry, Outcome, TARGETS};
use std::path::{Path, PathBuf};
use std::sync::mpsc;
use std::time::Duration;

/// Longest replay of one file (the campaign's libFuzzer time-out is 10 s on an instrumented
/// build; a release build is several times faster).
const BOUND: Duration = Duration::from_secs(20);

/// The corpus files of `target`, sorted by name.
fn corpus(target: &str) -> Vec<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fuzz/corpus")
        .join(target);
    let entries = std::fs::read_dir(&dir).unwrap_or_else(|e| panic!("{}: {e}", dir.display()));
    let mut files: Vec<PathBuf> = entries.map(|e| e.expect("a directory entry").path()).collect();
    files.sort();
    files
}

/// Runs `entry` on the bytes of `file` in its own thread: the outcome, or why it failed (a
/// panic, seen as the thread ending without an answer, or no answer within [`BOUND`]).
fn replay(entry: Entry, file: &Path) -> Result<Outcome, String> {
    let bytes = std::fs::read(file).map_err(|e| format!("{}: {e}", file.display()))?;
    let (tx, rx) = mpsc::channel();
    std::thread::spawn(move || {
        let _ = tx.send(entry(&bytes));
    });
    rx.recv_timeout(BOUND).map_err(|e| match e {
        mpsc::RecvTimeoutError::Timeout => format!("{}: did not finish within {BOUND:?}", file.display()),
        mpsc::RecvTimeoutError::Disconnected => format!("{}: panicked", file.display()),
    })
}

/// Replays the corpus of `target`; fails naming every file that panicked or hung.
fn replay_target(target: &str) {
    let (_, entry) = TARGETS
        .iter()
        .find(|(name, _)| *name == target)
        .expect("a known target");
    let files = corpus(target);
    assert!(!files.is_empty(), "the corpus of {target} is empty");
    let mut counts = [0usize; 3];
    let mut failures = Vec::new();
    for file in &files {
        match replay(*entry, file) {
            Ok(Outcome::Accepted) => counts[0] += 1,
            Ok(Outcome::Rejected) => counts[1] += 1,
            Ok(Outcome::Skipped) => counts[2] += 1,
            Err(why) => failures.push(why),
        }
    }
    eprintln!(
        "{target}: {} files: {} accepted, {} rejected, {} skipped",
        files.len(),
        counts[0],
        counts[1],
        counts[2]
    );
    assert!(failures.is_empty(), "{target}:\n{}", failures.join("\n"));
}

#[test]
fn scene_corpus_replays() {
    replay_target("scene");
}

#[test]
fn gmsh_corpus_replays() {
    replay_target("gmsh");
}

#[test]
fn accel_csv_corpus_replays() {
    replay_target("accel_csv");
}

#[test]
fn accel_at2_corpus_replays() {
    replay_target("accel_at2");
}

#[test]
fn state_codec_corpus_replays() {
    replay_target("state_codec");
}

#[test]
fn lock_file_corpus_replays() {
    replay_target("lock_file");
}

#[test]
fn checkpoint_inputs_corpus_replays() {
    replay_target("checkpoint_inputs");
}

/// The harness reaches the decoders' success path: the encoded initial states of every model
/// are accepted (so the campaign's seeds are valid checkpoint rows).
#[test]
fn state_codec_examples_are_accepted() {
    for (k, bytes) in cfrd::fuzzing::state_codec_examples().iter().enumerate() {
        assert_eq!(
            cfrd::fuzzing::state_codec(bytes),
            Outcome::Accepted,
            "example {k}"
        );
    }
}
