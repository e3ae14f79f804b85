//! `mdr-dem impact fig2` (the program's default job): the paper's Fig. 2 as a table and
//! `results/fig2.{csv,svg,png}`.

use super::common::{load_data, CommonArgs, Settings};
use super::curve::{compute_curves, curve_figure, print_table};
use clap::Args;
use mdr_impact::log_spaced;
use mdr_impact::output::{curve_csv, write_atomic};
use std::path::PathBuf;

/// Flags of `impact fig2`.
#[derive(Debug, Clone, Args)]
pub struct Fig2Args {
    #[command(flatten)]
    common: CommonArgs,
    /// Measured `v0_m_per_s,e_n` points to overlay.
    #[arg(long, value_name = "FILE")]
    data: Option<PathBuf>,
    /// Output directory.
    #[arg(long, value_name = "DIR", default_value = "results")]
    out_dir: PathBuf,
}

impl Default for Fig2Args {
    fn default() -> Self {
        Self {
            common: CommonArgs::default(),
            data: None,
            out_dir: PathBuf::from("results"),
        }
    }
}

/// Speeds listed in the Fig. 2 table.
const FIG2_TABLE_SPEEDS: [f64; 12] = [
    0.03, 0.1, 0.2, 0.28, 0.3, 0.5, 1.0, 2.0, 3.0, 5.0, 10.0, 30.0,
];

pub(super) fn run_fig2(args: &Fig2Args) -> anyhow::Result<()> {
    let settings = Settings::resolve(&args.common)?;
    let data = args.data.as_deref().map(load_data).transpose()?;
    let speeds = log_spaced(0.01, 30.0, 200);
    let curves = compute_curves(&settings, &speeds)?;
    println!(
        "Fig. 2 of Lyashenko & Popov (2018): steel ball R = {:.4} mm on steel, E* = {:.4e} Pa, \
         m = {:.4} g",
        settings.pair.effective_radius() * 1e3,
        settings.pair.effective_modulus(),
        settings.pair.reduced_mass() * 1e3
    );
    print_table(
        &compute_curves(&settings, &FIG2_TABLE_SPEEDS)?,
        settings.scale,
    );
    let dir = &args.out_dir;
    let csv_path = dir.join("fig2.csv");
    write_atomic(
        &csv_path,
        curve_csv(&curves[0].outcomes, settings.scale).as_bytes(),
    )?;
    println!("wrote {}", csv_path.display());
    let mut figure = curve_figure(&curves, settings.scale, data.as_deref(), true);
    figure.title = "Fig. 2: restitution of a steel ball on a steel plate (MDR model)".into();
    for extension in ["svg", "png"] {
        let path = dir.join(format!("fig2.{extension}"));
        figure.save(&path)?;
        println!("wrote {}", path.display());
    }
    Ok(())
}
