//! Seismic input: the design response spectrum of the Chinese hydraulic codes (spec seismic
//! §1), elastic response spectra (§2.2 step 5) and ground-motion records.

pub mod at2;
pub mod record;
pub mod response;
pub mod spectrum;

pub use at2::read_at2;
pub use record::{AccelComponent, Accelerogram, Axis, RecordError};
pub use response::{response_spectrum, Oscillator};
pub use spectrum::{CodeEdition, DesignSpectrum};
