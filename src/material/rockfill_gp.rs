//! Placeholder: being written (see material/mod.rs).
