//! Tests 1–3: head-on impacts. Elastic ones against Hertz (two spheres; a sphere on a rigid
//! plane), and prescribed restitution coefficients obtained from the MDR law's plasticity.

use super::{
    linspace, Resolution, ELASTIC_RESTITUTION_TOLERANCE, HERTZ_TOLERANCE,
    PLASTIC_RESTITUTION_TOLERANCE,
};
use crate::collision::{Backend, Collision, Target};
use crate::error::{invalid, Result};
use crate::materials;
use crate::reference::{self, HertzImpact};
use crate::report::{Check, Figure, Series, Style, TestReport, Tolerance};
use mdr_contact::normal::{MdrElastoPlastic, MdrState, NormalModel};
use mdr_contact::Material;
use mdr_impact::{Impact, NormalSpec};

/// Tests 1 and 2: elastic head-on impacts against Hertz.
fn normal_elastic(
    number: u8,
    title: &str,
    cases: &[(&str, Collision)],
    resolution: Resolution,
) -> Result<TestReport> {
    let mut checks = Vec::new();
    let mut figures = Vec::new();
    for (name, base) in cases {
        let collision = Collision {
            steps_per_contact: resolution.steps_per_contact,
            ..*base
        };
        let pair = collision.pair()?;
        let hertz = HertzImpact::new(&pair, collision.normal_speed);
        for backend in resolution.backends() {
            let out = collision.run(backend)?;
            let label = format!("{name}, {}", backend.label());
            // rapier counts whole steps in contact: allow one step on each side.
            let time_tolerance = match backend {
                Backend::RapierForce => HERTZ_TOLERANCE + 2.0 * out.time_step / hertz.contact_time,
                _ => HERTZ_TOLERANCE,
            };
            checks.push(Check::new(
                format!("contact time, {label}"),
                out.contact_time,
                hertz.contact_time,
                Tolerance::Relative(time_tolerance),
            ));
            checks.push(Check::new(
                format!("peak force, {label}"),
                out.peak_force,
                hertz.peak_force,
                Tolerance::Relative(HERTZ_TOLERANCE),
            ));
            checks.push(Check::new(
                format!("e_n, {label}"),
                out.normal_restitution,
                1.0,
                Tolerance::Absolute(ELASTIC_RESTITUTION_TOLERANCE),
            ));
        }
        // Force–overlap history of the validator against Hertz's curve (eq. 5).
        let pair = collision.pair()?;
        let (_, trace) = Impact::new(pair, NormalSpec::Hertz, collision.normal_speed)
            .steps_per_contact(resolution.steps_per_contact)
            .trace()?;
        let stride = (trace.len() / 60).max(1);
        let simulated: Vec<(f64, f64)> = trace
            .iter()
            .step_by(stride)
            .map(|p| (p.overlap * 1e6, p.force * 1e-3))
            .collect();
        let curve: Vec<(f64, f64)> = linspace(0.0, hertz.max_overlap, 100)
            .into_iter()
            .map(|d| (d * 1e6, reference::hertz_force(&pair, d) * 1e-3))
            .collect();
        let time: Vec<(f64, f64)> = trace
            .iter()
            .step_by(stride)
            .map(|p| (p.time * 1e6, p.force * 1e-3))
            .collect();
        let slug = name.replace(' ', "_");
        figures.push(Figure {
            name: format!("verify_test{number}_{slug}_force_overlap"),
            title: format!("Test {number} ({name}): force vs overlap"),
            x_label: "overlap (µm)".into(),
            y_label: "normal force (kN)".into(),
            series: vec![
                Series {
                    label: "Hertz, eq. (5)".into(),
                    points: curve,
                    style: Style::Line,
                },
                Series {
                    label: "validator (loading and unloading)".into(),
                    points: simulated,
                    style: Style::Points,
                },
            ],
        });
        figures.push(Figure {
            name: format!("verify_test{number}_{slug}_force_time"),
            title: format!(
                "Test {number} ({name}): force vs time; Hertz t_c = {:.2} µs, F_max = {:.3} kN",
                hertz.contact_time * 1e6,
                hertz.peak_force * 1e-3
            ),
            x_label: "time (µs)".into(),
            y_label: "normal force (kN)".into(),
            series: vec![
                Series {
                    label: "Hertz peak force".into(),
                    points: vec![
                        (0.0, hertz.peak_force * 1e-3),
                        (hertz.contact_time * 1e6, hertz.peak_force * 1e-3),
                    ],
                    style: Style::Dashed,
                },
                Series {
                    label: "validator".into(),
                    points: time,
                    style: Style::Points,
                },
            ],
        });
    }
    Ok(TestReport {
        number,
        title: title.into(),
        checks,
        figures,
        notes: Vec::new(),
    })
}

/// Test 1: elastic normal impact of two identical spheres (R = 10 mm, each at 10 m/s).
pub fn test1(resolution: Resolution) -> Result<TestReport> {
    let case = |m: Material| {
        Collision::head_on(
            0.01,
            m,
            Target::Sphere {
                radius: 0.01,
                material: m,
                spin: 0.0,
            },
            20.0,
        )
    };
    normal_elastic(
        1,
        "elastic normal impact of two identical spheres",
        &[
            ("glass", case(materials::glass())),
            ("limestone", case(materials::limestone())),
        ],
        resolution,
    )
}

/// Test 2: elastic normal impact of a sphere (R = 0.1 m, 0.2 m/s) on a rigid plane.
pub fn test2(resolution: Resolution) -> Result<TestReport> {
    let case = |m: Material| {
        Collision::head_on(
            0.1,
            m,
            Target::Plane {
                material: materials::rigid_for(&m),
            },
            0.2,
        )
    };
    normal_elastic(
        2,
        "elastic normal impact of a sphere with a rigid plane",
        &[
            ("aluminium alloy", case(materials::aluminium_alloy())),
            ("magnesium alloy", case(materials::magnesium_alloy())),
        ],
        resolution,
    )
}

/// Hardening ratio `Θ/E*` of test 3's MDR law: perfectly plastic, so that the whole range of
/// restitution coefficients down to 0.2 is reachable at 3.9 m/s.
pub const TEST3_HARDENING_RATIO: f64 = 0.0;

/// The critical line load `q_c` (N/m) that gives restitution `target` at speed `v` for `pair`
/// by the law's time-free energy route (docs/theory.md §4), by bisection in `log q_c`.
pub fn line_load_for_restitution(
    pair: &mdr_contact::ContactPair,
    hardening_ratio: f64,
    v: f64,
    target: f64,
) -> Result<f64> {
    if !(target > 0.0 && target < 1.0) {
        return Err(invalid("target restitution", target, "0 < e < 1"));
    }
    let e_of = |q: f64| -> Result<f64> {
        let law = MdrElastoPlastic::new(q, hardening_ratio)?.bind(pair)?;
        Ok(law
            .impact(&MdrState::default(), pair.reduced_mass(), v)?
            .restitution)
    };
    let (mut lo, mut hi) = (1e-2_f64.ln(), 1e9_f64.ln());
    if e_of(lo.exp())? > target || e_of(hi.exp())? < target {
        return Err(invalid(
            "target restitution",
            target,
            "a restitution reachable with q_c in [1e-2, 1e9] N/m",
        ));
    }
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if e_of(mid.exp())? < target {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Ok((0.5 * (lo + hi)).exp())
}

/// Test 3: normal impacts (R = 2.5 mm, 3.9 m/s, rigid plane) with prescribed restitution
/// coefficients, obtained here from plasticity: `q_c` is set by the energy route so that the MDR
/// law gives the prescribed `e`; the time integrations (closed form in the validator and in
/// rapier, the discrete spring bed in the validator) must reproduce it.
pub fn test3(resolution: Resolution) -> Result<TestReport> {
    let targets: Vec<f64> = if resolution.points >= 9 {
        vec![0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 0.95]
    } else {
        vec![0.2, 0.5, 0.8]
    };
    let mut checks = Vec::new();
    let mut series = Vec::new();
    for (name, m) in [
        ("aluminium oxide", materials::aluminium_oxide()),
        ("cast iron", materials::cast_iron()),
    ] {
        let base = Collision {
            steps_per_contact: resolution.steps_per_contact,
            ..Collision::head_on(
                0.0025,
                m,
                Target::Plane {
                    material: materials::rigid_for(&m),
                },
                3.9,
            )
        };
        let pair = base.pair()?;
        for backend in resolution.backends() {
            let mut points = Vec::new();
            for &e in &targets {
                let q_c = line_load_for_restitution(&pair, TEST3_HARDENING_RATIO, 3.9, e)?;
                let collision = Collision {
                    normal_law: MdrElastoPlastic::new(q_c, TEST3_HARDENING_RATIO)?,
                    ..base
                };
                let out = collision.run(backend)?;
                checks.push(Check::new(
                    format!("e_n for prescribed e = {e}, {name}, {}", backend.label()),
                    out.normal_restitution,
                    e,
                    Tolerance::Absolute(PLASTIC_RESTITUTION_TOLERANCE),
                ));
                points.push((e, out.normal_restitution));
            }
            series.push(Series {
                label: format!("{name}, {}", backend.label()),
                points,
                style: Style::Points,
            });
        }
    }
    series.insert(
        0,
        Series {
            label: "prescribed e (energy route)".into(),
            points: vec![(0.0, 0.0), (1.0, 1.0)],
            style: Style::Line,
        },
    );
    Ok(TestReport {
        number: 3,
        title: "normal contact with different coefficients of restitution (MDR plasticity)".into(),
        checks,
        figures: vec![Figure {
            name: "verify_test3_restitution".into(),
            title: "Test 3: measured vs prescribed e_n (R = 2.5 mm, 3.9 m/s)".into(),
            x_label: "prescribed e_n".into(),
            y_label: "measured e_n".into(),
            series,
        }],
        notes: Vec::new(),
    })
}
