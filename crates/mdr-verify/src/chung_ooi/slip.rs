//! Tests 5–8: slip from tangential speed or spin, on a rigid plane (5, 6) and between two
//! spheres (7, 8).

use super::sweep::{oblique_report, plane_case, ObliquePoint};
use super::{linspace, Resolution};
use crate::collision::{Collision, Target};
use crate::error::Result;
use crate::materials;
use crate::report::TestReport;
use mdr_contact::Material;

/// Friction coefficient of test 5.
pub const MU_5: f64 = 0.3;
/// Friction coefficient of tests 6–8.
pub const MU_6_TO_8: f64 = 0.4;

/// Test 5 (Chung & Ooi; Thornton et al.'s FEM case): sphere R = 10 µm on a rigid plane, normal
/// speed 5 m/s, tangential speed varied, elastic, μ = 0.3, steel and polyethylene.
pub fn test5(resolution: Resolution) -> Result<TestReport> {
    let psis = linspace(0.5, 14.0, resolution.points);
    let cases = [
        ("steel", materials::steel()),
        ("polyethylene", materials::polyethylene()),
    ]
    .into_iter()
    .map(|(name, m)| {
        let pts = psis
            .iter()
            .map(|&psi| ObliquePoint {
                x: psi,
                collision: plane_case(m, TEST5_RADIUS, 5.0, MU_5, psi * MU_5 * 5.0, 0.0),
            })
            .collect();
        (name.to_string(), pts)
    })
    .collect();
    oblique_report(
        5,
        "oblique impact on a rigid plane, constant normal speed, varying tangential speed",
        cases,
        "ψ = v_t / (μ v_n)",
        resolution,
    )
}

/// Radius of test 5's sphere (m).
pub const TEST5_RADIUS: f64 = 1.0e-5;

/// Test 6: spinning sphere (R = 0.1 m) on a rigid plane, normal speed 0.2 m/s, no tangential
/// speed, angular velocity varied; aluminium alloy and nylon, μ = 0.4.
pub fn test6(resolution: Resolution) -> Result<TestReport> {
    let psis = linspace(0.5, 14.0, resolution.points);
    let cases = materials_6_and_8()
        .into_iter()
        .map(|(name, m)| {
            let pts = psis
                .iter()
                .map(|&psi| ObliquePoint {
                    x: psi,
                    collision: plane_case(m, 0.1, 0.2, MU_6_TO_8, 0.0, psi * MU_6_TO_8 * 0.2 / 0.1),
                })
                .collect();
            (name.to_string(), pts)
        })
        .collect();
    oblique_report(
        6,
        "oblique impact of a spinning sphere on a rigid plane",
        cases,
        "R ω / (μ v_n)",
        resolution,
    )
}

fn materials_6_and_8() -> [(&'static str, Material); 2] {
    [
        ("aluminium alloy", materials::aluminium_alloy()),
        ("nylon", materials::nylon()),
    ]
}

/// Test 7: two identical spheres (R = 0.1 m) approaching at ±0.2 m/s (relative 0.4 m/s),
/// aluminium alloy and copper, μ = 0.4, angular velocity ω varied from 0.175 to 21 rad/s.
/// The paper's case: the spheres spin in opposite senses, so that their surfaces at the contact
/// move together (no slip): no tangential force may arise, ω' = ω and v_t' = 0. A second case
/// (not in the paper): both spin in the same sense, slip `2 R ω`.
pub fn test7(resolution: Resolution) -> Result<TestReport> {
    let omegas = linspace(0.175, 21.0, resolution.points);
    let mut cases = Vec::new();
    for (name, m) in [
        ("aluminium alloy", materials::aluminium_alloy()),
        ("copper", materials::copper()),
    ] {
        for (arrangement, sign) in [("counter-rotating", -1.0), ("co-rotating", 1.0)] {
            let pts = omegas
                .iter()
                .map(|&omega| ObliquePoint {
                    x: omega,
                    collision: Collision {
                        spin: omega,
                        friction: MU_6_TO_8,
                        ..Collision::head_on(
                            0.1,
                            m,
                            Target::Sphere {
                                radius: 0.1,
                                material: m,
                                spin: sign * omega,
                            },
                            0.4,
                        )
                    },
                })
                .collect();
            cases.push((format!("{name} {arrangement}"), pts));
        }
    }
    oblique_report(
        7,
        "two identical spheres, constant normal speed, varying angular velocity",
        cases,
        "ω (rad/s)",
        resolution,
    )
}

/// Test 8: a spinning sphere (R = 0.1 m, ω varied, no tangential speed) on a larger free sphere
/// at rest (R = 0.5 m, same material), normal speed 0.2 m/s, μ = 0.4; aluminium alloy and nylon.
/// A second case (not in the paper): no spin, tangential speed varied.
pub fn test8(resolution: Resolution) -> Result<TestReport> {
    let psis = linspace(0.5, 14.0, resolution.points);
    let mut cases = Vec::new();
    for (name, m) in materials_6_and_8() {
        for spinning in [true, false] {
            let pts = psis
                .iter()
                .map(|&psi| {
                    let slip = psi * MU_6_TO_8 * 0.2;
                    let (vt, spin) = if spinning {
                        (0.0, -slip / 0.1)
                    } else {
                        (slip, 0.0)
                    };
                    ObliquePoint {
                        x: psi,
                        collision: Collision {
                            tangential_speed: vt,
                            spin,
                            friction: MU_6_TO_8,
                            ..Collision::head_on(
                                0.1,
                                m,
                                Target::Sphere {
                                    radius: 0.5,
                                    material: m,
                                    spin: 0.0,
                                },
                                0.2,
                            )
                        },
                    }
                })
                .collect();
            let label = if spinning { "spinning" } else { "sliding" };
            cases.push((format!("{name} {label}"), pts));
        }
    }
    oblique_report(
        8,
        "two different spheres, constant normal speed, varying angular velocity",
        cases,
        "ψ = |v_slip| / (μ v_n)",
        resolution,
    )
}
