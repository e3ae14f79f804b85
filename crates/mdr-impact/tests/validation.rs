//! Validation of the single-impact validator against analytic results and independent
//! references. Tolerances are stated per test; every test fails when the physics is wrong.

use mdr_contact::normal::{thornton_restitution, MdrElastoPlastic, NormalModel, Thornton};
use mdr_contact::{ContactPair, Material};
use mdr_impact::{Impact, NormalSpec, Route, Sweep};

/// Steel ball of the paper (docs/theory.md §7).
fn paper_pair() -> ContactPair {
    ContactPair::paper_fig2()
}

/// Yield speed from the energy argument of docs/theory.md §4, written out here from the paper's
/// numbers (independent of the law crate): `m v²/2 = (8/15) E* √R u_c^{5/2}`,
/// `u_c = π q_c / (2 E*)` (eq. 11), `E* = E / (2 (1 − ν²))` (eq. 16).
fn paper_yield_speed_by_hand() -> f64 {
    let (e, nu, rho, r, q_c) = (2.0e11_f64, 0.286_f64, 7800.0_f64, 0.635e-2_f64, 3.8e5_f64);
    let e_star = e / (2.0 * (1.0 - nu * nu));
    let mass = 4.0 / 3.0 * std::f64::consts::PI * r.powi(3) * rho;
    let u_c = std::f64::consts::PI * q_c / (2.0 * e_star);
    let work = 8.0 / 15.0 * e_star * r.sqrt() * u_c.powf(2.5);
    (2.0 * work / mass).sqrt()
}

/// Hertz's contact-time coefficient (see `elastic_limit_restitution_one_and_hertz_contact_time`).
const HERTZ_TIME: f64 = 2.868265699195333;

fn time_integrated(speed: f64) -> mdr_impact::ImpactOutcome {
    Impact::paper(speed)
        .route(Route::TimeIntegration)
        .run()
        .unwrap()
}

/// Below the yield speed the MDR impact is Hertzian: `e_n = 1` to 1e-8 (time integration with
/// 2,000 steps per contact; measured 3.1e-9), and the contact time is Hertz's
/// `c (m²/(R E*² v0))^{1/5}` within 1e-6 (measured 1.3e-7), with
/// `c = 2 (15/16)^{2/5} √π Γ(7/5)/Γ(9/10) = 2.868265699195333` (twice the time to `d_max` of
/// `v = v0 √(1 − (d/d_max)^{5/2})`).
#[test]
fn elastic_limit_restitution_one_and_hertz_contact_time() {
    let pair = paper_pair();
    let v_y = paper_yield_speed_by_hand();
    let (m, r, e_star) = (
        pair.reduced_mass(),
        pair.effective_radius(),
        pair.effective_modulus(),
    );
    for fraction in [0.01, 0.1, 0.5, 0.95] {
        let v = fraction * v_y;
        let outcome = time_integrated(v);
        assert!(
            (outcome.normal_restitution - 1.0).abs() < 1e-8,
            "v = {v}: e_n = {}",
            outcome.normal_restitution
        );
        let hertz_time = HERTZ_TIME * (m * m / (r * e_star * e_star * v)).powf(0.2);
        let relative = (outcome.contact_time / hertz_time - 1.0).abs();
        assert!(
            relative < 1e-6,
            "v = {v}: t_c = {} vs {hertz_time}",
            outcome.contact_time
        );
        assert!(outcome.residual_overlap == 0.0);
        // The energy route agrees (exactly elastic).
        let energy = Impact::paper(v).route(Route::Energy).run().unwrap();
        assert_eq!(energy.normal_restitution, 1.0);
        assert!((energy.contact_time / hertz_time - 1.0).abs() < 1e-6);
    }
}

/// The speed at which `e_n` first drops below 1 is the energy-argument yield speed.
#[test]
fn yield_speed_matches_energy_argument() {
    let v_y = paper_yield_speed_by_hand();
    let from_law = Impact::paper(1.0).yield_speed().unwrap();
    assert!((from_law / v_y - 1.0).abs() < 1e-12, "{from_law} vs {v_y}");
    // Bisection on the impact outcome itself (energy route): the first speed with e_n < 1 (beyond
    // rounding: the loss grows like (v − v_y)^{5/2}, so a 1e-12 threshold places the onset to
    // ~1e-5).
    let (mut lo, mut hi) = (0.1 * v_y, 10.0 * v_y);
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        let e = Impact::paper(mid).run().unwrap().normal_restitution;
        if e < 1.0 - 1e-12 {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    assert!((hi / v_y - 1.0).abs() < 1e-4, "onset {hi} vs {v_y}");
    // The time integration shows the same onset: elastic just below, plastic just above.
    assert!((time_integrated(0.99 * v_y).normal_restitution - 1.0).abs() < 1e-6);
    assert!(time_integrated(1.2 * v_y).normal_restitution < 1.0 - 1e-3);
}

/// At high speed `e_n → sqrt(Θ/E*)`: the deviation shrinks monotonically with speed and is below
/// 1 % at 1,000 m/s (the correction is of order `u_c/d_max`).
#[test]
fn high_speed_limit_is_sqrt_theta() {
    for theta in [0.1, 0.37, 0.8] {
        let law = NormalSpec::Mdr(MdrElastoPlastic::new(3.8e5, theta).unwrap());
        let limit = theta.sqrt();
        let mut previous = f64::INFINITY;
        for v in [10.0, 100.0, 1000.0] {
            let e = Impact::new(paper_pair(), law, v)
                .run()
                .unwrap()
                .normal_restitution;
            let deviation = (e / limit - 1.0).abs();
            assert!(deviation < previous, "θ = {theta}, v = {v}: not converging");
            previous = deviation;
        }
        assert!(
            previous < 1e-2,
            "θ = {theta}: deviation {previous} at 1000 m/s"
        );
    }
}

/// `Θ = E*` makes the law elastic at every speed; Hertz is elastic; `q_c → ∞` is Hertz.
#[test]
fn elastic_special_cases() {
    let pair = paper_pair();
    for law in [
        NormalSpec::Mdr(MdrElastoPlastic::new(3.8e5, 1.0).unwrap()),
        NormalSpec::Mdr(MdrElastoPlastic::elastic()),
        NormalSpec::Hertz,
    ] {
        let outcome = Impact::new(pair, law, 5.0)
            .route(Route::TimeIntegration)
            .run()
            .unwrap();
        assert!((outcome.normal_restitution - 1.0).abs() < 1e-6, "{law:?}");
        let hertz_overlap = pair.hertz_max_overlap(5.0);
        assert!(
            (outcome.max_overlap / hertz_overlap - 1.0).abs() < 1e-5,
            "{law:?}"
        );
    }
}

/// Two equal free spheres behave as one sphere of the effective radius `R/2` and reduced mass
/// `m/2` on a half-space (docs/theory.md §1), and differently from the plain half-space case.
#[test]
fn equal_spheres_equal_half_space_with_effective_radius_and_reduced_mass() {
    let steel = Material::paper_steel();
    let radius = 0.635e-2;
    let mass = steel.sphere_mass(radius);
    let spheres = ContactPair::sphere_on_sphere(radius, &steel, radius, &steel).unwrap();
    let equivalent = ContactPair::sphere_on_half_space(radius / 2.0, &steel, &steel)
        .unwrap()
        .with_reduced_mass(mass / 2.0)
        .unwrap();
    let plain = ContactPair::sphere_on_half_space(radius, &steel, &steel).unwrap();
    for route in [Route::Energy, Route::TimeIntegration] {
        for v in [0.2, 1.0, 5.0] {
            let a = Impact::new(spheres, NormalSpec::paper(), v)
                .route(route)
                .run()
                .unwrap();
            let b = Impact::new(equivalent, NormalSpec::paper(), v)
                .route(route)
                .run()
                .unwrap();
            let c = Impact::new(plain, NormalSpec::paper(), v)
                .route(route)
                .run()
                .unwrap();
            for (x, y) in [
                (a.normal_restitution, b.normal_restitution),
                (a.max_overlap, b.max_overlap),
                (a.contact_time, b.contact_time),
                (a.peak_force, b.peak_force),
            ] {
                assert!((x / y - 1.0).abs() < 1e-12, "v = {v}: {x} vs {y}");
            }
            assert!((a.max_overlap / c.max_overlap - 1.0).abs() > 0.1);
        }
    }
}

/// Velocity Verlet with 2,000 steps per Hertz contact time reproduces the time-free energy route,
/// elastic to deep plastic: `e_n` within 2e-7 (measured 5.6e-8), `d_max`, contact time and peak
/// force within 5e-7 relative (measured 1.55e-7), the residual overlap within 5e-6 relative
/// (measured 1.7e-6, just above the yield speed where it is small).
#[test]
fn time_integration_agrees_with_energy_route() {
    for v in [0.05, 0.3, 1.0, 3.0, 10.0, 30.0] {
        let energy = Impact::paper(v).route(Route::Energy).run().unwrap();
        let time = time_integrated(v);
        assert!(
            (energy.normal_restitution - time.normal_restitution).abs() < 2e-7,
            "v = {v}: {} vs {}",
            energy.normal_restitution,
            time.normal_restitution
        );
        for (x, y, tolerance) in [
            (energy.max_overlap, time.max_overlap, 5e-7),
            (energy.contact_time, time.contact_time, 5e-7),
            (energy.peak_force, time.peak_force, 5e-7),
            (energy.residual_overlap, time.residual_overlap, 5e-6),
        ] {
            assert!(
                (x - y).abs() <= tolerance * x.abs().max(1e-30),
                "v = {v}: {x} vs {y}"
            );
        }
    }
}

/// The time step matters: with too few steps the time integration drifts from the energy route,
/// so the agreement above is not an accident of the comparison.
#[test]
fn coarse_time_step_is_visible() {
    let energy = Impact::paper(3.0).route(Route::Energy).run().unwrap();
    let coarse = Impact::paper(3.0)
        .route(Route::TimeIntegration)
        .steps_per_contact(12)
        .run()
        .unwrap();
    assert!((energy.normal_restitution - coarse.normal_restitution).abs() > 1e-4);
}

/// Thornton's law integrated in time reproduces Thornton's published restitution (his eq. 31,
/// an independent reference) to 3e-7 (measured 8.9e-8 at 2,000 steps per contact).
#[test]
fn thornton_matches_published_restitution() {
    let pair = paper_pair();
    let model = Thornton::new(1.0e9).unwrap();
    let v_y = model.bind(&pair).unwrap().yield_speed(pair.reduced_mass());
    for ratio in [0.5, 1.5, 3.0, 10.0, 30.0] {
        let e = Impact::new(pair, NormalSpec::Thornton(model), ratio * v_y)
            .run()
            .unwrap()
            .normal_restitution;
        let reference = thornton_restitution(ratio).unwrap();
        assert!(
            (e - reference).abs() < 3e-7,
            "v/v_y = {ratio}: {e} vs {reference}"
        );
    }
}

/// Results are in input order and do not depend on the number of threads.
#[test]
fn sweep_is_deterministic_for_any_thread_count() {
    let speeds = mdr_impact::log_spaced(0.05, 20.0, 24);
    let sweep = Sweep::speeds(
        Impact::paper(1.0)
            .route(Route::TimeIntegration)
            .steps_per_contact(200),
        &speeds,
    );
    let run_with = |threads| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| sweep.run().unwrap())
    };
    let one = run_with(1);
    let three = run_with(3);
    assert_eq!(one, three);
    for (outcome, v) in one.iter().zip(&speeds) {
        assert_eq!(outcome.speed, *v);
    }
    // e_n falls monotonically with speed above the yield speed.
    assert!(one
        .windows(2)
        .all(|w| w[1].normal_restitution <= w[0].normal_restitution + 1e-9));
}

/// Bad values are rejected with the key that names them.
#[test]
fn invalid_impacts_name_the_parameter() {
    let cases = [
        (Impact::paper(-1.0), "speed"),
        (Impact::paper(f64::NAN), "speed"),
        (Impact::paper(1.0).angle_degrees(90.0), "angles"),
        (Impact::paper(1.0).friction(-0.1), "mu"),
        (Impact::paper(1.0).steps_per_contact(3), "steps"),
        (
            Impact::new(paper_pair(), NormalSpec::Hertz, 1.0).route(Route::Energy),
            "route",
        ),
    ];
    for (impact, key) in cases {
        let error = impact.run().unwrap_err();
        assert_eq!(error.key(), Some(key), "{error}");
    }
}

/// The discrete MDR spring bed with 2,000 springs, integrated in time, agrees with the closed
/// form to 3e-7 in `e_n` and `d_max` and 3e-6 in the peak force (measured 7.4e-8, 1.0e-7,
/// 1.1e-6), and the agreement degrades with a coarse bed (so the comparison can fail).
#[test]
fn springs_agree_with_closed_form() {
    use mdr_impact::{Method, DEFAULT_SPRINGS};
    for v in [0.1, 0.5, 2.0, 10.0] {
        let closed = Impact::paper(v).run().unwrap();
        let springs = Impact::paper(v)
            .method(Method::Springs {
                springs: DEFAULT_SPRINGS,
            })
            .run()
            .unwrap();
        assert!(
            (closed.normal_restitution - springs.normal_restitution).abs() < 3e-7,
            "v = {v}: closed {} vs springs {}",
            closed.normal_restitution,
            springs.normal_restitution
        );
        assert!((closed.max_overlap / springs.max_overlap - 1.0).abs() < 3e-7);
        assert!((closed.peak_force / springs.peak_force - 1.0).abs() < 3e-6);
    }
    let closed = Impact::paper(2.0).run().unwrap();
    let coarse = Impact::paper(2.0)
        .method(Method::Springs { springs: 8 })
        .run()
        .unwrap();
    assert!(
        (closed.normal_restitution - coarse.normal_restitution).abs() > 1e-3
            || (closed.max_overlap / coarse.max_overlap - 1.0).abs() > 1e-3,
        "coarse bed: e_n {} vs {}, d_max {} vs {}",
        coarse.normal_restitution,
        closed.normal_restitution,
        coarse.max_overlap,
        closed.max_overlap
    );
}

/// A trace closes the hysteresis loop: it starts and ends at zero force, the force is positive
/// in between, the plastic work at the end equals the kinetic energy lost, and the last velocity
/// is `e_n v0`.
#[test]
fn trace_energy_balance() {
    let pair = paper_pair();
    let (outcome, points) = Impact::paper(2.0).trace().unwrap();
    let first = points.first().unwrap();
    let last = points.last().unwrap();
    assert_eq!(first.force, 0.0);
    assert_eq!(last.force, 0.0);
    assert!(points[1..points.len() - 1].iter().all(|p| p.force > 0.0));
    assert!((last.velocity - outcome.normal_restitution * 2.0).abs() < 1e-12);
    let lost = 0.5 * pair.reduced_mass() * 4.0 * (1.0 - outcome.normal_restitution.powi(2));
    // Measured: plastic work 1.2e-8 from the kinetic energy lost; the last overlap is the
    // outcome's residual overlap exactly.
    assert!(
        (last.plastic_work / lost - 1.0).abs() < 5e-8,
        "{} vs {lost}",
        last.plastic_work
    );
    assert!((last.overlap - outcome.residual_overlap).abs() <= 1e-12 * outcome.residual_overlap);
}
