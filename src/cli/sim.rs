//! `mdr-dem sim …`: simulations in rapier (drop/pair: issue 4; run: issue 5; ring: issue 8).
//! Each subcommand parses its flags here and calls a small function; the physics lives in the
//! library crates.

use anyhow::Context;
use clap::{Args, Subcommand, ValueEnum};
use mdr_contact::normal::MdrElastoPlastic;
use mdr_contact::Material;
use mdr_rapier::scenario::{CouplingMode, ImpactScene, SceneOutcome, Target};
use std::io::Write;
use std::path::Path;

/// `sim` subcommands.
#[derive(Debug, Subcommand)]
pub enum SimCommand {
    /// A sphere launched without gravity at a fixed half-space in rapier; prints
    /// `v0_m_per_s,e_n,steps`.
    Drop(DropArgs),
    /// Head-on impact of two free spheres in rapier (`--v0` is the relative approach speed);
    /// prints `v0_m_per_s,e_n,steps`.
    Pair(PairArgs),
    /// A planetary-ring shearing box (REBOUND's shearing sheet) with the MDR, Bridges or a
    /// constant restitution law.
    Ring(super::sim_ring::RingArgs),
    /// A granular scene from a TOML file (scenes/*.toml): VTK frames, energy books, plots,
    /// checkpoints; `--resume CHECKPOINT` continues a run.
    Run(super::sim_run::RunArgs),
}

/// Dispatch a `sim` subcommand.
pub fn run(cmd: SimCommand) -> anyhow::Result<()> {
    match cmd {
        SimCommand::Drop(args) => run_drop(&args),
        SimCommand::Pair(args) => run_pair(&args),
        SimCommand::Ring(args) => super::sim_ring::run_ring(&args),
        SimCommand::Run(args) => super::sim_run::run(&args),
    }
}

/// How the law enters rapier.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum ModeArg {
    /// Soft spheres: contact forces from the law, symplectic Euler.
    Force,
    /// Hard spheres: impulses with the law's restitution (physics hooks).
    Restitution,
}

impl From<ModeArg> for CouplingMode {
    fn from(m: ModeArg) -> Self {
        match m {
            ModeArg::Force => CouplingMode::Force,
            ModeArg::Restitution => CouplingMode::Restitution,
        }
    }
}

/// Material and law flags shared with `mdr-dem impact` (same names and defaults: the paper's
/// steel ball on a steel half-space).
#[derive(Debug, Clone, Args)]
pub struct SimMaterialArgs {
    /// Particle radius (m).
    #[arg(long, default_value_t = 0.635e-2)]
    pub radius: f64,
    /// Particle density (kg/m³).
    #[arg(long, default_value_t = 7800.0)]
    pub density: f64,
    /// Particle Young's modulus (Pa).
    #[arg(long, default_value_t = 2.0e11)]
    pub youngs: f64,
    /// Particle Poisson's ratio.
    #[arg(long, default_value_t = 0.286)]
    pub poisson: f64,
    /// Target Young's modulus (Pa); default: the particle's.
    #[arg(long)]
    pub target_youngs: Option<f64>,
    /// Target Poisson's ratio; default: the particle's.
    #[arg(long)]
    pub target_poisson: Option<f64>,
    /// Critical line load q_c (N/m), eq. (7).
    #[arg(long, default_value_t = 3.8e5)]
    pub qc: f64,
    /// Hardening ratio Θ/E*, eq. (12).
    #[arg(long, default_value_t = 0.37)]
    pub theta_ratio: f64,
    /// No plasticity (Hertz).
    #[arg(long)]
    pub elastic: bool,
    /// Friction coefficient μ.
    #[arg(long, default_value_t = 0.0)]
    pub mu: f64,
}

/// Flags of `sim drop`.
#[derive(Debug, Clone, Args)]
pub struct DropArgs {
    /// Impact speed(s) (m/s), comma-separated.
    #[arg(long, value_delimiter = ',', required = true)]
    pub v0: Vec<f64>,
    /// Coupling mode.
    #[arg(long, value_enum, default_value = "force")]
    pub mode: ModeArg,
    /// Angle of the impact velocity from the normal (degrees).
    #[arg(long, default_value_t = 0.0)]
    pub angle: f64,
    /// Force mode: time steps per Hertz contact time.
    #[arg(long, default_value_t = 1000.0)]
    pub steps_per_contact: f64,
    /// Output CSV file, `-` for standard output.
    #[arg(long, default_value = "-")]
    pub csv: String,
    #[command(flatten)]
    pub material: SimMaterialArgs,
}

/// Flags of `sim pair`.
#[derive(Debug, Clone, Args)]
pub struct PairArgs {
    /// Relative approach speed(s) (m/s), comma-separated.
    #[arg(long, value_delimiter = ',', required = true)]
    pub v0: Vec<f64>,
    /// Coupling mode.
    #[arg(long, value_enum, default_value = "force")]
    pub mode: ModeArg,
    /// Target sphere radius (m); default: the particle's.
    #[arg(long)]
    pub target_radius: Option<f64>,
    /// Target sphere density (kg/m³); default: the particle's.
    #[arg(long)]
    pub target_density: Option<f64>,
    /// Force mode: time steps per Hertz contact time.
    #[arg(long, default_value_t = 1000.0)]
    pub steps_per_contact: f64,
    /// Output CSV file, `-` for standard output.
    #[arg(long, default_value = "-")]
    pub csv: String,
    #[command(flatten)]
    pub material: SimMaterialArgs,
}

impl SimMaterialArgs {
    fn particle(&self) -> anyhow::Result<Material> {
        Ok(Material::new(self.youngs, self.poisson, self.density)?)
    }

    fn target(&self, density: f64) -> anyhow::Result<Material> {
        Ok(Material::new(
            self.target_youngs.unwrap_or(self.youngs),
            self.target_poisson.unwrap_or(self.poisson),
            density,
        )?)
    }

    fn model(&self) -> anyhow::Result<MdrElastoPlastic> {
        Ok(if self.elastic {
            MdrElastoPlastic::elastic()
        } else {
            MdrElastoPlastic::new(self.qc, self.theta_ratio)?
        })
    }

    fn scene(
        &self,
        target: Target,
        speed: f64,
        steps_per_contact: f64,
    ) -> anyhow::Result<ImpactScene> {
        Ok(ImpactScene {
            radius: self.radius,
            material: self.particle()?,
            target,
            model: self.model()?,
            friction: self.mu,
            speed,
            angle_degrees: 0.0,
            steps_per_contact,
        })
    }
}

fn run_drop(args: &DropArgs) -> anyhow::Result<()> {
    let m = &args.material;
    let target = Target::HalfSpace {
        material: m.target(m.density)?,
    };
    let rows = args
        .v0
        .iter()
        .map(|&v| {
            let scene = ImpactScene {
                angle_degrees: args.angle,
                ..m.scene(target, v, args.steps_per_contact)?
            };
            Ok(scene.run(args.mode.into())?)
        })
        .collect::<anyhow::Result<Vec<_>>>()?;
    write_csv(&args.csv, &rows)
}

fn run_pair(args: &PairArgs) -> anyhow::Result<()> {
    let m = &args.material;
    let target = Target::Sphere {
        radius: args.target_radius.unwrap_or(m.radius),
        material: m.target(args.target_density.unwrap_or(m.density))?,
    };
    let rows = args
        .v0
        .iter()
        .map(|&v| {
            Ok(m.scene(target, v, args.steps_per_contact)?
                .run(args.mode.into())?)
        })
        .collect::<anyhow::Result<Vec<_>>>()?;
    write_csv(&args.csv, &rows)
}

/// Write `v0_m_per_s,e_n,steps` rows to `path` (atomically: temp file + rename) or stdout.
fn write_csv(path: &str, rows: &[SceneOutcome]) -> anyhow::Result<()> {
    let mut text = String::from("v0_m_per_s,e_n,steps\n");
    for r in rows {
        text.push_str(&format!(
            "{},{},{}\n",
            r.speed, r.normal_restitution, r.steps
        ));
    }
    if path == "-" {
        std::io::stdout().write_all(text.as_bytes())?;
        return Ok(());
    }
    let path = Path::new(path);
    let tmp = path.with_extension("csv.tmp");
    std::fs::write(&tmp, text).with_context(|| format!("writing {}", tmp.display()))?;
    std::fs::rename(&tmp, path).with_context(|| format!("renaming to {}", path.display()))?;
    Ok(())
}
