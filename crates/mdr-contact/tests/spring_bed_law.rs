//! The discrete MDR spring bed (`SpringBed`) held to its springs worked out by hand on a bed
//! small enough to follow spring by spring: each spring is elastic, `f = E* Δx u` (eq. 2), up
//! to `u_crit = π q_c / (2 E*)` (eq. 11), loads plastically along
//! `f = E* Δx (u_crit + θ (u − u_crit))` (eqs. 9, 12), unloads and reloads elastically from the
//! plastic offset `u_pl = (1 − θ)(u_max − u_crit)` (eqs. 10, 13) and carries no tension; the
//! normal force is the weighted sum (eq. 6). The bed's geometry (`Δx = 2L/n`, springs at
//! `x_j = −L + (j + ½) Δx`, weight 2 for `±x` and 1 on the axis) and the checks of its
//! parameters are held too.
//!
//! The bed: a sphere of radius 1 m (`g(x) = x²`), `E* = 4 Pa`, `q_c = 2/π N/m` (so
//! `u_crit = 0.25 m`), `θ = 0.25`, `L = 1 m`, `n = 4`: `Δx = 0.5 m`, stored springs at
//! `x = 0.25, 0.75 m` with heights `g = 0.0625, 0.5625 m`, each standing for two;
//! `k_z = E* Δx = 2 N/m`. Binary-exact numbers where possible; tolerance 1e-12 (relative).

use mdr_contact::normal::{SphereSpringBed, SpringBed, SpringBedState};
use mdr_contact::prelude::*;
use mdr_contact::profile::{Profile, Sphere};
use std::f64::consts::PI;

fn assert_close(what: &str, got: f64, want: f64) {
    assert!(
        (got - want).abs() <= 1e-12 * want.abs().max(got.abs()),
        "{what}: {got} vs {want}"
    );
}

fn assert_all_close(what: &str, got: &[f64], want: &[f64]) {
    assert_eq!(got.len(), want.len(), "{what}: {got:?} vs {want:?}");
    for (g, w) in got.iter().zip(want) {
        assert_close(what, *g, *w);
    }
}

const E_STAR: f64 = 4.0;
const Q_C: f64 = 2.0 / PI;
const THETA: f64 = 0.25;
const U_C: f64 = 0.25;
const K: f64 = 2.0;
const HEIGHTS: [f64; 2] = [0.0625, 0.5625];

fn bed() -> SpringBed {
    SpringBed::new(Sphere::new(1.0).unwrap(), E_STAR, Q_C, THETA, 1.0, 4).unwrap()
}

/// One spring on its plastic loading line, eq. (12).
fn plastic(u: f64) -> f64 {
    K * (U_C + THETA * (u - U_C))
}

/// One spring unloading or reloading from `u_max`, eqs. (10), (13), without tension.
fn elastic(u: f64, u_max: f64) -> f64 {
    (K * (u - (1.0 - THETA) * (u_max - U_C).max(0.0))).max(0.0)
}

/// Area of one spring's loop loaded to `u_max` and unloaded to zero force: the work along the
/// elastic line and the plastic line, less the energy `f_max²/(2k)` it gives back.
fn loop_area(u_max: f64) -> f64 {
    if u_max <= U_C {
        return 0.0;
    }
    let f_max = plastic(u_max);
    let loading = 0.5 * K * U_C * U_C + 0.5 * (K * U_C + f_max) * (u_max - U_C);
    loading - f_max * f_max / (2.0 * K)
}

fn state_forces(bed: &SpringBed, state: &SpringBedState) -> Vec<f64> {
    bed.spring_forces(state).collect()
}

#[test]
fn the_bed_lays_out_its_springs_and_keeps_its_parameters() {
    let bed = bed();
    assert_eq!(bed.spring_count(), 4);
    assert_eq!(bed.spacing(), 0.5);
    assert_eq!(bed.covered_half_width(), 1.0);
    assert_eq!(bed.effective_modulus(), E_STAR);
    assert_eq!(bed.critical_line_load(), Q_C);
    assert_eq!(bed.hardening_ratio(), THETA);
    assert_close("u_crit = π q_c / (2E*)", bed.critical_displacement(), U_C);
    assert_eq!(bed.positions(), &[0.25, 0.75]);
    assert_eq!(bed.weights(), &[2.0, 2.0]);
    assert_eq!(bed.heights(), &HEIGHTS);
    assert_eq!(bed.profile().mdr_height(0.5), 0.25);
    // The first spring yields when d − g(0.25) = u_crit.
    assert_close("yield overlap", bed.yield_overlap(), 0.3125);

    // Odd counts put one spring on the axis, standing for itself alone: n = 5 over L = 1.25
    // gives Δx = 0.5 and springs at 0, 0.5, 1; n = 3 over L = 1.5 gives Δx = 1 and 0, 1.
    let five = bed.clone().half_width(1.25).unwrap().n_springs(5).unwrap();
    assert_eq!(five.spacing(), 0.5);
    assert_eq!(five.positions(), &[0.0, 0.5, 1.0]);
    assert_eq!(five.weights(), &[1.0, 2.0, 2.0]);
    assert_eq!(five.heights(), &[0.0, 0.25, 1.0]);
    assert_eq!(five.spring_count(), 5);
    assert_eq!(
        (five.effective_modulus(), five.critical_line_load()),
        (E_STAR, Q_C)
    );
    assert_eq!(five.hardening_ratio(), THETA);
    let three = bed.clone().half_width(1.5).unwrap().n_springs(3).unwrap();
    assert_eq!(three.positions(), &[0.0, 1.0]);
    assert_eq!(three.weights(), &[1.0, 2.0]);
    // Two springs: Δx = L, one stored spring at L/2.
    let two = bed.clone().n_springs(2).unwrap();
    assert_eq!(two.spacing(), 1.0);
    assert_eq!(two.positions(), &[0.5]);
    assert_eq!(two.weights(), &[2.0]);
    assert_eq!(two.covered_half_width(), 1.0);
    // Its spring (g = 0.25, k_z = E* Δx = 4 N/m) at d = 0.3 stores w f²/(2 k_z), f = 0.2 N.
    assert_close(
        "stored energy, k_z = 4",
        two.elastic_energy(&SpringBedState::default(), 0.3),
        2.0 * 0.2 * 0.2 / 8.0,
    );

    // A spacing gives n = ⌈2L/Δx⌉ springs.
    let sphere = Sphere::new(1.0).unwrap();
    let spaced = SpringBed::with_spacing(sphere, E_STAR, Q_C, THETA, 1.0, 0.5).unwrap();
    assert_eq!((spaced.spring_count(), spaced.spacing()), (4, 0.5));
    let spaced = SpringBed::with_spacing(sphere, E_STAR, Q_C, THETA, 1.25, 0.5).unwrap();
    assert_eq!((spaced.spring_count(), spaced.spacing()), (5, 0.5));
    assert_eq!(spaced.covered_half_width(), 1.25);
    let spaced = SpringBed::with_spacing(sphere, E_STAR, Q_C, THETA, 1.0, 0.3).unwrap();
    assert_eq!(spaced.spring_count(), 7);
    assert_close("Δx = 2L/7", spaced.spacing(), 2.0 / 7.0);
    assert_eq!(spaced.hardening_ratio(), THETA);
}

#[test]
fn a_sphere_bed_takes_the_pair_and_the_mdr_parameters() {
    // R = 4 m: g(x) = x²/4 and the default half-width R/4 = 1 m.
    let pair = ContactPair::new(E_STAR, 1.5, 4.0, 1.0).unwrap();
    let params = MdrElastoPlastic::new(Q_C, THETA).unwrap();
    let bed = SpringBed::sphere(&pair, &params, 4).unwrap();
    assert_eq!(bed.covered_half_width(), 1.0);
    assert_eq!(
        (
            bed.effective_modulus(),
            bed.critical_line_load(),
            bed.hardening_ratio()
        ),
        (E_STAR, Q_C, THETA)
    );
    assert_eq!(bed.heights(), &[0.015625, 0.140625]);
    let model = SphereSpringBed {
        params,
        n_springs: 4,
        half_width: None,
    };
    let bound = model.bind(&pair).unwrap();
    assert_eq!(
        (bound.covered_half_width(), bound.heights()),
        (1.0, bed.heights())
    );
    let narrow = SphereSpringBed {
        half_width: Some(0.5),
        ..model
    }
    .bind(&pair)
    .unwrap();
    assert_eq!((narrow.covered_half_width(), narrow.spacing()), (0.5, 0.25));
    assert_eq!(narrow.positions(), &[0.125, 0.375]);
    // Θ given as a modulus is resolved against the pair's E*: Θ = 1 Pa on E* = 4 Pa.
    let modulus = MdrElastoPlastic::with_hardening_modulus(Q_C, 1.0).unwrap();
    assert_eq!(
        SpringBed::sphere(&pair, &modulus, 4)
            .unwrap()
            .hardening_ratio(),
        THETA
    );
}

#[test]
fn springs_load_elastically_then_plastically_unload_from_their_offset_and_reload() {
    let bed = bed();
    let mut state = SpringBedState::default();

    // d = 0.3125: the inner spring is at u_crit exactly, still elastic (eq. 12 needs
    // u > u_crit); the outer one does not touch (u = −0.25).
    let r = bed.update(&mut state, 0.3125);
    assert_close("force at yield", r.force, 2.0 * K * U_C);
    assert_close("elastic stiffness at yield", r.stiffness, 2.0 * K);
    assert_eq!(r.contact_radius, 0.25);
    assert_eq!(state.max_displacements, vec![0.25, 0.0]);
    assert_eq!(state.overlap, 0.3125);

    // d = 0.5: the inner spring (u = 0.4375) is on its plastic line, the outer one is out.
    let r = bed.update(&mut state, 0.5);
    assert_close("plastic force", r.force, 2.0 * plastic(0.4375));
    assert_close("plastic force, by hand", r.force, 2.0 * 0.59375);
    assert_close("plastic stiffness", r.stiffness, 2.0 * THETA * K);
    assert_eq!(r.contact_radius, 0.25);
    assert_all_close("springs", &state_forces(&bed, &state), &[0.59375, 0.0]);
    assert!(!bed.is_saturated(&state));
    // Only the spring that yielded has a loop: the outer spring never reached u_crit.
    assert_close(
        "plastic work",
        bed.dissipated_work(&state),
        2.0 * loop_area(0.4375),
    );
    assert_close(
        "residual overlap",
        bed.residual_overlap(&state),
        0.0625 + (1.0 - THETA) * (0.4375 - U_C),
    );

    // d = 1: both springs plastic, the outer one at the bed's edge.
    let r = bed.update(&mut state, 1.0);
    let u_max = [0.9375, 0.4375];
    assert_close(
        "both plastic",
        r.force,
        2.0 * (plastic(u_max[0]) + plastic(u_max[1])),
    );
    assert_close("both plastic, stiffness", r.stiffness, 4.0 * THETA * K);
    assert_eq!(r.contact_radius, 0.75);
    assert!(bed.is_saturated(&state));
    assert_eq!(state.max_displacements, u_max.to_vec());

    // d = 0.8: both unload elastically from their offsets.
    let r = bed.update(&mut state, 0.8);
    let unloaded = [
        elastic(0.8 - 0.0625, u_max[0]),
        elastic(0.8 - 0.5625, u_max[1]),
    ];
    assert_all_close("unloaded springs", &state_forces(&bed, &state), &unloaded);
    assert_close("unloading", r.force, 2.0 * (unloaded[0] + unloaded[1]));
    assert_close("unloading, by hand", r.force, 2.0 * (0.44375 + 0.19375));
    assert_close("unloading stiffness", r.stiffness, 4.0 * K);
    assert_eq!(r.contact_radius, 0.75);
    assert_eq!(bed.max_overlap(&state), 1.0);
    assert_eq!(state.max_displacements, u_max.to_vec());
    // The bed lifts off where the first spring does: g + u_pl = 0.0625 + 0.515625.
    assert_close("residual overlap", bed.residual_overlap(&state), 0.578125);
    assert_close(
        "plastic work of both loops",
        bed.dissipated_work(&state),
        2.0 * (loop_area(u_max[0]) + loop_area(u_max[1])),
    );
    // The stored energy Σ w f²/(2k), here and (a trial on a copy of the history) at a new
    // maximum d = 1.2, where both springs are back on their plastic lines.
    assert_close(
        "stored energy",
        bed.elastic_energy(&state, 0.8),
        2.0 * (unloaded[0].powi(2) + unloaded[1].powi(2)) / (2.0 * K),
    );
    let before = state.clone();
    assert_close(
        "stored energy at a new maximum",
        bed.elastic_energy(&state, 1.2),
        2.0 * (plastic(1.1375).powi(2) + plastic(0.6375).powi(2)) / (2.0 * K),
    );
    assert_eq!(state, before);

    // d = 0.65: the outer spring has lifted off its offset (u = 0.0875 < u_pl = 0.140625), the
    // inner one still presses (u = 0.5875 > u_pl = 0.515625).
    let r = bed.update(&mut state, 0.65);
    assert_close("one spring left", r.force, 2.0 * elastic(0.5875, u_max[0]));
    assert_close("one spring left, by hand", r.force, 2.0 * 0.14375);
    assert_close("one spring left, stiffness", r.stiffness, 2.0 * K);
    assert_eq!(r.contact_radius, 0.25);
    assert!(!bed.is_saturated(&state));

    // d = 0.3: below the residual overlap: no force, no tension.
    let r = bed.update(&mut state, 0.3);
    assert_eq!((r.force, r.stiffness, r.contact_radius), (0.0, 0.0, 0.0));
    assert_eq!(state_forces(&bed, &state), vec![0.0, 0.0]);
    assert_eq!(bed.elastic_energy(&state, 0.3), 0.0);

    // Reloading below the previous maximum follows the elastic lines ...
    let r = bed.update(&mut state, 0.9);
    assert_close(
        "elastic reloading",
        r.force,
        2.0 * (elastic(0.8375, u_max[0]) + elastic(0.3375, u_max[1])),
    );
    assert_close("elastic reloading, stiffness", r.stiffness, 4.0 * K);
    // ... and past it the plastic ones again.
    let r = bed.update(&mut state, 1.1);
    assert_close(
        "plastic reloading",
        r.force,
        2.0 * (plastic(1.0375) + plastic(0.5375)),
    );
    assert_close("plastic reloading, stiffness", r.stiffness, 4.0 * THETA * K);
    assert_eq!(bed.max_overlap(&state), 1.1);
}

#[test]
fn the_spring_on_the_axis_counts_once() {
    // n = 5 over L = 1.25: springs at x = 0 (weight 1), 0.5, 1 (g = 0, 0.25, 1), k = 2 N/m.
    let bed = bed().half_width(1.25).unwrap().n_springs(5).unwrap();
    let mut state = SpringBedState::default();
    let r = bed.update(&mut state, 0.2);
    assert_close("axis spring alone", r.force, K * 0.2);
    assert_close("axis spring alone, stiffness", r.stiffness, K);
    assert_eq!(r.contact_radius, 0.0);
    // d = 0.3: the axis spring is plastic (u = 0.3), the pair at ±0.5 elastic (u = 0.05).
    let r = bed.update(&mut state, 0.3);
    assert_close("axis and one pair", r.force, plastic(0.3) + 2.0 * K * 0.05);
    assert_close(
        "axis and one pair, stiffness",
        r.stiffness,
        THETA * K + 2.0 * K,
    );
    assert_eq!(r.contact_radius, 0.5);
    assert_close("yield overlap", bed.yield_overlap(), U_C);
    assert_close(
        "plastic work of the axis spring",
        bed.dissipated_work(&state),
        loop_area(0.3),
    );
}

/// `g(x) = x²` tabulated up to `|x| = 1` (and NaN past `nan_beyond`).
#[derive(Debug)]
struct Table {
    nan_beyond: f64,
}

impl Profile for Table {
    fn height(&self, r: f64) -> f64 {
        0.5 * r * r
    }
    fn mdr_height(&self, x: f64) -> f64 {
        if x.abs() > self.nan_beyond {
            f64::NAN
        } else {
            x * x
        }
    }
    fn max_radius(&self) -> f64 {
        1.0
    }
}

fn out_of_range(result: Result<SpringBed>) -> &'static str {
    match result {
        Err(ContactError::OutOfRange { name, .. }) => name,
        other => panic!("expected OutOfRange, got {other:?}"),
    }
}

#[test]
fn bed_parameters_are_checked_at_their_limits() {
    let table = || Table { nan_beyond: 2.0 };
    let new = |e: f64, q_c: f64, theta: f64, half_width: f64, n: usize| {
        SpringBed::new(table(), e, q_c, theta, half_width, n)
    };
    assert!(new(E_STAR, Q_C, THETA, 1.0, 4).is_ok());
    // q_c in [0, ∞]: zero yields at once, infinity never.
    assert_eq!(
        new(E_STAR, 0.0, THETA, 1.0, 4)
            .unwrap()
            .critical_displacement(),
        0.0
    );
    assert_eq!(
        new(E_STAR, f64::INFINITY, THETA, 1.0, 4)
            .unwrap()
            .critical_displacement(),
        f64::INFINITY
    );
    assert_eq!(out_of_range(new(E_STAR, -1.0, THETA, 1.0, 4)), "q_c");
    assert_eq!(out_of_range(new(E_STAR, f64::NAN, THETA, 1.0, 4)), "q_c");
    // θ in [0, 1].
    assert!(new(E_STAR, Q_C, 0.0, 1.0, 4).is_ok() && new(E_STAR, Q_C, 1.0, 1.0, 4).is_ok());
    assert_eq!(out_of_range(new(E_STAR, Q_C, 1.5, 1.0, 4)), "theta_ratio");
    assert_eq!(
        out_of_range(new(0.0, Q_C, THETA, 1.0, 4)),
        "effective_modulus"
    );
    // The half-width up to the table's end, inclusive.
    assert_eq!(out_of_range(new(E_STAR, Q_C, THETA, 0.0, 4)), "half_width");
    assert_eq!(out_of_range(new(E_STAR, Q_C, THETA, 1.5, 4)), "half_width");
    assert_eq!(
        out_of_range(SpringBed::with_spacing(
            table(),
            E_STAR,
            Q_C,
            THETA,
            0.0,
            0.1
        )),
        "half_width"
    );
    assert_eq!(
        out_of_range(new(E_STAR, Q_C, THETA, 1.0, 4).and_then(|b| b.half_width(1.5))),
        "half_width"
    );
    // At least two springs.
    for n in [0, 1] {
        assert!(matches!(
            new(E_STAR, Q_C, THETA, 1.0, n),
            Err(ContactError::TooFew {
                name: "n_springs",
                min: 2,
                ..
            })
        ));
    }
    assert_eq!(new(E_STAR, Q_C, THETA, 1.0, 2).unwrap().spring_count(), 2);
    // A profile that is NaN where a spring sits is refused.
    assert!(matches!(
        SpringBed::new(Table { nan_beyond: 0.5 }, E_STAR, Q_C, THETA, 1.0, 4),
        Err(ContactError::NotFinite {
            name: "profile height g(x)",
            ..
        })
    ));
    // A spacing that would need more than 10⁸ springs is refused before any allocation.
    assert_eq!(
        out_of_range(SpringBed::with_spacing(
            table(),
            E_STAR,
            Q_C,
            THETA,
            1.0,
            2.0 / 1.5e8
        )),
        "spacing"
    );
    assert_eq!(
        out_of_range(SpringBed::with_spacing(
            table(),
            E_STAR,
            Q_C,
            THETA,
            1.0,
            0.0
        )),
        "spacing"
    );
}

/// The bound of `with_spacing` at its edge, on the count alone (a bed of 10⁸ springs would take
/// 1.2 GB): `L = 5·10⁷ m` and `Δx = 1 m` give exactly `2L/Δx = 10⁸` springs, which are allowed,
/// and half a metre more gives `10⁸ + 1`, refused naming `spacing` and the limit. Both counts
/// are exact in f64. A bound `n ≥ 10⁸` in place of `n > 10⁸` fails the first; `n == 10⁸` or
/// `n < 10⁸` the second.
#[test]
fn the_spring_count_for_a_spacing_is_bounded_at_exactly_ten_to_the_eight() {
    assert_eq!(SpringBed::MAX_SPRINGS, 100_000_000);
    assert_eq!(
        SpringBed::spring_count_for_spacing(5e7, 1.0).unwrap(),
        100_000_000
    );
    let refused = SpringBed::spring_count_for_spacing(5e7 + 0.5, 1.0).unwrap_err();
    assert!(matches!(
        refused,
        ContactError::OutOfRange {
            name: "spacing",
            value: 1.0,
            range: "[2 half_width / 1e8, inf)",
        }
    ));
    assert_eq!(
        refused.to_string(),
        "parameter `spacing` = 1 is outside the allowed range [2 half_width / 1e8, inf)"
    );
    // The count is ⌈2L/Δx⌉, the one `with_spacing` builds (4, 5 and 7 springs above).
    assert_eq!(SpringBed::spring_count_for_spacing(1.0, 0.5).unwrap(), 4);
    assert_eq!(SpringBed::spring_count_for_spacing(1.25, 0.5).unwrap(), 5);
    assert_eq!(SpringBed::spring_count_for_spacing(1.0, 0.3).unwrap(), 7);
    // Its own parameters are checked first.
    assert!(matches!(
        SpringBed::spring_count_for_spacing(0.0, 1.0),
        Err(ContactError::OutOfRange {
            name: "half_width",
            ..
        })
    ));
    assert!(matches!(
        SpringBed::spring_count_for_spacing(1.0, -1.0),
        Err(ContactError::OutOfRange {
            name: "spacing",
            ..
        })
    ));
}

/// A spring count beyond [`SpringBed::MAX_SPRINGS`] is refused before anything is allocated,
/// naming `n_springs` and its range: without the bound, `usize::MAX` springs abort the process
/// on the allocation of their positions.
#[test]
fn a_spring_count_beyond_ten_to_the_eight_is_refused_before_allocation() {
    for n in [SpringBed::MAX_SPRINGS + 1, usize::MAX] {
        let Err(refused) = SpringBed::new(Sphere::new(1.0).unwrap(), E_STAR, Q_C, THETA, 1.0, n)
        else {
            panic!("{n} springs taken");
        };
        assert!(
            matches!(
                refused,
                ContactError::OutOfRange {
                    name: "n_springs",
                    range: "[2, 1e8]",
                    ..
                }
            ),
            "{refused}"
        );
    }
}

/// A profile whose transformed height is NaN everywhere: a bed of it is refused at
/// `profile height g(x)`, after its springs are laid out.
#[derive(Debug)]
struct NanProfile;

impl Profile for NanProfile {
    fn height(&self, _r: f64) -> f64 {
        f64::NAN
    }

    fn mdr_height(&self, _x: f64) -> f64 {
        f64::NAN
    }

    fn max_radius(&self) -> f64 {
        1.0
    }
}

/// Exactly [`SpringBed::MAX_SPRINGS`] springs are taken: the count passes its bound, the
/// springs are laid out (5·10⁷ stored, about 1.2 GB for a moment) and the bed is refused only
/// for the profile's NaN height, not for the count.
#[test]
fn exactly_ten_to_the_eight_springs_pass_the_bound() {
    let Err(refused) = SpringBed::new(NanProfile, E_STAR, Q_C, THETA, 1.0, SpringBed::MAX_SPRINGS)
    else {
        panic!("a bed of a NaN profile taken");
    };
    assert!(
        refused.to_string().contains("profile height g(x)"),
        "{refused}"
    );
}
