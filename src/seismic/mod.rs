//! Seismic input: the design response spectrum of the Chinese hydraulic codes (spec seismic
//! §1), elastic response spectra (§2.2 step 5), ground-motion records and spectrum-compatible
//! artificial accelerograms (§2.2).

pub mod at2;
pub mod correction;
pub mod generator;
pub mod measures;
pub mod record;
pub mod response;
pub mod spectrum;
pub mod wavelet;

pub use at2::read_at2;
pub use generator::{generate_record, ComponentTarget, Envelope, GeneratedRecord, GeneratorSettings};
pub use record::{AccelComponent, Accelerogram, Axis, RecordError};
pub use response::{response_spectrum, Oscillator};
pub use spectrum::{CodeEdition, DesignSpectrum};
