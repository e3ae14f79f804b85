//! The law crate's shared parts against expectations written out here: the pair quantities of
//! two different materials (`E*` of eq. 3, `G*` of docs/theory.md §5, `R = R₁R₂/(R₁ + R₂)`, the
//! reduced mass), the Hertz impact's closed forms, the materials' ranges and the exact error
//! texts a user sees, the declared parameters' names and help lines, and the demo linear
//! dashpot's coefficient. Each test catches mutants of `material.rs`, `params.rs`, `error.rs`,
//! `model.rs` or `damping/linear_dashpot.rs` that the crate's other tests miss
//! (docs/verification.md §5).

use mdr_contact::nalgebra::Vector3;
use mdr_contact::params::{Declared, LawDeclaration, LawKind, Param, ParamProblem, Range};
use mdr_contact::prelude::*;
use std::f64::consts::PI;

/// `a` equals `b` to a relative `tol`.
fn close(a: f64, b: f64, tol: f64) -> bool {
    a.is_finite() && b.is_finite() && (a - b).abs() <= tol * b.abs()
}

/// Steel and glass, different in all three parameters.
fn steel() -> Material {
    Material::new(2.1e11, 0.29, 7850.0).unwrap()
}

fn glass() -> Material {
    Material::new(6.3e10, 0.22, 2500.0).unwrap()
}

#[test]
fn a_material_gives_back_its_parameters_and_its_shear_modulus_and_sphere_mass() {
    let m = steel();
    assert_eq!(
        (m.youngs_modulus(), m.poisson_ratio(), m.density()),
        (2.1e11, 0.29, 7850.0)
    );
    // G = E / (2 (1 + ν)).
    assert!(close(m.shear_modulus(), 2.1e11 / 2.58, 1e-14));
    // m = ρ 4π r³/3.
    let r = 0.003;
    assert!(close(
        m.sphere_mass(r),
        7850.0 * 4.0 * PI * r * r * r / 3.0,
        1e-14
    ));
    let p = Material::paper_steel();
    assert_eq!(
        (p.youngs_modulus(), p.poisson_ratio(), p.density()),
        (2.0e11, 0.286, 7800.0)
    );
}

#[test]
fn the_builder_names_every_parameter_and_leaves_none_unset() {
    let built = Material::builder()
        .youngs(6.3e10)
        .poisson(0.22)
        .density(2500.0)
        .build()
        .unwrap();
    assert_eq!(built, glass());
    // Set in another order: the same material (no parameter is swapped).
    let reordered = Material::builder()
        .density(2500.0)
        .poisson(0.22)
        .youngs(6.3e10)
        .build()
        .unwrap();
    assert_eq!(reordered, glass());
    let unset = |b: mdr_contact::material::MaterialBuilder| b.build().unwrap_err().to_string();
    assert_eq!(
        unset(Material::builder().poisson(0.22).density(2500.0)),
        "parameter `youngs_modulus` must be a finite number, got NaN"
    );
    assert_eq!(
        unset(Material::builder().youngs(6.3e10).density(2500.0)),
        "parameter `poisson_ratio` must be a finite number, got NaN"
    );
    assert_eq!(
        unset(Material::builder().youngs(6.3e10).poisson(0.22)),
        "parameter `density` must be a finite number, got NaN"
    );
}

#[test]
fn poissons_ratio_is_taken_in_minus_one_to_one_half_and_refused_with_its_range() {
    for nu in [-0.999_999, 0.0, 0.5] {
        assert_eq!(Material::new(1e9, nu, 1000.0).unwrap().poisson_ratio(), nu);
    }
    for (nu, text) in [(-1.0, "-1"), (0.500_001, "0.500001"), (-3.0, "-3")] {
        assert_eq!(
            Material::new(1e9, nu, 1000.0).unwrap_err().to_string(),
            format!("parameter `poisson_ratio` = {text} is outside the allowed range (-1, 0.5]")
        );
    }
    assert_eq!(
        Material::new(0.0, 0.3, 1000.0).unwrap_err().to_string(),
        "parameter `youngs_modulus` = 0 is outside the allowed range (0, inf)"
    );
    assert_eq!(
        Material::new(1e9, 0.3, -1.0).unwrap_err().to_string(),
        "parameter `density` = -1 is outside the allowed range (0, inf)"
    );
    assert!(Material::new(5e-324, 0.3, 5e-324).is_ok());
}

#[test]
fn two_different_materials_combine_by_their_compliances() {
    let (a, b) = (steel(), glass());
    // Eq. (3): 1/E* = (1 − ν₁²)/E₁ + (1 − ν₂²)/E₂.
    let e_star = 1.0 / ((1.0 - 0.29 * 0.29) / 2.1e11 + (1.0 - 0.22 * 0.22) / 6.3e10);
    assert!(close(effective_modulus(&a, &b), e_star, 1e-14));
    assert!(close(effective_modulus(&b, &a), e_star, 1e-14));
    // docs/theory.md §5: 1/G* = (2 − ν₁)/(4 G₁) + (2 − ν₂)/(4 G₂), G = E/(2(1 + ν)).
    let (g1, g2) = (2.1e11 / (2.0 * 1.29), 6.3e10 / (2.0 * 1.22));
    let g_star = 1.0 / ((2.0 - 0.29) / (4.0 * g1) + (2.0 - 0.22) / (4.0 * g2));
    assert!(close(effective_shear_modulus(&a, &b), g_star, 1e-14));
    assert!(close(effective_shear_modulus(&b, &a), g_star, 1e-14));
}

#[test]
fn pairs_of_spheres_and_of_a_sphere_and_a_wall_take_the_reduced_radius_and_mass() {
    let (a, b) = (steel(), glass());
    let e_star = 1.0 / ((1.0 - 0.29 * 0.29) / 2.1e11 + (1.0 - 0.22 * 0.22) / 6.3e10);
    let (g1, g2) = (2.1e11 / (2.0 * 1.29), 6.3e10 / (2.0 * 1.22));
    let g_star = 1.0 / ((2.0 - 0.29) / (4.0 * g1) + (2.0 - 0.22) / (4.0 * g2));
    let (r1, r2) = (0.002, 0.005);
    let (m1, m2) = (
        7850.0 * 4.0 * PI * r1 * r1 * r1 / 3.0,
        2500.0 * 4.0 * PI * r2 * r2 * r2 / 3.0,
    );
    let check = |p: ContactPair, r: f64, m: f64| {
        assert!(close(p.effective_modulus(), e_star, 1e-14), "{p:?}");
        assert!(close(p.effective_shear_modulus(), g_star, 1e-14), "{p:?}");
        assert!(close(p.effective_radius(), r, 1e-14), "{p:?}");
        assert!(close(p.reduced_mass(), m, 1e-14), "{p:?}");
    };
    let (r_pair, m_pair) = (1.0 / (1.0 / r1 + 1.0 / r2), 1.0 / (1.0 / m1 + 1.0 / m2));
    check(
        ContactPair::sphere_on_sphere(r1, &a, r2, &b).unwrap(),
        r_pair,
        m_pair,
    );
    let other = Counterpart::Sphere {
        radius: r2,
        material: b,
    };
    check(
        ContactPair::with_counterpart(r1, &a, &other).unwrap(),
        r_pair,
        m_pair,
    );
    // A wall: the sphere's own radius and mass.
    check(
        ContactPair::sphere_on_half_space(r1, &a, &b).unwrap(),
        r1,
        m1,
    );
    check(
        ContactPair::with_counterpart(r1, &a, &Counterpart::HalfSpace { material: b }).unwrap(),
        r1,
        m1,
    );
    let heavier = ContactPair::sphere_on_half_space(r1, &a, &b)
        .unwrap()
        .with_reduced_mass(0.25)
        .unwrap();
    check(heavier, r1, 0.25);
    assert_eq!(
        ContactPair::sphere_on_half_space(r1, &a, &b)
            .unwrap()
            .with_reduced_mass(0.0)
            .unwrap_err()
            .to_string(),
        "parameter `reduced_mass` = 0 is outside the allowed range (0, inf)"
    );
    assert_eq!(
        ContactPair::sphere_on_sphere(r1, &a, -r2, &b)
            .unwrap_err()
            .to_string(),
        "parameter `target_radius` = -0.005 is outside the allowed range (0, inf)"
    );
}

#[test]
fn a_pair_from_its_quantities_refuses_each_by_name() {
    let p = ContactPair::new(1e9, 4e8, 0.01, 0.002).unwrap();
    assert_eq!(
        (
            p.effective_modulus(),
            p.effective_shear_modulus(),
            p.effective_radius(),
            p.reduced_mass()
        ),
        (1e9, 4e8, 0.01, 0.002)
    );
    let refused = |q: [f64; 4]| {
        ContactPair::new(q[0], q[1], q[2], q[3])
            .unwrap_err()
            .to_string()
    };
    assert_eq!(
        refused([0.0, 4e8, 0.01, 0.002]),
        "parameter `effective_modulus` = 0 is outside the allowed range (0, inf)"
    );
    assert_eq!(
        refused([1e9, -4e8, 0.01, 0.002]),
        "parameter `effective_shear_modulus` = -400000000 is outside the allowed range (0, inf)"
    );
    assert_eq!(
        refused([1e9, 4e8, f64::INFINITY, 0.002]),
        "parameter `effective_radius` must be a finite number, got inf"
    );
    assert_eq!(
        refused([1e9, 4e8, 0.01, 0.0]),
        "parameter `reduced_mass` = 0 is outside the allowed range (0, inf)"
    );
}

#[test]
fn the_hertz_impact_lasts_and_reaches_its_closed_forms() {
    let pair = ContactPair::sphere_on_sphere(0.002, &steel(), 0.005, &glass()).unwrap();
    let (e, r, m) = (
        pair.effective_modulus(),
        pair.effective_radius(),
        pair.reduced_mass(),
    );
    for v in [0.01, 1.7, 30.0] {
        // The deepest overlap stores the kinetic energy: (8/15) E* √R δ^{5/2} = ½ m v².
        let d = pair.hertz_max_overlap(v);
        let stored = 8.0 / 15.0 * e * r.sqrt() * d.powf(2.5);
        assert!(close(stored, 0.5 * m * v * v, 1e-13), "{v}: {stored}");
        assert!(close(pair.hertz_max_overlap(-v), d, 1e-14));
        // t_c = 2.868 (m²/(R E*² v))^{1/5}, the same for an approach of either sign.
        let t = 2.868 * (m * m / (r * e * e * v)).powf(0.2);
        assert!(close(pair.hertz_contact_time(v), t, 1e-14), "{v}");
        assert!(close(pair.hertz_contact_time(-v), t, 1e-14), "{v}");
    }
}

#[cfg(feature = "demo-laws")]
#[test]
fn the_linear_dashpot_gives_back_its_coefficient() {
    use mdr_contact::damping::LinearDashpot;
    assert_eq!(LinearDashpot::new(2.5).unwrap().coefficient(), 2.5);
    assert_eq!(
        LinearDashpot::from_values(&[0.75]).unwrap().coefficient(),
        0.75
    );
    assert_eq!(LinearDashpot::new(0.0).unwrap().coefficient(), 0.0);
}

/// A declaration of two parameters: a required one in `(0, inf)` and a defaulted one in `[0, 1]`
/// with every published name overridden.
static PARAMS: &[Param] = &[
    Param::new("length_m", "L", "m", Range::POSITIVE, "the length"),
    Param::new("ratio", "r", "1", Range::UNIT_INTERVAL, "the ratio")
        .default(0.25)
        .flag("r")
        .python("rr")
        .lammps("rl"),
];

static DECLARATION: LawDeclaration = LawDeclaration {
    name: "two_params",
    kind: LawKind::Normal,
    summary: "",
    params: PARAMS,
};

#[test]
fn a_parameter_writes_its_help_line_and_its_published_names() {
    assert_eq!(PARAMS[0].help(), "L (m, in (0, inf)): the length");
    assert_eq!(
        PARAMS[1].help(),
        "r (1, in [0, 1], default 0.25): the ratio"
    );
    assert_eq!(PARAMS[0].default, None);
    assert_eq!(PARAMS[1].default, Some(0.25));
    assert_eq!(
        (
            PARAMS[0].flag_name(),
            PARAMS[0].python_name(),
            PARAMS[0].lammps_name()
        ),
        ("length-m".to_owned(), "length_m", "length_m")
    );
    assert_eq!(
        (
            PARAMS[1].flag_name(),
            PARAMS[1].python_name(),
            PARAMS[1].lammps_name()
        ),
        ("r".to_owned(), "rr", "rl")
    );
    assert_eq!(DECLARATION.param("ratio"), Some(&PARAMS[1]));
    assert_eq!(DECLARATION.param("length_m"), Some(&PARAMS[0]));
    assert_eq!(DECLARATION.param("length"), None);
}

#[test]
fn a_missing_or_refused_parameter_is_reported_with_its_help_line() {
    let missing = DECLARATION.values(|_| None).unwrap_err();
    assert_eq!(
        missing[0].to_string(),
        "`length_m` is required: L (m, in (0, inf)): the length"
    );
    let refused = DECLARATION
        .values(|p| Some(if p.key == "ratio" { 1.5 } else { 2.0 }))
        .unwrap_err();
    assert_eq!(refused.len(), 1);
    assert!(matches!(refused[0], ParamProblem::Invalid(p, _) if p.key == "ratio"));
    assert_eq!(
        refused[0].to_string(),
        "parameter `ratio` = 1.5 is outside the allowed range [0, 1] \
         (r (1, in [0, 1], default 0.25): the ratio)"
    );
    assert_eq!(
        DECLARATION
            .values(|p| (p.key == "length_m").then_some(3.0))
            .unwrap(),
        [3.0, 0.25]
    );
}

#[test]
fn a_value_is_checked_against_its_declared_range_with_the_exact_error() {
    let length = &PARAMS[0];
    assert_eq!(length.check(5e-324), Ok(5e-324));
    assert_eq!(length.check(7.5), Ok(7.5));
    assert_eq!(
        length.check(0.0).unwrap_err().to_string(),
        "parameter `length_m` = 0 is outside the allowed range (0, inf)"
    );
    assert_eq!(
        length.check(f64::NAN).unwrap_err().to_string(),
        "parameter `length_m` must be a finite number, got NaN"
    );
    assert_eq!(
        length.check(f64::NEG_INFINITY).unwrap_err().to_string(),
        "parameter `length_m` must be a finite number, got -inf"
    );
    let ratio = &PARAMS[1];
    for v in [0.0, 0.5, 1.0] {
        assert_eq!(ratio.check(v), Ok(v));
    }
    for v in [-1e-300, 1.0 + 1e-15] {
        assert!(ratio.check(v).is_err(), "{v}");
    }
}

#[test]
fn each_range_holds_its_bounds_and_only_finite_values() {
    // (0, inf), [0, inf), [0, 1] and an open interval (−1, 1).
    let open = Range {
        min: -1.0,
        min_inclusive: false,
        max: 1.0,
        max_inclusive: false,
        notation: "(-1, 1)",
    };
    let cases: [(Range, &[f64], &[f64]); 4] = [
        (
            Range::POSITIVE,
            &[5e-324, 1.0, 1e300],
            &[0.0, -1.0, f64::INFINITY, f64::NAN],
        ),
        (
            Range::NON_NEGATIVE,
            &[0.0, 2.0, 1e300],
            &[-5e-324, f64::INFINITY, f64::NAN],
        ),
        (
            Range::UNIT_INTERVAL,
            &[0.0, 0.5, 1.0],
            &[-1e-300, 1.0 + 1e-15, f64::NAN],
        ),
        (
            open,
            &[-0.999, 0.0, 0.999],
            &[-1.0, 1.0, -2.0, 2.0, f64::NAN],
        ),
    ];
    for (range, inside, outside) in cases {
        for &v in inside {
            assert!(range.contains(v), "{} should contain {v}", range.notation);
        }
        for &v in outside {
            assert!(
                !range.contains(v),
                "{} should not contain {v}",
                range.notation
            );
        }
    }
}

#[test]
fn books_add_what_they_are_given_and_no_books_report_nan() {
    let mut books = Books::default();
    books.add_friction_work(0.5);
    books.add_friction_work(0.25);
    books.add_damping_work(2.0);
    books.add_damping_work(0.125);
    // Stiffness energies may be lost as well as gained.
    books.add_tangential_stiffness_energy(0.75);
    books.add_tangential_stiffness_energy(-0.25);
    books.add_rolling_stiffness_energy(1.5);
    books.add_rolling_stiffness_energy(-0.25);
    assert_eq!(
        (
            books.friction_work(),
            books.damping_work(),
            books.tangential_stiffness_energy(),
            books.rolling_stiffness_energy()
        ),
        (0.75, 2.125, 0.5, 1.25)
    );
    assert_eq!(
        books,
        Books {
            friction_work: 0.75,
            damping_work: 2.125,
            tangential_stiffness_energy: 0.5,
            rolling_stiffness_energy: 1.25,
        }
    );
    let mut none = NoBooks;
    none.add_friction_work(1.0);
    none.add_damping_work(1.0);
    none.add_tangential_stiffness_energy(1.0);
    none.add_rolling_stiffness_energy(1.0);
    assert!(none.friction_work().is_nan());
    assert!(none.damping_work().is_nan());
    assert!(none.tangential_stiffness_energy().is_nan());
    assert!(none.rolling_stiffness_energy().is_nan());
}

/// Hertz with Mindlin friction and LAMMPS' Hertzian dashpots (`m γ_n √(R δ)`, tangential
/// `ratio ·` that), bound to a pair of round numbers.
fn damped_hertz_mindlin(
) -> ContactLaw<HertzLaw, MindlinLaw, mdr_contact::damping::HertzianViscousLaw> {
    let pair = ContactPair::new(1.5e5, 28_571.0, 0.25, 0.3).unwrap();
    ContactModel::new(Hertz)
        .with_tangential(Mindlin::new(0.5).unwrap())
        .with_damping(
            HertzianViscous::new(50.0)
                .unwrap()
                .with_tangential_ratio(0.5)
                .unwrap(),
        )
        .bind(&pair)
        .unwrap()
}

/// `a` equals `b` component by component to `tol` of `|b|`.
fn close_vector(a: Vector3<f64>, b: Vector3<f64>, tol: f64) -> bool {
    (a - b).norm() <= tol * b.norm()
}

#[test]
fn a_sticking_contact_adds_both_dashpots_to_its_springs_along_a_tilted_normal() {
    let law = damped_hertz_mindlin();
    let (e, g, r, m, gamma_n, ratio) = (1.5e5_f64, 28_571.0, 0.25_f64, 0.3, 50.0, 0.5);
    // Body 1 approaches body 2 along the normal n at 0.2 m/s and slides across it.
    let n = Vector3::new(0.6, 0.0, 0.8);
    let (t1, t2) = (Vector3::new(0.8, 0.0, -0.6), Vector3::y());
    let v_t: Vector3<f64> = t1 * 0.3 + t2 * 0.1;
    let (d, dt, approach) = (1e-3_f64, 1e-4, 0.2);
    let mut state = law.new_state();
    let out = law.update(
        &mut state,
        &ContactInput {
            overlap: d,
            normal: n,
            relative_velocity: v_t - approach * n,
            dt,
        },
    );
    // Hertz, eq. (5), and its contact radius; the normal dashpot pushes while approaching.
    let f_hertz = 4.0 / 3.0 * e * r.sqrt() * d.powf(1.5);
    let dashpot = m * gamma_n * (r * d).sqrt();
    let f_n = f_hertz + dashpot * approach;
    assert!(close(out.normal_force, f_n, 1e-13), "{}", out.normal_force);
    // The springs stick (|k_t ξ| ≪ μ F_N): F_t = −2 G* a ξ with ξ = v_t Δt (docs/theory.md §5),
    // and the tangential dashpot −ratio · dashpot · v_t acts on top.
    let k_t = 2.0 * g * (r * d).sqrt();
    assert!(!out.tangential.sliding);
    let force = n * f_n - v_t * (k_t * dt) - v_t * (ratio * dashpot);
    assert!(close_vector(out.force, force, 1e-13), "{}", out.force);
    // Both dashpots' work of the step: (c v_n² + η_t |v_t|²) Δt; nothing to friction.
    let work = (dashpot * approach * approach + ratio * dashpot * v_t.norm_squared()) * dt;
    assert!(close(state.books.damping_work, work, 1e-13));
    assert_eq!(state.books.friction_work, 0.0);
}

#[test]
fn a_dashpot_never_pulls_a_separating_contact_together() {
    let law = damped_hertz_mindlin();
    let (e, r, m, gamma_n) = (1.5e5_f64, 0.25_f64, 0.3, 50.0);
    let n = Vector3::z();
    let (d, dt) = (1e-3_f64, 1e-4);
    let f_hertz = 4.0 / 3.0 * e * r.sqrt() * d.powf(1.5);
    let dashpot = m * gamma_n * (r * d).sqrt();
    // Separating slowly the dashpot takes a part of the spring's push; fast, all of it, and no
    // more: the normal force stops at 0 and the dashpot works against the spring's force only.
    for (speed, f_n) in [(0.1, f_hertz - dashpot * 0.1), (20.0, 0.0)] {
        assert!(f_n >= 0.0 && dashpot * 20.0 > f_hertz);
        let mut state = law.new_state();
        let out = law.update(&mut state, &ContactInput::normal_only(d, speed, dt));
        assert!(
            close(out.normal_force, f_n, 1e-13) || out.normal_force == f_n,
            "{speed}"
        );
        assert!(close_vector(out.force, n * f_n, 1e-13) || out.force == n * f_n);
        let work = (f_hertz - f_n) * speed * dt;
        assert!(close(state.books.damping_work, work, 1e-13), "{speed}");
    }
}

#[test]
fn a_body_inside_the_crater_it_left_feels_no_dashpot() {
    let pair = ContactPair::paper_fig2();
    let law = ContactModel::new(MdrElastoPlastic::paper())
        .with_tangential(Mindlin::new(0.3).unwrap())
        .with_damping(
            HertzianViscous::new(5e4)
                .unwrap()
                .with_tangential_ratio(0.5)
                .unwrap(),
        )
        .bind(&pair)
        .unwrap();
    let mut state = law.new_state();
    let input = |overlap, speed| ContactInput {
        overlap,
        normal: Vector3::z(),
        relative_velocity: Vector3::new(0.05, 0.0, speed),
        dt: 1e-7,
    };
    // Load well past the yield depth u_c ≈ 5.5 µm, then leave the contact.
    assert!(law.update(&mut state, &input(2e-5, -0.1)).normal_force > 0.0);
    let residual = law.normal.residual_overlap(&state.normal);
    assert!(residual > 0.0);
    // Back inside the crater, short of its floor, and approaching it again: no contact, so no
    // force of either spring or either dashpot, and no work.
    let out = law.update(&mut state, &input(0.5 * residual, -0.1));
    assert_eq!(out.normal_force, 0.0);
    assert_eq!(out.force, Vector3::zeros());
    let damping_work = state.books.damping_work;
    law.update(&mut state, &input(0.6 * residual, -0.1));
    assert_eq!(state.books.damping_work, damping_work);
}

#[test]
fn the_coulomb_limit_of_a_sliding_contact_counts_the_normal_dashpot() {
    let law = damped_hertz_mindlin();
    let (e, r, m, gamma_n, mu) = (1.5e5_f64, 0.25_f64, 0.3, 50.0, 0.5);
    let (d, dt, approach, slide) = (1e-3_f64, 1e-4, 0.2, 100.0);
    let mut state = law.new_state();
    let out = law.update(
        &mut state,
        &ContactInput {
            overlap: d,
            normal: Vector3::z(),
            relative_velocity: Vector3::new(slide, 0.0, -approach),
            dt,
        },
    );
    // Gross slip at once (k_t |ξ| = 2 G* a · 10⁻² m ≫ μ F_N): the spring holds μ F_N against
    // the sliding, with F_N the Hertz force plus the normal dashpot's push, and the tangential
    // dashpot is off.
    let f_n = 4.0 / 3.0 * e * r.sqrt() * d.powf(1.5) + m * gamma_n * (r * d).sqrt() * approach;
    assert!(out.tangential.sliding);
    let friction = Vector3::new(-mu * f_n, 0.0, 0.0);
    assert!(
        close_vector(out.tangential.force, friction, 1e-13),
        "{}",
        out.tangential.force
    );
    assert!(
        close_vector(out.force, Vector3::z() * f_n + friction, 1e-13),
        "{}",
        out.force
    );
}
