//! `mdr-dem sim ring`: a planetary-ring shearing box with REBOUND's shearing-sheet defaults; the
//! physics lives in `mdr-ring` ([`mdr_ring::app::run`]).

use anyhow::Context;
use clap::{Args, ValueEnum};
use mdr_contact::normal::MdrElastoPlastic;
use mdr_contact::Material;
use mdr_ring::app::{run, LawChoice, RunOptions};
use mdr_ring::prelude::*;
use std::path::PathBuf;

/// Which restitution law resolves the impacts.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum RingLawArg {
    /// MDR elasto-plastic law for ice (energy route; --youngs, --poisson, --qc, --theta-ratio).
    Mdr,
    /// Bridges et al. (1984): ε(v) = min(1, 0.32 (v / 1 cm/s)^-0.234) (REBOUND's default).
    Bridges,
    /// A constant ε (--eps).
    Constant,
}

/// Self-gravity solver of `sim ring`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum RingGravityArg {
    /// Barnes–Hut tree over the box and its ghost boxes, O(N log N) (REBOUND's method); what a
    /// bare `--gravity` selects.
    Tree,
    /// Direct sum over the same ghost boxes, O(N²) (`--ghost-boxes 0`: nearest image only).
    Direct,
    /// No self-gravity (the default without the flag).
    None,
}

/// Flags of `sim ring`; defaults are REBOUND's shearing sheet (Ω = 1.3143527e-4 s⁻¹,
/// Σ = 400 kg/m², ρ = 400 kg/m³, radii 1–4 m with slope −3, 200 m box, Δt = 10⁻³ orbit).
#[derive(Debug, Clone, Args)]
pub struct RingArgs {
    /// Number of particles (instead of --surface-density).
    #[arg(long, conflicts_with = "surface_density")]
    pub particles: Option<usize>,
    /// Surface density Σ (kg/m²): particles are drawn until their mass reaches Σ L².
    #[arg(long)]
    pub surface_density: Option<f64>,
    /// Restitution law.
    #[arg(long, value_enum, default_value_t = RingLawArg::Bridges)]
    pub law: RingLawArg,
    /// ε of the constant law.
    #[arg(long, default_value_t = 0.5)]
    pub eps: f64,
    /// Length of the run (orbits); averages are over its second half.
    #[arg(long, default_value_t = 20.0)]
    pub orbits: f64,
    /// Side of the square box (m).
    #[arg(long = "box", default_value_t = 200.0)]
    pub box_size: f64,
    /// Seed of the initial conditions.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Orbital frequency Ω (1/s).
    #[arg(long, default_value_t = REBOUND_OMEGA)]
    pub omega: f64,
    /// Time step (orbits).
    #[arg(long, default_value_t = 1e-3)]
    pub dt_orbits: f64,
    /// Self-gravity: `tree` (what `--gravity` alone selects), `direct` or `none` (the default).
    #[arg(long, value_enum, num_args = 0..=1, default_missing_value = "tree")]
    pub gravity: Option<RingGravityArg>,
    /// Opening angle θ of the tree (a node of side w at distance d is taken whole when w < θ d).
    #[arg(long, default_value_t = mdr_ring::gravity::DEFAULT_OPENING_ANGLE)]
    pub opening_angle: f64,
    /// Ghost boxes on each side summed by the gravity solver (REBOUND: 2; direct only: 0 = nearest
    /// image).
    #[arg(long, default_value_t = mdr_ring::gravity::DEFAULT_GHOST_BOXES)]
    pub ghost_boxes: usize,
    /// Plummer softening length of the gravity (m).
    #[arg(long, default_value_t = 0.1)]
    pub softening: f64,
    /// MDR: Young's modulus of ice (Pa).
    #[arg(long, default_value_t = 9.0e9)]
    pub youngs: f64,
    /// MDR: Poisson's ratio of ice.
    #[arg(long, default_value_t = 0.33)]
    pub poisson: f64,
    /// MDR: critical line load q_c (N/m), eq. (7).
    #[arg(long, default_value_t = 8.0e3)]
    pub qc: f64,
    /// MDR: hardening ratio Θ/E*, eq. (12).
    #[arg(long, default_value_t = 0.2)]
    pub theta_ratio: f64,
    /// MDR: work of adhesion Δγ of ice on ice (J/m², ≥ 0; the scenes' `work_of_adhesion_j_per_m2`):
    /// impacts pay the adhesive hysteresis, slow ones stick (docs/theory.md §9).
    #[arg(long, default_value_t = 0.0)]
    pub work_of_adhesion: f64,
    /// Print the summary as one JSON object on stdout.
    #[arg(long)]
    pub json: bool,
    /// Output directory: timeseries.csv, summary.json, equilibration.svg, restitution.svg,
    /// frames/ring_*.vtk, frames/sigma_*.png (surface density) and frames/top_*.png (the patch
    /// seen from above).
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Interval between frames (VTK and the two PNG images, orbits); needs --out.
    #[arg(long, default_value_t = 1.0)]
    pub frame_orbits: f64,
    /// No progress lines on stderr.
    #[arg(long)]
    pub quiet: bool,
}

/// Run `sim ring`.
pub fn run_ring(args: &RingArgs) -> anyhow::Result<()> {
    let law = match args.law {
        RingLawArg::Bridges => LawChoice::Bridges(BridgesLaw::default()),
        RingLawArg::Constant => LawChoice::Constant(ConstantRestitution::new(args.eps)?),
        RingLawArg::Mdr => {
            let ice = Material::new(args.youngs, args.poisson, 400.0)?;
            let model = MdrElastoPlastic::new(args.qc, args.theta_ratio)?;
            LawChoice::Mdr(
                MdrRestitution::new(ice, model)?.with_work_of_adhesion(args.work_of_adhesion)?,
            )
        }
    };
    let mut config = RingConfig::default()
        .seed(args.seed)
        .box_size(args.box_size)
        .dt_orbits(args.dt_orbits);
    config.omega = args.omega;
    if let Some(n) = args.particles {
        config = config.particles(n);
    } else if let Some(sigma) = args.surface_density {
        config = config.surface_density(sigma);
    }
    let solver = match args.gravity {
        None | Some(RingGravityArg::None) => None,
        Some(RingGravityArg::Tree) => Some(GravitySolver::Tree {
            opening_angle: args.opening_angle,
            ghost_boxes: args.ghost_boxes,
        }),
        Some(RingGravityArg::Direct) => Some(GravitySolver::Direct {
            ghost_boxes: args.ghost_boxes,
        }),
    };
    if let Some(solver) = solver {
        config = config.gravity(SelfGravity {
            softening: args.softening,
            solver,
            ..SelfGravity::default()
        });
    }
    let options = RunOptions {
        config,
        law,
        orbits: args.orbits,
        out: args.out.clone(),
        frame_orbits: args.out.as_ref().map(|_| args.frame_orbits),
        progress: !args.quiet,
    };
    let report = run(&options).context("ring run failed")?;
    if args.json {
        println!("{}", serde_json::to_string(&report)?);
    } else {
        let s = &report.summary;
        println!(
            "{} particles, law {}, {} orbits (averages over the second half)",
            s.particles, report.law.name, report.orbits
        );
        println!(
            "c = {:.4} mm/s (sigma_x {:.4}, sigma_y {:.4}, sigma_z {:.4}; number-weighted {:.4})",
            s.c_m_per_s * 1e3,
            s.sigma_x_m_per_s * 1e3,
            s.sigma_y_m_per_s * 1e3,
            s.sigma_z_m_per_s * 1e3,
            s.c_number_m_per_s * 1e3
        );
        println!("c/(r_mean Omega) = {:.3}", s.c_over_mean_r_omega);
        println!(
            "z_rms = {:.3} m (number-weighted {:.3} m), mid-plane filling factor {:.4}",
            s.z_rms_m, s.z_rms_number_m, s.filling_factor_z0
        );
        println!(
            "{:.3} collisions per particle per orbit, {:.3} s wall per orbit",
            s.collisions_per_particle_per_orbit, s.wall_s_per_orbit
        );
        let shown = |v: Option<f64>| v.map_or("none".to_string(), |v| format!("{v:.1}"));
        println!(
            "gravity {}, Toomre Q = {:.2}, wakes: pitch {} deg, wavelength {} m, anisotropy {}",
            report.gravity,
            s.toomre_q,
            shown(report.wake_pitch_deg),
            shown(report.wake_wavelength_m),
            report
                .wake_anisotropy
                .map_or("none".to_string(), |v| format!("{v:.2}"))
        );
    }
    Ok(())
}
