//! The damping sub-models against their formulas, written out here from the documentation they
//! cite, and one physical property each: LAMMPS `gran/hertz/history`'s dashpot
//! `F_d = m γ_n √(R δ) dδ/dt` (tangential `γ_t = ratio · γ_n`), Tsuji's viscoelastic dashpot
//! `F_d = η √(m k_n) dδ/dt` (k_n the normal law's tangent stiffness), whose restitution on a Hertz
//! contact does not depend on the impact speed (k_n ∝ δ^{1/2}, Tsuji, Tanaka & Ishida 1992), while
//! the LAMMPS dashpot's falls with speed.

use mdr_contact::damping::{
    DampingLaw, DampingModel, HertzianViscous, NoDamping, StiffnessViscous,
};
use mdr_contact::normal::{Hertz, NormalLaw, NormalModel, NormalResponse};
use mdr_contact::ContactPair;

const E_STAR: f64 = 1.5e8;
const RADIUS: f64 = 0.01;
const MASS: f64 = 0.02;

fn pair() -> ContactPair {
    ContactPair::new(E_STAR, 0.4 * E_STAR, RADIUS, MASS).unwrap()
}

fn response(stiffness: f64) -> NormalResponse {
    NormalResponse {
        force: 1.0,
        contact_radius: 1e-4,
        stiffness,
    }
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-13 * b.abs().max(1e-300)
}

#[test]
fn hertzian_viscous_is_lammps_gran_hertz_history() {
    let (gamma_n, ratio) = (37.0, 0.3);
    let law = HertzianViscous::new(gamma_n)
        .unwrap()
        .with_tangential_ratio(ratio)
        .unwrap()
        .bind(&pair())
        .unwrap();
    for (overlap, rate) in [(1e-6, 0.3), (4e-5, -1.7), (2e-4, 2.5)] {
        let eta = MASS * gamma_n * (RADIUS * overlap).sqrt();
        let r = response(123.0);
        assert!(close(law.normal_coefficient(&r, overlap), eta));
        assert!(close(law.normal_force(&r, overlap, rate), eta * rate));
        assert!(close(law.tangential_coefficient(&r, overlap), ratio * eta));
    }
    assert_eq!(law.normal_coefficient(&response(1.0), 0.0), 0.0);
    assert_eq!(law.normal_coefficient(&response(1.0), -1e-6), 0.0);
    assert_eq!(law.tangential_ratio(), ratio);
    let plain = HertzianViscous::new(gamma_n)
        .unwrap()
        .bind(&pair())
        .unwrap();
    assert_eq!(plain.tangential_ratio(), 0.0);
}

#[test]
fn stiffness_viscous_is_tsuji() {
    let (eta, ratio) = (0.4, 0.7);
    let law = StiffnessViscous::new(eta)
        .unwrap()
        .with_tangential_ratio(ratio)
        .unwrap()
        .bind(&pair())
        .unwrap();
    for (stiffness, rate) in [(1e3, 0.2), (5e5, -3.0), (2e7, 1.1)] {
        let r = response(stiffness);
        let c = eta * (MASS * stiffness).sqrt();
        assert!(close(law.normal_coefficient(&r, 1e-5), c));
        assert!(close(law.normal_force(&r, 1e-5, rate), c * rate));
        assert!(close(law.tangential_coefficient(&r, 1e-5), ratio * c));
    }
    assert_eq!(law.tangential_ratio(), ratio);
    let plain = StiffnessViscous::new(eta).unwrap().bind(&pair()).unwrap();
    assert_eq!(plain.tangential_ratio(), 0.0);
}

#[test]
fn no_damping_adds_nothing() {
    let law = NoDamping.bind(&pair()).unwrap();
    let r = response(1e6);
    assert_eq!(law.normal_coefficient(&r, 1e-5), 0.0);
    assert_eq!(law.normal_force(&r, 1e-5, 3.0), 0.0);
    assert_eq!(law.tangential_ratio(), 0.0);
    assert_eq!(law.tangential_coefficient(&r, 1e-5), 0.0);
}

/// Restitution of a head-on Hertz impact at `speed` with the dashpot `damping`: velocity Verlet
/// on `m δ'' = −F_H(δ) − F_d`, the dashpot taken at the half-step velocity, 20 000 steps per Hertz
/// contact time; the contact ends when the total force would pull.
fn damped_restitution<D: DampingLaw>(damping: &D, speed: f64) -> f64 {
    let pair = pair();
    let law = Hertz.bind(&pair).unwrap();
    let mut state = Default::default();
    let dt = pair.hertz_contact_time(speed) / 20_000.0;
    let (mut d, mut v) = (0.0_f64, speed);
    let mut a = 0.0;
    for _ in 0..1_000_000 {
        let v_half = v + 0.5 * a * dt;
        d += v_half * dt;
        let r = law.update(&mut state, d);
        let force = (r.force + damping.normal_force(&r, d, v_half)).max(0.0);
        if d <= 0.0 || (v_half < 0.0 && force == 0.0) {
            return -v_half / speed;
        }
        a = -force / MASS;
        v = v_half + 0.5 * a * dt;
    }
    panic!("the impact did not end");
}

#[test]
fn tsuji_restitution_does_not_depend_on_speed_and_lammps_falls_with_it() {
    let tsuji = StiffnessViscous::new(0.2).unwrap().bind(&pair()).unwrap();
    let (slow, fast) = (
        damped_restitution(&tsuji, 0.05),
        damped_restitution(&tsuji, 5.0),
    );
    assert!(slow < 0.9, "{slow}");
    // Measured difference 1e-5 (the step); any other power of δ in the dashpot changes e by
    // percents over two decades of speed.
    assert!((slow - fast).abs() < 1e-3, "{slow} {fast}");
    let lammps = HertzianViscous::new(2.0e6).unwrap().bind(&pair()).unwrap();
    let (slow, fast) = (
        damped_restitution(&lammps, 0.05),
        damped_restitution(&lammps, 5.0),
    );
    assert!(slow < 1.0 && fast < slow - 0.05, "{slow} {fast}");
    let none = damped_restitution(&NoDamping, 1.0);
    assert!((none - 1.0).abs() < 1e-3, "{none}");
}
