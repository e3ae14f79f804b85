//! What the scene validation works out for a scene besides its errors, held to hand-written
//! scenes: the jamming warning for an orifice narrower than four mean particle diameters, the
//! largest speed estimated when `max_speed_m_per_s` is absent, and the Hertz contact time of the
//! scene's shortest pair, each against its value worked out by hand. Parsing only: no scene is
//! run.
//! Each test fails with the mutants of the validation it is written for (docs/verification.md
//! §5 names them).

mod common;

use mdr_sim::scene::validate::parse_scene;
use mdr_sim::scene::{Problem, Scene};
use std::f64::consts::PI;

/// The column's `[run]`, gravity, material `grain` and MDR contact with `run_edit` applied to
/// the text, then `groups` and `walls`.
fn scene(run_edit: impl Fn(String) -> String, groups: &str, walls: &str) -> String {
    let text = run_edit(common::column(2, 2, 0.01, 0.0, ""));
    let head = &text[..text.find("[[particles]]").unwrap()];
    format!("{head}{groups}\n{walls}")
}

/// A group of material `material` read from `file`, with `extra` lines.
fn csv_group(material: &str, file: &str, extra: &str) -> String {
    format!(
        "[[particles]]\nmaterial = \"{material}\"\nplacement = \"csv\"\nfile = \"{file}\"\n{extra}\n"
    )
}

/// `text` parsed as `scene.toml` beside `files` (name, rows `[x, y, z, radius]` in m, written
/// as CSV) in a fresh directory; panics with the problems when it is refused.
fn taken(files: &[(&str, &[[f64; 4]])], text: &str) -> Scene {
    let dir = common::temp_dir("hints");
    for (name, spheres) in files {
        let mut csv = String::from("x_m,y_m,z_m,radius_m\n");
        for [x, y, z, r] in *spheres {
            csv.push_str(&format!("{x:?},{y:?},{z:?},{r:?}\n"));
        }
        common::write(&dir, name, &csv);
    }
    let path = common::write(&dir, "scene.toml", text);
    parse_scene(&path, text).unwrap_or_else(|e| panic!("{e}\n{text}"))
}

fn relative_error(a: f64, b: f64) -> f64 {
    ((a - b) / b).abs()
}

/// `2⁻⁹ m`: sums and means of a few multiples of it are exact in binary.
const UNIT: f64 = 1.0 / 512.0;

/// Two spheres of radii `UNIT` and `3 UNIT` (mean diameter `d = 4 UNIT = 2⁻⁷ m`, exact) above an
/// orifice plate of outer radius 5 cm with the orifice `hole` (m).
fn over_an_orifice(hole: f64) -> Scene {
    let plate = format!(
        "[[walls]]\nkind = \"orifice_plate\"\nmaterial = \"grain\"\ncenter_m = [0.0, 0.0, 0.0]\n\
         outer_radius_m = 0.05\norifice_diameter_m = {hole:?}\n"
    );
    let spheres = [[-0.01, 0.0, 0.02, UNIT], [0.01, 0.0, 0.02, 3.0 * UNIT]];
    taken(
        &[("spheres.csv", &spheres)],
        &scene(|t| t, &csv_group("grain", "spheres.csv", ""), &plate),
    )
}

fn jamming_warnings(scene: &Scene) -> Vec<&Problem> {
    scene
        .warnings
        .iter()
        .filter(|w| w.key == "walls[0].orifice_diameter_m")
        .collect()
}

/// An orifice narrower than 4 mean particle diameters is warned at its key (Zuriguel et al.
/// 2005, `JAMMING_RATIO`): the mean diameter of spheres of 2⁻⁹ and 3·2⁻⁹ m is 2⁻⁷ m, so the
/// limit is exactly 2⁻⁵ = 0.03125 m: 0.0312 m is warned (3.99 d), 0.03125 m and 0.04 m (5.12 d)
/// are not.
#[test]
fn an_orifice_below_four_mean_diameters_is_warned() {
    let s = over_an_orifice(0.0312);
    let warnings = jamming_warnings(&s);
    assert_eq!(warnings.len(), 1, "{:#?}", s.warnings);
    assert_eq!(
        warnings[0].message,
        "an orifice of 0.0312 m is 3.99 mean particle diameters (d = 7.8125e-3 m): below about 4 d \
         arches jam it and the flow stops (the hopper headline reports \"jammed\"); Beverloo's law \
         holds from about 6 d"
    );
    for hole in [0.03125, 0.04] {
        let s = over_an_orifice(hole);
        assert!(jamming_warnings(&s).is_empty(), "{hole}: {:#?}", s.warnings);
    }
}

/// Without `max_speed_m_per_s` the largest speed is twice the largest initial speed plus the
/// free-fall speed `√(2 g H)` over the spheres' extent `H` along gravity (docs/user-guide.md):
/// spheres 10 cm apart in height, one of them 30 cm aside, moving at 0.5 m/s under 9.81 m/s²
/// give `1 + √1.962` m/s; without gravity `2 · 0.5` m/s; at rest without gravity the floor of
/// 0.1 m/s.
#[test]
fn the_largest_speed_is_estimated_from_the_initial_speeds_and_the_fall() {
    let without_max_speed = |t: String| t.replace("max_speed_m_per_s = 1.0\n", "");
    let weightless = |t: String| {
        without_max_speed(t).replace(
            "acceleration_m_per_s2 = [0.0, 0.0, -9.81]",
            "acceleration_m_per_s2 = [0.0, 0.0, 0.0]",
        )
    };
    let spheres = [[0.0, 0.0, 0.01, 0.002], [0.3, 0.0, 0.11, 0.002]];
    let moving = csv_group(
        "grain",
        "spheres.csv",
        "velocity_m_per_s = [0.3, -0.4, 0.0]",
    );
    let at_rest = csv_group("grain", "spheres.csv", "");
    let files = [("spheres.csv", &spheres[..])];

    let s = taken(&files, &scene(without_max_speed, &moving, ""));
    let expected = 2.0 * 0.5 + (2.0_f64 * 9.81 * 0.1).sqrt();
    assert!(
        relative_error(s.max_speed, expected) < 1e-13,
        "{}",
        s.max_speed
    );
    assert!(
        s.warnings.iter().any(|w| w.key == "run.dt_s"
            && w.message
                .starts_with("dt_s = \"auto\" without `max_speed_m_per_s`: assuming 2.401 m/s")),
        "{:#?}",
        s.warnings
    );
    let s = taken(&files, &scene(weightless, &moving, ""));
    assert!(relative_error(s.max_speed, 1.0) < 1e-13, "{}", s.max_speed);
    let s = taken(&files, &scene(weightless, &at_rest, ""));
    assert_eq!(s.max_speed, 0.1);
    // Given, it is taken as it is.
    let s = taken(&files, &scene(|t| t, &moving, ""));
    assert_eq!(s.max_speed, 1.0);
}

/// A material `(E, ν, ρ)` (Pa, –, kg/m³).
type Material = (f64, f64, f64);
const GRAIN: Material = (5.0e7, 0.25, 2500.0);
const STEEL: Material = (2.0e11, 0.3, 7800.0);

fn mass(radius: f64, (_, _, density): Material) -> f64 {
    density * 4.0 / 3.0 * PI * radius.powi(3)
}

/// `E* = 1/((1 − ν₁²)/E₁ + (1 − ν₂²)/E₂)`.
fn effective_modulus((e1, nu1, _): Material, (e2, nu2, _): Material) -> f64 {
    1.0 / ((1.0 - nu1 * nu1) / e1 + (1.0 - nu2 * nu2) / e2)
}

/// Hertz's contact time of an elastic impact at 1 m/s, `2.868 (m²/(R E*² v))^{1/5}` (Johnson,
/// Contact Mechanics, §11.4), of the reduced mass `m` and radius `r`.
fn hertz_time(m: f64, r: f64, e_star: f64) -> f64 {
    2.868 * (m * m / (r * e_star * e_star * 1.0)).powf(0.2)
}

/// Two spheres of radii `r1`, `r2`.
fn sphere_pair(r1: f64, a: Material, r2: f64, b: Material) -> f64 {
    let (m1, m2) = (mass(r1, a), mass(r2, b));
    hertz_time(
        m1 * m2 / (m1 + m2),
        r1 * r2 / (r1 + r2),
        effective_modulus(a, b),
    )
}

/// A sphere on a fixed wall: its own mass and radius.
fn on_wall(r: f64, a: Material, wall: Material) -> f64 {
    hertz_time(mass(r, a), r, effective_modulus(a, wall))
}

const STEEL_TABLE: &str = "[[material]]\nname = \"steel\"\nyoungs_pa = 2.0e11\n\
                           poisson_ratio = 0.3\ndensity_kg_per_m3 = 7800.0\n\n[contact]";

fn floor(material: &str) -> String {
    format!(
        "[[walls]]\nkind = \"plane\"\nmaterial = \"{material}\"\npoint_m = [0.0, 0.0, 0.0]\n\
         normal = [0.0, 0.0, 1.0]\n"
    )
}

/// The time step follows the shortest Hertz contact of the scene (at `max_speed_m_per_s =
/// 1`), the smallest sphere of each material against every material and wall: grain spheres of
/// 2 and 3 mm with steel spheres of 1 and 1.5 mm on a grain floor are timed by two steel spheres
/// of 1 mm; grain spheres alone on a steel floor by the 2 mm sphere on the floor (`E*` twice the
/// grain pair's, beating the pair's halved mass and radius); the step is the contact time / 50.
#[test]
fn the_time_step_follows_the_shortest_contact() {
    let with_steel = |t: String| t.replace("[contact]", STEEL_TABLE);
    let grain = [[-0.02, 0.0, 0.01, 0.002], [0.0, 0.0, 0.01, 0.003]];
    let steel = [[0.02, 0.0, 0.01, 0.0015], [0.03, 0.0, 0.01, 0.001]];
    let groups = csv_group("grain", "grain.csv", "") + &csv_group("steel", "steel.csv", "");
    let s = taken(
        &[("grain.csv", &grain[..]), ("steel.csv", &steel[..])],
        &scene(with_steel, &groups, &floor("grain")),
    );
    let expected = sphere_pair(0.001, STEEL, 0.001, STEEL);
    let others = [
        sphere_pair(0.002, GRAIN, 0.002, GRAIN),
        sphere_pair(0.002, GRAIN, 0.001, STEEL),
        on_wall(0.002, GRAIN, GRAIN),
        on_wall(0.001, STEEL, GRAIN),
    ];
    assert!(
        others.iter().all(|&t| t > 1.2 * expected),
        "{others:?} {expected}"
    );
    assert!(
        relative_error(s.contact_time, expected) < 1e-12,
        "{} {expected}",
        s.contact_time
    );
    assert!(relative_error(s.dt, expected / 50.0) < 1e-12, "{}", s.dt);

    let s = taken(
        &[("grain.csv", &grain[..])],
        &scene(
            with_steel,
            &csv_group("grain", "grain.csv", ""),
            &floor("steel"),
        ),
    );
    let expected = on_wall(0.002, GRAIN, STEEL);
    let pair = sphere_pair(0.002, GRAIN, 0.002, GRAIN);
    assert!(pair > 1.1 * expected, "{pair} {expected}");
    assert!(
        relative_error(s.contact_time, expected) < 1e-12,
        "{} {expected}",
        s.contact_time
    );
}
