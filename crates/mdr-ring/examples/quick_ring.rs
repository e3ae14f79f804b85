//! A ring run without the `mdr-dem` program:
//! `cargo run --release -p mdr-ring --example quick_ring -- ORBITS SEED LAW [EPS] [OUT]`
//! with LAW one of `bridges`, `mdr`, `constant`; prints the summary as JSON.

use mdr_ring::app::{run, LawChoice, RunOptions};
use mdr_ring::prelude::*;
use std::path::PathBuf;

fn main() -> Result<()> {
    let args: Vec<String> = std::env::args().collect();
    let orbits: f64 = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(2.0);
    let seed: u64 = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(1);
    let eps: f64 = args.get(4).and_then(|s| s.parse().ok()).unwrap_or(0.5);
    let law = match args.get(3).map(String::as_str).unwrap_or("bridges") {
        "mdr" => LawChoice::Mdr(MdrRestitution::ice()),
        "constant" => LawChoice::Constant(ConstantRestitution::new(eps)?),
        _ => LawChoice::Bridges(BridgesLaw::default()),
    };
    let options = RunOptions {
        config: RingConfig::default().seed(seed),
        law,
        orbits,
        out: args.get(5).map(PathBuf::from),
        frame_orbits: None,
        progress: true,
    };
    let report = run(&options)?;
    println!(
        "{}",
        serde_json::to_string_pretty(&report).unwrap_or_default()
    );
    Ok(())
}
