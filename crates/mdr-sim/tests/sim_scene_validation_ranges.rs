//! The scene validation's range checks of the materials' works of adhesion: every material's
//! `work_of_adhesion_j_per_m2` is checked against `[0, inf)` J/m², whether or not a sphere or
//! wall of that material meets another.

mod common;

use mdr_sim::scene::validate::parse_scene;
use std::path::Path;

/// The reference column with a second material, `spare`, that no sphere or wall uses, with the
/// work of adhesion `gamma` (as written in TOML).
fn with_spare_material(gamma: &str) -> String {
    let text = common::column(1, 1, 0.01, 0.0, "");
    text.replacen(
        "[contact]",
        &format!(
            "[[material]]\nname = \"spare\"\nyoungs_pa = 5.0e7\npoisson_ratio = 0.25\n\
             density_kg_per_m3 = 2500.0\nwork_of_adhesion_j_per_m2 = {gamma}\n\n[contact]"
        ),
        1,
    )
}

#[test]
fn every_materials_work_of_adhesion_is_range_checked_even_when_unused() {
    for bad in ["-0.5", "-1e-300", "inf", "-inf", "nan"] {
        let text = with_spare_material(bad);
        let problems = parse_scene(Path::new("scene.toml"), &text)
            .err()
            .unwrap_or_else(|| panic!("Δγ = {bad} was taken"));
        let errors: Vec<_> = problems.errors().collect();
        assert_eq!(errors.len(), 1, "{bad}: {problems}");
        assert_eq!(errors[0].key, "material[1].work_of_adhesion_j_per_m2");
        assert!(
            errors[0]
                .message
                .contains("is outside the allowed range [0, inf) J/m²"),
            "{bad}: {problems}"
        );
    }
    // The range's bound and a finite value are taken; a material no sphere or wall uses adds
    // no pair, so the scene keeps the plain MDR law.
    for good in ["0.0", "2.5", "1e300"] {
        let text = with_spare_material(good);
        let scene = parse_scene(Path::new("scene.toml"), &text)
            .unwrap_or_else(|e| panic!("Δγ = {good}: {e}"));
        assert_eq!(scene.contact.normal.law, "mdr", "{good}");
    }
}

/// The column with the plain Hertz law in place of MDR.
fn hertz(text: &str) -> String {
    text.replace(
        "normal = \"mdr\"\ncritical_line_load_n_per_m = 100.0\nhardening_ratio = 0.37",
        "normal = \"hertz\"",
    )
}

/// Only a positive work of adhesion asks for the adhesive law: materials that all give
/// `Δγ = 0` leave any normal law as it is, and a law without adhesion is refused at the key of
/// the first material that gives one.
#[test]
fn only_a_positive_work_of_adhesion_asks_for_the_adhesive_law() {
    let text = hertz(&with_spare_material("0.0"));
    assert!(text.contains("normal = \"hertz\""));
    let scene = parse_scene(Path::new("scene.toml"), &text).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(scene.contact.normal.law, "hertz");
    let text = hertz(&with_spare_material("2.5"));
    let problems = parse_scene(Path::new("scene.toml"), &text)
        .err()
        .unwrap_or_else(|| panic!("Δγ = 2.5 with normal = \"hertz\" was taken"));
    let errors: Vec<_> = problems.errors().collect();
    assert_eq!(errors.len(), 1, "{problems}");
    assert_eq!(errors[0].key, "material[1].work_of_adhesion_j_per_m2");
    assert!(
        errors[0].message.contains("needs normal = \"mdr\""),
        "{problems}"
    );
}
