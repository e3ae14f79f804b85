//! Free motion in Hill's frame: the SEI keeps a collisionless particle's epicycle amplitude,
//! vertical amplitude and guiding centre to 1e-6 over 100 orbits; rapier's plain
//! integration of the Coriolis and tidal terms as an external force does not.

use mdr_ring::hill::{HillFrame, Sei};
use mdr_ring::prelude::REBOUND_OMEGA;
use rapier3d_f64::math::Vector;
use rapier3d_f64::prelude::*;

fn frame() -> HillFrame {
    HillFrame::new(REBOUND_OMEGA).unwrap()
}

/// A particle on an epicycle of 5 m about a guiding centre at x_g = 20 m, with 2 m vertical
/// amplitude, starting half-way round.
fn initial() -> (Vector, Vector) {
    let f = frame();
    let w = f.omega();
    let (xg, rho, zamp) = (20.0, 5.0, 2.0);
    // x = x_g + ρ cos φ, ẋ = −Ωρ sin φ, ẏ = −(3/2)Ω x_g − 2Ω(x − x_g).
    let phi: f64 = 0.7;
    let x = xg + rho * phi.cos();
    let vx = -w * rho * phi.sin();
    let vy = -1.5 * w * xg - 2.0 * w * (x - xg);
    (
        Vector::new(x, 3.0, zamp * 0.3_f64.cos()),
        Vector::new(vx, vy, -w * zamp * 0.3_f64.sin()),
    )
}

struct Drift {
    guiding_x: f64,
    guiding_y: f64,
    amplitude: f64,
    vertical: f64,
}

/// Relative drifts of the constants of motion after `orbits`, against the exact solution
/// (`x_g`, `ρ`, `z` amplitude constant; `y_g` moving at `−(3/2) Ω x_g`), measured in units of the
/// epicycle amplitude (5 m) or the vertical amplitude (2 m).
fn drifts(p: Vector, v: Vector, p0: Vector, v0: Vector, t: f64) -> Drift {
    let f = frame();
    let xg0 = f.guiding_centre_x(p0, v0);
    let yg_exact = f.guiding_centre_y(p0, v0) - 1.5 * f.omega() * xg0 * t;
    let rho0 = f.epicycle_amplitude(p0, v0);
    let zamp0 = f.vertical_amplitude(p0, v0);
    Drift {
        guiding_x: (f.guiding_centre_x(p, v) - xg0).abs() / rho0,
        guiding_y: (f.guiding_centre_y(p, v) - yg_exact).abs() / rho0,
        amplitude: (f.epicycle_amplitude(p, v) - rho0).abs() / rho0,
        vertical: (f.vertical_amplitude(p, v) - zamp0).abs() / zamp0,
    }
}

#[test]
fn sei_keeps_epicycle_and_guiding_centre_over_100_orbits() {
    let f = frame();
    let dt = 1e-3 * f.period();
    let sei = Sei::new(f, dt).unwrap();
    let (p0, v0) = initial();
    let (mut p, mut v) = (p0, v0);
    let steps = 100_000;
    for _ in 0..steps {
        sei.advance(&mut p, &mut v);
    }
    let d = drifts(p, v, p0, v0, steps as f64 * dt);
    assert!(d.guiding_x < 1e-6, "x_g drift {}", d.guiding_x);
    assert!(d.guiding_y < 1e-6, "y_g drift {}", d.guiding_y);
    assert!(
        d.amplitude < 1e-6,
        "epicycle amplitude drift {}",
        d.amplitude
    );
    assert!(d.vertical < 1e-6, "vertical amplitude drift {}", d.vertical);
}

#[test]
fn sei_matches_the_analytic_epicycle() {
    // After exactly a quarter orbit the radial phasor has turned by 90°.
    let f = frame();
    let (p0, v0) = initial();
    let quarter = Sei::new(f, 0.25 * f.period()).unwrap();
    let (mut p, mut v) = (p0, v0);
    quarter.advance(&mut p, &mut v);
    let xg = f.guiding_centre_x(p0, v0);
    let w = f.omega();
    // Ω(x − x_g) → ẋ, ẋ → −Ω(x − x_g).
    assert!((w * (p.x - xg) - v0.x).abs() < 1e-12);
    assert!((v.x + w * (p0.x - xg)).abs() < 1e-12);
    assert!((w * p.z - v0.z).abs() < 1e-12);
}

/// rapier integrating the Coriolis and tidal terms as an external force (one body, symplectic
/// Euler in rapier's solver): returns the drifts after `orbits`.
fn rapier_drift(orbits: usize) -> Drift {
    let f = frame();
    let dt = 1e-3 * f.period();
    let (p0, v0) = initial();
    let mut world = PhysicsWorld::new();
    world.gravity = Vector::ZERO;
    world.integration_parameters.dt = dt;
    let (body, _) = world.insert(
        RigidBodyBuilder::dynamic()
            .translation(p0)
            .linvel(v0)
            .can_sleep(false),
        ColliderBuilder::ball(1.0).mass(1.0),
    );
    let steps = orbits * 1000;
    for _ in 0..steps {
        let b = &mut world.bodies[body];
        let force = f.acceleration(b.translation(), b.linvel()) * b.mass();
        b.reset_forces(false);
        b.add_force(force, true);
        world.step();
    }
    let b = &world.bodies[body];
    drifts(b.translation(), b.linvel(), p0, v0, steps as f64 * dt)
}

#[test]
fn rapier_external_force_integration_drifts() {
    // Ten orbits already exceed the 1e-6 budget by orders of magnitude.
    let d = rapier_drift(10);
    eprintln!(
        "rapier, 10 orbits: x_g {:.2e}, y_g {:.2e}, epicycle {:.2e}, vertical {:.2e}",
        d.guiding_x, d.guiding_y, d.amplitude, d.vertical
    );
    assert!(d.amplitude.max(d.guiding_x).max(d.guiding_y) > 1e-4);
}

/// Over 100 orbits rapier's epicycle keeps growing by the same factor per step (the explicit
/// Coriolis rotation, docs/rings.md §2): `ln(ρ₁₀₀/ρ₀) = 10 ln(ρ₁₀/ρ₀)` within 5 % (measured
/// 10.04; ρ₁₀/ρ₀ = 1.76, ρ₁₀₀/ρ₀ = 291), while the SEI keeps it to 1e-6 (test above). A bounded
/// or saturating error would fail the ratio.
#[test]
fn rapier_external_force_drift_grows_geometrically_over_100_orbits() {
    let ten = rapier_drift(10);
    let hundred = rapier_drift(100);
    eprintln!(
        "rapier, 100 orbits: x_g {:.3e}, y_g {:.3e}, epicycle {:.3e}, vertical {:.3e}",
        hundred.guiding_x, hundred.guiding_y, hundred.amplitude, hundred.vertical
    );
    let ratio = (1.0 + hundred.amplitude).ln() / (1.0 + ten.amplitude).ln();
    assert!(
        (ratio / 10.0 - 1.0).abs() < 0.05,
        "ln growth over 100 orbits / over 10 = {ratio} (epicycle {} and {})",
        ten.amplitude,
        hundred.amplitude
    );
    assert!(hundred.amplitude > 100.0, "epicycle {}", hundred.amplitude);
}
