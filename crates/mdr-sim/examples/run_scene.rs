//! Run a scene file without the `mdr-dem` binary: `cargo run --release -p mdr-sim --example
//! run_scene -- scenes/column.toml [OUT_DIR]`.

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let scene_path = args.next().ok_or("usage: run_scene SCENE.toml [OUT_DIR]")?;
    let scene = mdr_sim::load_scene(scene_path.as_ref()).map_err(|p| p.to_string())?;
    for w in &scene.warnings {
        eprintln!("{w}");
    }
    let out = args.next().unwrap_or_else(|| format!("out/{}", scene.name));
    let summary = mdr_sim::run_scene(&scene, &mdr_sim::RunOptions::new(out))?;
    let (first, last) = (&summary.energy[0], summary.energy.last().expect("rows"));
    println!(
        "t = {:.4e} s, {} steps, {:.1} s, {:.3e} particle-steps/s; balance {:.6e} -> {:.6e} J",
        summary.time,
        summary.step,
        summary.wall_seconds,
        summary.step as f64 * scene.particles.len() as f64 / summary.wall_seconds,
        first.balance_j,
        last.balance_j
    );
    println!("{}", summary.headline.text);
    Ok(())
}
