//! Post-processing: what turns a run's results into the tables and figures an engineer reads.
//!
//! | file | what it holds |
//! |---|---|
//! | [`profiles`] | the static outputs (the seed's Figs. 7–11): slab, interface and dam profiles, probe stress paths |
//! | `profiles_from_results` | the static figures of a run from its results files, parts of a restarted run joined (feature `native`) |
//! | [`accuracy`] | `cfrd accuracy`: a run's slab table against a reference run's |
//! | [`output`] | writing one table or figure into the output directory |
//! | `quake` | the crest's history and summary of an earthquake stage (feature `native`) |
//! | [`quake_clock`] | every dynamic stage of a scene on one time axis, for the quake's histories and figures |
//! | `quake_fields` | an earthquake stage's fields read back from the results files (feature `native`) |
//! | `quake_figures` | the dynamic outputs (the seed's Figs. 12–20) (feature `native`) |
//! | `quake_probes` | the probes' histories through an earthquake (feature `native`) |
//!
//! Results are read through [`crate::io`]'s results reader only; figures are drawn with
//! [`crate::plot`]. Nothing here runs the solver.

pub mod accuracy;
pub mod output;
pub mod profiles;
#[cfg(feature = "native")]
pub mod profiles_from_results;
#[cfg(feature = "native")]
pub mod quake;
pub mod quake_clock;
#[cfg(feature = "native")]
pub mod quake_fields;
#[cfg(feature = "native")]
pub mod quake_figures;
#[cfg(feature = "native")]
pub mod quake_probes;
