//! `mdr-dem verify [--test N] [--plot DIR] [--quick]`: the Chung & Ooi (2011) benchmark tests
//! on the validator and the rapier force mode, with figures that overlay the
//! references. The tests themselves live in `mdr-verify`.

use anyhow::{bail, Context};
use clap::Args;
use mdr_verify::chung_ooi::{self, Resolution};
use std::path::PathBuf;

/// Flags of `mdr-dem verify`.
#[derive(Debug, Clone, Args)]
pub struct VerifyArgs {
    /// Run only test N (1–8); all tests by default.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u8).range(1..=8))]
    pub test: Option<u8>,
    /// Write SVG figures (reference overlaid) into DIR.
    #[arg(long, value_name = "DIR")]
    pub plot: Option<PathBuf>,
    /// Coarse sweeps (the CI resolution) instead of the full ones.
    #[arg(long)]
    pub quick: bool,
}

/// Run the selected tests, print their checks, write the figures; fail if a check fails.
pub fn run(args: VerifyArgs) -> anyhow::Result<()> {
    let resolution = if args.quick {
        Resolution::ci()
    } else {
        Resolution::full()
    };
    let numbers: Vec<u8> = match args.test {
        Some(n) => vec![n],
        None => (1..=8).collect(),
    };
    let mut failed = Vec::new();
    for n in numbers {
        let report = chung_ooi::run(n, resolution).with_context(|| format!("test {n}"))?;
        print!("{report}");
        if let Some(dir) = &args.plot {
            for figure in &report.figures {
                let path = mdr_verify::plot::write_svg(figure, dir)
                    .with_context(|| format!("figure {}", figure.name))?;
                println!("  figure: {}", path.display());
            }
        }
        if !report.passed() {
            failed.push(n);
        }
    }
    if !failed.is_empty() {
        bail!("verification failed in test(s) {failed:?}");
    }
    Ok(())
}
