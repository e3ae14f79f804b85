//! A quick ring run with the Bridges law, printing one line per orbit:
//! `cargo run --release -p mdr-ring --example quick_ring -- [orbits] [seed] [particles|0] [prediction_m]`.

use mdr_ring::prelude::*;

fn main() -> Result<()> {
    let args: Vec<String> = std::env::args().collect();
    let orbits: f64 = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(2.0);
    let seed: u64 = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(1);
    let mut config = RingConfig::default().seed(seed);
    if let Some(n) = args
        .get(3)
        .and_then(|s| s.parse().ok())
        .filter(|&n: &usize| n > 0)
    {
        config = config.particles(n);
    }
    if let Some(d) = args.get(4).and_then(|s| s.parse().ok()) {
        config = config.collisions(CollisionSettings {
            prediction_distance: d,
            ..CollisionSettings::default()
        });
    }
    let mut ring = RingSimulation::new(config, BridgesLaw::default())?;
    println!("N = {}", ring.particles().len());
    let result = ring.run(orbits, |s, _| {
        if (s.t_orbits * 10.0).round() as u64 % 10 == 0 {
            println!(
                "t {:5.1} c {:.3} mm/s z_rms {:.2} m FF0 {:.3} coll {} wall {:.1} s",
                s.t_orbits,
                s.c * 1e3,
                s.z_rms,
                s.filling_factor_z0,
                s.collisions,
                s.wall_s
            );
        }
    })?;
    println!(
        "{}",
        serde_json::to_string_pretty(&result.summary).unwrap_or_default()
    );
    Ok(())
}
