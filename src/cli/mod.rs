//! The command line of the `cfrd` binary.
//!
//! | file | what it holds |
//! |---|---|
//! | `args` | the subcommands and their options, and the parsers of option values |
//! | `commands` | the commands without MPI (schema, point, accel, compare, export, accuracy, overlay, profiles, partition, bench materials) |
//! | `mpi_commands` | the commands under MPI (run, check, bench solver) |

pub mod args;
pub mod commands;
pub mod mpi_commands;
