//! `mdr-dem sim run SCENE.toml --device gpu`: the scene on the GPU path
//! ([`mdr_gpu::run_gpu_scene`]) with the CPU run's output folder, frames, headline and progress;
//! the energy books the device keeps; no checkpoints. What the GPU path lacks is refused by name
//! before anything is written.

use super::sim_run::{prepare_output_folder, shell_word, RunArgs};
use super::{Exit, Refused, EXIT_INTERRUPTED};
use anyhow::Context;
use std::path::Path;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

/// Run a checked scene on the GPU (`--check`: only say whether it would run).
pub fn run(args: &RunArgs, scene: &mdr_sim::Scene, out: &Path) -> anyhow::Result<()> {
    if let Some(checkpoint) = &args.resume {
        return Err(Refused(format!(
            "--resume {}: the GPU run starts from the scene's set-up only (it reads no \
             checkpoint); continue the run on the CPU path (leave out --device gpu)",
            checkpoint.display()
        ))
        .into());
    }
    mdr_gpu::gpu_run_support(scene, args.no_checkpoints)?;
    if scene.source.run.max_energy_drift.is_none() {
        eprintln!(
            "--device gpu: the energy guard (max_energy_drift) is not applied: the GPU keeps no \
             dissipated works; the wall guard is checked at every sample"
        );
    }
    if args.check {
        eprintln!("--device gpu: the GPU path runs this scene");
        return Ok(());
    }
    let ctx = mdr_gpu::GpuContext::new()?;
    prepare_output_folder(args, scene, out)?;
    let interrupt = Arc::new(AtomicBool::new(false));
    {
        let flag = Arc::clone(&interrupt);
        ctrlc::set_handler(move || flag.store(true, Ordering::SeqCst))
            .context("installing the Ctrl-C handler")?;
    }
    let options = mdr_gpu::GpuRunOptions {
        out_dir: out.to_path_buf(),
        quiet: args.quiet,
        interrupt: Some(interrupt),
        without_checkpoints: args.no_checkpoints,
        device: mdr_gpu::GpuOptions {
            max_neighbours: args.max_neighbours,
            cell_capacity: args.cell_capacity,
            laws: None,
        },
        ..mdr_gpu::GpuRunOptions::default()
    };
    let summary = mdr_gpu::run_gpu_scene(&ctx, scene, &options)?;
    let adapter = format!(
        "on {}{}",
        summary.adapter,
        if ctx.is_cpu_device() {
            " (a CPU device)"
        } else {
            ""
        }
    );
    if summary.stopped_early {
        eprintln!(
            "interrupted at t = {:.6e} s (step {}) after {:.1} s {adapter}; the frames and series \
             up to there are in {} (the GPU run writes no checkpoint: rerun with\n  {} sim run {} \
             --out <folder>\nto start again)",
            summary.time,
            summary.step,
            summary.wall_seconds,
            out.display(),
            shell_word(
                &std::env::args()
                    .next()
                    .unwrap_or_else(|| "mdr-dem".to_owned())
            ),
            shell_word(&args.scene.display().to_string())
        );
        return Err(Exit(EXIT_INTERRUPTED).into());
    }
    println!(
        "done: t = {:.6e} s, {} steps in {:.1} s {adapter}",
        summary.time, summary.step, summary.wall_seconds
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
