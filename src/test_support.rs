//! Helpers shared by the unit tests.

use proptest::test_runner::{FailurePersistence, FileFailurePersistence};

/// Where the property tests keep the failing cases they found: beside the test's source file,
/// as `<file>.proptest-regressions` (checked in; proptest replays them before new cases).
pub(crate) fn proptest_persistence() -> Option<Box<dyn FailurePersistence>> {
    Some(Box::new(FileFailurePersistence::WithSource(
        "proptest-regressions",
    )))
}
