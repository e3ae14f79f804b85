//! Figures of docs/rings.md from finished runs:
//! `cargo run --release -p mdr-ring --example ring_figures -- OUT_DIR [--name STEM] LABEL=PATH ...`
//! where PATH is either an mdr-dem `timeseries.csv` or a REBOUND `ring.py --json` file. Writes
//! `OUT_DIR/STEM.svg` (c, z_rms and FF(z=0) against time for every run; STEM defaults to
//! `ring_equilibration`) and, without `--name`, `OUT_DIR/ring_restitution.svg` (the MDR ice law's
//! e(v) next to Bridges').

use mdr_ring::app::{write_restitution_svg, LawChoice};
use mdr_ring::diagnostics::Sample;
use mdr_ring::output::write_equilibration_svg;
use mdr_ring::prelude::*;
use std::path::Path;

fn read_samples(path: &Path) -> std::result::Result<Vec<Sample>, Box<dyn std::error::Error>> {
    if path.extension().is_some_and(|e| e == "csv") {
        let mut reader = csv::Reader::from_path(path)?;
        return Ok(reader
            .deserialize()
            .collect::<std::result::Result<_, _>>()?);
    }
    // REBOUND's ring.py: {"history": [{"t_orb", "c", "zrms", "ff0", "coll", "wall"}, ...]}.
    let value: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(path)?)?;
    let history = value["history"]
        .as_array()
        .ok_or("no history in the REBOUND file")?;
    Ok(history
        .iter()
        .map(|h| Sample {
            t_orbits: h["t_orb"].as_f64().unwrap_or(f64::NAN),
            c: h["c"].as_f64().unwrap_or(f64::NAN),
            z_rms: h["zrms"].as_f64().unwrap_or(f64::NAN),
            filling_factor_z0: h["ff0"].as_f64().unwrap_or(f64::NAN),
            ..Sample::default()
        })
        .collect())
}

fn main() -> std::result::Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let out = Path::new(
        args.first()
            .ok_or("usage: ring_figures OUT_DIR LABEL=PATH ...")?,
    );
    let (name, specs) = match args.get(1).map(String::as_str) {
        Some("--name") => (
            Some(args.get(2).ok_or("--name needs a file stem")?.as_str()),
            &args[3..],
        ),
        _ => (None, &args[1..]),
    };
    let mut runs = Vec::new();
    for spec in specs {
        let (label, path) = spec.split_once('=').ok_or("runs are given as LABEL=PATH")?;
        runs.push((label.to_string(), read_samples(Path::new(path))?));
    }
    let borrowed: Vec<(String, &[Sample])> = runs
        .iter()
        .map(|(l, s)| (l.clone(), s.as_slice()))
        .collect();
    let stem = name.unwrap_or("ring_equilibration");
    write_equilibration_svg(&out.join(format!("{stem}.svg")), &borrowed)?;
    if name.is_some() {
        return Ok(());
    }
    write_restitution_svg(
        &out.join("ring_restitution.svg"),
        &LawChoice::Mdr(MdrRestitution::ice()),
    )?;
    Ok(())
}
