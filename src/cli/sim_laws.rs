//! `mdr-dem sim laws`: the laws a scene can name, each with its parameters as the law declares
//! them (scene key, symbol, unit, allowed range, default, equation), so the list is the
//! registry itself, never a copy of it: the normal laws, then the tangential, damping and
//! rolling-resistance laws.

use clap::Args;
use mdr_contact::params::LawDeclaration;
use mdr_sim::laws::registry::{NORMAL_LAWS, SUB_MODEL_KINDS};

/// Flags of `sim laws`.
#[derive(Debug, Args)]
pub struct LawsArgs {
    /// Print one JSON array instead of text: the normal laws first, then the tangential,
    /// damping and rolling laws, each with its `kind`.
    #[arg(long)]
    pub json: bool,
}

/// Every registered law: the normal laws, then each sub-model kind's.
fn declarations() -> Vec<LawDeclaration> {
    NORMAL_LAWS
        .iter()
        .map(|e| e.declaration)
        .chain(
            SUB_MODEL_KINDS
                .iter()
                .flat_map(|k| k.laws)
                .map(|e| e.declaration),
        )
        .collect()
}

/// Print the registered laws.
pub fn run(args: &LawsArgs) -> anyhow::Result<()> {
    if args.json {
        println!("{}", serde_json::to_string_pretty(&declarations())?);
        return Ok(());
    }
    for entry in NORMAL_LAWS {
        print_law(
            "normal",
            &entry.declaration,
            "",
            "(no parameters beyond the materials')",
        );
    }
    for kind in &SUB_MODEL_KINDS {
        for entry in kind.laws {
            let default = if entry.declaration.name == kind.default {
                " (default)"
            } else {
                ""
            };
            print_law(kind.key, &entry.declaration, default, "(no parameters)");
        }
    }
    Ok(())
}

/// `key = "name"[ (default)]: summary`, then one line per parameter.
fn print_law(key: &str, law: &LawDeclaration, note: &str, none: &str) {
    println!("{key} = \"{}\"{note}: {}", law.name, law.summary);
    if law.params.is_empty() {
        println!("    {none}");
    }
    for p in law.params {
        println!("    {} = …  {}", p.key, p.help());
    }
}
