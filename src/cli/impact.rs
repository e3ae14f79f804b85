//! `mdr-dem impact …` (owned by the validator work, issue 3).

use clap::Subcommand;

/// `impact` subcommands.
#[derive(Debug, Subcommand)]
pub enum ImpactCommand {
    /// Reproduce the paper's Fig. 2 (the default job).
    Fig2,
}

/// The default job (no arguments).
pub fn run_default() -> anyhow::Result<()> {
    run(ImpactCommand::Fig2)
}

/// Dispatch an `impact` subcommand.
pub fn run(cmd: ImpactCommand) -> anyhow::Result<()> {
    match cmd {
        ImpactCommand::Fig2 => anyhow::bail!("impact fig2 is not built yet"),
    }
}
