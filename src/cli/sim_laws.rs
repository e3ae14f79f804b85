//! `mdr-dem sim laws`: the normal laws a scene can name, each with its parameters as the law
//! declares them (scene key, symbol, unit, allowed range, default, equation), so the list is
//! the registry itself, never a copy of it.

use clap::Args;
use mdr_sim::laws::registry::NORMAL_LAWS;

/// Flags of `sim laws`.
#[derive(Debug, Args)]
pub struct LawsArgs {
    /// Print one JSON array instead of text.
    #[arg(long)]
    pub json: bool,
}

/// Print the registered normal laws.
pub fn run(args: &LawsArgs) -> anyhow::Result<()> {
    if args.json {
        let laws: Vec<_> = NORMAL_LAWS.iter().map(|e| e.declaration).collect();
        println!("{}", serde_json::to_string_pretty(&laws)?);
        return Ok(());
    }
    for entry in NORMAL_LAWS {
        let d = &entry.declaration;
        println!("normal = \"{}\": {}", d.name, d.summary);
        if d.params.is_empty() {
            println!("    (no parameters beyond the materials')");
        }
        for p in d.params {
            println!("    {} = …  {}", p.key, p.help());
        }
    }
    Ok(())
}
