//! Malformed and extreme scene files: each gives a clear error (file, line, key, allowed range)
//! or a warning, never a panic. Includes a seeded mutation sweep over a valid scene.

mod common;

use mdr_sim::scene::validate::parse_scene;
use mdr_sim::scene::{Problems, Severity};
use mdr_sim::walls::WallPiece;
use nalgebra::Vector3;
use std::path::Path;

fn good() -> String {
    common::column(2, 2, 0.01, 0.3, "")
}

fn problems(text: &str) -> Problems {
    match parse_scene(Path::new("scene.toml"), text) {
        Ok(scene) => Problems(scene.warnings),
        Err(p) => p,
    }
}

/// The first error mentioning `key`; panics with all problems when there is none.
fn error_on(text: &str, key: &str) -> mdr_sim::scene::Problem {
    let p = problems(text);
    let found = p
        .errors()
        .find(|e| e.key.contains(key) || e.message.contains(key))
        .cloned();
    found.unwrap_or_else(|| panic!("no error about `{key}`; got:\n{p}"))
}

fn line_of(text: &str, needle: &str) -> usize {
    text.lines()
        .position(|l| l.contains(needle))
        .expect("needle")
        + 1
}

#[test]
fn the_reference_scene_is_valid() {
    let p = problems(&good());
    assert!(!p.has_errors(), "{p}");
}

#[test]
fn nan_and_negative_sizes_name_key_line_and_range() {
    let text = good().replace("radius_m = 0.002", "radius_m = nan");
    let e = error_on(&text, "radius_m");
    assert_eq!(e.line, line_of(&text, "radius_m = nan"));
    assert!(e.message.contains("finite"), "{e}");

    let text = good().replace("radius_m = 0.002", "radius_m = -0.002");
    let e = error_on(&text, "radius_m");
    assert!(e.message.contains("(0, inf)"), "{e}");
    assert_eq!(e.key, "particles[0].radius_m");
    assert_eq!(e.line, line_of(&text, "radius_m = -0.002"));
    assert!(e.to_string().starts_with("scene.toml:"), "{e}");
}

#[test]
fn zero_and_huge_counts_are_refused() {
    let e = error_on(&good().replace("count = 8", "count = 0"), "count");
    assert!(e.message.contains("[1, 1000000]"), "{e}");
    let e = error_on(
        &good().replace("count = 8", "count = 1000000000000"),
        "count",
    );
    assert!(e.message.contains("[1, 1000000]"), "{e}");
    let e = error_on(&good().replace("count = 8", "count = -3"), "count");
    assert!(e.line > 0, "{e}");
}

#[test]
fn material_parameters_are_checked_by_the_law_crate() {
    let text = good().replace("poisson_ratio = 0.25", "poisson_ratio = 0.7");
    let e = error_on(&text, "poisson_ratio");
    assert!(e.message.contains("(-1, 0.5]"), "{e}");
    assert_eq!(e.line, line_of(&text, "poisson_ratio = 0.7"));
    let e = error_on(
        &good().replace("hardening_ratio = 0.37", "hardening_ratio = 1.5"),
        "hardening_ratio",
    );
    assert!(e.message.contains("[0, 1]"), "{e}");
    let e = error_on(
        &good().replace("friction = 0.3", "friction = -1.0"),
        "friction",
    );
    assert!(e.message.contains("[0, inf)"), "{e}");
}

#[test]
fn every_unknown_key_is_reported_at_once() {
    let text = good()
        .replace("seed = 5", "seed = 5\nspeed_of_light = 3e8")
        .replace("count = 8", "count = 8\nradius = 0.1");
    let p = problems(&text);
    let unknown: Vec<_> = p
        .errors()
        .filter(|e| e.message.contains("unknown field"))
        .collect();
    assert_eq!(unknown.len(), 2, "{p}");
    assert_eq!(unknown[0].line, line_of(&text, "speed_of_light"));
    assert_eq!(unknown[1].line, line_of(&text, "radius = 0.1"));
    assert!(
        unknown[1].message.contains("radius_m"),
        "the message lists the allowed keys: {p}"
    );
}

#[test]
fn range_checks_hold_at_their_bounds() {
    // (0, inf): zero is outside.
    let e = error_on(
        &good().replace("duration_s = 0.01", "duration_s = 0.0"),
        "duration_s",
    );
    assert!(e.message.contains("(0, inf)"), "{e}");
    // [0, inf): zero is inside, a negative value outside.
    let text = good().replace("jitter_fraction = 0.8", "jitter_fraction = 0.0");
    assert!(!problems(&text).has_errors(), "{}", problems(&text));
    let e = error_on(
        &good().replace("jitter_fraction = 0.8", "jitter_fraction = -0.1"),
        "jitter_fraction",
    );
    assert!(e.message.contains("[0, inf)"), "{e}");
    // A direction must be non-zero, and is made a unit vector.
    let e = error_on(
        &good().replace("normal = [0.0, 0.0, 1.0]", "normal = [0.0, 0.0, 0.0]"),
        "walls[0].normal",
    );
    assert!(e.message.contains("non-zero"), "{e}");
    let text = good().replace("normal = [0.0, 0.0, 1.0]", "normal = [0.0, 0.0, 2.5]");
    let scene = parse_scene(Path::new("scene.toml"), &text).unwrap();
    match &scene.walls[0].pieces[..] {
        [WallPiece::HalfSpace { normal, .. }] => assert_eq!(*normal, Vector3::z()),
        other => panic!("expected one half-space, got {other:?}"),
    }
}

#[test]
fn a_wall_takes_the_material_it_names() {
    let text = good()
        .replace(
            "[contact]",
            "[[material]]\nname = \"steel\"\nyoungs_pa = 2.0e11\npoisson_ratio = 0.3\n\
             density_kg_per_m3 = 7800.0\n\n[contact]",
        )
        .replace(
            "kind = \"plane\"\nmaterial = \"grain\"",
            "kind = \"plane\"\nmaterial = \"steel\"",
        );
    let scene = parse_scene(Path::new("scene.toml"), &text).unwrap();
    assert_eq!(scene.materials[1].0, "steel");
    assert_eq!(scene.walls[0].material, 1);
}

#[test]
fn keys_that_do_not_belong_to_the_chosen_kind_are_errors() {
    let text = good().replace(
        "normal = [0.0, 0.0, 1.0]",
        "normal = [0.0, 0.0, 1.0]\nradius_m = 0.1",
    );
    let e = error_on(&text, "walls[0].radius_m");
    assert!(e.message.contains("not used"), "{e}");
    let e = error_on(
        &good().replace("tangential = \"mindlin\"\n", ""),
        "friction",
    );
    assert!(e.message.contains("mindlin"), "{e}");
}

#[test]
fn overlapping_placement_is_refused() {
    let dir = common::temp_dir("overlap");
    std::fs::write(
        dir.join("bed.csv"),
        "x_m,y_m,z_m,radius_m\n0,0,0.01,0.002\n0.003,0,0.01,0.002\n0.02,0,0.01,0.002\n",
    )
    .unwrap();
    let text = good()
        .replace("count = 8\n", "")
        .replace("radius_m = 0.002\n", "")
        .replace(
            "placement = \"lattice\"",
            "placement = \"csv\"\nfile = \"bed.csv\"",
        )
        .lines()
        .filter(|l| {
            !l.starts_with("region_") && !l.starts_with("gap_") && !l.starts_with("jitter_")
        })
        .collect::<Vec<_>>()
        .join("\n");
    let path = common::write(&dir, "scene.toml", &text);
    let err = parse_scene(&path, &text).unwrap_err();
    let e = err
        .errors()
        .find(|e| e.message.contains("overlap"))
        .expect("overlap error");
    assert!(
        e.message.contains("particle 0") && e.message.contains("particle 1"),
        "{e}"
    );
    // A particle inside the floor is refused too.
    std::fs::write(
        dir.join("bed.csv"),
        "x_m,y_m,z_m,radius_m\n0,0,0.001,0.002\n",
    )
    .unwrap();
    let err = parse_scene(&path, &text).unwrap_err();
    assert!(err.errors().any(|e| e.key == "walls[0]"), "{err}");
}

#[test]
fn a_far_too_large_step_is_an_error_and_a_coarse_one_a_warning() {
    let text = good().replace("dt_s = \"auto\"", "dt_s = 1e-3");
    let e = error_on(&text, "dt_s");
    assert!(e.message.contains("far too large"), "{e}");
    assert_eq!(e.line, line_of(&text, "dt_s = 1e-3"));
    // Hertz time here is ~2e-4 s: 20 steps per contact is allowed with a warning.
    let text = good().replace("dt_s = \"auto\"", "dt_s = 1e-5");
    let p = problems(&text);
    assert!(!p.has_errors(), "{p}");
    assert!(p.warnings().any(|w| w.key == "run.dt_s"), "{p}");
}

#[test]
fn structure_errors_have_lines_too() {
    let p = problems(&good().replace("[contact]", "[contact]\nnormal2 = 1"));
    assert!(p.has_errors());
    let p = problems("this is not toml = = =");
    assert!(p.errors().next().unwrap().line > 0, "{p}");
    let p = problems("");
    assert!(p.has_errors(), "an empty file is refused");
    let p = problems(&good().replace("normal = \"mdr\"", "normal = \"elastic\""));
    assert!(p.errors().next().unwrap().line > 0, "{p}");
    let p = problems(&good().replace("[[particles]]", "[[particles_]]"));
    assert!(p.has_errors(), "{p}");
}

/// Seeded mutation sweep: replace one number of a valid scene by an extreme value, or drop or
/// duplicate one line; every variant parses to a scene or to problems, never a panic.
#[test]
fn mutated_scenes_never_panic() {
    let base = good();
    let lines: Vec<&str> = base.lines().collect();
    let extremes = [
        "nan",
        "inf",
        "-inf",
        "0",
        "-0.0",
        "1e308",
        "-1e308",
        "1e-320",
        "-1",
        "18446744073709551615",
        "\"text\"",
        "[]",
        "[1.0]",
        "true",
    ];
    let mut state: u64 = 0x9e37_79b9_7f4a_7c15;
    let mut next = || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        state
    };
    let mut variants = 0;
    for _ in 0..400 {
        let i = (next() % lines.len() as u64) as usize;
        let mut out: Vec<String> = lines.iter().map(|s| s.to_string()).collect();
        match next() % 3 {
            0 => {
                if let Some((k, _)) = lines[i].split_once('=') {
                    let v = extremes[(next() % extremes.len() as u64) as usize];
                    out[i] = format!("{k}= {v}");
                } else {
                    continue;
                }
            }
            1 => {
                out.remove(i);
            }
            _ => out.insert(i, lines[i].to_owned()),
        }
        let text = out.join("\n");
        let result = std::panic::catch_unwind(|| problems(&text));
        assert!(result.is_ok(), "panic on variant:\n{text}");
        variants += 1;
        let p = result.unwrap();
        for e in p.errors() {
            assert!(!e.message.is_empty());
        }
    }
    assert!(variants > 200);
    let _ = Severity::Error;
}

#[test]
fn force_path_is_checked_with_line_and_key() {
    let text = good().replacen("[run]\n", "[run]\nforce_path = \"octree\"\n", 1);
    let e = error_on(&text, "force_path");
    assert_eq!(e.line, line_of(&text, "force_path = \"octree\""));
    assert!(e.message.contains("neighbour_list"), "{e}");

    let text = good().replacen("[run]\n", "[run]\nforce_path = \"rapier\"\n", 1);
    assert!(!problems(&text).has_errors());

    let text = good().replacen(
        "[run]\n",
        "[run]\ncoupling = \"restitution\"\nforce_path = \"neighbour_list\"\n",
        1,
    );
    let e = error_on(&text, "force_path");
    assert_eq!(e.key, "run.force_path");
    assert_eq!(e.line, line_of(&text, "force_path = "));
}

#[test]
fn neighbour_skin_is_checked_with_line_and_key() {
    let text = good().replacen("[run]\n", "[run]\nneighbour_skin_m = -0.001\n", 1);
    let e = error_on(&text, "neighbour_skin_m");
    assert_eq!(e.key, "run.neighbour_skin_m");
    assert_eq!(e.line, line_of(&text, "neighbour_skin_m = -0.001"));
    assert!(e.message.contains("(0, inf)"), "{e}");

    let text = good().replacen("[run]\n", "[run]\nneighbour_skin_m = 0.001\n", 1);
    assert!(!problems(&text).has_errors());

    let text = good().replacen(
        "[run]\n",
        "[run]\nforce_path = \"rapier\"\nneighbour_skin_m = 0.001\n",
        1,
    );
    let e = error_on(&text, "neighbour_skin_m");
    assert!(e.message.contains("neighbour-list path only"), "{e}");
}

/// A `[contact]` parameter of the wrong type is one error at its key ("invalid type"), not a
/// second one for the number it is not.
#[test]
fn a_contact_parameter_that_is_not_a_number_is_one_error_at_its_key() {
    let text = good().replace(
        "critical_line_load_n_per_m = 100.0",
        "critical_line_load_n_per_m = \"100\"",
    );
    let p = problems(&text);
    let at_key: Vec<_> = p
        .errors()
        .filter(|e| e.key == "contact.critical_line_load_n_per_m")
        .collect();
    assert_eq!(at_key.len(), 1, "{p}");
    assert!(
        at_key[0].message.contains("invalid type: string")
            && at_key[0].message.contains("expected a number"),
        "{p}"
    );
    assert_eq!(at_key[0].line, line_of(&text, "critical_line_load_n_per_m"));
}

/// An unknown `[contact]` key lists the keys the table takes: `normal` first, the sub-model
/// kinds and their parameters, then the normal law's parameters.
#[test]
fn an_unknown_contact_key_lists_the_keys_of_the_table() {
    let text = good().replace(
        "hardening_ratio = 0.37",
        "hardening_ratio = 0.37\nfrobnicate = 1",
    );
    let e = error_on(&text, "contact.frobnicate");
    assert!(e.message.contains("unknown field `frobnicate`"), "{e}");
    let expected = e.message.split("expected one of ").nth(1).unwrap_or("");
    assert!(expected.starts_with("`normal`, "), "{e}");
    for key in [
        "`tangential`",
        "`friction`",
        "`rolling_friction`",
        "`critical_line_load_n_per_m`",
        "`hardening_ratio`",
    ] {
        assert!(expected.contains(key), "{key} missing: {e}");
    }
    assert!(
        !expected.contains("``") && !expected.contains("xyzzy"),
        "{e}"
    );
}

/// A scene of spheres of material `sphere` (`count` of them) on a plane of material `wall`,
/// with the materials `(name, work of adhesion in J/m²)` in that order.
fn adhesion_scene(materials: &[(&str, f64)], sphere: &str, count: usize, wall: &str) -> String {
    let block: String = materials
        .iter()
        .map(|(name, gamma)| {
            format!(
                "[[material]]\nname = \"{name}\"\nyoungs_pa = 5.0e7\npoisson_ratio = 0.25\n\
                 density_kg_per_m3 = 2500.0\nwork_of_adhesion_j_per_m2 = {gamma:?}\n\n"
            )
        })
        .collect();
    let text = common::column(1, count, 0.01, 0.0, "");
    let start = text.find("[[material]]").unwrap();
    let end = text.find("[contact]").unwrap();
    let text = format!("{}{block}{}", &text[..start], &text[end..]);
    text.replacen(
        "material = \"grain\"\ncount",
        &format!("material = \"{sphere}\"\ncount"),
        1,
    )
    .replace(
        "kind = \"plane\"\nmaterial = \"grain\"",
        &format!("kind = \"plane\"\nmaterial = \"{wall}\""),
    )
}

/// The adhesive law a scene runs carries the largest work of adhesion of the material pairs
/// that meet, `√(Δγ_i Δγ_j)` (docs/theory.md §9): sphere–sphere pairs only of materials with
/// spheres (a material with itself only with two spheres or more), sphere–wall pairs; a
/// material that no sphere has and no wall names adds nothing, whether listed before or after
/// the spheres'.
#[test]
fn the_adhesive_law_carries_the_largest_work_of_the_pairs_that_meet() {
    let carried = |text: &str| {
        let scene =
            parse_scene(Path::new("scene.toml"), text).unwrap_or_else(|e| panic!("{e}\n{text}"));
        assert_eq!(scene.contact.normal.law, "adhesive_mdr");
        scene.contact.normal.values[2]
    };
    // Two spheres of Δγ = 1 on a floor of 4: grain–grain 1, grain–floor 2; the unused
    // materials (16 before, 9 after) would give 4 or 8, and 3.
    let materials = [
        ("unused", 16.0),
        ("grain", 1.0),
        ("floor", 4.0),
        ("glue", 9.0),
    ];
    assert_eq!(
        carried(&adhesion_scene(&materials, "grain", 2, "floor")),
        2.0
    );
    // One sphere of Δγ = 4 on a floor of 1: only the sphere–wall pair, 2 (not 4).
    let materials = [("sticky", 4.0), ("floor", 1.0)];
    assert_eq!(
        carried(&adhesion_scene(&materials, "sticky", 1, "floor")),
        2.0
    );
    // Two such spheres: their own pair, 4.
    assert_eq!(
        carried(&adhesion_scene(&materials, "sticky", 2, "floor")),
        4.0
    );
}
