//! Seismic input: the design response spectrum of the Chinese hydraulic codes (spec seismic
//! §1) and elastic response spectra (§2.2 step 5).

pub mod response;
pub mod spectrum;

pub use response::{response_spectrum, Oscillator};
pub use spectrum::{CodeEdition, DesignSpectrum};
