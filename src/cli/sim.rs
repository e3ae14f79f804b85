//! `mdr-dem sim …`: simulations in rapier: one impact (drop, pair), scenes (run), ring (ring).
//! Each subcommand parses its flags here and calls a small function; the physics lives in the
//! library crates.

use super::impact::{
    contact_error, friction, materials, normal_laws, registered_law, CommonArgs, MethodName,
};
use anyhow::{anyhow, bail, Context};
use clap::{Args, Subcommand, ValueEnum};
use mdr_contact::normal::{AdhesiveMdr, MdrElastoPlastic};
use mdr_contact::{ContactPair, Material};
use mdr_impact::NormalSpec;
use mdr_rapier::scenario::{CouplingMode, ImpactScene, SceneLaw, SceneOutcome, Target};
use mdr_rapier::CouplingError;
use std::io::Write;
use std::path::Path;

/// `sim` subcommands.
#[derive(Debug, Subcommand)]
pub enum SimCommand {
    /// A sphere launched without gravity at a fixed half-space in rapier; prints
    /// `v0_m_per_s,e_n,steps,stuck,time_step_s`.
    Drop(DropArgs),
    /// Head-on impact of two free spheres in rapier (`--v0` is the relative approach speed);
    /// prints `v0_m_per_s,e_n,steps,stuck,time_step_s`.
    Pair(PairArgs),
    /// A planetary-ring shearing box (REBOUND's shearing sheet) with the MDR, Bridges or a
    /// constant restitution law.
    Ring(super::sim_ring::RingArgs),
    /// A granular scene from a TOML file (scenes/*.toml): VTK frames, energy books, plots,
    /// checkpoints; `--resume CHECKPOINT` continues a run.
    Run(super::sim_run::RunArgs),
    /// The laws a scene can name (`[contact] normal = "…"`, then `tangential`, `damping`,
    /// `rolling`), each with its parameters' scene keys, units, allowed ranges and equations.
    Laws(super::sim_laws::LawsArgs),
}

/// Dispatch a `sim` subcommand.
pub fn run(cmd: SimCommand) -> anyhow::Result<()> {
    match cmd {
        SimCommand::Drop(args) => run_drop(&args),
        SimCommand::Pair(args) => run_pair(&args),
        SimCommand::Ring(args) => super::sim_ring::run_ring(&args),
        SimCommand::Run(args) => super::sim_run::run(&args),
        SimCommand::Laws(args) => super::sim_laws::run(&args),
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

/// Flags shared by `sim drop` and `sim pair`.
#[derive(Debug, Clone, Args)]
pub struct ImpactRunArgs {
    /// Impact speed(s) (m/s), comma-separated; for `pair` the relative approach speed.
    #[arg(
        long,
        value_delimiter = ',',
        required = true,
        allow_negative_numbers = true
    )]
    pub v0: Vec<f64>,
    /// Coupling mode.
    #[arg(long, value_enum, default_value = "force")]
    pub mode: ModeArg,
    /// Force mode: time steps per contact time: Hertz's, or for a registered law other than mdr,
    /// adhesive_mdr, thornton and hertz the shorter of Hertz's and the law's [default: 1000]
    /// (same as --steps).
    #[arg(long)]
    pub steps_per_contact: Option<f64>,
    /// Output CSV file, `-` for standard output.
    #[arg(long, default_value = "-")]
    pub csv: String,
    /// Material and law flags, as in `mdr-dem impact` (and the same `--config` file keys).
    #[command(flatten)]
    pub common: CommonArgs,
}

/// Flags of `sim drop`.
#[derive(Debug, Clone, Args)]
pub struct DropArgs {
    /// Angle of the impact velocity from the normal (degrees).
    #[arg(long, default_value_t = 0.0)]
    pub angle: f64,
    #[command(flatten)]
    pub run: ImpactRunArgs,
}

/// Flags of `sim pair`. `--target-radius` and `--target-density` default to the particle's.
#[derive(Debug, Clone, Args)]
pub struct PairArgs {
    #[command(flatten)]
    pub run: ImpactRunArgs,
}

/// Default time steps per Hertz contact time in rapier (1 % accuracy needs ≳ 50; 1,000 gives
/// e_n to ~1e-4).
const DEFAULT_STEPS_PER_CONTACT: f64 = 1000.0;

/// What `sim drop|pair` take from the common flags.
struct SceneSettings {
    radius: f64,
    particle: Material,
    target: Target,
    law: SceneLaw,
    friction: f64,
    steps_per_contact: f64,
}

impl SceneSettings {
    /// Resolve the common flags (file values under flags) for a half-space (`drop`) or a free
    /// sphere target (`pair`, defaulting to a copy of the particle).
    fn resolve(
        common: &CommonArgs,
        steps_per_contact: Option<f64>,
        sphere_target: bool,
    ) -> anyhow::Result<Self> {
        let a = common.merged()?;
        refuse_validator_only_flags(&a)?;
        let (particle, target_material) = materials(&a)?;
        let radius = a.radius.unwrap_or(0.635e-2);
        let target = if sphere_target {
            Target::Sphere {
                radius: a.target_radius.unwrap_or(radius),
                material: target_material,
            }
        } else {
            if a.target_radius.is_some() || a.target_density.is_some() {
                bail!(
                    "invalid value for --target-radius/--target-density: `sim drop` hits a \
                     half-space; use `sim pair` for a sphere target"
                );
            }
            Target::HalfSpace {
                material: target_material,
            }
        };
        let pair = match target {
            Target::HalfSpace { material } => {
                ContactPair::sphere_on_half_space(radius, &particle, &material)
            }
            Target::Sphere {
                radius: r2,
                material,
            } => ContactPair::sphere_on_sphere(radius, &particle, r2, &material),
        }
        .map_err(contact_error(false))?;
        // Validates `--work-of-adhesion` (finite, ≥ 0, with the MDR law only).
        let (_, laws) = normal_laws(&a, &pair)?;
        let adhesion = a.work_of_adhesion.unwrap_or(0.0);
        let law = match laws.as_slice() {
            [NormalSpec::Mdr(model)] if adhesion > 0.0 => SceneLaw::AdhesiveMdr(
                AdhesiveMdr::new(*model, adhesion).map_err(contact_error(false))?,
            ),
            [NormalSpec::Mdr(model)] => SceneLaw::Mdr(*model),
            [NormalSpec::Hertz] => SceneLaw::Mdr(MdrElastoPlastic::elastic()),
            [NormalSpec::Thornton(model)] => SceneLaw::Thornton(*model),
            // Any other registered law, with the values its declared flags gave (checked there).
            [NormalSpec::Declared(law)] => SceneLaw::Declared(
                registered_law(law.name())?
                    .impact_scene
                    .with_values(law.values())
                    .map_err(|e| anyhow!("invalid value for --law: {e}"))?,
            ),
            _ => bail!("invalid value for --law: `sim drop|pair` run one law at a time"),
        };
        let steps_per_contact = match (steps_per_contact, a.steps) {
            (Some(_), Some(_)) => {
                bail!("invalid value for --steps: give --steps or --steps-per-contact, not both")
            }
            (Some(n), None) => n,
            (None, Some(n)) => n as f64,
            (None, None) => DEFAULT_STEPS_PER_CONTACT,
        };
        if !(steps_per_contact.is_finite() && steps_per_contact >= 10.0) {
            bail!(
                "invalid value for --steps-per-contact: {steps_per_contact} (at least 10 steps \
                 per contact)"
            );
        }
        Ok(Self {
            radius,
            particle,
            target,
            law,
            friction: friction(&a)?,
            steps_per_contact,
        })
    }

    fn scene(&self, speed: f64, angle_degrees: f64) -> ImpactScene {
        ImpactScene {
            radius: self.radius,
            material: self.particle,
            target: self.target,
            model: self.law,
            friction: self.friction,
            speed,
            angle_degrees,
            steps_per_contact: self.steps_per_contact,
        }
    }
}

/// The validator's numerical options have no meaning in rapier: refuse them by name.
fn refuse_validator_only_flags(a: &CommonArgs) -> anyhow::Result<()> {
    if a.method == Some(MethodName::Springs) || a.springs.is_some() {
        bail!(
            "invalid value for --method/--springs: rapier runs the closed-form law; the spring bed \
             is the validator's (`mdr-dem impact … --method springs`)"
        );
    }
    if a.scale.is_some() {
        bail!("invalid value for --scale: `sim` reports the model's raw e_n (no scale)");
    }
    Ok(())
}

/// A library error of one scene, naming the flag that caused it where there is one.
fn scene_error(e: CouplingError) -> anyhow::Error {
    match &e {
        CouplingError::OutOfRange { name, .. } => {
            let flag = match *name {
                "v0" => "--v0",
                "angle" => "--angle",
                "radius" => "--radius",
                "steps_per_contact" => "--steps-per-contact",
                _ => return anyhow::Error::new(e),
            };
            anyhow!("invalid value for {flag}: {e}")
        }
        CouplingError::Unsupported(_) => anyhow!("invalid value for --mode/--law: {e}"),
        _ => anyhow::Error::new(e),
    }
}

fn run_drop(args: &DropArgs) -> anyhow::Result<()> {
    run_impacts(&args.run, false, args.angle)
}

fn run_pair(args: &PairArgs) -> anyhow::Result<()> {
    run_impacts(&args.run, true, 0.0)
}

/// One rapier impact per `--v0`, at a half-space or (`sphere_target`) a free sphere.
fn run_impacts(args: &ImpactRunArgs, sphere_target: bool, angle: f64) -> anyhow::Result<()> {
    let settings = SceneSettings::resolve(&args.common, args.steps_per_contact, sphere_target)?;
    let rows = args
        .v0
        .iter()
        .map(|&v| {
            settings
                .scene(v, angle)
                .run(args.mode.into())
                .map_err(scene_error)
        })
        .collect::<anyhow::Result<Vec<_>>>()?;
    write_csv(&args.csv, &rows)
}

/// Write `v0_m_per_s,e_n,steps,stuck,time_step_s` rows to `path` (atomically) or stdout;
/// `stuck` is 1 where the sphere stuck (adhesion; `e_n = 0`), else 0, as in `mdr-dem impact`;
/// in force mode `steps × time_step_s` is the contact's duration.
fn write_csv(path: &str, rows: &[SceneOutcome]) -> anyhow::Result<()> {
    let mut text = String::from("v0_m_per_s,e_n,steps,stuck,time_step_s\n");
    for r in rows {
        text.push_str(&format!(
            "{},{},{},{},{}\n",
            r.speed,
            r.normal_restitution,
            r.steps,
            u8::from(r.stuck),
            r.time_step
        ));
    }
    if path == "-" {
        std::io::stdout().write_all(text.as_bytes())?;
        return Ok(());
    }
    let path = Path::new(path);
    mdr_output::write_atomic(path, text.as_bytes())
        .with_context(|| format!("writing {}", path.display()))
}
