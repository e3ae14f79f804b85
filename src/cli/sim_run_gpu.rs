//! `mdr-dem sim run SCENE.toml --device gpu`: the scene on the GPU path
//! ([`mdr_gpu::run_gpu_scene`]) with the CPU run's output folder, frames, headline and progress;
//! the CPU run's energy books and energy guard; checkpoints in the CPU run's format, and `--resume` from a
//! checkpoint of either device; a hopper's orifice sweep as the CPU runs it, each run on the GPU.
//! What the GPU path lacks is refused by name before anything is written.

use super::sim_run::{
    prepare_output_folder, print_sweep, refuse_sweep_resume, shell_word, sweep_interrupted, RunArgs,
};
use super::{Exit, Refused, EXIT_INTERRUPTED};
use anyhow::Context;
use std::path::Path;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

/// Run a checked scene on the GPU (`--check`: only say whether it would run).
pub fn run(args: &RunArgs, scene: &mdr_sim::Scene, out: &Path) -> anyhow::Result<()> {
    mdr_gpu::gpu_run_support(scene)?;
    if args.check {
        eprintln!("--device gpu: the GPU path runs this scene");
        return Ok(());
    }
    let sweep = scene.source.run.orifice_sweep_m.is_some();
    if sweep {
        refuse_sweep_resume(args)?;
    }
    if let Some(checkpoint) = &args.resume {
        if let Err(e) = std::fs::metadata(checkpoint) {
            return Err(Refused(format!("checkpoint {}: {e}", checkpoint.display())).into());
        }
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
        resume: args.resume.clone(),
        device: mdr_gpu::GpuOptions {
            max_neighbours: args.max_neighbours,
            cell_capacity: args.cell_capacity,
            laws: None,
        },
        ..mdr_gpu::GpuRunOptions::default()
    };
    let adapter = format!(
        "on {}{}",
        ctx.adapter_name(),
        if ctx.is_cpu_device() {
            " (a CPU device)"
        } else {
            ""
        }
    );
    if sweep {
        let sweep = mdr_gpu::run_gpu_orifice_sweep(&ctx, scene, &options)?;
        return print_sweep(&sweep, |run, n| {
            sweep_interrupted(
                &scene.name,
                n,
                (run.time, run.step),
                run.checkpoint.as_deref(),
                &format!(" {adapter}"),
            )
        });
    }
    let summary = mdr_gpu::run_gpu_scene(&ctx, scene, &options)?;
    if summary.stopped_early {
        let program = shell_word(
            &std::env::args()
                .next()
                .unwrap_or_else(|| "mdr-dem".to_owned()),
        );
        let scene_file = shell_word(&args.scene.display().to_string());
        let next = match &summary.checkpoint {
            Some(checkpoint) => format!(
                "continue with (on either device):\n  {program} sim run {scene_file} --out {} \
                 --resume {} --device gpu",
                shell_word(&out.display().to_string()),
                shell_word(&checkpoint.display().to_string())
            ),
            None => format!(
                "no checkpoint was written (--no-checkpoints): rerun with\n  {program} sim run \
                 {scene_file} --out <folder>\nto start again"
            ),
        };
        eprintln!(
            "interrupted at t = {:.6e} s (step {}) after {:.1} s {adapter}; the frames and series \
             up to there are in {}; {next}",
            summary.time,
            summary.step,
            summary.wall_seconds,
            out.display(),
        );
        return Err(Exit(EXIT_INTERRUPTED).into());
    }
    println!(
        "done: t = {:.6e} s, {} steps in {:.1} s {adapter}{}",
        summary.time,
        summary.step - summary.start_step,
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
