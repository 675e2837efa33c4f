//! Seismic input: the design response spectrum of the Chinese hydraulic codes (spec seismic
//! §1).

pub mod spectrum;

pub use spectrum::{CodeEdition, DesignSpectrum};
