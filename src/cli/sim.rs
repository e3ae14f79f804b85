//! `mdr-dem sim …` (drop/pair: issue 4; run: issue 5; ring: issue 8).

use clap::Subcommand;

/// `sim` subcommands.
#[derive(Debug, Subcommand)]
pub enum SimCommand {
    /// Single sphere on a half-space in rapier.
    Drop,
}

/// Dispatch a `sim` subcommand.
pub fn run(cmd: SimCommand) -> anyhow::Result<()> {
    match cmd {
        SimCommand::Drop => anyhow::bail!("sim drop is not built yet"),
    }
}
