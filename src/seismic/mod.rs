//! Seismic input: the design response spectrum of the Chinese hydraulic codes, elastic
//! response spectra, spectrum-compatible artificial accelerograms, record readers and the
//! `cfrd accel` command (spec seismic §1, §2; the generator's algorithm and measured
//! performance are in [`algorithm`]).
//!
//! A time integrator loads a record and evaluates the ground acceleration a_g(t) (m/s², axes
//! x stream, y dam axis, z up) with [`Accelerogram`]:
//!
//! ```no_run
//! use cfrd::seismic::Accelerogram;
//! let record = Accelerogram::read_csv("out/accel/seed_quake.csv".as_ref()).unwrap();
//! let [a_x, a_y, a_z] = record.at(1.234);
//! ```

pub mod algorithm;
pub mod at2;
pub mod command;
pub mod correction;
pub mod filter;
pub mod generator;
pub mod measures;
pub mod record;
pub mod response;
pub mod spec;
pub mod spectrum;
#[cfg(test)]
mod tests;
pub mod wavelet;

pub use at2::read_at2;
pub use command::{run_file, AccelError, AccelSummary};
pub use generator::{generate_record, ComponentTarget, Envelope, GeneratedRecord, GeneratorSettings};
pub use record::{AccelComponent, Accelerogram, Axis, RecordError};
pub use response::{response_spectrum, Oscillator};
pub use spec::AccelSpecFile;
pub use spectrum::{CodeEdition, DesignSpectrum};
