//! The O(1) Mindlin law against its definition written out (docs/theory.md §5): stick
//! `F_t = −2G* a ξ` with `½ k_t |ξ|²` stored; gross slip at `μ F_N` with `μ F_N` times the slip
//! length dissipated; the radius rescale of a shrinking contact in both forms, and without it;
//! the energy a contact releases when it opens.

use mdr_contact::normal::NormalResponse;
use mdr_contact::prelude::*;
use mdr_contact::tangential::MindlinForm;
use nalgebra::Vector3;

const MU: f64 = 0.3;

fn input(dx: f64, force: f64, a: f64) -> TangentialInput {
    TangentialInput {
        normal: Vector3::z(),
        displacement_increment: Vector3::new(dx, 0.0, 0.0),
        normal_response: NormalResponse {
            force,
            contact_radius: a,
            stiffness: 0.0,
        },
    }
}

fn close(x: f64, y: f64) -> bool {
    (x - y).abs() <= 1e-12 * y.abs()
}

#[test]
fn stick_slip_and_the_coulomb_cap() {
    let pair = ContactPair::paper_fig2();
    let g = pair.effective_shear_modulus();
    let model = Mindlin::new(MU).unwrap();
    assert_eq!(model.friction_coefficient(), MU);
    let law = model.bind(&pair).unwrap();
    let (a, f_n) = (1e-4, 50.0);
    let k = 2.0 * g * a;
    assert!(close(law.stiffness(a), k));
    let mut state = MindlinState::default();

    // Stick: two increments add up, the force is −k ξ, nothing dissipated.
    let dx = 0.2 * MU * f_n / k;
    assert!(!law.update(&mut state, &input(dx, f_n, a)).sliding);
    let r = law.update(&mut state, &input(dx, f_n, a));
    let xi = 2.0 * dx;
    assert!(close(r.force.x, -k * xi), "{}", r.force.x);
    assert_eq!(r.force.y, 0.0);
    assert!(!r.sliding);
    assert_eq!(r.dissipated, 0.0);
    assert!(close(r.elastic_energy, 0.5 * k * xi * xi));
    assert!(close(state.displacement.x, xi));
    assert_eq!(state.contact_radius, a);

    // Gross slip: the trial force k(ξ + Δ) exceeds μ F_N; the spring is reset to the cap and
    // μ F_N times the slip length (the excess of the trial displacement) is dissipated.
    let step = MU * f_n / k;
    let r = law.update(&mut state, &input(step, f_n, a));
    let trial = xi + step;
    let kept = MU * f_n / k;
    assert!(r.sliding);
    assert!(close(r.force.x, -MU * f_n), "{}", r.force.x);
    assert!(
        close(r.dissipated, MU * f_n * (trial - kept)),
        "{}",
        r.dissipated
    );
    assert!(close(r.elastic_energy, 0.5 * k * kept * kept));
    assert!(close(state.displacement.x, kept));

    // Reversing sticks again: the force falls by k Δ.
    let back = 0.1 * kept;
    let r = law.update(&mut state, &input(-back, f_n, a));
    assert!(!r.sliding);
    assert!(close(r.force.x, -k * (kept - back)));

    // A contact that opens forgets its displacement and releases the energy it held.
    let held = 0.5 * k * (kept - back).powi(2);
    let r = law.update(&mut state, &input(0.0, 0.0, 0.0));
    assert_eq!(r.force, Vector3::zeros());
    assert!(close(r.stiffness_energy, -held), "{}", r.stiffness_energy);
    assert_eq!(state, MindlinState::default());
    assert!(close(
        law.stiffness_energy_change(1e-12, a, 0.0),
        -0.5 * k * 1e-12
    ));
    assert_eq!(law.stiffness_energy_change(0.0, a, 2.0 * a), 0.0);
}

/// A contact that shrinks from `a` to `a/2` at a fixed displacement: the displacement form
/// rescales ξ by `a/a_prev` (force `k(a/2) ξ/2`, a quarter), without the rescale it keeps ξ
/// (force `k(a/2) ξ`, a half); the force form keeps the force times `a/a_prev` (a half) and
/// without the rescale the whole force. Growing back to `a` the displacement form keeps ξ
/// (force doubles) and the force form keeps the force.
#[test]
fn radius_rescale_in_both_forms() {
    let pair = ContactPair::paper_fig2();
    let g = pair.effective_shear_modulus();
    let (a, f_n) = (1e-4, 1e3);
    let k = |r: f64| 2.0 * g * r;
    let xi = 1e-8;
    let cases = [
        (MindlinForm::Displacement, true, 0.25, 0.5),
        (MindlinForm::Displacement, false, 0.5, 1.0),
        (MindlinForm::Force, true, 0.5, 0.5),
        (MindlinForm::Force, false, 1.0, 1.0),
    ];
    for (form, rescale, shrunk, regrown) in cases {
        let law = Mindlin::new(MU)
            .unwrap()
            .form(form)
            .rescale_on_unloading(rescale)
            .bind(&pair)
            .unwrap();
        let mut state = MindlinState::default();
        let f0 = law.update(&mut state, &input(xi, f_n, a)).force.x;
        assert!(close(f0, -k(a) * xi));
        let r = law.update(&mut state, &input(0.0, f_n, 0.5 * a));
        assert!(
            close(r.force.x, shrunk * f0),
            "{form:?}, rescale {rescale}: shrunk {} vs {}",
            r.force.x,
            shrunk * f0
        );
        // The spring's energy changes without work: ½k'|ξ'|² − ½k|ξ|².
        let before = 0.5 * k(a) * xi * xi;
        assert!(
            close(r.stiffness_energy, r.elastic_energy - before),
            "{form:?}, rescale {rescale}: {} vs {}",
            r.stiffness_energy,
            r.elastic_energy - before
        );
        let r = law.update(&mut state, &input(0.0, f_n, a));
        assert!(
            close(r.force.x, regrown * f0),
            "{form:?}, rescale {rescale}: regrown {} vs {}",
            r.force.x,
            regrown * f0
        );
    }
}

/// Coulomb's law with no compressive load: `|F_t| ≤ μ max(F_N, 0) = 0`. A contact whose springs
/// still touch (`a > 0`) but carry no normal load (`F_N = 0`) or a tensile one (`F_N < 0`)
/// transmits no tangential force, and the energy the springs held leaves the books as released
/// (`stiffness_energy = −½k|ξ|²`, nothing dissipated): the balance `ΔE = W + stiffness_energy −
/// dissipated` with `W = 0` (no force).
#[test]
fn no_compressive_load_carries_no_tangential_force() {
    let pair = ContactPair::paper_fig2();
    let law = Mindlin::new(MU).unwrap().bind(&pair).unwrap();
    let (a, f_n) = (1e-4, 50.0);
    let k = law.stiffness(a);
    for load in [0.0, -0.2 * f_n] {
        let mut state = MindlinState::default();
        let xi = 0.5 * MU * f_n / k;
        let held = law.update(&mut state, &input(xi, f_n, a)).elastic_energy;
        assert!(close(held, 0.5 * k * xi * xi));
        let r = law.update(&mut state, &input(0.1 * xi, load, a));
        assert_eq!(r.force, Vector3::zeros(), "F_N = {load}");
        assert_eq!(r.elastic_energy, 0.0);
        assert_eq!(r.dissipated, 0.0);
        assert!(
            close(r.stiffness_energy, -held),
            "F_N = {load}: {} vs {}",
            r.stiffness_energy,
            -held
        );
        assert_eq!(state, MindlinState::default());
    }
}

/// Only the tangential part of the relative displacement loads the springs (§5: `Δu_t = Δu −
/// n (n·Δu)`); a displacement stored along what becomes the new normal has no part in the new
/// contact plane and is dropped, so only the step's own tangential increment remains.
#[test]
fn only_the_tangential_displacement_loads_the_springs() {
    let pair = ContactPair::paper_fig2();
    let law = Mindlin::new(MU).unwrap().bind(&pair).unwrap();
    let (a, f_n) = (1e-4, 50.0);
    let k = law.stiffness(a);
    let dx = 0.1 * MU * f_n / k;
    // A normal component of the increment (here 100 dx) is not a tangential displacement.
    let mut state = MindlinState::default();
    let mut along = input(dx, f_n, a);
    along.displacement_increment.z = 100.0 * dx;
    let r = law.update(&mut state, &along);
    assert!(close(r.force.x, -k * dx), "{:?}", r.force);
    assert_eq!((r.force.y, r.force.z), (0.0, 0.0));
    assert!(close(r.elastic_energy, 0.5 * k * dx * dx));
    // The plane turns by 90° about y: the stored ξ (along x) lies along the new normal.
    let step = 0.5 * dx;
    let r = law.update(
        &mut state,
        &TangentialInput {
            normal: Vector3::x(),
            displacement_increment: Vector3::new(0.0, step, 0.0),
            normal_response: NormalResponse {
                force: f_n,
                contact_radius: a,
                stiffness: 0.0,
            },
        },
    );
    assert_eq!(r.force.x, 0.0);
    assert!(close(r.force.y, -k * step), "{:?}", r.force);
    assert_eq!(r.force.z, 0.0);
    assert!(close(r.elastic_energy, 0.5 * k * step * step));
}
