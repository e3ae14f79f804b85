//! The flags every `impact` subcommand shares ([`CommonArgs`]: materials, law, method), the
//! `--config` file they may come from, their checks, and the small helpers the subcommands use
//! to name a bad flag and to write files.

use super::law_flags::{registered_law, LawParamArgs};
use anyhow::{anyhow, Context};
use clap::{Args, ValueEnum};
use mdr_contact::normal::{AdhesiveMdr, MdrElastoPlastic, NormalLaw, NormalModel, Thornton};
use mdr_contact::params::{Declared, LawDeclaration, Param};
use mdr_contact::tangential::Mindlin;
use mdr_contact::{ContactError, ContactPair, Material};
use mdr_impact::output::{read_measurements, write_atomic, Measurement};
use mdr_impact::plot::Figure;
use mdr_impact::{
    Impact, ImpactError, Method, NormalSpec, Progress, DEFAULT_SPRINGS, DEFAULT_STEPS_PER_CONTACT,
    PAPER_SCALE,
};
use serde::Deserialize;
use std::io::Write;
use std::path::{Path, PathBuf};

/// How the normal law is represented.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum MethodName {
    /// Closed-form law (energy route for head-on MDR impacts).
    Closed,
    /// Discrete MDR spring bed integrated in time.
    Springs,
}

/// A TOML value that is one item or a list (`law = "mdr"` or `law = ["mdr", "hertz"]`).
#[derive(Debug, Clone, Deserialize)]
#[serde(untagged)]
enum OneOrMany<T> {
    One(T),
    Many(Vec<T>),
}

fn one_or_many<'de, D, T>(deserializer: D) -> Result<Option<Vec<T>>, D::Error>
where
    D: serde::Deserializer<'de>,
    T: Deserialize<'de>,
{
    Ok(
        Option::<OneOrMany<T>>::deserialize(deserializer)?.map(|v| match v {
            OneOrMany::One(x) => vec![x],
            OneOrMany::Many(xs) => xs,
        }),
    )
}

/// Material and law flags common to every `impact` subcommand (SI units). Defaults: the paper's
/// steel ball (R = 0.635 cm) on a steel half-space, `q_c = 3.8·10⁵ N/m`, `Θ/E* = 0.37`.
/// The same keys (e.g. `radius = 0.005`, `theta-ratio = 0.4`, `law = ["mdr", "hertz"]`) may be
/// given in the `--config` file.
#[derive(Debug, Clone, Default, Args, Deserialize)]
#[serde(default, rename_all = "kebab-case")]
pub struct CommonArgs {
    /// Particle radius (m) [default: 0.00635].
    #[arg(long, allow_negative_numbers = true, value_name = "M")]
    pub radius: Option<f64>,
    /// Particle density (kg/m³) [default: 7800].
    #[arg(long, allow_negative_numbers = true, value_name = "KG_PER_M3")]
    pub density: Option<f64>,
    /// Particle Young's modulus (Pa) [default: 2e11].
    #[arg(long, allow_negative_numbers = true, value_name = "PA")]
    pub youngs: Option<f64>,
    /// Particle Poisson's ratio [default: 0.286].
    #[arg(long, allow_negative_numbers = true)]
    pub poisson: Option<f64>,
    /// Target Young's modulus (Pa) [default: the particle's].
    #[arg(long, allow_negative_numbers = true, value_name = "PA")]
    pub target_youngs: Option<f64>,
    /// Target Poisson's ratio [default: the particle's].
    #[arg(long, allow_negative_numbers = true)]
    pub target_poisson: Option<f64>,
    /// Target sphere radius (m); with --target-density a head-on sphere–sphere impact
    /// (effective radius, reduced mass). Omit both for a half-space.
    #[arg(long, allow_negative_numbers = true, value_name = "M")]
    pub target_radius: Option<f64>,
    /// Target sphere density (kg/m³); see --target-radius.
    #[arg(long, allow_negative_numbers = true, value_name = "KG_PER_M3")]
    pub target_density: Option<f64>,
    /// No plasticity (every law becomes Hertz).
    #[arg(long)]
    pub elastic: bool,
    /// Normal law(s), by registered name; several (comma-separated or repeated) give one
    /// comparison [default: mdr].
    #[arg(long, value_delimiter = ',', help = law_help())]
    #[serde(deserialize_with = "one_or_many")]
    pub law: Option<Vec<String>>,
    /// Work of adhesion Δγ (J/m², ≥ 0): Heß's adhesion rule on the MDR springs; the contact
    /// holds past zero overlap until it lets go, and slow impacts stick (e_n = 0) [default: 0].
    #[arg(long, allow_negative_numbers = true, value_name = "J_PER_M2",
        help = format!("{}; the contact holds past zero overlap until it lets go, and slow \
            impacts stick (e_n = 0)", declared_help::<AdhesiveMdr>(2, "0")))]
    pub work_of_adhesion: Option<f64>,
    /// Friction coefficient μ (oblique impacts) [default: 0.2].
    #[arg(long, allow_negative_numbers = true, value_name = "VALUE",
        help = declared_help::<Mindlin>(0, "0.2"))]
    pub mu: Option<f64>,
    /// Scale applied to the model's e_n (docs/theory.md §7) [default: 0.95].
    #[arg(long, allow_negative_numbers = true)]
    pub scale: Option<f64>,
    /// closed (closed-form law) or springs (discrete spring bed in time) [default: closed; oblique:
    /// springs].
    #[arg(long, value_enum)]
    pub method: Option<MethodName>,
    /// Number of springs of the bed for --method springs [default: 2000].
    #[arg(long)]
    pub springs: Option<usize>,
    /// Time steps per Hertz contact time [default: 2000].
    #[arg(long)]
    pub steps: Option<usize>,
    /// The parameters of the registered laws, one flag each as the law declares it (`--qc`,
    /// `--theta-ratio`, `--yield-stress`, …). In a `--config` file it takes every key the
    /// fields above do not, and refuses those that are no law's flag.
    #[command(flatten)]
    #[serde(flatten)]
    pub law_params: LawParamArgs,
    /// TOML file with any of these keys; flags override it.
    #[arg(long, value_name = "FILE.toml")]
    #[serde(skip)]
    pub config: Option<PathBuf>,
    /// No progress bar.
    #[arg(long, short)]
    #[serde(skip)]
    pub quiet: bool,
}

impl CommonArgs {
    /// Flags over file values.
    pub(crate) fn merged(&self) -> anyhow::Result<CommonArgs> {
        let Some(path) = &self.config else {
            return Ok(self.clone());
        };
        let text = std::fs::read_to_string(path)
            .with_context(|| format!("--config: cannot read `{}`", path.display()))?;
        let file: CommonArgs = toml::from_str(&text)
            .map_err(|e| anyhow!("--config: `{}` is not valid: {e}", path.display()))?;
        let law_params = self
            .law_params
            .merged(&file.law_params)
            .map_err(|e| anyhow!("--config: `{}` is not valid: {e}", path.display()))?;
        macro_rules! pick {
            ($($f:ident),*) => {
                CommonArgs {
                    $($f: self.$f.clone().or(file.$f.clone()),)*
                    law_params,
                    // A switch on the command line, a boolean in the file.
                    elastic: self.elastic || file.elastic,
                    config: None,
                    quiet: self.quiet,
                }
            };
        }
        Ok(pick!(
            radius,
            density,
            youngs,
            poisson,
            target_youngs,
            target_poisson,
            target_radius,
            target_density,
            law,
            work_of_adhesion,
            mu,
            scale,
            method,
            springs,
            steps
        ))
    }
}

/// Everything the common flags resolve to.
#[derive(Debug, Clone)]
pub(super) struct Settings {
    pub(super) pair: ContactPair,
    pub(super) laws: Vec<NormalSpec>,
    pub(super) mdr: MdrElastoPlastic,
    pub(super) method: Option<Method>,
    pub(super) steps: usize,
    pub(super) mu: f64,
    pub(super) work_of_adhesion: f64,
    pub(super) scale: f64,
    pub(super) quiet: bool,
    pub(super) half_space: bool,
}

/// The help of `--law`: the registered laws' names and summaries.
fn law_help() -> String {
    let laws = mdr_sim::laws::registry::NORMAL_LAWS
        .iter()
        .map(|e| format!("{} ({})", e.declaration.name, e.declaration.summary))
        .collect::<Vec<_>>()
        .join("; ");
    format!(
        "Normal law(s), by registered name (`mdr-dem sim laws`); several (comma-separated or \
         repeated) give one comparison: {laws} [default: mdr]"
    )
}

/// Map a law-crate parameter name to the flag it came from; `target` for the target material.
fn flag_for(name: &str, target: bool) -> &'static str {
    match (name, target) {
        ("youngs_modulus", false) => "--youngs",
        ("youngs_modulus", true) => "--target-youngs",
        ("poisson_ratio", false) => "--poisson",
        ("poisson_ratio", true) => "--target-poisson",
        ("density", false) => "--density",
        ("density", true) => "--target-density",
        ("radius", _) => "--radius",
        ("target_radius", _) => "--target-radius",
        ("q_c", _) => "--qc",
        ("theta_ratio" | "theta", _) => "--theta-ratio",
        ("yield_stress", _) => "--yield-stress",
        ("mu", _) => "--mu",
        ("work_of_adhesion", _) => "--work-of-adhesion",
        ("n_springs" | "half_width" | "spacing", _) => "--springs",
        _ => "a material or law flag",
    }
}

/// The help of a law parameter's flag, as the law declares the parameter (symbol, unit,
/// range, equation), with the flag's default.
fn declared_help<L: Declared>(param: usize, default: &str) -> String {
    format!(
        "{} [default: {default}]",
        L::DECLARATION.params[param].help()
    )
}

pub(crate) fn contact_error(target: bool) -> impl Fn(ContactError) -> anyhow::Error {
    move |e| {
        let name = match &e {
            ContactError::NotFinite { name, .. }
            | ContactError::OutOfRange { name, .. }
            | ContactError::TooFew { name, .. }
            | ContactError::InvalidTable { name, .. } => *name,
        };
        anyhow!("invalid value for {}: {e}", flag_for(name, target))
    }
}

/// Turn a library error into a message naming the flag; `speed_flag` is the flag that gave the
/// impact speed of this command.
pub(super) fn impact_error(speed_flag: &'static str) -> impl Fn(ImpactError) -> anyhow::Error {
    move |e| match &e {
        ImpactError::Parameter { source, .. } => contact_error(false)(source.clone()),
        ImpactError::Invalid { key, .. } => {
            let flag = match *key {
                "speed" => speed_flag.to_string(),
                "route" => "--method".to_string(),
                other => format!("--{other}"),
            };
            anyhow!("invalid value for {flag}: {e}")
        }
        _ => anyhow::Error::new(e),
    }
}

pub(super) fn positive(flag: &str, value: f64) -> anyhow::Result<f64> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(anyhow!(
            "invalid value for {flag}: {value} (must be a finite number > 0)"
        ))
    }
}

/// The particle and target materials of the merged flags (`--youngs`, `--poisson`, `--density`
/// and the `--target-…` ones, each defaulting to the particle's).
pub(crate) fn materials(a: &CommonArgs) -> anyhow::Result<(Material, Material)> {
    let particle = Material::new(
        a.youngs.unwrap_or(2.0e11),
        a.poisson.unwrap_or(0.286),
        a.density.unwrap_or(7800.0),
    )
    .map_err(contact_error(false))?;
    let target = Material::new(
        a.target_youngs.unwrap_or(particle.youngs_modulus()),
        a.target_poisson.unwrap_or(particle.poisson_ratio()),
        a.target_density.unwrap_or(particle.density()),
    )
    .map_err(contact_error(true))?;
    Ok((particle, target))
}

/// The MDR parameters and the normal laws (`--law`, `--elastic` and the law-parameter flags
/// each registered law declares, `--qc`, `--theta-ratio`, `--yield-stress`, …) of the merged
/// flags for `pair`, in the order given, without repeats. The MDR parameters are resolved
/// whatever the laws: they set Thornton's default yield pressure (the same yield speed) and the
/// fit's start.
pub(crate) fn normal_laws(
    a: &CommonArgs,
    pair: &ContactPair,
) -> anyhow::Result<(MdrElastoPlastic, Vec<NormalSpec>)> {
    let params = &a.law_params;
    let mdr =
        MdrElastoPlastic::from_values(&params.values(&MdrElastoPlastic::DECLARATION, |_| None)?)
            .map_err(contact_error(false))?;
    let matched_yield_pressure = mdr_impact::law::thornton_matched_yield_stress(
        pair,
        mdr.bind(pair)
            .map_err(contact_error(false))?
            .yield_overlap(),
    );
    let adhesive = work_of_adhesion(a)? > 0.0;
    let names = a.law.clone().unwrap_or_else(|| vec!["mdr".to_owned()]);
    let mut laws = Vec::new();
    let mut declarations: Vec<&LawDeclaration> = vec![&MdrElastoPlastic::DECLARATION];
    for name in &names {
        let entry = registered_law(name)?;
        declarations.push(&entry.declaration);
        // The adhesive MDR law is the MDR law with the validator's `--work-of-adhesion`
        // (its Δγ, which the impact integrates with Heß's rule): it needs the flag.
        let adhesive_law = entry.declaration.name == AdhesiveMdr::DECLARATION.name;
        if adhesive_law && a.work_of_adhesion.is_none() {
            return Err(anyhow!(
                "invalid value for --law: `{name}` needs --work-of-adhesion ({})",
                AdhesiveMdr::DECLARATION.params[2].help()
            ));
        }
        let spec = match (entry.declaration.name, a.elastic) {
            // Adhesion is the MDR law's: its elastic limit is JKR, not Hertz.
            ("mdr", true) if adhesive => NormalSpec::Mdr(MdrElastoPlastic::elastic()),
            (_, true) if adhesive_law => NormalSpec::Mdr(MdrElastoPlastic::elastic()),
            (_, true) | ("hertz", _) => NormalSpec::Hertz,
            ("mdr", false) => NormalSpec::Mdr(mdr),
            (_, false) if adhesive_law => NormalSpec::Mdr(mdr),
            ("thornton", false) => NormalSpec::Thornton(
                Thornton::from_values(
                    &params.values(&Thornton::DECLARATION, |_| Some(matched_yield_pressure))?,
                )
                .map_err(contact_error(false))?,
            ),
            (_, false) => NormalSpec::Declared(
                entry
                    .impact
                    .with_values(&params.values(&entry.declaration, |_| None)?)
                    .map_err(|e| anyhow!("invalid value for --law: {e}"))?,
            ),
        };
        if !laws.contains(&spec) {
            laws.push(spec);
        }
    }
    if laws.is_empty() {
        return Err(anyhow!(
            "invalid value for --law: give at least one of {}",
            mdr_sim::laws::registry::normal_law_names().join(", ")
        ));
    }
    if let Some(flag) = params.unused_by(&declarations).first() {
        return Err(anyhow!(
            "invalid value for {flag}: it is a parameter of none of the laws given with --law ({})",
            names.join(", ")
        ));
    }
    if adhesive && laws.iter().any(|l| !matches!(l, NormalSpec::Mdr(_))) {
        return Err(anyhow!(
            "invalid value for --law: --work-of-adhesion is part of the MDR law; use it with \
             --law mdr or --law adhesive_mdr"
        ));
    }
    Ok((mdr, laws))
}

/// `--work-of-adhesion` (J/m²), default 0.
pub(crate) fn work_of_adhesion(a: &CommonArgs) -> anyhow::Result<f64> {
    declared_flag(&AdhesiveMdr::DECLARATION.params[2], a.work_of_adhesion, 0.0)
}

/// `--mu`, default 0.2.
pub(crate) fn friction(a: &CommonArgs) -> anyhow::Result<f64> {
    declared_flag(&Mindlin::DECLARATION.params[0], a.mu, 0.2)
}

/// The value of the flag of declared parameter `param` (`given`, else `default`), checked
/// against the declared range; the error names the flag, the range and the equation.
pub(crate) fn declared_flag(
    param: &Param,
    given: Option<f64>,
    default: f64,
) -> anyhow::Result<f64> {
    let value = given.unwrap_or(default);
    param.check(value).map_err(|_| {
        anyhow!(
            "invalid value for --{}: {value} (must be a finite number in {}; {})",
            param.flag_name(),
            param.range.notation,
            param.help()
        )
    })
}

impl Settings {
    pub(super) fn resolve(args: &CommonArgs) -> anyhow::Result<Settings> {
        let a = args.merged()?;
        let (particle, target_material) = materials(&a)?;
        let radius = a.radius.unwrap_or(0.635e-2);
        let (pair, half_space) = match (a.target_radius, a.target_density) {
            (None, None) => (
                ContactPair::sphere_on_half_space(radius, &particle, &target_material)
                    .map_err(contact_error(false))?,
                true,
            ),
            (Some(target_radius), Some(_)) => (
                ContactPair::sphere_on_sphere(radius, &particle, target_radius, &target_material)
                    .map_err(contact_error(false))?,
                false,
            ),
            (Some(_), None) => {
                return Err(anyhow!(
                    "invalid value for --target-radius: a target sphere needs --target-density too \
                     (omit both for a half-space)"
                ))
            }
            (None, Some(_)) => {
                return Err(anyhow!(
                    "invalid value for --target-density: a target sphere needs --target-radius too \
                     (omit both for a half-space)"
                ))
            }
        };
        let (mdr, laws) = normal_laws(&a, &pair)?;
        let mu = friction(&a)?;
        let work_of_adhesion = work_of_adhesion(&a)?;
        let scale = positive("--scale", a.scale.unwrap_or(PAPER_SCALE))?;
        let steps = a.steps.unwrap_or(DEFAULT_STEPS_PER_CONTACT);
        if steps < 10 {
            return Err(anyhow!(
                "invalid value for --steps: {steps} (at least 10 steps per contact)"
            ));
        }
        let springs = a.springs.unwrap_or(DEFAULT_SPRINGS);
        if !(2..=mdr_contact::normal::SpringBed::MAX_SPRINGS).contains(&springs) {
            return Err(anyhow!(
                "invalid value for --springs: {springs} (2 to {} springs)",
                mdr_contact::normal::SpringBed::MAX_SPRINGS
            ));
        }
        if a.springs.is_some() && a.method == Some(MethodName::Closed) {
            return Err(anyhow!(
                "invalid value for --springs: it applies to --method springs only"
            ));
        }
        let method = a.method.map(|m| match m {
            MethodName::Closed => Method::Closed,
            MethodName::Springs => Method::Springs { springs },
        });
        if matches!(method, Some(Method::Springs { .. }))
            && laws.iter().any(|l| !matches!(l, NormalSpec::Mdr(_)))
        {
            return Err(anyhow!(
                "invalid value for --method: springs is the discrete MDR law; use it with --law mdr \
                 (and without --elastic)"
            ));
        }
        Ok(Settings {
            pair,
            laws,
            mdr,
            method,
            steps,
            mu,
            work_of_adhesion,
            scale,
            quiet: a.quiet,
            half_space,
        })
    }

    pub(super) fn impact(&self, law: NormalSpec, speed: f64) -> Impact {
        Impact::new(self.pair, law, speed)
            .method(self.method.unwrap_or(Method::Closed))
            .steps_per_contact(self.steps)
            .friction(self.mu)
            .work_of_adhesion(self.work_of_adhesion)
    }

    pub(super) fn progress(&self) -> Progress {
        if self.quiet {
            Progress::Hidden
        } else {
            Progress::Auto
        }
    }
}

/// Parse a comma-separated list of numbers for `flag`.
pub(super) fn number_list(flag: &str, text: &str) -> anyhow::Result<Vec<f64>> {
    text.split(',')
        .map(|s| {
            s.trim()
                .parse::<f64>()
                .map_err(|_| anyhow!("invalid value for {flag}: `{s}` is not a number"))
        })
        .collect()
}

/// Write `text` to `path`, or to stdout for `-`.
pub(super) fn emit(path: &Path, text: &str) -> anyhow::Result<()> {
    if path == Path::new("-") {
        std::io::stdout().write_all(text.as_bytes())?;
        Ok(())
    } else {
        write_atomic(path, text.as_bytes())?;
        eprintln!("wrote {}", path.display());
        Ok(())
    }
}

pub(super) fn load_data(path: &Path) -> anyhow::Result<Vec<Measurement>> {
    read_measurements(path).map_err(|e| anyhow!("invalid value for --data: {e}"))
}

pub(super) fn save_plot(figure: &Figure, path: &Path) -> anyhow::Result<()> {
    figure
        .save(path)
        .map_err(|e| anyhow!("invalid value for --plot: {e}"))?;
    eprintln!("wrote {}", path.display());
    Ok(())
}
