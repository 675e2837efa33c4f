//! What the fuzz targets share: each runs one entry function of [`cfrd::fuzzing`] on the input
//! and counts its outcome; at exit the counts are printed to standard error as one line,
//! `cfrd-fuzz outcomes: accepted=A rejected=R skipped=S`, which `scripts/fuzz_campaign.sh`
//! reads. A panic is not counted here: libFuzzer reports it as a crash and stops.

use cfrd::fuzzing::{Entry, Outcome};
use libfuzzer_sys::Corpus;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Once;

/// Inputs accepted, rejected with an error, and skipped (over the scene's size budget).
static COUNTS: [AtomicU64; 3] = [AtomicU64::new(0), AtomicU64::new(0), AtomicU64::new(0)];

/// Registers [`print_counts`] once per process.
static AT_EXIT: Once = Once::new();

/// Runs `entry` on `data`, counts the outcome, and keeps the input out of the corpus when it
/// was skipped.
pub fn run(entry: Entry, data: &[u8]) -> Corpus {
    AT_EXIT.call_once(|| {
        // SAFETY: `print_counts` is a plain `extern "C" fn()` that only reads atomics and
        // writes to standard error; registering it has no other precondition.
        unsafe {
            libc::atexit(print_counts);
        }
    });
    let outcome = entry(data);
    let slot = match outcome {
        Outcome::Accepted => 0,
        Outcome::Rejected => 1,
        Outcome::Skipped => 2,
    };
    COUNTS[slot].fetch_add(1, Ordering::Relaxed);
    if outcome == Outcome::Skipped {
        Corpus::Reject
    } else {
        Corpus::Keep
    }
}

/// Prints the outcome counts (called by the C library at exit, after libFuzzer's last run).
extern "C" fn print_counts() {
    let [a, r, s] = COUNTS.each_ref().map(|c| c.load(Ordering::Relaxed));
    eprintln!("cfrd-fuzz outcomes: accepted={a} rejected={r} skipped={s}");
}
