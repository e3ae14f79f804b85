//! The energy the O(1) Mindlin law reports for a stored state, `TangentialLaw::elastic_energy`
//! (docs/theory.md §5: `½ k_t(a) |ξ|²` with `k_t = 2 G* a` at the stored contact radius), against
//! the work done on the spring: at a fixed contact radius the spring is linear, so the work
//! `−Σ ½(F_{i−1} + F_i)·Δu_i` of a stick path (the trapezoid rule, exact for a linear force) is
//! what it stores; after gross slip it holds `½ (μ F_N)²/k_t`, the energy of a spring at the
//! Coulomb limit. `mindlin_law.rs` checks the energy each update returns; this checks the one
//! read back from the state alone: the other tests of the law miss all seven mutants of it
//! (its value `0`, `±1`; `*` → `+`, `/`), which this one catches (docs/verification.md §5).

use mdr_contact::normal::NormalResponse;
use mdr_contact::prelude::*;
use nalgebra::Vector3;

const MU: f64 = 0.3;

fn input(du: Vector3<f64>, force: f64, a: f64) -> TangentialInput {
    TangentialInput {
        normal: Vector3::z(),
        displacement_increment: du,
        normal_response: NormalResponse {
            force,
            contact_radius: a,
            stiffness: 0.0,
        },
    }
}

#[test]
fn the_stored_energy_is_the_work_done_on_the_spring_and_the_coulomb_limits_after_slip() {
    let pair = ContactPair::paper_fig2();
    let law = Mindlin::new(MU).unwrap().bind(&pair).unwrap();
    let (a, f_n) = (2.5e-4, 80.0);
    let k = 2.0 * pair.effective_shear_modulus() * a;
    let limit = MU * f_n / k;
    let mut state = MindlinState::default();
    assert_eq!(law.elastic_energy(&state), 0.0);

    // A bent stick path in the plane, reaching 0.6 of the Coulomb limit.
    let steps = [
        Vector3::new(0.2, 0.1, 0.0),
        Vector3::new(0.15, -0.05, 0.0),
        Vector3::new(-0.05, 0.3, 0.0),
        Vector3::new(0.1, 0.1, 0.0),
    ];
    let mut force = Vector3::zeros();
    let mut work = 0.0;
    for step in steps {
        let du = step * limit;
        let r = law.update(&mut state, &input(du, f_n, a));
        assert!(!r.sliding);
        work -= 0.5 * (force + r.force).dot(&du);
        force = r.force;
    }
    let stored = law.elastic_energy(&state);
    assert!((stored - work).abs() <= 1e-12 * work, "{stored} vs {work}");

    // Gross slip: the spring is held at the Coulomb limit.
    law.update(
        &mut state,
        &input(Vector3::new(3.0 * limit, 0.0, 0.0), f_n, a),
    );
    let at_limit = 0.5 * (MU * f_n).powi(2) / k;
    let stored = law.elastic_energy(&state);
    assert!(
        (stored - at_limit).abs() <= 1e-12 * at_limit,
        "{stored} vs {at_limit}"
    );
}
