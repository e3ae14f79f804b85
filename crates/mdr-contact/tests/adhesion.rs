//! The adhesive MDR law (Heß's rule on the plastic springs) against references that are not
//! this code: the JKR solution in the elastic limit, the non-adhesive law at `Δγ = 0`, the
//! continuum energy of the released annulus, and the spring bed against the closed form.

use mdr_contact::prelude::*;
use proptest::prelude::*;
use std::f64::consts::PI;

const GAMMA: f64 = 0.5; // J/m²

/// A soft micro contact where adhesion matters: glass-like E*, R = 5 µm.
fn micro_pair() -> ContactPair {
    let glass = Material::new(63e9, 0.2, 2500.0).unwrap();
    ContactPair::sphere_on_half_space(5e-6, &glass, &glass).unwrap()
}

fn jkr_overlap(a: f64, r: f64, e: f64, gamma: f64) -> f64 {
    a * a / r - (2.0 * PI * a * gamma / e).sqrt()
}

fn jkr_force(a: f64, r: f64, e: f64, gamma: f64) -> f64 {
    4.0 * e * a.powi(3) / (3.0 * r) - (8.0 * PI * gamma * e * a.powi(3)).sqrt()
}

fn elastic_law(pair: &ContactPair, gamma: f64) -> AdhesiveMdrLaw {
    AdhesiveMdr::new(MdrElastoPlastic::elastic(), gamma)
        .unwrap()
        .bind(pair)
        .unwrap()
}

/// Minimise `f` over `[lo, hi]` by golden section (f unimodal there).
fn golden_min(f: impl Fn(f64) -> f64, mut lo: f64, mut hi: f64) -> (f64, f64) {
    let g = 0.5 * (5f64.sqrt() - 1.0);
    for _ in 0..200 {
        let x1 = hi - g * (hi - lo);
        let x2 = lo + g * (hi - lo);
        if f(x1) < f(x2) {
            hi = x2;
        } else {
            lo = x1;
        }
    }
    let x = 0.5 * (lo + hi);
    (x, f(x))
}

#[test]
fn closed_form_unloads_along_jkr() {
    let pair = micro_pair();
    let (r, e) = (pair.effective_radius(), pair.effective_modulus());
    let law = elastic_law(&pair, GAMMA);
    let mut state = AdhesiveMdrState::default();
    let d0 = 2e-8;
    let loaded = law.update(&mut state, d0);
    // Loading is Hertz: springs attach with zero elongation.
    let hertz = 4.0 / 3.0 * e * r.sqrt() * d0.powf(1.5);
    assert!((loaded.force - hertz).abs() < 1e-12 * hertz);
    let scale = 1.5 * PI * GAMMA * r;
    let mut d = d0;
    let mut checked = 0;
    while law.holds(&state) {
        d -= 1e-11;
        let response = law.update(&mut state, d);
        let a = response.contact_radius;
        if a < (r * d0).sqrt() * (1.0 - 1e-12) && a > 0.0 {
            // On the retreating front: the JKR branch, parametrised by a.
            assert!(
                (d - jkr_overlap(a, r, e, GAMMA)).abs() < 1e-9 * d0,
                "d={d} a={a}"
            );
            assert!((response.force - jkr_force(a, r, e, GAMMA)).abs() < 1e-9 * scale);
            checked += 1;
        }
    }
    assert!(checked > 100, "{checked}");
}

#[test]
fn closed_form_pull_off_is_three_halves_pi_gamma_r() {
    let pair = micro_pair();
    let r = pair.effective_radius();
    let law = elastic_law(&pair, GAMMA);
    let mut state = AdhesiveMdrState::default();
    law.update(&mut state, 2e-8);
    // The tensile force under displacement control, as a function of the overlap on the front.
    let tension = |d: f64| law.evaluate(&state, d).force;
    let snap = law.detachment_overlap(&state);
    let (_, f_min) = golden_min(tension, snap, 2e-8);
    let expected = 1.5 * PI * GAMMA * r;
    assert!(
        (-f_min - expected).abs() < 1e-9 * expected,
        "{f_min} {expected}"
    );
    assert_eq!(law.pull_off_force(), expected);
}

#[test]
fn closed_form_snaps_off_at_the_jkr_overlap() {
    let pair = micro_pair();
    let (r, e) = (pair.effective_radius(), pair.effective_modulus());
    let law = elastic_law(&pair, GAMMA);
    let mut state = AdhesiveMdrState::default();
    law.update(&mut state, 2e-8);
    // Displacement control: dδ/da = 0 at a³ = π Δγ R² / (8 E*).
    let a_snap = (PI * GAMMA * r * r / (8.0 * e)).cbrt();
    let d_snap = jkr_overlap(a_snap, r, e, GAMMA);
    assert!(d_snap < 0.0);
    let reach = law.detachment_overlap(&state);
    assert!(
        (reach - d_snap).abs() < 1e-12 * d_snap.abs(),
        "{reach} {d_snap}"
    );
    let above = law.evaluate(&state, d_snap * (1.0 - 1e-6));
    assert!(above.force < 0.0 && above.contact_radius > 0.0);
    let mut below = state;
    let released = law.update(&mut below, d_snap * (1.0 + 1e-6));
    assert_eq!(released.force, 0.0);
    assert!(!law.holds(&below));
}

#[test]
fn released_annulus_costs_its_surface_energy() {
    // Slow unloading along the front: the springs let go with Δl_max(x)²·E*/2 each, which
    // integrates to Δγ times the area of the released annulus, π Δγ (a0² − a1²).
    let pair = micro_pair();
    let r = pair.effective_radius();
    let law = elastic_law(&pair, GAMMA);
    let mut state = AdhesiveMdrState::default();
    let d0 = 2e-8;
    law.update(&mut state, d0);
    let a0 = (r * d0).sqrt();
    let mut d = d0;
    let steps = 20000;
    let d_end = -1.5e-9;
    let mut work_in = 0.0;
    let mut previous_force = law.evaluate(&state, d0).force;
    for i in 1..=steps {
        let next = d0 + (d_end - d0) * i as f64 / steps as f64;
        let f = law.update(&mut state, next).force;
        work_in += 0.5 * (f + previous_force) * (next - d);
        previous_force = f;
        d = next;
    }
    assert!(law.holds(&state));
    let a1 = state.contact_radius;
    let expected = PI * GAMMA * (a0 * a0 - a1 * a1);
    assert!(
        (state.adhesive_work - expected).abs() < 2e-3 * expected,
        "{} {expected}",
        state.adhesive_work
    );
    // Books: the Hertz loading work = what is stored now + what was released + the work
    // the contact did while unloading (work_in is negative: returned).
    let loading = 0.4 * 4.0 / 3.0 * pair.effective_modulus() * r.sqrt() * d0.powf(2.5);
    let stored = law.elastic_energy(&state, d);
    let closes = loading + work_in - stored - law.dissipated_work(&state);
    assert!(closes.abs() < 1e-3 * loading, "{closes} {loading}");
}

#[test]
fn work_of_adhesion_is_checked() {
    for bad in [-1e-3, f64::NAN, f64::INFINITY] {
        let err = AdhesiveMdr::new(MdrElastoPlastic::paper(), bad).unwrap_err();
        assert!(err.to_string().contains("work_of_adhesion"), "{err}");
    }
    assert!(AdhesiveMdr::new(MdrElastoPlastic::paper(), 0.0).is_ok());
}

/// Micro glass contact with plasticity: `u_c = π q_c / (2E*)` ≈ 10 nm, `Θ = 0.3 E*`.
fn micro_plastic() -> MdrElastoPlastic {
    MdrElastoPlastic::new(210.0, 0.3).unwrap()
}

#[test]
fn tiny_adhesion_tends_to_the_plastic_law() {
    // Reference: the non-adhesive closed form on every branch (loading, unloading through the
    // crater, the flattened zone). The adhesive terms scale with √Δγ.
    let pair = micro_pair();
    let plain = micro_plastic().bind(&pair).unwrap();
    let sticky = AdhesiveMdr::new(micro_plastic(), 1e-14)
        .unwrap()
        .bind(&pair)
        .unwrap();
    let (mut a, mut b) = (MdrState::default(), AdhesiveMdrState::default());
    let history = [
        1e-8, 3e-8, 2.5e-8, 1.6e-8, 1.2e-8, 2e-8, 4e-8, 3.1e-8, 2.6e-8,
    ];
    for d in history {
        let expected = plain.update(&mut a, d).force;
        let got = sticky.update(&mut b, d).force;
        assert!(
            (got - expected).abs() <= 1e-6 * expected,
            "{d}: {got} {expected}"
        );
    }
    // The plastic work books as in the plain law.
    let plastic = plain.dissipated_work(&a);
    assert!((sticky.dissipated_work(&b) - plastic).abs() < 1e-6 * plastic);
}

#[test]
fn crater_enlarges_the_pull_off_force() {
    // With the flattened crater the neck at pull-off is wider than JKR's; the elastic law is
    // the lower reference.
    let pair = micro_pair();
    let law = AdhesiveMdr::new(micro_plastic(), GAMMA)
        .unwrap()
        .bind(&pair)
        .unwrap();
    let mut state = AdhesiveMdrState::default();
    law.update(&mut state, 6e-8);
    let tension = |d: f64| law.evaluate(&state, d).force;
    let (_, f_min) = golden_min(tension, law.detachment_overlap(&state), 6e-8);
    assert!(-f_min > 1.2 * law.pull_off_force(), "{f_min}");
}

/// A bed fine enough for the micro contact up to 60 nm of overlap.
fn micro_bed(model: &AdhesiveMdr, springs: usize) -> AdhesiveSpringBed {
    AdhesiveSpringBed::sphere(&micro_pair(), model, springs)
        .unwrap()
        .half_width(6e-7)
        .unwrap()
}

#[test]
fn spring_bed_pull_off_within_its_discretisation() {
    // 4000 springs over ±0.6 µm: Δx = 0.3 nm against a pull-off neck radius of ≈ 76 nm.
    let model = AdhesiveMdr::new(MdrElastoPlastic::elastic(), GAMMA).unwrap();
    let bed = micro_bed(&model, 4000);
    let mut state = AdhesiveSpringBedState::default();
    bed.update(&mut state, 2e-8);
    let mut d = 2e-8;
    let mut f_min = 0.0_f64;
    while bed.holds(&state) {
        d -= 1e-12;
        f_min = f_min.min(bed.update(&mut state, d).force);
    }
    let expected = 1.5 * PI * GAMMA * micro_pair().effective_radius();
    assert!(
        (-f_min - expected).abs() < 5e-3 * expected,
        "{f_min} {expected}"
    );
    // It lets go near the JKR snap-off overlap.
    let (r, e) = (
        micro_pair().effective_radius(),
        micro_pair().effective_modulus(),
    );
    let a_snap = (PI * GAMMA * r * r / (8.0 * e)).cbrt();
    let d_snap = jkr_overlap(a_snap, r, e, GAMMA);
    assert!((d - d_snap).abs() < 5e-3 * d_snap.abs(), "{d} {d_snap}");
}

#[test]
fn zero_adhesion_is_the_plain_law_bit_for_bit() {
    let pair = ContactPair::paper_fig2();
    let plain = MdrElastoPlastic::paper().bind(&pair).unwrap();
    let law = AdhesiveMdr::new(MdrElastoPlastic::paper(), 0.0)
        .unwrap()
        .bind(&pair)
        .unwrap();
    let bed = SpringBed::sphere(&pair, &MdrElastoPlastic::paper(), 500)
        .unwrap()
        .half_width(2e-4)
        .unwrap();
    let sticky_bed = AdhesiveSpringBed::new(bed.clone(), 0.0).unwrap();
    let (mut s1, mut s2) = (MdrState::default(), AdhesiveMdrState::default());
    let (mut b1, mut b2) = (SpringBedState::default(), AdhesiveSpringBedState::default());
    let mut d: f64 = 0.0;
    for i in 0..400 {
        // A deterministic load history with reversals and separations.
        d = 1.2e-5 * ((i as f64 * 0.37).sin() * (i as f64 * 0.011).cos()) + 1e-6;
        assert_eq!(plain.update(&mut s1, d), law.update(&mut s2, d));
        assert_eq!(bed.update(&mut b1, d), sticky_bed.update(&mut b2, d));
        assert!(!law.holds(&s2) && !sticky_bed.holds(&b2));
    }
    assert_eq!(plain.dissipated_work(&s1), law.dissipated_work(&s2));
    assert_eq!(plain.elastic_energy(&s1, d), law.elastic_energy(&s2, d));
    assert_eq!(bed.dissipated_work(&b1), sticky_bed.dissipated_work(&b2));
}

#[test]
fn adhesion_raises_the_coulomb_limit_by_twice_the_pull_off_force() {
    // Thornton & Yin (1991), LAMMPS `jkr`: the sliding force is μ (F_n + 2 F_c). At the overlap
    // where the held contact carries no normal force, it is μ 2 F_c, not zero.
    let pair = micro_pair();
    let mu = 0.3;
    let model = ContactModel::new(AdhesiveMdr::new(MdrElastoPlastic::elastic(), GAMMA).unwrap())
        .with_tangential(Mindlin::new(mu).unwrap());
    let law = model.bind(&pair).unwrap();
    let mut state = law.new_state();
    let dt = 1e-9;
    law.update(&mut state, &ContactInput::normal_only(2e-8, 0.0, dt));
    // Unload to the zero-force overlap of the JKR branch: a³ = 9·... solve F(a) = 0 → a³ = 9π Δγ R²/(2E*).
    let (r, e) = (pair.effective_radius(), pair.effective_modulus());
    let a0 = (4.5 * PI * GAMMA * r * r / e).cbrt();
    let d0 = jkr_overlap(a0, r, e, GAMMA);
    let mut d = 2e-8;
    while d > d0 {
        d = (d - 1e-11).max(d0);
        law.update(&mut state, &ContactInput::normal_only(d, 0.0, dt));
    }
    let mut input = ContactInput::normal_only(d0, 0.0, dt);
    input.relative_velocity.x = 1.0; // 1 nm per step: far past gross slip
    let mut out = law.update(&mut state, &input);
    for _ in 0..200 {
        out = law.update(&mut state, &input);
    }
    assert!(out.normal_force.abs() < 1e-6 * law.normal.pull_off_force());
    let expected = mu * (out.normal_force + 2.0 * law.normal.pull_off_force());
    assert!(out.tangential.sliding);
    assert!(
        (out.force.x.abs() - expected).abs() < 1e-6 * expected,
        "{:?} {expected}",
        out.force
    );
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]
    /// The closed form equals the spring bed (the reference for any profile) within its
    /// discretisation on random load histories, elastic and plastic, through let-go and re-touch.
    #[test]
    fn spring_bed_matches_closed_form(
        plastic in any::<bool>(),
        history in proptest::collection::vec(-2.5e-9..5e-8f64, 1..25),
    ) {
        let params = if plastic { micro_plastic() } else { MdrElastoPlastic::elastic() };
        let model = AdhesiveMdr::new(params, GAMMA).unwrap();
        let law = model.bind(&micro_pair()).unwrap();
        let bed = micro_bed(&model, 4000);
        let (mut closed, mut springs) = (AdhesiveMdrState::default(), AdhesiveSpringBedState::default());
        // The bed resolves the attached edge to ±Δx/2, and the edge spring is stretched by up
        // to Δl_max(a): a force error of the order E* Δx Δl_max(a_max).
        let a_max = (micro_pair().effective_radius() * 5e-8).sqrt();
        let edge = micro_pair().effective_modulus() * bed.bed().spacing()
            * law.critical_elongation(a_max);
        for d in history {
            // Within a discretisation band of the let-go overlap one form may hold and the
            // other not: skip the comparison there (not the history).
            let reach = law.detachment_overlap(&closed);
            let near_let_go = (d - reach).abs() < 2e-11;
            let f_closed = law.update(&mut closed, d).force;
            let f_bed = bed.update(&mut springs, d).force;
            if !near_let_go {
                prop_assert!((f_closed - f_bed).abs() < 4.0 * edge + 1e-3 * f_closed.abs(),
                    "d={d} closed={f_closed} bed={f_bed}");
            }
        }
    }
}

/// Quasi-static work `∫ F dδ` along a path sampled finely between the given overlaps.
fn path_work<L: NormalLaw>(law: &L, state: &mut L::State, turns: &[f64], step: f64) -> f64 {
    let mut work = 0.0;
    let mut d = 0.0;
    let mut force = 0.0;
    for &target in turns {
        let n = ((target - d).abs() / step).ceil().max(1.0) as usize;
        let start = d;
        for i in 1..=n {
            let next = start + (target - start) * i as f64 / n as f64;
            let f = law.update(state, next).force;
            work += 0.5 * (f + force) * (next - d);
            force = f;
            d = next;
        }
    }
    work
}

#[test]
fn books_close_through_plastic_loading_let_go_and_retouch() {
    // Work done on the contact = stored elastic energy + plastic work + the energy the springs
    // held when they let go, for both forms.
    let model = AdhesiveMdr::new(micro_plastic(), GAMMA).unwrap();
    let law = model.bind(&micro_pair()).unwrap();
    let bed = micro_bed(&model, 4000);
    let turns = [4e-8, 1.5e-8, 3e-8, -3e-9, 2.5e-8, 1.9e-8];
    let mut closed = AdhesiveMdrState::default();
    let work = path_work(&law, &mut closed, &turns, 1e-12);
    let books = law.elastic_energy(&closed, 1.9e-8) + law.dissipated_work(&closed);
    assert!(closed.adhesive_work > 0.0);
    assert!((work - books).abs() < 1e-4 * work, "{work} {books}");
    let mut springs = AdhesiveSpringBedState::default();
    let work = path_work(&bed, &mut springs, &turns, 1e-12);
    let books = bed.elastic_energy(&springs, 1.9e-8) + bed.dissipated_work(&springs);
    assert!((work - books).abs() < 1e-3 * work, "{work} {books}");
}

#[test]
fn jkr_check_rejects_a_wrong_work_of_adhesion() {
    // Negative control: a law with Δγ off by 1 % leaves the JKR branch of Δγ by far more than
    // the 1e-9 the closed form is held to.
    let pair = micro_pair();
    let (r, e) = (pair.effective_radius(), pair.effective_modulus());
    let law = elastic_law(&pair, 1.01 * GAMMA);
    let mut state = AdhesiveMdrState::default();
    law.update(&mut state, 2e-8);
    let a = law.update(&mut state, 0.0).contact_radius;
    assert!((0.0 - jkr_overlap(a, r, e, GAMMA)).abs() > 1e-4 * 2e-8);
}

#[test]
fn closed_form_unloads_along_jkr_for_a_large_contact() {
    // The paper's steel ball (R = 6.35 mm) with Δγ = 1 J/m²: the attached edge retreats by
    // about 1 % of its radius beyond the touching radius (ε = c√a_t/d ≈ 0.01–0.1), the regime of
    // the edge's series solution; the JKR branch (A8) holds there to the same 1e-9.
    let pair = ContactPair::paper_fig2();
    let (r, e) = (pair.effective_radius(), pair.effective_modulus());
    let gamma = 1.0;
    let law = elastic_law(&pair, gamma);
    let mut state = AdhesiveMdrState::default();
    let d0 = 1e-5;
    law.update(&mut state, d0);
    let scale = 1.5 * PI * gamma * r;
    let mut checked = 0;
    for k in 1..200 {
        let d = d0 * (1.0 - 0.005 * k as f64);
        let previous = state.contact_radius;
        let response = law.update(&mut state, d);
        let a = response.contact_radius;
        // On the retreating front (the edge moved in, and lies outside the touching radius).
        if a < previous && a > (r * d).sqrt() * (1.0 + 1e-6) {
            assert!(
                (d - jkr_overlap(a, r, e, gamma)).abs() < 1e-9 * d0,
                "d={d} a={a}"
            );
            assert!(
                (response.force - jkr_force(a, r, e, gamma)).abs() < 1e-9 * scale,
                "d={d}: {} vs {}",
                response.force,
                jkr_force(a, r, e, gamma)
            );
            assert_eq!(response.stiffness, 2.0 * e * a);
            checked += 1;
        }
    }
    assert!(checked > 150, "{checked}");
    assert!(law.holds(&state));
}
