//! `mdr-dem sim run SCENE.toml [--resume CHECKPOINT] [--quiet] [--out DIR] [--threads T]`: a
//! granular scene from a TOML file. Checks the file, runs it with a progress bar, writes VTK
//! frames, the energy books, plots and checkpoints; Ctrl-C writes a final checkpoint and exits
//! cleanly.

use anyhow::Context;
use clap::Args;
use mdr_sim::scene::Problems;
use mdr_sim::{load_scene, run_scene, RunOptions};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

/// Flags of `sim run`.
#[derive(Debug, Clone, Args)]
pub struct RunArgs {
    /// Scene file (TOML); see docs/user-guide.md and the examples in scenes/.
    pub scene: PathBuf,
    /// Continue from a checkpoint written by an earlier run of the same scene.
    #[arg(long)]
    pub resume: Option<PathBuf>,
    /// No progress bar (for scripts); problems and the summary still go to stderr/stdout.
    #[arg(long)]
    pub quiet: bool,
    /// Output directory (default: `out/<run name>` next to the current directory).
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Only check the scene file and print what would run.
    #[arg(long)]
    pub check: bool,
    /// Worker threads (default: the RAYON_NUM_THREADS environment variable, else every core).
    /// The trajectory does not depend on it.
    #[arg(long)]
    pub threads: Option<usize>,
}

/// Run `mdr-dem sim run`.
pub fn run(args: &RunArgs) -> anyhow::Result<()> {
    let pool = args.threads.map(super::rayon_pool).transpose()?;
    let scene = match load_scene(&args.scene) {
        Ok(scene) => scene,
        Err(problems) => {
            print_problems(&problems);
            anyhow::bail!(
                "{} refused: {} error(s)",
                args.scene.display(),
                problems.errors().count()
            );
        }
    };
    for warning in &scene.warnings {
        eprintln!("{warning}");
    }
    let out = args
        .out
        .clone()
        .unwrap_or_else(|| PathBuf::from("out").join(&scene.name));
    eprintln!(
        "scene `{}`: {} particles, {} walls, dt = {:.3e} s{} ({:.1} steps per contact at {:.3} m/s), {} steps; output in {}",
        scene.name,
        scene.particles.len(),
        scene.walls.len(),
        scene.dt,
        if scene.dt_auto { " (auto)" } else { "" },
        scene.contact_time / scene.dt,
        scene.max_speed,
        scene.total_steps(),
        out.display()
    );
    if args.check {
        return Ok(());
    }
    match pool {
        Some(pool) => pool.install(|| run_checked(args, &scene, &out)),
        None => run_checked(args, &scene, &out),
    }
}

/// The run of a checked scene, on the current rayon pool.
fn run_checked(args: &RunArgs, scene: &mdr_sim::Scene, out: &Path) -> anyhow::Result<()> {
    let interrupt = Arc::new(AtomicBool::new(false));
    {
        let flag = Arc::clone(&interrupt);
        ctrlc::set_handler(move || flag.store(true, Ordering::SeqCst))
            .context("installing the Ctrl-C handler")?;
    }
    let options = RunOptions::new(out)
        .quiet(args.quiet)
        .resume(args.resume.clone())
        .interrupt(interrupt);
    if scene.source.run.orifice_sweep_m.is_some() {
        anyhow::ensure!(
            args.resume.is_none(),
            "--resume continues one run: write its diameter into orifice_diameter_m, remove orifice_sweep_m and resume that scene"
        );
        let sweep = mdr_sim::headline::run_orifice_sweep(scene, &options)?;
        for run in &sweep.runs {
            println!("{}", run.headline.text);
        }
        println!("{}", sweep.text);
        return Ok(());
    }
    let summary = run_scene(scene, &options)?;
    if summary.stopped_early {
        eprintln!(
            "interrupted at t = {:.6e} s (step {}); continue with:\n  mdr-dem sim run {} --resume {}",
            summary.time,
            summary.step,
            args.scene.display(),
            summary
                .checkpoint
                .as_ref()
                .map_or("<checkpoint>".to_owned(), |p| p.display().to_string())
        );
        return Ok(());
    }
    if let (Some(first), Some(last)) = (summary.energy.first(), summary.energy.last()) {
        // The energy the run moved around: a drum turning a bed that starts at rest near the
        // origin has little initial energy but dissipates all the work the drum does.
        let dissipated = last.plastic_j + last.friction_j + last.damping_j + last.rolling_j;
        let scale = first
            .kinetic()
            .abs()
            .max(first.gravitational_j.abs())
            .max(dissipated.abs())
            .max(last.wall_work_j.abs())
            .max(1e-300);
        println!(
            "done: t = {:.6e} s, {} steps in {:.1} s; energy balance drift {:.3e} J ({:.3} % of the energy scale: the largest of the initial kinetic and gravitational energies, the dissipated work and the wall work)",
            summary.time,
            summary.step,
            summary.wall_seconds,
            last.balance_j - first.balance_j,
            100.0 * (last.balance_j - first.balance_j) / scale
        );
    }
    if !summary.headline.text.is_empty() {
        println!("{}", summary.headline.text);
    }
    println!(
        "ParaView: open {}",
        out.join(format!("{}.pvd", scene.name)).display()
    );
    Ok(())
}

fn print_problems(problems: &Problems) {
    for p in &problems.0 {
        eprintln!("{p}");
    }
}
