//! Test 4: oblique impacts at constant speed and varying angle, against the experiment of
//! Kharaz, Gorham & Salman (2001).

use super::sweep::{oblique_study, ObliquePoint};
use super::{linspace, Resolution};
use crate::collision::{Backend, Collision, CollisionOutcome, Target};
use crate::error::Result;
use crate::kharaz;
use crate::materials;
use crate::report::{Check, Figure, Series, Style, TestReport, Tolerance};
use mdr_contact::Material;

/// Friction coefficient of test 4 (Kharaz et al. 2001).
pub const MU_4: f64 = 0.092;

/// Test 4: oblique impact of a sphere (R = 2.5 mm) on a rigid plane at 3.9 m/s, angle varied
/// (Kharaz, Gorham & Salman 2001 set-up): tangential restitution, rebound angle and spin.
pub fn test4(resolution: Resolution) -> Result<TestReport> {
    let angles = linspace(5.0, 85.0, resolution.points);
    let mut report = TestReport {
        number: 4,
        title: "oblique impact of a sphere with a rigid plane, constant speed, varying angle"
            .into(),
        checks: Vec::new(),
        figures: Vec::new(),
        notes: Vec::new(),
    };
    for (case, m) in [
        ("aluminium oxide", materials::aluminium_oxide()),
        ("aluminium alloy", materials::aluminium_alloy()),
    ] {
        let points: Vec<ObliquePoint> = angles
            .iter()
            .map(|&a| {
                let r = a.to_radians();
                ObliquePoint {
                    x: a,
                    collision: Collision {
                        tangential_speed: 3.9 * r.sin(),
                        friction: MU_4,
                        ..Collision::head_on(
                            0.0025,
                            m,
                            Target::Plane {
                                material: materials::rigid_for(&m),
                            },
                            3.9 * r.cos(),
                        )
                    },
                }
            })
            .collect();
        let (c, f, n, outcomes) =
            oblique_study(4, case, &points, "impact angle (degrees)", resolution)?;
        report.checks.extend(c);
        report.figures.extend(f);
        report.notes.extend(n);
        // Tangential restitution and rebound angle with the sliding theory:
        // e_t = 1 − μ(1+e)/tan θ, tan θ' = e_t tan θ / e.
        let mut et_series = vec![Series {
            label: "gross sliding theory, e_t = 1 − 2μ/tan θ".into(),
            points: angles
                .iter()
                .filter(|a| a.to_radians().tan() / MU_4 > 1.15 * 7.0)
                .map(|&a| (a, 1.0 - 2.0 * MU_4 / a.to_radians().tan()))
                .collect(),
            style: Style::Line,
        }];
        let mut rebound_series = vec![Series {
            label: "gross sliding theory".into(),
            points: angles
                .iter()
                .filter(|a| a.to_radians().tan() / MU_4 > 1.15 * 7.0)
                .map(|&a| {
                    let t = a.to_radians().tan();
                    (a, ((1.0 - 2.0 * MU_4 / t) * t).atan().to_degrees())
                })
                .collect(),
            style: Style::Line,
        }];
        for (k, backend) in resolution.backends().iter().enumerate() {
            let et: Vec<(f64, f64)> = points
                .iter()
                .zip(&outcomes[k])
                .map(|(p, o)| (p.x, o.tangential_velocity / p.collision.tangential_speed))
                .collect();
            let rebound: Vec<(f64, f64)> = points
                .iter()
                .zip(&outcomes[k])
                .map(|(p, o)| {
                    let vn_out = o.normal_restitution * p.collision.normal_speed;
                    (p.x, o.tangential_velocity.atan2(vn_out).to_degrees())
                })
                .collect();
            et_series.push(Series {
                label: backend.label().into(),
                points: et,
                style: Style::Points,
            });
            rebound_series.push(Series {
                label: backend.label().into(),
                points: rebound,
                style: Style::Points,
            });
        }
        let slug = case.replace(' ', "_");
        if case == "aluminium oxide" {
            et_series.push(measured(&kharaz::TANGENTIAL_RESTITUTION));
            rebound_series.push(measured(&kharaz::REBOUND_ANGLE_CENTRE));
            kharaz_comparison(m, resolution, &mut report)?;
        }
        report.figures.push(Figure {
            name: format!("verify_test4_{slug}_et"),
            title: format!("Test 4 ({case}): tangential restitution e_t"),
            x_label: "impact angle (degrees)".into(),
            y_label: "e_t = v_t' / v_t".into(),
            series: et_series,
        });
        report.figures.push(Figure {
            name: format!("verify_test4_{slug}_rebound"),
            title: format!("Test 4 ({case}): rebound angle of the centre"),
            x_label: "impact angle (degrees)".into(),
            y_label: "rebound angle (degrees)".into(),
            series: rebound_series,
        });
    }
    Ok(report)
}

fn measured(points: &[(f64, f64)]) -> Series {
    Series {
        label: "experiment, Kharaz, Gorham & Salman (2001)".into(),
        points: points.to_vec(),
        style: Style::Measured,
    }
}

/// Impact angle (°) from which the Kharaz, Gorham & Salman (2001) points are asserted: the
/// contact slides for the whole impact there (ψ = tan θ/μ > 1.15·3.5(1+e) at θ ≥ 28°), where the
/// result does not depend on the tangential compliance nor on the anvil's (soda-lime glass, not
/// rigid) stiffness. Below it the differences are measured and reported (notes), not asserted.
/// Budget of every tolerance (docs/verification.md §3): the paper's e = 0.98 against our elastic
/// e = 1, digitisation of the published figures (about 1 % of the axis range) and the scatter of
/// the experiment.
pub const KHARAZ_SLIDING_ANGLE: f64 = 28.0;
/// e_t against experiment (absolute): e = 0.98 vs 1 moves the sliding e_t by `0.02 μ/tan θ ≤
/// 0.004`, digitisation 0.01; measured ≤ 0.008.
pub const KHARAZ_ET_TOLERANCE: f64 = 0.02;
/// Spin against experiment (relative): e = 0.98 vs 1 lowers the sliding spin by 1 %; the measured
/// spins lie 0.2–7.5 % above the gross-sliding value, which both laws reproduce within 0.5 %
/// (an impulse identity, so the excess is experimental).
pub const KHARAZ_SPIN_TOLERANCE: f64 = 0.08;
/// Rebound angle of the centre against experiment (absolute, degrees): e = 0.98 vs 1 shifts it by
/// ≤ 0.7°, digitisation ≈ 0.6°; measured ≤ 0.21°.
pub const KHARAZ_CENTRE_ANGLE_TOLERANCE: f64 = 1.5;
/// Rebound angle of the contact point against experiment (absolute, degrees): in sliding
/// `tan φ' = (tan θ − 3.5 μ (1+e))/e`, so e = 0.98 vs 1 shifts it by 0.9–1.1° at 50–70°;
/// digitisation ≈ 1°; measured ≤ 2.7° (experiment above the simulation throughout).
pub const KHARAZ_CONTACT_ANGLE_TOLERANCE: f64 = 3.0;

/// Test 4 (aluminium oxide) against the experimental points: checks in gross sliding, the
/// stick/transition range measured and reported as notes; figures of spin (rad/s) and rebound
/// angle of the contact point with the experiment.
fn kharaz_comparison(m: Material, resolution: Resolution, report: &mut TestReport) -> Result<()> {
    let backends = [
        Backend::ValidatorMindlin,
        Backend::ValidatorSpringBed {
            springs: resolution.springs,
        },
    ];
    let at = |angle: f64, backend: Backend| -> Result<(Collision, CollisionOutcome)> {
        let r = angle.to_radians();
        let c = Collision {
            tangential_speed: 3.9 * r.sin(),
            friction: MU_4,
            steps_per_contact: resolution.steps_per_contact,
            ..Collision::head_on(
                0.0025,
                m,
                Target::Plane {
                    material: materials::rigid_for(&m),
                },
                3.9 * r.cos(),
            )
        };
        let out = c.run(backend)?;
        Ok((c, out))
    };
    type Quantity = fn(&Collision, &CollisionOutcome) -> f64;
    let e_t: Quantity = |c, o| {
        if c.tangential_speed > 0.0 {
            o.tangential_velocity / c.tangential_speed
        } else {
            1.0
        }
    };
    let spin: Quantity = |_, o| o.spin;
    let centre: Quantity = |c, o| {
        o.tangential_velocity
            .atan2(o.normal_restitution * c.normal_speed)
            .to_degrees()
    };
    let contact: Quantity = |c, o| {
        (o.tangential_velocity - c.radius * o.spin)
            .atan2(o.normal_restitution * c.normal_speed)
            .to_degrees()
    };
    /// Name, experimental points, computed quantity, tolerance.
    type Row = (&'static str, &'static [(f64, f64)], Quantity, Tolerance);
    let quantities: [Row; 4] = [
        (
            "e_t",
            &kharaz::TANGENTIAL_RESTITUTION,
            e_t,
            Tolerance::Absolute(KHARAZ_ET_TOLERANCE),
        ),
        (
            "spin ω' (rad/s)",
            &kharaz::SPIN,
            spin,
            Tolerance::Relative(KHARAZ_SPIN_TOLERANCE),
        ),
        (
            "rebound angle of the centre (°)",
            &kharaz::REBOUND_ANGLE_CENTRE,
            centre,
            Tolerance::Absolute(KHARAZ_CENTRE_ANGLE_TOLERANCE),
        ),
        (
            "rebound angle of the contact point (°)",
            &kharaz::REBOUND_ANGLE_CONTACT,
            contact,
            Tolerance::Absolute(KHARAZ_CONTACT_ANGLE_TOLERANCE),
        ),
    ];
    let mut spin_series = vec![measured(&kharaz::SPIN)];
    let mut contact_series = vec![measured(&kharaz::REBOUND_ANGLE_CONTACT)];
    for backend in backends {
        let mut computed: Vec<Vec<(f64, f64)>> = Vec::new();
        for (name, data, quantity, tolerance) in quantities {
            let mut worst_stick: (f64, f64) = (0.0, 0.0);
            let mut points = Vec::new();
            for &(angle, experiment) in data {
                let (c, out) = at(angle, backend)?;
                let value = quantity(&c, &out);
                points.push((angle, value));
                if angle >= KHARAZ_SLIDING_ANGLE {
                    report.checks.push(Check::new(
                        format!(
                            "{name} vs experiment (Kharaz et al. 2001), θ = {angle:.1}°, {}",
                            backend.label()
                        ),
                        value,
                        experiment,
                        tolerance,
                    ));
                } else if (value - experiment).abs() > worst_stick.1.abs() {
                    worst_stick = (angle, value - experiment);
                }
            }
            report.notes.push(format!(
                "aluminium oxide, {}: {name} − experiment below {KHARAZ_SLIDING_ANGLE}° (stick/\
                 transition, not asserted): largest {:+.3} at θ = {:.1}°",
                backend.label(),
                worst_stick.1,
                worst_stick.0
            ));
            computed.push(points);
        }
        spin_series.push(Series {
            label: backend.label().into(),
            points: computed[1].clone(),
            style: Style::Points,
        });
        contact_series.push(Series {
            label: backend.label().into(),
            points: computed[3].clone(),
            style: Style::Points,
        });
    }
    report.figures.push(Figure {
        name: "verify_test4_aluminium_oxide_spin_experiment".into(),
        title: "Test 4 (aluminium oxide): spin after impact vs experiment".into(),
        x_label: "impact angle (degrees)".into(),
        y_label: "ω' (rad/s)".into(),
        series: spin_series,
    });
    report.figures.push(Figure {
        name: "verify_test4_aluminium_oxide_rebound_contact".into(),
        title: "Test 4 (aluminium oxide): rebound angle of the contact point".into(),
        x_label: "impact angle (degrees)".into(),
        y_label: "atan((v_t' − R ω')/v_n') (degrees)".into(),
        series: contact_series,
    });
    Ok(())
}
