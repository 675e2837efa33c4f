//! Fuzz target: [`cfrd::fuzzing::lock_file`] on every input; an `Err` is fine, a panic is a bug.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| -> libfuzzer_sys::Corpus {
    cfrd_fuzz::run(cfrd::fuzzing::lock_file, data)
});
