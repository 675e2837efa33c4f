//! Scenes: the YAML input that decides what is built and assembled.
//!
//! [`Scene::load`] parses (unknown keys rejected, every error names its YAML path), validates
//! values (units, ranges) and cross-references against the mesh (blocks, sets), and resolves the
//! scene into typed objects: the materials of each block and the list of physics
//! [`Term`]s. The solver iterates over the terms; nothing the scene does not ask for is built.

pub mod blocks;
mod checks;
pub mod dynamic;
pub mod error;
pub mod inputs;
pub mod modal;
pub mod output_spec;
pub mod parse;
pub mod ranges;
pub mod record;
pub mod resolved;
pub mod restraint;
pub mod schema;
pub mod stages;
pub mod term;
#[cfg(test)]
mod tests;
pub mod text;

/// The embedded default scene (`cfrd run` without a scene file).
pub const DEFAULT_SCENE: &str = include_str!("../../inputs/scenes/default_dam.yaml");

pub use error::SceneError;
pub use resolved::Scene;
pub use schema::SceneFile;
pub use stages::Stage;
pub use term::Term;
