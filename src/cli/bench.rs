//! `mdr-dem bench …`: throughput benchmarks. `bench bed` runs the neighbour-list path on the
//! settled 10,000-sphere bed of `benches/lammps/` with the system of that directory's `in.bench`
//! (`hertzhist`), or with the MDR law (the loop is `mdr_rapier::neighbour_list::bed::bench_bed`, which
//! Python's `mdr_dem.bench_bed` runs too); see `docs/performance.md`.

use anyhow::{anyhow, bail, Context};
use clap::{Args, Subcommand, ValueEnum};
use mdr_contact::params::Declared;
use mdr_contact::rolling::EpsdRolling;
use mdr_rapier::neighbour_list::bed::{
    bench_bed, peak_rss_mb, process_cpu_seconds, reference_data, settled_bed, Bed, BedSpec,
    BenchFigures, BenchLaw, BenchSettings, BenchValue,
};
use std::path::{Path, PathBuf};
use std::time::Instant;

/// `bench` subcommands.
#[derive(Debug, Subcommand)]
pub enum BenchCommand {
    /// Throughput of the neighbour-list path on a settled bed (LAMMPS `gran/hertz/history`
    /// system: `kn = 2e5`, `γn = 50`, `μ = 0.5`, floor `z = 0`, x/y periodic, `g = 1`,
    /// `dt = 1e-4`): particle-steps per second, ms per step, contacts per particle, peak memory.
    Bed(BedArgs),
    /// Generate a settled bed by lattice + settling and write it as a LAMMPS data file.
    MakeBed(MakeBedArgs),
    /// Throughput of a scene file's steps (forces, energy books, headline tracker, integration;
    /// no output files) after untimed warm-up steps: particle-steps per second (wall and CPU),
    /// ms per step, contacts per particle, peak memory.
    Scene(SceneArgs),
}

/// Flags of `bench scene`.
#[derive(Debug, Args)]
pub struct SceneArgs {
    /// The scene file (TOML).
    pub scene: PathBuf,
    /// Timed steps.
    #[arg(long, default_value_t = 1_000)]
    pub steps: u64,
    /// Untimed steps before the timed ones (the first neighbour-list build, allocations).
    #[arg(long, default_value_t = 100)]
    pub warmup: u64,
    /// Worker threads.
    #[arg(long, default_value_t = 1)]
    pub threads: usize,
    /// Start from a checkpoint written by `sim run` of the same scene (a settled bed, a
    /// discharge under way) instead of the scene's set-up.
    #[arg(long)]
    pub resume: Option<PathBuf>,
    /// Print one JSON object instead of text.
    #[arg(long)]
    pub json: bool,
    /// Where the steps run (`gpu`: force-mode scenes whose walls are planes, boxes and exact
    /// cylinders, cones and orifice plates, on a device with 64-bit floats; docs/gpu.md).
    #[arg(long, value_enum, default_value_t = DeviceArg::Cpu)]
    pub device: DeviceArg,
    /// With `--device gpu`: neighbour slots per particle (1 to 64).
    #[arg(long, default_value_t = 16)]
    pub max_neighbours: u32,
    /// With `--device gpu`: particles per cell of the binning grid (1 to 64).
    #[arg(long, default_value_t = 12)]
    pub cell_capacity: u32,
}

/// Contact law of `bench bed`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum LawArg {
    /// Hertz (`E* = 1.5e5` ⇔ `kn = 2e5`).
    Hertz,
    /// The MDR elasto-plastic law (`q_c` from `--qc`, `Θ = 0.37 E*`).
    Mdr,
    /// Thornton's elastic–perfectly-plastic law (`p_y` from `--yield-stress`).
    Thornton,
    /// The adhesive MDR law (`q_c` from `--qc`, `Θ = 0.37 E*`, `Δγ` from
    /// `--work-of-adhesion`).
    AdhesiveMdr,
}

/// Where `bench bed` steps the bed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum DeviceArg {
    /// The neighbour-list stepper on `--threads` CPU threads.
    Cpu,
    /// wgpu compute shaders in f64 (a Vulkan, Metal or DX12 device with 64-bit floats; on
    /// Linux without a GPU, Mesa's lavapipe: docs/gpu.md).
    Gpu,
}

/// Flags of `bench bed`.
#[derive(Debug, Args)]
pub struct BedArgs {
    /// LAMMPS data file of the bed (default: the repository's `benches/lammps/settled.data`).
    #[arg(long)]
    pub data: Option<PathBuf>,
    /// Contact law.
    #[arg(long, value_enum, default_value_t = LawArg::Hertz)]
    pub law: LawArg,
    /// Timed steps.
    #[arg(long, default_value_t = 10_000)]
    pub steps: usize,
    /// Untimed warm-up steps (as `nwarm` of in.bench).
    #[arg(long, default_value_t = 2_000)]
    pub warmup: usize,
    /// Worker threads.
    #[arg(long, default_value_t = 1)]
    pub threads: usize,
    /// Repeat the bed `tile × tile` times in x and y (scaling runs; at most 10⁸ spheres in all).
    #[arg(long, default_value_t = 1)]
    pub tile: usize,
    /// MDR critical line load `q_c` (force/length, reduced units) for `--law mdr` and
    /// `--law adhesive-mdr`.
    #[arg(long, allow_negative_numbers = true, default_value_t = 10.0)]
    pub qc: f64,
    /// Thornton's limiting contact pressure `p_y` (reduced units) for `--law thornton`.
    #[arg(long, allow_negative_numbers = true, default_value_t = 1000.0)]
    pub yield_stress: f64,
    /// Work of adhesion `Δγ` (energy per area, reduced units) for `--law adhesive-mdr`.
    #[arg(long, allow_negative_numbers = true, default_value_t = 2.0)]
    pub work_of_adhesion: f64,
    /// Rolling resistance coefficient `μ_r` (elastic–plastic spring rolling resistance,
    /// `EpsdRolling`), with any law; help and flag name as `EpsdRolling` declares them.
    #[arg(long, allow_negative_numbers = true, value_name = "VALUE",
        help = format!("{}; with any law [default: off]", EpsdRolling::DECLARATION.params[0].help()))]
    pub rolling: Option<f64>,
    /// Neighbour skin (as LAMMPS `neighbor 0.1 bin`).
    #[arg(long, default_value_t = 0.1)]
    pub skin: f64,
    /// Do not integrate particle orientations (LAMMPS `atom_style sphere` keeps none; sphere
    /// trajectories are unchanged).
    #[arg(long)]
    pub no_orientation: bool,
    /// Keep no friction and damping work books in the pair histories (LAMMPS keeps none;
    /// trajectories are unchanged, see `state_checksum`).
    #[arg(long)]
    pub no_work_books: bool,
    /// Print one JSON object instead of text.
    #[arg(long)]
    pub json: bool,
    /// Where the steps run (`gpu`: docs/gpu.md).
    #[arg(long, value_enum, default_value_t = DeviceArg::Cpu)]
    pub device: DeviceArg,
    /// With `--device gpu`: also run the CPU path (on `--threads` threads) on the same bed for
    /// the same steps, and report the largest position difference after the run
    /// (`max_position_difference_diameters`).
    #[arg(long)]
    pub compare_cpu: bool,
    /// With `--device gpu`: neighbour slots per particle (1 to 64; the reference bed has at
    /// most 11 neighbours within the cutoff).
    #[arg(long, default_value_t = 16)]
    pub max_neighbours: u32,
}

/// Flags of `bench make-bed`.
#[derive(Debug, Args)]
pub struct MakeBedArgs {
    /// Number of spheres (at most 10⁸).
    #[arg(long, default_value_t = 1000)]
    pub count: usize,
    /// Settling steps (dt = 1e-4).
    #[arg(long, default_value_t = 40_000)]
    pub settle_steps: usize,
    /// Worker threads.
    #[arg(long, default_value_t = 2)]
    pub threads: usize,
    /// Seed of the lattice jitter.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Output LAMMPS data file.
    #[arg(long)]
    pub out: PathBuf,
}

/// Dispatch a `bench` subcommand.
pub fn run(cmd: BenchCommand) -> anyhow::Result<()> {
    match cmd {
        BenchCommand::Bed(args) => run_bed(&args),
        BenchCommand::Scene(args) => run_scene_bench(&args),
        BenchCommand::MakeBed(args) => {
            let pool = super::rayon_pool(args.threads)?;
            let spec = BedSpec {
                count: args.count,
                settle_steps: args.settle_steps,
                seed: args.seed,
                ..BedSpec::default()
            };
            let bed = pool.install(|| settled_bed(&spec))?;
            bed.write_lammps(&args.out)?;
            println!("wrote {} spheres to {}", bed.len(), args.out.display());
            Ok(())
        }
    }
}

fn run_bed(args: &BedArgs) -> anyhow::Result<()> {
    let path = match &args.data {
        Some(p) => p.clone(),
        None => reference_data(Path::new(env!("CARGO_MANIFEST_DIR")))
            .map_err(|e| anyhow::anyhow!("{e}; pass --data PATH"))?,
    };
    let settings = BenchSettings {
        law: bench_law(args),
        rolling: args.rolling,
        steps: args.steps,
        warmup: args.warmup,
        threads: args.threads,
        tile: args.tile,
        skin: args.skin,
        orientation: !args.no_orientation,
        work_books: !args.no_work_books,
    };
    check_law_flags(&settings)?;
    settings.validate()?;
    let bed = Bed::read_lammps(&path).with_context(|| format!("reading {}", path.display()))?;
    if args.device == DeviceArg::Gpu {
        return run_bed_gpu(args, &bed, &settings);
    }
    if args.compare_cpu {
        bail!("--compare-cpu compares the GPU path with the CPU path: it needs --device gpu");
    }
    let figures = bench_bed(&bed, &settings)?;
    if args.json {
        let device = [("device", BenchValue::Text("cpu"))];
        println!("{}", serde_json::to_string(&BedJson(&figures, &device))?);
    } else {
        println!(
            "bench bed: {} spheres, law {}, {} threads, {} timed steps after {} warm-up steps{}",
            figures.particles,
            figures.law,
            figures.threads,
            figures.steps,
            args.warmup,
            if figures.orientation {
                ""
            } else {
                ", orientations not integrated"
            }
        );
        println!(
            "  {:.3} M particle-steps/s, {:.3} ms/step",
            figures.particle_steps_per_s / 1e6,
            figures.ms_per_step
        );
        println!(
            "  {:.3} M particle-steps per CPU second ({:.2} CPU s in {:.2} s)",
            figures.particle_steps_per_cpu_s / 1e6,
            figures.cpu_seconds,
            figures.wall_seconds
        );
        println!(
            "  {:.3} contacts per particle (sphere-sphere, as LAMMPS contact/atom), {} floor contacts",
            figures.contacts_per_particle, figures.floor_contacts
        );
        if figures.law != "hertz" {
            println!(
                "  {:.1} % of sphere-sphere contacts plastic (largest overlap beyond the yield overlap)",
                100.0 * figures.plastic_contact_fraction
            );
        }
        println!(
            "  peak RSS {:.1} MB; stepper buffers {:.0} bytes per particle; {} neighbour-list builds",
            figures.peak_rss_mb, figures.stepper_bytes_per_particle, figures.rebuilds
        );
        println!("  final state checksum {}", figures.state_checksum);
    }
    Ok(())
}

/// The normal law `bench bed` runs, with its parameters from the flags.
fn bench_law(args: &BedArgs) -> BenchLaw {
    match args.law {
        LawArg::Hertz => BenchLaw::Hertz,
        LawArg::Mdr => BenchLaw::Mdr { qc: args.qc },
        LawArg::Thornton => BenchLaw::Thornton {
            yield_pressure: args.yield_stress,
        },
        LawArg::AdhesiveMdr => BenchLaw::AdhesiveMdr {
            qc: args.qc,
            work_of_adhesion: args.work_of_adhesion,
        },
    }
}

/// Check the law's and the rolling resistance's parameters, naming the flag that set a bad one.
fn check_law_flags(settings: &BenchSettings) -> anyhow::Result<()> {
    let named = |flag: &str, law: BenchLaw| law.validate().map_err(|e| anyhow!("{flag}: {e}"));
    match settings.law {
        BenchLaw::Hertz => {}
        BenchLaw::Mdr { .. } => named("--qc", settings.law)?,
        BenchLaw::Thornton { .. } => named("--yield-stress", settings.law)?,
        BenchLaw::AdhesiveMdr { qc, .. } => {
            named("--qc", BenchLaw::Mdr { qc })?;
            named("--work-of-adhesion", settings.law)?;
        }
    }
    if let Some(mu) = settings.rolling {
        let rolling_only = BenchSettings {
            law: BenchLaw::Hertz,
            rolling: Some(mu),
            ..BenchSettings::default()
        };
        rolling_only
            .validate()
            .map_err(|e| anyhow!("--rolling: {e}"))?;
    }
    Ok(())
}

/// `bench bed --device gpu`: the bed on the device, optionally compared with the CPU path.
fn run_bed_gpu(args: &BedArgs, bed: &Bed, settings: &BenchSettings) -> anyhow::Result<()> {
    let laws = mdr_gpu::GpuLaws::of(settings);
    let ctx = mdr_gpu::GpuContext::new()?;
    let options = mdr_gpu::GpuOptions {
        max_neighbours: args.max_neighbours,
        laws: Some(laws),
        ..mdr_gpu::GpuOptions::default()
    };
    let (gpu, state) = mdr_gpu::bench_bed_gpu(&ctx, bed, settings, &options)?;
    let difference = if args.compare_cpu {
        let cpu = mdr_gpu::cpu_reference_run_with(
            bed,
            settings,
            &laws,
            settings.warmup + settings.steps,
        )?;
        Some(mdr_gpu::differences(&state, &cpu))
    } else {
        None
    };
    let figures = &gpu.figures;
    if args.json {
        let mut extra = vec![("device", BenchValue::Text("gpu"))];
        extra.extend(gpu.fields());
        if let Some(d) = &difference {
            extra.push((
                "max_position_difference_diameters",
                BenchValue::Real(d.position_diameters),
            ));
            extra.push(("max_velocity_difference", BenchValue::Real(d.velocity)));
        }
        println!("{}", serde_json::to_string(&BedJson(figures, &extra))?);
        return Ok(());
    }
    println!(
        "bench bed --device gpu: {} spheres, law {}, {} timed steps after {} warm-up steps on {}{}",
        figures.particles,
        figures.law,
        figures.steps,
        args.warmup,
        gpu.adapter,
        if gpu.cpu_device {
            " (a CPU device: correct, but no measure of a GPU's speed)"
        } else {
            ""
        }
    );
    println!(
        "  {:.3} M particle-steps/s, {:.3} ms/step",
        figures.particle_steps_per_s / 1e6,
        figures.ms_per_step
    );
    println!(
        "  {:.3} contacts per particle, {} floor contacts; {} neighbour-list builds",
        figures.contacts_per_particle, figures.floor_contacts, figures.rebuilds
    );
    println!(
        "  device memory {:.0} bytes per sphere ({} neighbour slots per sphere)",
        gpu.device_bytes_per_particle, gpu.max_neighbours
    );
    println!("  final state checksum {}", figures.state_checksum);
    if let Some(d) = &difference {
        println!(
            "  against the CPU path after {} steps: largest position difference {:.3e} diameters, \
             velocity {:.3e}, {} touching pairs ({} unmatched)",
            settings.warmup + settings.steps,
            d.position_diameters,
            d.velocity,
            d.pairs,
            d.unmatched_pairs
        );
    }
    Ok(())
}

/// `bench bed --json`: the figures as one object, with the keys and in the order of
/// [`BenchFigures::fields`], then the extra fields (`device`, the GPU's).
struct BedJson<'a>(&'a BenchFigures, &'a [(&'static str, BenchValue<'a>)]);

impl serde::Serialize for BedJson<'_> {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeMap;
        let fields = self.0.fields();
        let mut map = serializer.serialize_map(Some(fields.len() + self.1.len()))?;
        for (key, value) in fields.into_iter().chain(self.1.iter().cloned()) {
            match value {
                BenchValue::Real(x) => map.serialize_entry(key, &x)?,
                BenchValue::Count(n) => map.serialize_entry(key, &n)?,
                BenchValue::Flag(b) => map.serialize_entry(key, &b)?,
                BenchValue::Text(t) => map.serialize_entry(key, t)?,
            }
        }
        map.end()
    }
}

/// Figures of one `bench scene` run.
#[derive(Debug, serde::Serialize)]
struct SceneFigures {
    particle_steps_per_s: f64,
    /// Particle-steps per CPU second of the timed loop (all threads, their busy waits between
    /// the parallel passes included).
    cpu_particle_steps_per_s: f64,
    ms_per_step: f64,
    /// Sphere–sphere contacts per particle at the last step (`2 × pairs / particles`, as
    /// LAMMPS `contact/atom` and `bench bed`).
    contacts_per_particle: f64,
    /// Sphere–wall contacts at the last step.
    wall_contacts: usize,
    peak_rss_mb: f64,
    threads: usize,
    particles: usize,
    steps: u64,
    warmup: u64,
    cpu_seconds: f64,
    wall_seconds: f64,
    /// `"neighbour_list"` or `"rapier"` (`force_path`), or `"restitution"`.
    path: &'static str,
    /// Step the run started from (0, or the checkpoint's step with `--resume`).
    start_step: u64,
    /// The largest sphere speed at the last step (m/s; neighbour-list path): with the skin,
    /// what sets how often the lists are rebuilt.
    max_speed_m_per_s: Option<f64>,
    /// Neighbour-list builds during the timed steps (neighbour-list path).
    rebuilds: Option<u64>,
    /// Listed sphere pairs per particle at the last step (`2 × listed pairs / particles`,
    /// neighbour-list path): what the pair loop tests each step, touching or not.
    listed_pairs_per_particle: Option<f64>,
    /// Wall time per particle-step of each part of the timed steps (ns; neighbour-list path),
    /// as LAMMPS's timing breakdown.
    breakdown_ns_per_particle_step: Option<Breakdown>,
    scene: String,
    /// `"cpu"` or `"gpu"`.
    device: &'static str,
    /// The GPU adapter (`--device gpu`).
    adapter: Option<String>,
    /// Bytes of device buffers per sphere (`--device gpu`).
    device_bytes_per_particle: Option<f64>,
}

/// Wall time per particle-step of each part of a neighbour-list step (ns): the stepper's
/// [`mdr_sim::run::StepTimings`], and the rest of the step.
#[derive(Debug, serde::Serialize)]
struct Breakdown {
    /// Sphere–sphere pairs with the per-particle sums (LAMMPS `Pair`).
    pairs: f64,
    /// Neighbour-list builds (LAMMPS `Neigh`).
    builds: f64,
    /// Particle–wall pairs.
    surfaces: f64,
    /// Integration of the spheres.
    integration: f64,
    /// Reactions on rapier bodies and rapier's step.
    rapier: f64,
    /// The rest: scene events, energy books, the headline tracker.
    rest: f64,
}

impl Breakdown {
    fn new(timings: &mdr_sim::run::StepTimings, wall_seconds: f64, particle_steps: f64) -> Self {
        let per = |d: std::time::Duration| 1e9 * d.as_secs_f64() / particle_steps;
        Self {
            pairs: per(timings.pairs),
            builds: per(timings.builds),
            surfaces: per(timings.surfaces),
            integration: per(timings.integration),
            rapier: per(timings.rapier),
            rest: (1e9 * wall_seconds / particle_steps - per(timings.total())).max(0.0),
        }
    }
}

/// `bench scene`'s figures: the scene's warm-up and timed steps on the current thread.
fn time_scene(args: &SceneArgs, scene: &mdr_sim::scene::Scene) -> anyhow::Result<SceneFigures> {
    let mut steps = match &args.resume {
        Some(path) => mdr_sim::run::SceneSteps::resume(scene, path)?,
        None => mdr_sim::run::SceneSteps::new(scene)?,
    };
    let start_step = steps.steps_done();
    for _ in 0..args.warmup {
        steps.step()?;
    }
    let rebuilds0 = steps.rebuilds();
    steps.time_steps(true);
    let cpu0 = process_cpu_seconds();
    let start = Instant::now();
    for _ in 0..args.steps {
        steps.step()?;
    }
    let seconds = start.elapsed().as_secs_f64();
    let cpu_seconds = match (cpu0, process_cpu_seconds()) {
        (Some(a), Some(b)) => b - a,
        _ => f64::NAN,
    };
    let n = steps.particles();
    let contacts = steps.contacts();
    let work = (n as u64 * args.steps) as f64;
    Ok(SceneFigures {
        particle_steps_per_s: work / seconds,
        cpu_particle_steps_per_s: work / cpu_seconds,
        ms_per_step: 1e3 * seconds / args.steps as f64,
        contacts_per_particle: 2.0 * contacts.sphere as f64 / n as f64,
        wall_contacts: contacts.wall,
        peak_rss_mb: peak_rss_mb(),
        threads: args.threads,
        particles: n,
        steps: args.steps,
        warmup: args.warmup,
        cpu_seconds,
        wall_seconds: seconds,
        path: match (scene.coupling, scene.force_path) {
            (mdr_sim::scene::CouplingMode::Restitution, _) => "restitution",
            (_, mdr_sim::scene::ForcePath::Rapier) => "rapier",
            (_, mdr_sim::scene::ForcePath::NeighbourList) => "neighbour_list",
        },
        start_step,
        max_speed_m_per_s: steps.max_speed(),
        rebuilds: steps
            .rebuilds()
            .zip(rebuilds0)
            .map(|(now, before)| now - before),
        listed_pairs_per_particle: steps.listed_pairs().map(|p| 2.0 * p as f64 / n as f64),
        breakdown_ns_per_particle_step: steps
            .step_timings()
            .map(|t| Breakdown::new(&t, seconds, work)),
        scene: scene.name.clone(),
        device: "cpu",
        adapter: None,
        device_bytes_per_particle: None,
    })
}

/// `bench scene --device gpu`'s figures: the scene's warm-up and timed steps on the device
/// (the timed steps end when the device has finished them).
fn time_scene_gpu(args: &SceneArgs, scene: &mdr_sim::scene::Scene) -> anyhow::Result<SceneFigures> {
    if args.resume.is_some() {
        bail!(
            "--resume: the GPU path starts from the scene's set-up only (it reads no checkpoint); \
             leave out --resume or use --device cpu"
        );
    }
    let ctx = mdr_gpu::GpuContext::new()?;
    let options = mdr_gpu::GpuOptions {
        max_neighbours: args.max_neighbours,
        cell_capacity: args.cell_capacity,
        laws: None,
    };
    let mut gpu = mdr_gpu::GpuScene::new(&ctx, scene, &options)?;
    let as_steps = |n: u64, flag: &str| {
        usize::try_from(n).map_err(|_| anyhow!("{flag} = {n} is outside the allowed range"))
    };
    gpu.step(as_steps(args.warmup, "--warmup")?)?;
    let rebuilds0 = gpu.rebuilds()?;
    let cpu0 = process_cpu_seconds();
    let start = Instant::now();
    gpu.step(as_steps(args.steps, "--steps")?)?;
    let seconds = start.elapsed().as_secs_f64();
    let cpu_seconds = match (cpu0, process_cpu_seconds()) {
        (Some(a), Some(b)) => b - a,
        _ => f64::NAN,
    };
    let rebuilds = gpu.rebuilds()? - rebuilds0;
    let state = gpu.state()?;
    let n = gpu.len();
    let work = (n as u64 * args.steps) as f64;
    let listed = state.pairs.len();
    let touching = state.pairs.iter().filter(|p| p.active).count();
    Ok(SceneFigures {
        particle_steps_per_s: work / seconds,
        cpu_particle_steps_per_s: work / cpu_seconds,
        ms_per_step: 1e3 * seconds / args.steps as f64,
        contacts_per_particle: 2.0 * touching as f64 / n as f64,
        wall_contacts: state.floor.iter().filter(|w| w.is_some()).count(),
        peak_rss_mb: peak_rss_mb(),
        threads: 1,
        particles: n,
        steps: args.steps,
        warmup: args.warmup,
        cpu_seconds,
        wall_seconds: seconds,
        path: "neighbour_list",
        start_step: 0,
        max_speed_m_per_s: Some(state.linvel.iter().map(|v| v.norm()).fold(0.0, f64::max)),
        rebuilds: Some(rebuilds),
        listed_pairs_per_particle: Some(2.0 * listed as f64 / n as f64),
        breakdown_ns_per_particle_step: None,
        scene: scene.name.clone(),
        device: "gpu",
        adapter: Some(format!(
            "{}{}",
            ctx.adapter_name(),
            if ctx.is_cpu_device() {
                " (a CPU device: correct, but no measure of a GPU's speed)"
            } else {
                ""
            }
        )),
        device_bytes_per_particle: Some(gpu.device_bytes() as f64 / n as f64),
    })
}

/// Below this many sphere contacts per particle, `bench scene` warns that it timed free flight.
const FEW_CONTACTS_PER_PARTICLE: f64 = 0.5;

fn run_scene_bench(args: &SceneArgs) -> anyhow::Result<()> {
    if args.steps == 0 {
        bail!("--steps = 0 is outside the allowed range [1, inf) (timed steps)");
    }
    let pool = super::rayon_pool(args.threads)?;
    let scene = mdr_sim::scene::load_scene(&args.scene).map_err(|p| anyhow::anyhow!("{p}"))?;
    let figures = match args.device {
        DeviceArg::Gpu => time_scene_gpu(args, &scene)?,
        // The run's steps with the pool's other threads awake between passes, as `sim run`
        // has them.
        DeviceArg::Cpu => pool.install(|| {
            mdr_rapier::neighbour_list::with_workers_awake(|| time_scene(args, &scene))
        })?,
    };
    if figures.contacts_per_particle < FEW_CONTACTS_PER_PARTICLE {
        eprintln!(
            "warning: the timed steps had {:.3} sphere contacts per particle: they time spheres in \
             free flight, not a granular flow (a settled bed has about 6); start the timing later \
             with --warmup, or from a checkpoint of the flowing state with --resume",
            figures.contacts_per_particle
        );
    }
    if args.json {
        println!("{}", serde_json::to_string(&figures)?);
    } else {
        match &figures.adapter {
            Some(adapter) => println!(
                "bench scene {} --device gpu: {} spheres, {} path, {} timed steps after {} warm-up steps from step {} on {adapter}",
                figures.scene,
                figures.particles,
                figures.path,
                figures.steps,
                figures.warmup,
                figures.start_step
            ),
            None => println!(
                "bench scene {}: {} spheres, {} path, {} threads, {} timed steps after {} warm-up steps from step {}",
                figures.scene,
                figures.particles,
                figures.path,
                figures.threads,
                figures.steps,
                figures.warmup,
                figures.start_step
            ),
        }
        println!(
            "  {:.3} M particle-steps/s, {:.3} ms/step",
            figures.particle_steps_per_s / 1e6,
            figures.ms_per_step
        );
        println!(
            "  {:.3} M particle-steps per CPU second ({:.2} CPU s in {:.2} s)",
            figures.cpu_particle_steps_per_s / 1e6,
            figures.cpu_seconds,
            figures.wall_seconds
        );
        println!(
            "  {:.3} contacts per particle (sphere-sphere), {} wall contacts",
            figures.contacts_per_particle, figures.wall_contacts
        );
        if let Some(listed) = figures.listed_pairs_per_particle {
            println!("  {listed:.3} listed pairs per particle (touching or within the skin)");
        }
        match (figures.rebuilds, figures.max_speed_m_per_s) {
            (Some(r), Some(v)) => println!(
                "  peak RSS {:.1} MB; {r} neighbour-list builds; largest sphere speed {v:.3} m/s",
                figures.peak_rss_mb
            ),
            (Some(r), None) => println!(
                "  peak RSS {:.1} MB; {r} neighbour-list builds",
                figures.peak_rss_mb
            ),
            (None, _) => println!("  peak RSS {:.1} MB", figures.peak_rss_mb),
        }
        if let Some(bytes) = figures.device_bytes_per_particle {
            println!("  device memory {bytes:.0} bytes per sphere");
        }
        if let Some(b) = &figures.breakdown_ns_per_particle_step {
            println!(
                "  ns per particle-step: sphere pairs {:.1}, neighbour builds {:.1}, walls {:.1}, \
                 integration {:.1}, rapier {:.1}, rest {:.1}",
                b.pairs, b.builds, b.surfaces, b.integration, b.rapier, b.rest
            );
        }
    }
    Ok(())
}
