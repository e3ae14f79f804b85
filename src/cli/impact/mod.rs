//! `mdr-dem impact …`: the single-impact validator. Flags are parsed and checked here;
//! the physics lives in `mdr-contact` and the integration in `mdr-impact`.
//!
//! Every `impact` subcommand takes the common material/law flags ([`CommonArgs`]); the same keys
//! may be given in a TOML file with `--config FILE.toml`, and flags override the file.
//!
//! One module per subcommand (`fig2`, `curve`, `trace`, `fit`, `oblique`); the shared flags,
//! their checks and the output helpers are in `common`; the law-parameter flags, derived from
//! the registered laws' declarations, in `law_flags`.

mod common;
mod curve;
mod fig2;
mod fit;
mod law_flags;
mod oblique;
mod trace;

use clap::Subcommand;

pub(crate) use common::{contact_error, friction, materials, normal_laws};
pub use common::{CommonArgs, MethodName};
pub use curve::CurveArgs;
pub use fig2::Fig2Args;
pub use fit::FitArgs;
pub(crate) use law_flags::registered_law;
pub use oblique::ObliqueArgs;
pub use trace::TraceArgs;

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
        ImpactCommand::Fig2(args) => fig2::run_fig2(&args),
        ImpactCommand::Curve(args) => curve::run_curve(&args),
        ImpactCommand::Trace(args) => trace::run_trace(&args),
        ImpactCommand::Fit(args) => fit::run_fit(&args),
        ImpactCommand::Oblique(args) => oblique::run_oblique(&args),
    }
}
