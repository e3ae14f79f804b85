//! The adhesive MDR spring bed (`AdhesiveSpringBed`) held to its springs worked out by hand:
//! a spring attaches when it touches (`u − u_pl ≥ 0`), carries tension `E* Δx (u − u_pl)` while
//! attached (eq. 10), and the outermost attached spring lets go once its elongation exceeds
//! `Δl_max(x) = √(2π x Δγ / E*)` (Popov & Heß), then the next one inwards, each at the overlap
//! `min(h_i − Δl_max(x_i), the level of the spring outside it)`, booking `w k Δl²/2` as
//! adhesive work.
//!
//! The bed of `spring_bed_law.rs`: a sphere of radius 1 m (`g = x²`), `E* = 4 Pa`, `L = 1 m`,
//! `n = 4` (`Δx = 0.5 m`, springs at `x = 0.25, 0.75 m`, `g = 0.0625, 0.5625 m`, weight 2,
//! `k = 2 N/m`); `Δγ = E* c²/(2π)` makes `Δl_max = c √x` with `c` exact. Tolerance 1e-12.

use mdr_contact::normal::{
    AdhesiveSpringBed, AdhesiveSpringBedState, SphereAdhesiveSpringBed, SpringBed,
};
use mdr_contact::prelude::*;
use mdr_contact::profile::Sphere;
use std::f64::consts::PI;

fn assert_close(what: &str, got: f64, want: f64) {
    assert!(
        (got - want).abs() <= 1e-12 * want.abs().max(got.abs()),
        "{what}: {got} vs {want}"
    );
}

const E_STAR: f64 = 4.0;
const K: f64 = 2.0;
const Q_C: f64 = 2.0 / PI;
const THETA: f64 = 0.25;

fn bed(critical_line_load: f64, theta: f64) -> SpringBed {
    SpringBed::new(
        Sphere::new(1.0).unwrap(),
        E_STAR,
        critical_line_load,
        theta,
        1.0,
        4,
    )
    .unwrap()
}

/// `Δγ` with `Δl_max(x) = c √x`.
fn work_of_adhesion(c: f64) -> f64 {
    E_STAR * c * c / (2.0 * PI)
}

fn elastic_bed(c: f64) -> AdhesiveSpringBed {
    AdhesiveSpringBed::new(bed(f64::INFINITY, 1.0), work_of_adhesion(c)).unwrap()
}

#[test]
fn springs_attach_on_touch_pull_when_stretched_and_let_go_past_their_limit() {
    // c = 0.5: Δl_max = 0.25 m at x = 0.25, 0.5 √0.75 m at x = 0.75.
    let law = elastic_bed(0.5);
    let outer_limit = 0.5 * 0.75f64.sqrt();
    let mut state = AdhesiveSpringBedState::default();

    // d = 0.5625: the outer spring just touches (u = 0) and is attached: it counts in the
    // contact radius and the stiffness with zero force.
    let r = law.update(&mut state, 0.5625);
    assert_close("touching", r.force, 2.0 * K * 0.5);
    assert_close("touching, stiffness", r.stiffness, 4.0 * K);
    assert_eq!(r.contact_radius, 0.75);
    assert_eq!(state.attached, vec![true, true]);

    let r = law.update(&mut state, 1.0);
    assert_close("loaded", r.force, 2.0 * K * (0.9375 + 0.4375));
    assert_eq!(law.max_overlap(&state), 1.0);

    // d = 0.2: the outer spring is stretched by 0.3625 m (< 0.433 m) and pulls.
    let r = law.update(&mut state, 0.2);
    assert_close("pulling", r.force, 2.0 * K * (0.1375 - 0.3625));
    assert_close("pulling, stiffness", r.stiffness, 4.0 * K);
    assert_eq!(r.contact_radius, 0.75);
    assert!(law.holds(&state));
    assert_eq!(state.adhesive_work, 0.0);
    assert_eq!(law.dissipated_work(&state), 0.0);
    // Unloading lets the outer spring go first, at 0.5625 − 0.433, before the inner one at
    // 0.0625 − 0.25.
    assert_close(
        "detachment overlap",
        law.detachment_overlap(&state),
        -0.1875,
    );
    // Stored energy Σ w f²/(2k) over the attached springs, here and on a trial step to d = 0.1
    // that lets the outer spring go (the history is left as it was).
    let energy = |f: f64| 2.0 * f * f / (2.0 * K);
    assert_close(
        "stored energy",
        law.elastic_energy(&state, 0.2),
        energy(K * 0.1375) + energy(K * 0.3625),
    );
    let before = state.clone();
    assert_close(
        "stored energy after a let-go",
        law.elastic_energy(&state, 0.1),
        energy(K * 0.0375),
    );
    assert_eq!(state, before);

    // d = 0.1: the outer spring (stretched 0.4625 m) lets go with w k Δl_max²/2.
    let r = law.update(&mut state, 0.1);
    assert_eq!(state.attached, vec![true, false]);
    let outer_work = 2.0 * 0.5 * K * outer_limit * outer_limit;
    assert_close("outer let-go work", state.adhesive_work, outer_work);
    assert_close("outer let-go work, by hand", outer_work, 0.375);
    assert_close("one spring left", r.force, 2.0 * K * 0.0375);
    assert_close("one spring left, stiffness", r.stiffness, 2.0 * K);
    assert_eq!(r.contact_radius, 0.25);
    assert_close("dissipated", law.dissipated_work(&state), 0.375);

    // d = −0.1875: the inner spring is stretched by exactly its limit and still holds.
    let r = law.update(&mut state, -0.1875);
    assert_close("at the limit", r.force, -2.0 * K * 0.25);
    assert!(law.holds(&state));
    assert_eq!(r.contact_radius, 0.25);

    // Past it the inner spring lets go too: nothing holds, no force.
    let r = law.update(&mut state, -0.2);
    assert_eq!((r.force, r.stiffness, r.contact_radius), (0.0, 0.0, 0.0));
    assert!(!law.holds(&state));
    assert_close("both let-go works", state.adhesive_work, 0.375 + 0.125);
    // Detached, the bed lifts off where its first spring touches: g(0.25).
    assert_eq!(law.detachment_overlap(&state), 0.0625);
    assert_eq!(law.residual_overlap(&state), 0.0625);
    assert_eq!(law.elastic_energy(&state, -0.2), 0.0);

    // Pressed in again, both springs attach again.
    let r = law.update(&mut state, 0.5625);
    assert_eq!(state.attached, vec![true, true]);
    assert_close("re-attached", r.force, 2.0 * K * 0.5);
    assert_eq!(r.contact_radius, 0.75);
}

#[test]
fn an_inner_spring_lets_go_no_later_than_the_spring_outside_it() {
    // c = 0.5, one step from d = 1 to d = −0.3: each spring lets go at its own limit, the
    // same works as step by step.
    let law = elastic_bed(0.5);
    let mut state = AdhesiveSpringBedState::default();
    law.update(&mut state, 1.0);
    let r = law.update(&mut state, -0.3);
    assert_eq!(r.force, 0.0);
    assert_close("both let go", state.adhesive_work, 0.375 + 0.125);

    // c = 2: Δl_max = 1 m at x = 0.25 and √3 m at x = 0.75. The outer spring lets go at
    // d = 0.5625 − √3 ≈ −1.17, where the inner one is already stretched by √3 − 0.5 > 1 m: it
    // lets go there too, with that stretch.
    let law = elastic_bed(2.0);
    let mut state = AdhesiveSpringBedState::default();
    law.update(&mut state, 1.0);
    assert_close(
        "detachment overlap",
        law.detachment_overlap(&state),
        0.5625 - 3f64.sqrt(),
    );
    law.update(&mut state, -1.5);
    let stretch = 3f64.sqrt() - 0.5;
    assert_close(
        "cascade work",
        state.adhesive_work,
        2.0 * 0.5 * K * 3.0 + 2.0 * 0.5 * K * stretch * stretch,
    );
    assert!(!law.holds(&state));
}

#[test]
fn plastic_springs_attach_and_let_go_from_their_offsets() {
    // u_crit = 0.25 m, θ = 0.25, c = 0.5. Loaded to d = 1 (u_max = 0.9375, 0.4375) the
    // springs keep the offsets u_pl = 0.75 (u_max − 0.25) = 0.515625, 0.140625 m.
    let law = AdhesiveSpringBed::new(bed(Q_C, THETA), work_of_adhesion(0.5)).unwrap();
    assert_eq!(law.yield_overlap(), 0.3125);
    let plastic = |u: f64| K * (0.25 + THETA * (u - 0.25));
    let mut state = AdhesiveSpringBedState::default();
    let r = law.update(&mut state, 1.0);
    assert_close(
        "plastic loading",
        r.force,
        2.0 * (plastic(0.9375) + plastic(0.4375)),
    );
    assert_close("plastic loading, stiffness", r.stiffness, 4.0 * THETA * K);
    // d = 0.5: both stretched from their offsets (0.078125 and 0.203125 m), both under
    // their limits (0.25 and 0.433 m): both pull.
    let r = law.update(&mut state, 0.5);
    assert_close(
        "plastic springs pull",
        r.force,
        -2.0 * K * (0.078125 + 0.203125),
    );
    assert_close("elastic unloading stiffness", r.stiffness, 4.0 * K);
    assert_close(
        "residual overlap",
        law.residual_overlap(&state),
        0.0625 + 0.515625,
    );
    let outer = 0.5625 + 0.140625 - 0.5 * 0.75f64.sqrt();
    assert_close("detachment overlap", law.detachment_overlap(&state), outer);
    let loops = law.bed().dissipated_work(&state.bed);
    assert!(loops > 0.0);
    assert_close("no adhesive work yet", law.dissipated_work(&state), loops);
    // d = 0.2: the outer spring lets go at `outer`; the inner one, stretched past its own limit
    // by then, at the same overlap.
    law.update(&mut state, 0.2);
    assert!(!law.holds(&state));
    let inner = 0.0625 + 0.515625 - outer;
    let adhesive = 2.0 * 0.5 * K * (0.1875 + inner * inner);
    assert_close("let-go works", state.adhesive_work, adhesive);
    assert_close(
        "plastic and adhesive work",
        law.dissipated_work(&state),
        loops + adhesive,
    );
    // An offset spring attaches again only once it touches: u − u_pl ≥ 0.
    let r = law.update(&mut state, 0.578125);
    assert_eq!(state.attached, vec![true, false]);
    assert_eq!((r.force, r.contact_radius), (0.0, 0.25));
}

#[test]
fn without_adhesion_the_bed_is_the_plain_spring_bed() {
    let plain = bed(Q_C, THETA);
    let law = AdhesiveSpringBed::new(plain.clone(), 0.0).unwrap();
    let mut state = AdhesiveSpringBedState::default();
    let mut plain_state = Default::default();
    for d in [0.9, 0.5, -0.1, 0.7] {
        assert_eq!(
            law.update(&mut state, d),
            plain.update(&mut plain_state, d),
            "d = {d}"
        );
        assert_eq!(state.bed, plain_state);
        assert_eq!(
            law.elastic_energy(&state, d),
            plain.elastic_energy(&plain_state, d)
        );
    }
    assert_eq!(law.max_overlap(&state), 0.9);
    assert!(!law.holds(&state));
    assert_eq!(
        law.detachment_overlap(&state),
        plain.residual_overlap(&plain_state)
    );
    assert_eq!(
        law.dissipated_work(&state),
        plain.dissipated_work(&plain_state)
    );
    // Without adhesion no spring holds, whatever the state says.
    let attached = AdhesiveSpringBedState {
        attached: vec![true, true],
        ..state
    };
    assert!(!law.holds(&attached));
}

#[test]
fn the_pull_off_force_and_the_parameters() {
    let gamma = work_of_adhesion(0.5);
    let law = AdhesiveSpringBed::new(bed(Q_C, THETA), gamma).unwrap();
    assert_eq!(law.work_of_adhesion(), gamma);
    assert_eq!(law.bed().spring_count(), 4);
    // A general profile has no closed-form pull-off force; a sphere has JKR's (3/2) π Δγ R.
    assert_eq!(law.pull_off_force(), 0.0);
    let pair = ContactPair::new(E_STAR, 1.5, 4.0, 1.0).unwrap();
    let jkr = 1.5 * PI * gamma * 4.0;
    assert_close(
        "JKR pull-off",
        law.clone().with_sphere_pull_off(&pair).pull_off_force(),
        jkr,
    );
    let model = AdhesiveMdr::new(MdrElastoPlastic::new(Q_C, THETA).unwrap(), gamma).unwrap();
    let sphere = AdhesiveSpringBed::sphere(&pair, &model, 4).unwrap();
    assert_close("sphere pull-off", sphere.pull_off_force(), jkr);
    assert_eq!(sphere.bed().covered_half_width(), 1.0);
    let narrow = sphere.half_width(0.5).unwrap();
    assert_close("pull-off kept", narrow.pull_off_force(), jkr);
    assert_eq!(narrow.work_of_adhesion(), gamma);
    assert_eq!(narrow.bed().covered_half_width(), 0.5);
    let bound = SphereAdhesiveSpringBed {
        model,
        n_springs: 4,
        half_width: None,
    }
    .bind(&pair)
    .unwrap();
    assert_eq!(bound.bed().covered_half_width(), 1.0);
    assert_close("bound pull-off", bound.pull_off_force(), jkr);
    let bound = SphereAdhesiveSpringBed {
        model,
        n_springs: 4,
        half_width: Some(0.5),
    }
    .bind(&pair)
    .unwrap();
    assert_eq!(bound.bed().covered_half_width(), 0.5);
    assert_eq!(bound.bed().heights(), &[0.00390625, 0.03515625]);

    // Two springs over L = 1 (one stored at x = 0.5, g = 0.25, k_z = E* Δx = 4 N/m): at
    // d = 0.3 it stores w f²/(2 k_z) with f = 0.2 N.
    let two = AdhesiveSpringBed::new(bed(Q_C, THETA).n_springs(2).unwrap(), gamma).unwrap();
    assert_close(
        "stored energy, k_z = 4",
        two.elastic_energy(&AdhesiveSpringBedState::default(), 0.3),
        2.0 * 0.2 * 0.2 / 8.0,
    );
    assert!(matches!(
        AdhesiveSpringBed::new(bed(Q_C, THETA), -1.0),
        Err(ContactError::OutOfRange {
            name: "work_of_adhesion",
            ..
        })
    ));
    assert!(matches!(
        AdhesiveSpringBed::new(bed(Q_C, THETA), f64::NAN),
        Err(ContactError::NotFinite {
            name: "work_of_adhesion",
            ..
        })
    ));
}
