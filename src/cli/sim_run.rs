//! `mdr-dem sim run SCENE.toml [--resume CHECKPOINT] [--quiet] [--out DIR] [--overwrite] [--check] [--threads T]
//! [--device cpu|gpu]`: a granular scene from a TOML file. Checks the file, runs it with a
//! progress bar, writes VTK frames, the energy books, plots and checkpoints; Ctrl-C writes a
//! final checkpoint and exits with status 130, printing the command that continues the run.
//! `--device gpu` runs a force-mode scene on the GPU path (`sim_run_gpu`).

use super::bench::DeviceArg;
use super::{Exit, Refused, EXIT_INTERRUPTED};
use anyhow::Context;
use clap::Args;
use mdr_sim::output::energy::BalanceDrift;
use mdr_sim::run::{SweepRun, SweepSummary};
use mdr_sim::scene::Problems;
use mdr_sim::{load_scene, run_scene, RunOptions};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::Duration;

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
    /// Replace the run(s) whose files are in the output folder (refused without it).
    #[arg(long)]
    pub overwrite: bool,
    /// Where the steps run (`gpu`: force-mode scenes whose walls are planes, boxes and exact
    /// cylinders, cones and orifice plates, on a device with 64-bit floats; it writes the frames, the kinetic and gravitational energy
    /// books, the headline and checkpoints that either device resumes: docs/gpu.md).
    #[arg(long, value_enum, default_value_t = DeviceArg::Cpu)]
    pub device: DeviceArg,
    /// With `--device gpu`: write no checkpoints (not even at the end or at an interrupt),
    /// whatever the scene's `checkpoint_interval_s`.
    #[arg(long)]
    pub no_checkpoints: bool,
    /// With `--device gpu`: neighbour slots per particle (1 to 64).
    #[arg(long, default_value_t = 16)]
    pub max_neighbours: u32,
    /// With `--device gpu`: particles per cell of the binning grid (1 to 64).
    #[arg(long, default_value_t = 12)]
    pub cell_capacity: u32,
}

/// Run `mdr-dem sim run`.
pub fn run(args: &RunArgs) -> anyhow::Result<()> {
    if args.device == DeviceArg::Cpu && args.no_checkpoints {
        return Err(Refused(
            "--no-checkpoints is for --device gpu; the CPU run always writes its checkpoints"
                .to_owned(),
        )
        .into());
    }
    let pool = args.threads.map(super::rayon_pool).transpose()?;
    let scene = match load_scene(&args.scene) {
        Ok(scene) => scene,
        Err(problems) => {
            print_problems(&problems);
            return Err(Refused(format!(
                "{} refused: {} error(s)",
                args.scene.display(),
                problems.errors().count()
            ))
            .into());
        }
    };
    for warning in &scene.warnings {
        eprintln!("{warning}");
    }
    let out = output_folder(args, &scene);
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
    if args.device == DeviceArg::Gpu {
        return super::sim_run_gpu::run(args, &scene, &out);
    }
    if args.check {
        let estimate = || mdr_sim::run::estimate_run_time(&scene, Duration::from_secs(1));
        let estimate = match &pool {
            Some(pool) => pool.install(estimate),
            None => estimate(),
        }?;
        eprintln!("{estimate}");
        return Ok(());
    }
    if let Some(checkpoint) = &args.resume {
        if let Err(e) = std::fs::metadata(checkpoint) {
            return Err(Refused(format!("checkpoint {}: {e}", checkpoint.display())).into());
        }
    }
    prepare_output_folder(args, &scene, &out)?;
    match pool {
        Some(pool) => pool.install(|| run_checked(args, &scene, &out)),
        None => run_checked(args, &scene, &out),
    }
}

/// `--out`, else the folder of the run a resumed checkpoint belongs to (the parent of its
/// `checkpoints/` folder), else `out/<run name>`.
pub(super) fn output_folder(args: &RunArgs, scene: &mdr_sim::Scene) -> PathBuf {
    if let Some(out) = &args.out {
        return out.clone();
    }
    args.resume
        .as_deref()
        .and_then(checkpoint_run_folder)
        .unwrap_or_else(|| PathBuf::from("out").join(&scene.name))
}

/// The run folder of a checkpoint in a `checkpoints/` folder.
fn checkpoint_run_folder(checkpoint: &Path) -> Option<PathBuf> {
    let dir = checkpoint.parent()?;
    (dir.file_name()? == "checkpoints").then(|| {
        dir.parent()
            .filter(|p| !p.as_os_str().is_empty())
            .map_or_else(|| PathBuf::from("."), Path::to_path_buf)
    })
}

/// The same folder, compared through the file system where both exist.
fn same_folder(a: &Path, b: &Path) -> bool {
    match (a.canonicalize(), b.canonicalize()) {
        (Ok(a), Ok(b)) => a == b,
        _ => a == b,
    }
}

/// An output folder holding the files of another run is refused unless `--overwrite` is given,
/// and then those runs' files are removed. A resumed run continues its own folder (the one its
/// checkpoint is in) without `--overwrite`; the run loop removes the files past the checkpoint.
pub(super) fn prepare_output_folder(
    args: &RunArgs,
    scene: &mdr_sim::Scene,
    out: &Path,
) -> anyhow::Result<()> {
    let own = args
        .resume
        .as_deref()
        .and_then(checkpoint_run_folder)
        .is_some_and(|dir| same_folder(&dir, out));
    if own {
        return Ok(());
    }
    let mut folders = vec![out.to_path_buf()];
    if let Some(sweep) = &scene.source.run.orifice_sweep_m {
        folders.extend((0..sweep.len()).map(|i| out.join(format!("{}_D{i}", scene.name))));
    }
    let held: Vec<(PathBuf, String)> = folders
        .iter()
        .flat_map(|dir| {
            mdr_sim::output::run_dir::runs_in(dir)
                .into_iter()
                .map(move |name| (dir.clone(), name))
        })
        .collect();
    if held.is_empty() {
        return Ok(());
    }
    if !args.overwrite {
        let names: Vec<String> = held
            .iter()
            .map(|(dir, name)| format!("`{name}` in {}", dir.display()))
            .collect();
        return Err(Refused(format!(
            "the output folder {} holds the files of another run ({}): pass --overwrite to replace \
             them, or choose another folder with --out{}",
            out.display(),
            names.join(", "),
            if args.resume.is_some() {
                " (a resumed run continues in the folder its checkpoint is in)"
            } else {
                ""
            }
        ))
        .into());
    }
    for (dir, name) in &held {
        mdr_sim::output::run_dir::remove_run(dir, name)
            .with_context(|| format!("removing run `{name}` from {}", dir.display()))?;
    }
    Ok(())
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
        .interrupt(interrupt)
        .estimate(true);
    if scene.source.run.orifice_sweep_m.is_some() {
        refuse_sweep_resume(args)?;
        let sweep = mdr_sim::run::run_orifice_sweep(scene, &options)?;
        return print_sweep(&sweep, |run, n| {
            sweep_interrupted(
                &scene.name,
                n,
                (run.time, run.step),
                run.checkpoint.as_deref(),
                "",
            )
        });
    }
    let summary = run_scene(scene, &options)?;
    let ran = summary.step - summary.start_step;
    let drift = BalanceDrift::of(&summary.energy).map_or_else(String::new, |d| {
        format!(
            "; energy balance drift {:.3e} J ({:.3} % of the energy scale: the largest of the initial kinetic and gravitational energies, the dissipated work and the wall work)",
            d.joules,
            100.0 * d.fraction
        )
    });
    if summary.stopped_early {
        eprintln!(
            "interrupted at t = {:.6e} s (step {}) after {ran} steps in {:.1} s{drift}; continue with:\n  {}",
            summary.time,
            summary.step,
            summary.wall_seconds,
            resume_command(args, out, summary.checkpoint.as_deref())
        );
        return Err(Exit(EXIT_INTERRUPTED).into());
    }
    println!(
        "done: t = {:.6e} s, {ran} steps in {:.1} s{}{drift}",
        summary.time,
        summary.wall_seconds,
        if summary.start_step > 0 {
            format!(" (from step {} to {})", summary.start_step, summary.step)
        } else {
            String::new()
        }
    );
    if !summary.headline.text.is_empty() {
        println!("{}", summary.headline.text);
    }
    println!(
        "ParaView: open {}",
        out.join(format!("{}.pvd", scene.name)).display()
    );
    Ok(())
}

/// A sweep is not resumed as a whole: `--resume` is refused for a scene with
/// `orifice_sweep_m`, on either device.
pub(super) fn refuse_sweep_resume(args: &RunArgs) -> anyhow::Result<()> {
    if args.resume.is_some() {
        return Err(Refused(
            "--resume continues one run of a sweep: write its diameter into orifice_diameter_m and its name `<name>_D<i>` (the folder its checkpoint is in) into name, remove orifice_sweep_m and resume that scene".to_owned(),
        )
        .into());
    }
    Ok(())
}

/// The message of a sweep interrupted in its run `n` (from 1) at `(time, step)`, `device` the
/// run's device as said after "the sweep" (empty on the CPU): how to resume that run alone. The
/// checkpoint's fingerprint holds the run's name, so the name is part of the recipe.
pub(super) fn sweep_interrupted(
    name: &str,
    n: usize,
    (time, step): (f64, u64),
    checkpoint: Option<&Path>,
    device: &str,
) -> String {
    let next = match checkpoint {
        Some(checkpoint) => format!(
            "a sweep is not resumed: write that run's diameter into orifice_diameter_m and its \
             name `{name}_D{}` into name, remove orifice_sweep_m and resume it (on either device) \
             with --resume {}",
            n - 1,
            shell_word(&checkpoint.display().to_string())
        ),
        None => "no checkpoint was written (--no-checkpoints): run the sweep again to start again"
            .to_owned(),
    };
    format!("interrupted at t = {time:.6e} s (step {step}) of run {n} of the sweep{device}; {next}")
}

/// A finished sweep, on either device: each run's headline and the sweep's table and fit on
/// stdout; if a run was interrupted, `interrupted(run, its number in the sweep)` on stderr and
/// the interrupt's exit status.
pub(super) fn print_sweep<R: SweepRun>(
    sweep: &SweepSummary<R>,
    interrupted: impl FnOnce(&R, usize) -> String,
) -> anyhow::Result<()> {
    for run in &sweep.runs {
        println!("{}", run.headline().text);
    }
    println!("{}", sweep.text);
    if let Some(run) = sweep.runs.iter().find(|r| r.stopped_early()) {
        eprintln!("{}", interrupted(run, sweep.runs.len()));
        return Err(Exit(EXIT_INTERRUPTED).into());
    }
    Ok(())
}

/// The command that continues an interrupted run, as it can be pasted into a shell: this
/// program as it was called, the scene, `--out`, the checkpoint, and the flags that shape the
/// run (`--threads`, `--quiet`).
fn resume_command(args: &RunArgs, out: &Path, checkpoint: Option<&Path>) -> String {
    let program = std::env::args()
        .next()
        .unwrap_or_else(|| "mdr-dem".to_owned());
    let mut words = vec![
        shell_word(&program),
        "sim run".to_owned(),
        shell_word(&args.scene.display().to_string()),
        "--out".to_owned(),
        shell_word(&out.display().to_string()),
        "--resume".to_owned(),
        checkpoint.map_or_else(
            || "<checkpoint>".to_owned(),
            |p| shell_word(&p.display().to_string()),
        ),
    ];
    if let Some(t) = args.threads {
        words.push(format!("--threads {t}"));
    }
    if args.quiet {
        words.push("--quiet".to_owned());
    }
    words.join(" ")
}

/// `word` quoted for a POSIX shell where it holds anything but letters, digits and `_./:=+-`.
pub(super) fn shell_word(word: &str) -> String {
    let plain = !word.is_empty()
        && word
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || "_./:=+-".contains(c));
    if plain {
        word.to_owned()
    } else {
        format!("'{}'", word.replace('\'', r"'\''"))
    }
}

fn print_problems(problems: &Problems) {
    for p in &problems.0 {
        eprintln!("{p}");
    }
}
