//! The `mdr-dem` command-line program. With no arguments it runs the main job: the paper's
//! Fig. 2 (`mdr-dem impact fig2`).

use clap::{Parser, Subcommand};

mod cli;

/// MDR elasto-plastic contact law for DEM: single-impact validator, rapier coupling, granular runs.
#[derive(Debug, Parser)]
#[command(name = "mdr-dem", version, about)]
struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
}

// Parsed once per run: the size difference between variants costs nothing worth a Box.
#[allow(clippy::large_enum_variant)]
#[derive(Debug, Subcommand)]
enum Command {
    /// Single-impact validator: e_n(v0) curves, traces, fits, oblique impacts.
    #[command(subcommand)]
    Impact(cli::impact::ImpactCommand),
    /// Simulations in rapier: single drops, pairs, scenes, rings.
    #[command(subcommand)]
    Sim(cli::sim::SimCommand),
    /// Throughput benchmarks: the neighbour-list path on a settled bed, side by side with LAMMPS.
    #[command(subcommand)]
    Bench(cli::bench::BenchCommand),
    /// Verification suite: the Chung & Ooi (2011) benchmark tests with reference plots.
    Verify(cli::verify::VerifyArgs),
}

fn main() -> std::process::ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        None => cli::impact::run_default(),
        Some(Command::Impact(cmd)) => cli::impact::run(cmd),
        Some(Command::Sim(cmd)) => cli::sim::run(cmd),
        Some(Command::Bench(cmd)) => cli::bench::run(cmd),
        Some(Command::Verify(args)) => cli::verify::run(args),
    };
    match result {
        Ok(()) => std::process::ExitCode::from(cli::EXIT_FINISHED),
        Err(err) => {
            // `Exit` carries a status whose messages are already printed.
            if !err.is::<cli::Exit>() {
                eprintln!("error: {}", cli::error_text(&err));
            }
            std::process::ExitCode::from(cli::exit_code(&err))
        }
    }
}
