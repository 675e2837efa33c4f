//! The `cfrd` command line: a thin layer that parses arguments and calls the library.

mod cli;

use clap::Parser;
use cli::args::{Bench, Cli, Command};
use cli::{commands, mpi_commands};
use std::process::ExitCode;

fn main() -> ExitCode {
    let args = match cli::args::utf8_args(std::env::args_os()) {
        Ok(args) => args,
        Err(message) => {
            eprintln!("error: {message}");
            return ExitCode::from(2);
        }
    };
    let (args, petsc) = cli::args::split_petsc_options(args);
    match Cli::parse_from(args).command {
        Command::Schema => commands::schema(),
        Command::Point { test, out } => commands::point(&test, &out),
        Command::Accel { spec, out } => commands::accel(&spec, &out),
        Command::Compare {
            a,
            b,
            tolerance,
            common,
        } => commands::compare(&a, &b, tolerance, common),
        Command::Export {
            results,
            fields,
            stage,
            step,
            set,
            scene,
            probes,
            out,
        } => {
            let step = match (stage, step) {
                (Some(s), _) => cfrd::io::export::StepChoice::Stage(s),
                (None, Some(n)) => cfrd::io::export::StepChoice::Number(n),
                (None, None) => cfrd::io::export::StepChoice::Last,
            };
            let req = cfrd::io::export::ExportRequest {
                results,
                step,
                fields,
                rows: cfrd::io::export::RowChoice { set, scene, probes },
            };
            commands::export(&req, out.as_deref())
        }
        Command::Accuracy {
            reference,
            quake,
            runs,
            out,
        } => commands::accuracy(&reference, quake, &runs, &out),
        Command::Overlay { runs, out, quake } => commands::overlay(&runs, &out, quake),
        Command::Profiles { scene, runs, out } => commands::profiles(&scene, &runs, &out),
        Command::Partition { scene, parts, out } => commands::partition(&scene, parts, &out),
        Command::Bench(Bench::Materials { quick }) => commands::bench_materials(quick),
        Command::Bench(Bench::Solver { dofs, out }) => mpi_commands::bench_solver(dofs, out, petsc),
        Command::Check { scene } => mpi_commands::check(scene),
        Command::Run(args) => mpi_commands::run(args, petsc),
    }
}
