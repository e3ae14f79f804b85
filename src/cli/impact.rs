//! `mdr-dem impact …`: the single-impact validator. Flags are parsed and checked here;
//! the physics lives in `mdr-contact` and the integration in `mdr-impact`.
//!
//! Every `impact` subcommand takes the common material/law flags ([`CommonArgs`]); the same keys
//! may be given in a TOML file with `--config FILE.toml`, and flags override the file.

use anyhow::{anyhow, Context};
use clap::{Args, Subcommand, ValueEnum};
use mdr_contact::normal::{MdrElastoPlastic, NormalLaw, NormalModel, Thornton};
use mdr_contact::{ContactError, ContactPair, Material};
use mdr_impact::fit::{fit, predict, FitParameter, FitValues};
use mdr_impact::output::{
    curve_csv, oblique_csv, read_measurements, trace_csv, write_atomic, Measurement,
};
use mdr_impact::plot::Figure;
use mdr_impact::{
    log_spaced, Impact, ImpactError, ImpactOutcome, Method, NormalSpec, Progress, Sweep,
    TangentialSpec, DEFAULT_SPRINGS, DEFAULT_STEPS_PER_CONTACT, PAPER_SCALE,
};
use serde::Deserialize;
use std::io::Write;
use std::path::{Path, PathBuf};

/// `impact` subcommands.
#[derive(Debug, Subcommand)]
pub enum ImpactCommand {
    /// Reproduce the paper's Fig. 2 (the default job): table, results/fig2.{csv,svg,png}.
    Fig2(Fig2Args),
    /// Restitution against impact speed; CSV
    /// `v0_m_per_s,e_n,e_n_scaled,d_max_m,d_residual_m,contact_time_s,f_max_n`.
    Curve(CurveArgs),
    /// Time history of one impact; CSV `t_s,d_m,v_m_per_s,f_n,contact_radius_m,plastic_work_j`
    /// and a force–indentation plot.
    Trace(TraceArgs),
    /// Least-squares fit of q_c, Θ/E* and the scale to measured `v0_m_per_s,e_n` data.
    Fit(FitArgs),
    /// Oblique impacts on a half-space with friction and rotation; CSV
    /// `angle_deg,e_n,e_t,rebound_angle_deg,omega_rad_per_s`.
    Oblique(ObliqueArgs),
}

/// The default job (no arguments): `impact fig2` with its defaults.
pub fn run_default() -> anyhow::Result<()> {
    run(ImpactCommand::Fig2(Fig2Args::default()))
}

/// Dispatch an `impact` subcommand.
pub fn run(cmd: ImpactCommand) -> anyhow::Result<()> {
    match cmd {
        ImpactCommand::Fig2(args) => run_fig2(&args),
        ImpactCommand::Curve(args) => run_curve(&args),
        ImpactCommand::Trace(args) => run_trace(&args),
        ImpactCommand::Fit(args) => run_fit(&args),
        ImpactCommand::Oblique(args) => run_oblique(&args),
    }
}

// ---------------------------------------------------------------------------------------------
// Common flags and the configuration file
// ---------------------------------------------------------------------------------------------

/// Normal law names on the command line.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum LawName {
    /// MDR elasto-plastic law (Lyashenko & Popov 2018).
    Mdr,
    /// Thornton (1997) elastic–perfectly-plastic law.
    Thornton,
    /// Hertz, elastic.
    Hertz,
}

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
#[serde(default, rename_all = "kebab-case", deny_unknown_fields)]
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
    /// Critical line load q_c (N/m), eq. (7) [default: 3.8e5].
    #[arg(long, allow_negative_numbers = true, value_name = "N_PER_M")]
    pub qc: Option<f64>,
    /// Hardening ratio Θ/E*, eq. (12) [default: 0.37].
    #[arg(long, allow_negative_numbers = true)]
    pub theta_ratio: Option<f64>,
    /// No plasticity (every law becomes Hertz).
    #[arg(long)]
    pub elastic: bool,
    /// Normal law(s): mdr, thornton, hertz; several (comma-separated or repeated) give one
    /// comparison [default: mdr].
    #[arg(long, value_enum, value_delimiter = ',')]
    #[serde(deserialize_with = "one_or_many")]
    pub law: Option<Vec<LawName>>,
    /// Thornton's limiting contact pressure (Pa) [default: the value whose yield speed equals the
    /// MDR law's].
    #[arg(long, allow_negative_numbers = true, value_name = "PA")]
    pub yield_stress: Option<f64>,
    /// Friction coefficient μ (oblique impacts) [default: 0.2].
    #[arg(long, allow_negative_numbers = true)]
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
        macro_rules! pick {
            ($($f:ident),*) => {
                CommonArgs {
                    $($f: self.$f.clone().or(file.$f.clone()),)*
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
            qc,
            theta_ratio,
            law,
            yield_stress,
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
struct Settings {
    pair: ContactPair,
    laws: Vec<NormalSpec>,
    mdr: MdrElastoPlastic,
    method: Option<Method>,
    steps: usize,
    mu: f64,
    scale: f64,
    quiet: bool,
    half_space: bool,
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
        ("n_springs" | "half_width" | "spacing", _) => "--springs",
        _ => "a material or law flag",
    }
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
fn impact_error(speed_flag: &'static str) -> impl Fn(ImpactError) -> anyhow::Error {
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

fn positive(flag: &str, value: f64) -> anyhow::Result<f64> {
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

/// The MDR parameters and the normal laws (`--law`, `--elastic`, `--qc`, `--theta-ratio`,
/// `--yield-stress`) of the merged flags for `pair`, in the order given, without repeats.
pub(crate) fn normal_laws(
    a: &CommonArgs,
    pair: &ContactPair,
) -> anyhow::Result<(MdrElastoPlastic, Vec<NormalSpec>)> {
    let mdr = MdrElastoPlastic::new(a.qc.unwrap_or(3.8e5), a.theta_ratio.unwrap_or(0.37))
        .map_err(contact_error(false))?;
    // Thornton's default p_y: the same yield overlap as the MDR law,
    // δ_y = R (π p_y / (2E*))² = u_c = π q_c / (2E*).
    let e_star = pair.effective_modulus();
    let default_yield_stress = {
        let u_c = mdr
            .bind(pair)
            .map_err(contact_error(false))?
            .yield_overlap();
        2.0 * e_star / std::f64::consts::PI * (u_c / pair.effective_radius()).sqrt()
    };
    let mut laws = Vec::new();
    for name in a.law.clone().unwrap_or_else(|| vec![LawName::Mdr]) {
        let spec = match (name, a.elastic) {
            (_, true) | (LawName::Hertz, _) => NormalSpec::Hertz,
            (LawName::Mdr, false) => NormalSpec::Mdr(mdr),
            (LawName::Thornton, false) => NormalSpec::Thornton(
                Thornton::new(a.yield_stress.unwrap_or(default_yield_stress))
                    .map_err(contact_error(false))?,
            ),
        };
        if !laws.contains(&spec) {
            laws.push(spec);
        }
    }
    if laws.is_empty() {
        return Err(anyhow!(
            "invalid value for --law: give at least one of mdr, thornton, hertz"
        ));
    }
    Ok((mdr, laws))
}

/// `--mu`, default 0.2.
pub(crate) fn friction(a: &CommonArgs) -> anyhow::Result<f64> {
    let mu = a.mu.unwrap_or(0.2);
    if !(mu.is_finite() && mu >= 0.0) {
        return Err(anyhow!(
            "invalid value for --mu: {mu} (must be a finite number ≥ 0)"
        ));
    }
    Ok(mu)
}

impl Settings {
    fn resolve(args: &CommonArgs) -> anyhow::Result<Settings> {
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
        let scale = positive("--scale", a.scale.unwrap_or(PAPER_SCALE))?;
        let steps = a.steps.unwrap_or(DEFAULT_STEPS_PER_CONTACT);
        if steps < 10 {
            return Err(anyhow!(
                "invalid value for --steps: {steps} (at least 10 steps per contact)"
            ));
        }
        let springs = a.springs.unwrap_or(DEFAULT_SPRINGS);
        if springs < 2 {
            return Err(anyhow!(
                "invalid value for --springs: {springs} (at least 2 springs)"
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
            scale,
            quiet: a.quiet,
            half_space,
        })
    }

    fn impact(&self, law: NormalSpec, speed: f64) -> Impact {
        Impact::new(self.pair, law, speed)
            .method(self.method.unwrap_or(Method::Closed))
            .steps_per_contact(self.steps)
            .friction(self.mu)
    }

    fn progress(&self) -> Progress {
        if self.quiet {
            Progress::Hidden
        } else {
            Progress::Auto
        }
    }
}

/// Parse a comma-separated list of numbers for `flag`.
fn number_list(flag: &str, text: &str) -> anyhow::Result<Vec<f64>> {
    text.split(',')
        .map(|s| {
            s.trim()
                .parse::<f64>()
                .map_err(|_| anyhow!("invalid value for {flag}: `{s}` is not a number"))
        })
        .collect()
}

/// Write `text` to `path`, or to stdout for `-`.
fn emit(path: &Path, text: &str) -> anyhow::Result<()> {
    if path == Path::new("-") {
        std::io::stdout().write_all(text.as_bytes())?;
        Ok(())
    } else {
        write_atomic(path, text.as_bytes())?;
        eprintln!("wrote {}", path.display());
        Ok(())
    }
}

fn load_data(path: &Path) -> anyhow::Result<Vec<Measurement>> {
    read_measurements(path).map_err(|e| anyhow!("invalid value for --data: {e}"))
}

fn save_plot(figure: &Figure, path: &Path) -> anyhow::Result<()> {
    figure
        .save(path)
        .map_err(|e| anyhow!("invalid value for --plot: {e}"))?;
    eprintln!("wrote {}", path.display());
    Ok(())
}

// ---------------------------------------------------------------------------------------------
// curve and fig2
// ---------------------------------------------------------------------------------------------

/// Flags of `impact curve`.
#[derive(Debug, Clone, Args)]
pub struct CurveArgs {
    #[command(flatten)]
    common: CommonArgs,
    /// Impact speeds (m/s), comma-separated.
    #[arg(long, conflicts_with_all = ["v_min", "v_max", "points"])]
    velocities: Option<String>,
    /// Smallest speed of a log-spaced sweep (m/s).
    #[arg(long, allow_negative_numbers = true, default_value_t = 0.01)]
    v_min: f64,
    /// Largest speed of a log-spaced sweep (m/s).
    #[arg(long, allow_negative_numbers = true, default_value_t = 30.0)]
    v_max: f64,
    /// Number of log-spaced speeds.
    #[arg(long, default_value_t = 200)]
    points: usize,
    /// CSV output file, or `-` for stdout (several laws: one file per law, `NAME_<law>.csv`).
    #[arg(long, value_name = "PATH|-")]
    csv: Option<PathBuf>,
    /// Plot file (.svg or .png).
    #[arg(long, value_name = "PATH")]
    plot: Option<PathBuf>,
    /// Measured `v0_m_per_s,e_n` points to overlay on the plot.
    #[arg(long, value_name = "FILE")]
    data: Option<PathBuf>,
}

/// Flags of `impact fig2`.
#[derive(Debug, Clone, Args)]
pub struct Fig2Args {
    #[command(flatten)]
    common: CommonArgs,
    /// Measured `v0_m_per_s,e_n` points to overlay.
    #[arg(long, value_name = "FILE")]
    data: Option<PathBuf>,
    /// Output directory.
    #[arg(long, value_name = "DIR", default_value = "results")]
    out_dir: PathBuf,
}

impl Default for Fig2Args {
    fn default() -> Self {
        Self {
            common: CommonArgs::default(),
            data: None,
            out_dir: PathBuf::from("results"),
        }
    }
}

fn speeds_of(args: &CurveArgs) -> anyhow::Result<Vec<f64>> {
    if let Some(list) = &args.velocities {
        let speeds = number_list("--velocities", list)?;
        for &v in &speeds {
            positive("--velocities", v)?;
        }
        return Ok(speeds);
    }
    positive("--v-min", args.v_min)?;
    positive("--v-max", args.v_max)?;
    if args.v_max <= args.v_min {
        return Err(anyhow!(
            "invalid value for --v-max: {} must exceed --v-min {}",
            args.v_max,
            args.v_min
        ));
    }
    if args.points < 2 {
        return Err(anyhow!(
            "invalid value for --points: {} (at least 2)",
            args.points
        ));
    }
    Ok(log_spaced(args.v_min, args.v_max, args.points))
}

/// One law's curve.
struct Curve {
    law: NormalSpec,
    outcomes: Vec<ImpactOutcome>,
    yield_speed: f64,
}

fn compute_curves(settings: &Settings, speeds: &[f64]) -> anyhow::Result<Vec<Curve>> {
    settings
        .laws
        .iter()
        .map(|&law| {
            let template = settings.impact(law, 1.0);
            let outcomes = Sweep::speeds(template, speeds)
                .progress(settings.progress())
                .run()
                .map_err(impact_error("--velocities"))?;
            let yield_speed = template
                .yield_speed()
                .map_err(impact_error("--velocities"))?;
            Ok(Curve {
                law,
                outcomes,
                yield_speed,
            })
        })
        .collect()
}

fn law_label(law: &NormalSpec) -> String {
    match law {
        NormalSpec::Mdr(m) => {
            let theta = match m.hardening() {
                mdr_contact::normal::Hardening::Ratio(r) => format!("{r}"),
                mdr_contact::normal::Hardening::Modulus(t) => format!("{t:.3e} Pa"),
            };
            format!(
                "MDR (q_c = {:.3e} N/m, Θ/E* = {theta})",
                m.critical_line_load()
            )
        }
        NormalSpec::Thornton(t) => format!("Thornton (p_y = {:.3e} Pa)", t.yield_pressure()),
        NormalSpec::Hertz => "Hertz".into(),
    }
}

fn curve_figure(
    curves: &[Curve],
    scale: f64,
    data: Option<&[Measurement]>,
    with_raw: bool,
) -> Figure {
    let mut figure = Figure::new(
        "Coefficient of restitution vs impact speed",
        "impact speed v0 (m/s)",
        "coefficient of restitution e",
    )
    .log_x(true);
    for curve in curves {
        let label = law_label(&curve.law);
        let scaled = curve
            .outcomes
            .iter()
            .map(|o| (o.speed, scale * o.normal_restitution))
            .collect();
        figure = figure.line(format!("{label}, scaled × {scale}"), scaled, false);
        if with_raw {
            let raw = curve
                .outcomes
                .iter()
                .map(|o| (o.speed, o.normal_restitution))
                .collect();
            figure = figure.line(format!("{label}, raw"), raw, true);
        }
    }
    for curve in curves {
        if curve.yield_speed.is_finite() {
            figure = figure.marker(
                format!(
                    "yield speed {} = {:.3} m/s",
                    curve.law.name(),
                    curve.yield_speed
                ),
                curve.yield_speed,
            );
        }
    }
    if let Some(points) = data {
        figure = figure.scatter(
            "measured",
            points.iter().map(|m| (m.speed, m.restitution)).collect(),
        );
    }
    let low = curves
        .iter()
        .flat_map(|c| c.outcomes.iter().map(|o| scale * o.normal_restitution))
        .chain(data.unwrap_or(&[]).iter().map(|m| m.restitution))
        .fold(1.0_f64, f64::min);
    figure.y_range((low - 0.05).clamp(0.0, 0.9), 1.05)
}

fn print_table(curves: &[Curve], scale: f64) {
    for curve in curves {
        println!("{}", law_label(&curve.law));
        println!("  yield speed: {:.4} m/s", curve.yield_speed);
        println!(
            "  {:>10}  {:>8}  {:>10}  {:>11}  {:>11}  {:>12}  {:>10}",
            "v0 (m/s)", "e_n", "e_n scaled", "d_max (µm)", "d_res (µm)", "t_c (µs)", "F_max (N)"
        );
        for o in &curve.outcomes {
            println!(
                "  {:>10.4}  {:>8.5}  {:>10.5}  {:>11.4}  {:>11.4}  {:>12.3}  {:>10.2}",
                o.speed,
                o.normal_restitution,
                scale * o.normal_restitution,
                o.max_overlap * 1e6,
                o.residual_overlap * 1e6,
                o.contact_time * 1e6,
                o.peak_force
            );
        }
    }
}

fn run_curve(args: &CurveArgs) -> anyhow::Result<()> {
    let settings = Settings::resolve(&args.common)?;
    let speeds = speeds_of(args)?;
    let data = args.data.as_deref().map(load_data).transpose()?;
    if settings.laws.len() > 1 && args.csv.as_deref() == Some(Path::new("-")) {
        return Err(anyhow!(
            "invalid value for --csv: several laws write one file each; give a file path, not `-`"
        ));
    }
    let curves = compute_curves(&settings, &speeds)?;
    match &args.csv {
        Some(path) if curves.len() == 1 => {
            emit(path, &curve_csv(&curves[0].outcomes, settings.scale))?
        }
        Some(path) => {
            for curve in &curves {
                let stem = path.file_stem().unwrap_or_default().to_string_lossy();
                let file = path.with_file_name(format!("{stem}_{}.csv", curve.law.name()));
                emit(&file, &curve_csv(&curve.outcomes, settings.scale))?;
            }
        }
        None => print_table(&curves, settings.scale),
    }
    if let Some(path) = &args.plot {
        let figure = curve_figure(&curves, settings.scale, data.as_deref(), curves.len() == 1);
        save_plot(&figure, path)?;
    }
    Ok(())
}

/// Speeds listed in the Fig. 2 table.
const FIG2_TABLE_SPEEDS: [f64; 12] = [
    0.03, 0.1, 0.2, 0.28, 0.3, 0.5, 1.0, 2.0, 3.0, 5.0, 10.0, 30.0,
];

fn run_fig2(args: &Fig2Args) -> anyhow::Result<()> {
    let settings = Settings::resolve(&args.common)?;
    let data = args.data.as_deref().map(load_data).transpose()?;
    let speeds = log_spaced(0.01, 30.0, 200);
    let curves = compute_curves(&settings, &speeds)?;
    println!(
        "Fig. 2 of Lyashenko & Popov (2018): steel ball R = {:.4} mm on steel, E* = {:.4e} Pa, \
         m = {:.4} g",
        settings.pair.effective_radius() * 1e3,
        settings.pair.effective_modulus(),
        settings.pair.reduced_mass() * 1e3
    );
    print_table(
        &compute_curves(&settings, &FIG2_TABLE_SPEEDS)?,
        settings.scale,
    );
    let dir = &args.out_dir;
    let csv_path = dir.join("fig2.csv");
    write_atomic(
        &csv_path,
        curve_csv(&curves[0].outcomes, settings.scale).as_bytes(),
    )?;
    println!("wrote {}", csv_path.display());
    let mut figure = curve_figure(&curves, settings.scale, data.as_deref(), true);
    figure.title = "Fig. 2: restitution of a steel ball on a steel plate (MDR model)".into();
    for extension in ["svg", "png"] {
        let path = dir.join(format!("fig2.{extension}"));
        figure.save(&path)?;
        println!("wrote {}", path.display());
    }
    Ok(())
}

// ---------------------------------------------------------------------------------------------
// trace
// ---------------------------------------------------------------------------------------------

/// Flags of `impact trace`.
#[derive(Debug, Clone, Args)]
pub struct TraceArgs {
    #[command(flatten)]
    common: CommonArgs,
    /// Impact speed (m/s).
    #[arg(long, allow_negative_numbers = true)]
    v0: f64,
    /// CSV output file, or `-` for stdout [default: stdout].
    #[arg(long, value_name = "PATH|-")]
    csv: Option<PathBuf>,
    /// Force–indentation plot (.svg or .png).
    #[arg(long, value_name = "PATH")]
    plot: Option<PathBuf>,
}

fn run_trace(args: &TraceArgs) -> anyhow::Result<()> {
    let settings = Settings::resolve(&args.common)?;
    positive("--v0", args.v0)?;
    if settings.laws.len() != 1 {
        return Err(anyhow!("invalid value for --law: trace takes one law"));
    }
    let (outcome, points) = settings
        .impact(settings.laws[0], args.v0)
        .trace()
        .map_err(impact_error("--v0"))?;
    emit(
        args.csv.as_deref().unwrap_or(Path::new("-")),
        &trace_csv(&points),
    )?;
    eprintln!(
        "e_n = {:.6}, d_max = {:.4} µm, residual = {:.4} µm, t_c = {:.3} µs, F_max = {:.2} N",
        outcome.normal_restitution,
        outcome.max_overlap * 1e6,
        outcome.residual_overlap * 1e6,
        outcome.contact_time * 1e6,
        outcome.peak_force
    );
    if let Some(path) = &args.plot {
        let loop_points = points.iter().map(|p| (p.overlap * 1e6, p.force)).collect();
        let figure = Figure::new(
            format!(
                "Force–indentation at v0 = {} m/s ({}), e_n = {:.4}",
                args.v0,
                settings.laws[0].name(),
                outcome.normal_restitution
            ),
            "indentation d (µm)",
            "normal force F (N)",
        )
        .line("loading and unloading", loop_points, false)
        .marker(
            format!("residual depth {:.3} µm", outcome.residual_overlap * 1e6),
            outcome.residual_overlap * 1e6,
        );
        save_plot(&figure, path)?;
    }
    Ok(())
}

// ---------------------------------------------------------------------------------------------
// fit
// ---------------------------------------------------------------------------------------------

/// Flags of `impact fit`.
#[derive(Debug, Clone, Args)]
pub struct FitArgs {
    #[command(flatten)]
    common: CommonArgs,
    /// Measured data, CSV with header `v0_m_per_s,e_n`.
    #[arg(long, value_name = "FILE.csv")]
    data: PathBuf,
    /// Parameters to fit, comma-separated subset of qc,theta_ratio,scale.
    #[arg(long, default_value = "qc,theta_ratio,scale")]
    free: String,
    /// Print one JSON object (keys q_c, theta_ratio, scale, rmse, n_points, and uncertainties).
    #[arg(long)]
    json: bool,
    /// Plot of the data and the fitted curve (.svg or .png).
    #[arg(long, value_name = "PATH")]
    plot: Option<PathBuf>,
}

fn run_fit(args: &FitArgs) -> anyhow::Result<()> {
    let settings = Settings::resolve(&args.common)?;
    if settings.laws != [NormalSpec::Mdr(settings.mdr)] {
        return Err(anyhow!(
            "invalid value for --law: the fit adjusts the MDR law (--law mdr, not --elastic)"
        ));
    }
    let free = args
        .free
        .split(',')
        .map(FitParameter::parse)
        .collect::<Result<Vec<_>, _>>()
        .map_err(impact_error("--data"))?;
    let data = load_data(&args.data)?;
    let hardening = match settings.mdr.hardening() {
        mdr_contact::normal::Hardening::Ratio(r) => r,
        mdr_contact::normal::Hardening::Modulus(t) => t / settings.pair.effective_modulus(),
    };
    let initial = FitValues {
        q_c: settings.mdr.critical_line_load(),
        theta_ratio: hardening,
        scale: settings.scale,
    };
    let report = fit(&settings.pair, initial, &free, &data).map_err(|e| match e {
        ImpactError::Underdetermined(_) => anyhow!("--data: {e}"),
        other => impact_error("--data")(other),
    })?;
    let sigma = |p: FitParameter| {
        report
            .uncertainties
            .iter()
            .find(|(q, _)| *q == p)
            .map(|(_, s)| *s)
    };
    if args.json {
        let mut object = serde_json::json!({
            "q_c": report.values.q_c,
            "theta_ratio": report.values.theta_ratio,
            "scale": report.values.scale,
            "rmse": report.rmse,
            "n_points": report.n_points,
        });
        let mut uncertainty = serde_json::Map::new();
        for (p, key) in [
            (FitParameter::CriticalLineLoad, "q_c"),
            (FitParameter::HardeningRatio, "theta_ratio"),
            (FitParameter::Scale, "scale"),
        ] {
            if let Some(s) = sigma(p) {
                uncertainty.insert(key.into(), s.into());
            }
        }
        object["uncertainty"] = uncertainty.into();
        object["yield_speed_m_per_s"] = report.yield_speed.into();
        println!("{object}");
    } else {
        let show = |name: &str, value: f64, p: FitParameter| match sigma(p) {
            Some(s) => println!("{name:>12} = {value:.6e} ± {s:.2e}"),
            None => println!("{name:>12} = {value:.6e} (fixed)"),
        };
        show(
            "q_c (N/m)",
            report.values.q_c,
            FitParameter::CriticalLineLoad,
        );
        show(
            "theta_ratio",
            report.values.theta_ratio,
            FitParameter::HardeningRatio,
        );
        show("scale", report.values.scale, FitParameter::Scale);
        println!("{:>12} = {:.3e}", "rmse", report.rmse);
        println!("{:>12} = {}", "n_points", report.n_points);
        println!(
            "{:>12} = {:.4} m/s ({} points above it)",
            "yield speed", report.yield_speed, report.n_plastic
        );
    }
    if let Some(path) = &args.plot {
        let (lo, hi) = data.iter().fold((f64::INFINITY, 0.0_f64), |(lo, hi), m| {
            (lo.min(m.speed), hi.max(m.speed))
        });
        let speeds = log_spaced(lo / 2.0, hi * 2.0, 200);
        let model = predict(&settings.pair, &report.values, &speeds)?;
        let figure = Figure::new(
            "Fit of the MDR law to measured restitution",
            "impact speed v0 (m/s)",
            "coefficient of restitution e",
        )
        .log_x(true)
        .line(
            format!(
                "fit: q_c = {:.3e} N/m, Θ/E* = {:.3}, scale = {:.3}",
                report.values.q_c, report.values.theta_ratio, report.values.scale
            ),
            speeds.into_iter().zip(model).collect(),
            false,
        )
        .scatter(
            "measured",
            data.iter().map(|m| (m.speed, m.restitution)).collect(),
        )
        .marker(
            format!("yield speed {:.3} m/s", report.yield_speed),
            report.yield_speed,
        );
        save_plot(&figure, path)?;
    }
    Ok(())
}

// ---------------------------------------------------------------------------------------------
// oblique
// ---------------------------------------------------------------------------------------------

/// Tangential law names.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum TangentialName {
    /// MDR spring bed with per-spring stick/slip (needs --method springs).
    Springs,
    /// O(1) incremental Mindlin law with a Coulomb cap.
    Mindlin,
}

/// Flags of `impact oblique`.
#[derive(Debug, Clone, Args)]
pub struct ObliqueArgs {
    #[command(flatten)]
    common: CommonArgs,
    /// Impact speed (m/s).
    #[arg(long, allow_negative_numbers = true)]
    speed: f64,
    /// Impact angles from the normal (degrees, in [0, 90)), comma-separated.
    #[arg(long, default_value = "5,10,20,30,40,50,60,70,80,85")]
    angles: String,
    /// Tangential law [default: springs, the MDR spring bed; mindlin with --method closed].
    #[arg(long, value_enum)]
    tangential: Option<TangentialName>,
    /// Initial angular velocity (rad/s), positive in the sense of rolling forward.
    #[arg(long, allow_negative_numbers = true, default_value_t = 0.0)]
    spin: f64,
    /// CSV output file, or `-` for stdout [default: stdout].
    #[arg(long, value_name = "PATH|-")]
    csv: Option<PathBuf>,
    /// Plot of e_n, e_t and the rebound angle against the impact angle (.svg or .png).
    #[arg(long, value_name = "PATH")]
    plot: Option<PathBuf>,
}

fn run_oblique(args: &ObliqueArgs) -> anyhow::Result<()> {
    let settings = Settings::resolve(&args.common)?;
    positive("--speed", args.speed)?;
    if !args.spin.is_finite() {
        return Err(anyhow!(
            "invalid value for --spin: {} (must be finite)",
            args.spin
        ));
    }
    if !settings.half_space {
        return Err(anyhow!(
            "invalid value for --target-radius: oblique impacts are computed on a half-space; \
             omit --target-radius and --target-density"
        ));
    }
    if settings.laws.len() != 1 {
        return Err(anyhow!("invalid value for --law: oblique takes one law"));
    }
    let angles = number_list("--angles", &args.angles)?;
    for &a in &angles {
        if !(a.is_finite() && (0.0..90.0).contains(&a)) {
            return Err(anyhow!(
                "invalid value for --angles: {a} (angles from the normal in [0, 90) degrees)"
            ));
        }
    }
    let law = settings.laws[0];
    let tangential = match args.tangential {
        Some(TangentialName::Springs) => TangentialSpec::SpringBed,
        Some(TangentialName::Mindlin) => TangentialSpec::Mindlin,
        None if matches!(law, NormalSpec::Mdr(_)) && settings.method != Some(Method::Closed) => {
            TangentialSpec::SpringBed
        }
        None => TangentialSpec::Mindlin,
    };
    let method = match (settings.method, tangential) {
        (Some(m), _) => m,
        (None, TangentialSpec::SpringBed) => Method::Springs {
            springs: args.common.springs.unwrap_or(DEFAULT_SPRINGS),
        },
        (None, TangentialSpec::Mindlin) => Method::Closed,
    };
    if tangential == TangentialSpec::SpringBed && !matches!(method, Method::Springs { .. }) {
        return Err(anyhow!(
            "invalid value for --tangential: springs needs --method springs (or use --tangential mindlin)"
        ));
    }
    let template = settings
        .impact(law, args.speed)
        .method(method)
        .tangential(tangential)
        .spin(args.spin);
    let outcomes = Sweep::angles(template, &angles)
        .progress(settings.progress())
        .run()
        .map_err(impact_error("--speed"))?;
    emit(
        args.csv.as_deref().unwrap_or(Path::new("-")),
        &oblique_csv(&outcomes),
    )?;
    if let Some(path) = &args.plot {
        let series = |f: &dyn Fn(&ImpactOutcome) -> f64| {
            outcomes
                .iter()
                .map(|o| (o.angle_degrees, f(o)))
                .collect::<Vec<_>>()
        };
        let figure = Figure::new(
            format!(
                "Oblique impact at {} m/s, μ = {} ({} tangential law)",
                args.speed,
                settings.mu,
                tangential.name()
            ),
            "impact angle from the normal (degrees)",
            "coefficient of restitution",
        )
        .line("e_n", series(&|o| o.normal_restitution), false)
        .line(
            "e_t = |v_t,out| / |v_t,in|",
            series(&|o| o.tangential_restitution.unwrap_or(f64::NAN)),
            false,
        )
        .line(
            "rebound angle / impact angle",
            series(&|o| o.rebound_angle_degrees / o.angle_degrees),
            true,
        );
        save_plot(&figure, path)?;
    }
    Ok(())
}
