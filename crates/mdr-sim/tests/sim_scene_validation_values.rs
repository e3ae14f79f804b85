//! Reading a scene file and checking its values, on a hand-written scene whose lines are known:
//! an unreadable or empty file, the structural pass (type errors, unknown keys with their
//! "did you mean", duplicates) and the checker's common range checks (finite, `(0, inf)`,
//! `[0, inf)`, vectors, unit directions, required and unused keys, files, the periodic box), each
//! held to the exact text, line and column a user sees.

mod common;

use mdr_sim::scene::validate::{load_scene, parse_scene};
use mdr_sim::scene::{Problem, Problems, Scene, Severity};
use mdr_sim::walls::WallPiece;
use nalgebra::Vector3;
use std::path::Path;

/// The scene of these tests; line numbers below refer to it.
const SCENE: &str = r#"[run]
name = "values"
duration_s = 0.01
dt_s = 5e-6
max_speed_m_per_s = 1.0
output_interval_s = 0.005

[gravity]
acceleration_m_per_s2 = [0.0, 0.0, -9.81]

[[material]]
name = "grain"
youngs_pa = 1.0e7
poisson_ratio = 0.3
density_kg_per_m3 = 2500.0

[contact]
normal = "hertz"
tangential = "mindlin"
friction = 0.5

[[particles]]
material = "grain"
count = 2
radius_m = 0.002
placement = "lattice"
region_min_m = [0.0, 0.0, 0.0]
region_max_m = [0.1, 0.1, 0.1]
gap_fraction = 0.25
jitter_fraction = 0.0

[[walls]]
kind = "plane"
material = "grain"
point_m = [0.0, 0.0, 0.0]
normal = [0.0, 0.0, 2.0]
"#;

/// The message of the unknown key `radius_mm` in `[[particles]]`.
const RADIUS_MM_UNKNOWN: &str = "unknown field `radius_mm`, expected one of `material`, `count`, \
     `radius_m`, `size_distribution`, `radius_min_m`, `radius_max_m`, `radius_std_m`, \
     `radius_classes`, `placement`, `region_min_m`, `region_max_m`, `region_radius_m`, \
     `gap_fraction`, `jitter_fraction`, `file`, `length_scale_m`, `max_initial_overlap_fraction`, \
     `velocity_m_per_s`; did you mean `radius_m`?";

/// `SCENE` with `from` (which must occur in it) replaced by `to`.
fn with(from: &str, to: &str) -> String {
    assert!(SCENE.contains(from), "{from}");
    SCENE.replacen(from, to, 1)
}

/// `SCENE` with `lines` added to `[run]`, after line 6.
fn with_run(lines: &str) -> String {
    with(
        "output_interval_s = 0.005\n",
        &format!("output_interval_s = 0.005\n{lines}\n"),
    )
}

fn parse(text: &str) -> Result<Scene, Problems> {
    parse_scene(Path::new("dir/scene.toml"), text)
}

fn ok(text: &str) -> Scene {
    parse(text).unwrap_or_else(|e| panic!("{e}"))
}

fn refused(text: &str) -> Vec<Problem> {
    match parse(text) {
        Ok(_) => panic!("taken:\n{text}"),
        Err(p) => p.0,
    }
}

/// The one problem of `text`, an error: `(line, column, key, message)`.
fn one_error(text: &str) -> (usize, usize, String, String) {
    let problems = refused(text);
    assert_eq!(problems.len(), 1, "{}", Problems(problems.clone()));
    let p = &problems[0];
    assert_eq!(p.severity, Severity::Error, "{p}");
    assert_eq!(p.file, Path::new("dir/scene.toml"), "{p}");
    (p.line, p.column, p.key.clone(), p.message.clone())
}

fn error(line: usize, column: usize, key: &str, message: &str) -> (usize, usize, String, String) {
    (line, column, key.to_owned(), message.to_owned())
}

#[test]
fn the_hand_written_scene_is_read_with_its_values() {
    let scene = ok(SCENE);
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
    assert_eq!(scene.name, "values");
    assert_eq!(scene.duration, 0.01);
    assert_eq!(scene.output_interval, 0.005);
    // Not given: a tenth of the output interval.
    assert_eq!(scene.energy_interval, 0.0005);
    assert_eq!(scene.max_speed, 1.0);
    assert_eq!(scene.gravity, Vector3::new(0.0, 0.0, -9.81));
    assert_eq!(scene.periodic, None);
    assert_eq!(scene.discharge_height, None);
    // Two lattice sites along x from the corner `lo + r`, at the spacing `2r (1 + gap)` =
    // 5 mm, without jitter.
    let at: Vec<_> = scene.particles.iter().map(|p| p.position).collect();
    assert_eq!(at.len(), 2);
    assert_eq!(at[0], Vector3::new(0.002, 0.002, 0.002));
    assert!(
        (at[1] - Vector3::new(0.007, 0.002, 0.002)).norm() < 1e-17,
        "{at:?}"
    );
    assert!(scene.particles.iter().all(|p| p.radius == 0.002));
    // The wall's normal is made a unit vector.
    match &scene.walls[0].pieces[..] {
        [WallPiece::HalfSpace { point, normal }] => {
            assert_eq!(*normal, Vector3::new(0.0, 0.0, 1.0));
            assert_eq!(*point + scene.walls[0].origin, Vector3::zeros());
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn a_scene_file_is_loaded_from_its_path() {
    let dir = common::temp_dir("values_load");
    let path = common::write(&dir, "scene.toml", SCENE);
    let scene = load_scene(&path).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(scene.name, "values");
    assert_eq!(scene.file, path);
    // A file that cannot be read: one error naming the file, without line or key, with the
    // operating system's reason.
    let missing = dir.join("missing.toml");
    let reason = std::fs::read_to_string(&missing).unwrap_err();
    let problems = load_scene(&missing).expect_err("a missing file was taken");
    assert_eq!(
        problems.0,
        vec![Problem {
            severity: Severity::Error,
            file: missing.clone(),
            line: 0,
            column: 0,
            key: String::new(),
            message: format!("cannot read the scene file: {reason}"),
        }]
    );
}

#[test]
fn an_empty_scene_file_is_one_error_saying_what_a_scene_needs() {
    let problems = parse_scene(Path::new("empty.toml"), " \n\t\n").unwrap_err();
    assert_eq!(
        problems.to_string(),
        "the scene file has 1 error(s):\n  empty.toml: error: the scene file is empty (4 bytes): a \
         scene needs [run], [[material]], [contact] and [[particles]] (copy one of scenes/*.toml)\n"
    );
}

/// A warning alone leaves the scene to run and comes with it; with an error as well the scene is
/// refused and the error comes first.
#[test]
fn a_warning_alone_keeps_the_scene_and_comes_with_it() {
    let text = with("output_interval_s = 0.005", "output_interval_s = 0.02");
    let scene = ok(&text);
    let warning = "= 0.02 s is longer than the run (0.01 s): only the first and last frames are \
                   written";
    assert_eq!(
        scene.warnings,
        vec![Problem {
            severity: Severity::Warning,
            file: "dir/scene.toml".into(),
            line: 6,
            column: 21,
            key: "run.output_interval_s".into(),
            message: warning.into(),
        }]
    );
    let text = text.replace("radius_m = 0.002", "radius_m = -0.002");
    let problems = refused(&text);
    let seen: Vec<_> = problems
        .iter()
        .map(|p| (p.severity, p.line, p.key.as_str(), p.message.as_str()))
        .collect();
    assert_eq!(
        seen,
        vec![
            (
                Severity::Error,
                25,
                "particles[0].radius_m",
                "= -0.002 is outside the allowed range (0, inf)"
            ),
            (Severity::Warning, 6, "run.output_interval_s", warning),
        ]
    );
}

/// A value of the wrong type is one error at its value, and the scene is refused, even where the
/// key is optional (a parse that went on without it would take the scene).
#[test]
fn a_value_of_the_wrong_type_is_one_error_and_refuses_the_scene() {
    assert_eq!(
        one_error(&with_run("seed = \"five\"")),
        error(7, 8, "seed", "invalid type: string \"five\", expected u64")
    );
    assert_eq!(
        one_error(&with("duration_s = 0.01", "duration_s = \"long\"")),
        error(
            3,
            14,
            "duration_s",
            "invalid type: string \"long\", expected f64"
        )
    );
}

/// Unknown keys alone on their lines are all reported, each with the allowed names and the
/// nearest one, and the values are still checked.
#[test]
fn every_unknown_key_is_named_with_the_nearest_allowed_one_and_the_values_still_checked() {
    let text = SCENE
        .replace("duration_s = 0.01", "duration_s = -1.0")
        .replace(
            "acceleration_m_per_s2 = [0.0, 0.0, -9.81]",
            "acceleration_m_per_s2 = [0.0, 0.0, -9.81]\nacceleration_m_per_s = 1.0",
        )
        .replace("radius_m = 0.002", "radius_m = 0.002\nradius_mm = 2.0");
    let problems = refused(&text);
    let seen: Vec<_> = problems
        .iter()
        .map(|p| (p.line, p.column, p.key.as_str(), p.message.as_str()))
        .collect();
    assert_eq!(
        seen,
        vec![
            (
                3,
                14,
                "run.duration_s",
                "= -1 is outside the allowed range (0, inf)"
            ),
            (
                10,
                1,
                "acceleration_m_per_s",
                "unknown field `acceleration_m_per_s`, expected `acceleration_m_per_s2`; did you \
                 mean `acceleration_m_per_s2`?"
            ),
            (27, 1, "radius_mm", RADIUS_MM_UNKNOWN),
        ]
    );
}

/// "did you mean" names the nearest allowed name within a third of the unknown name's length
/// in edits (at least one), and nothing beyond.
#[test]
fn did_you_mean_reaches_a_third_of_the_names_length() {
    let gravity = "acceleration_m_per_s2 = [0.0, 0.0, -9.81]";
    let unknown = |name: &str| {
        let text = with(gravity, &format!("{gravity}\n{name} = 1.0"));
        let (line, column, key, message) = one_error(&text);
        assert_eq!((line, column, key.as_str()), (10, 1, name));
        message
    };
    // 16 characters, 5 edits from the name: within a third.
    assert_eq!(
        unknown("acceleration_m_p"),
        "unknown field `acceleration_m_p`, expected `acceleration_m_per_s2`; did you mean \
         `acceleration_m_per_s2`?"
    );
    // 15 characters, 6 edits: beyond a third.
    assert_eq!(
        unknown("acceleration_m_"),
        "unknown field `acceleration_m_`, expected `acceleration_m_per_s2`"
    );
    // An unknown variant, 5 characters: one edit at most.
    let (line, column, key, message) = one_error(&with_run("coupling = \"forse\""));
    assert_eq!((line, column, key.as_str()), (7, 12, "coupling"));
    assert_eq!(
        message,
        "unknown variant `forse`, expected `force` or `restitution`; did you mean `force`?"
    );
    let (_, _, _, message) = one_error(&with_run("coupling = \"farse\""));
    assert_eq!(
        message,
        "unknown variant `farse`, expected `force` or `restitution`"
    );
}

#[test]
fn a_key_or_table_given_twice_is_named_where_it_is_repeated() {
    assert_eq!(
        one_error(&with_run("duration_s = 0.02")),
        error(
            7,
            1,
            "duration_s",
            "duplicate key: `duration_s` is given a second time in the same table; keep one"
        )
    );
    assert_eq!(
        one_error(&format!(
            "{SCENE}\n[gravity]\nacceleration_m_per_s2 = [0.0, 0.0, 0.0]\n"
        )),
        error(
            38,
            2,
            "gravity",
            "duplicate table: [gravity] is defined a second time here (a table written once per \
             file; [[…]] for a list of tables)"
        )
    );
}

/// The law crate's errors on a material or the contact are placed at the scene file's key.
#[test]
fn material_and_contact_errors_are_at_the_scene_files_keys() {
    for (from, to, line, column, key, message) in [
        (
            "youngs_pa = 1.0e7",
            "youngs_pa = -1.0e7",
            13,
            13,
            "material[0].youngs_pa",
            "parameter `youngs_modulus` = -10000000 is outside the allowed range (0, inf)",
        ),
        (
            "poisson_ratio = 0.3",
            "poisson_ratio = 0.7",
            14,
            17,
            "material[0].poisson_ratio",
            "parameter `poisson_ratio` = 0.7 is outside the allowed range (-1, 0.5]",
        ),
        (
            "density_kg_per_m3 = 2500.0",
            "density_kg_per_m3 = 0.0",
            15,
            21,
            "material[0].density_kg_per_m3",
            "parameter `density` = 0 is outside the allowed range (0, inf)",
        ),
        (
            "friction = 0.5",
            "friction = -0.5",
            20,
            12,
            "contact.friction",
            "parameter `friction` = -0.5 is outside the allowed range [0, inf): μ (1, in [0, inf)): \
             Coulomb friction coefficient: |F_t| ≤ μ F_n",
        ),
    ] {
        assert_eq!(
            one_error(&with(from, to)),
            error(line, column, key, message),
            "{to}"
        );
    }
}

#[test]
fn a_value_that_is_not_finite_is_named_with_its_value() {
    for (to, message) in [
        ("duration_s = nan", "must be a finite number, got NaN"),
        ("duration_s = inf", "must be a finite number, got inf"),
        ("duration_s = -inf", "must be a finite number, got -inf"),
    ] {
        assert_eq!(
            one_error(&with("duration_s = 0.01", to)),
            error(3, 14, "run.duration_s", message)
        );
    }
    assert_eq!(
        one_error(&with("[0.0, 0.0, -9.81]", "[0.0, nan, -9.81]")),
        error(
            9,
            25,
            "gravity.acceleration_m_per_s2",
            "every component must be a finite number, got [0.0, NaN, -9.81]"
        )
    );
}

/// `(0, inf)` and `[0, inf)` at and beyond their bound, and the values taken as written.
#[test]
fn positive_and_non_negative_values_hold_at_their_bounds() {
    assert_eq!(
        one_error(&with("duration_s = 0.01", "duration_s = 0.0")),
        error(
            3,
            14,
            "run.duration_s",
            "= 0 is outside the allowed range (0, inf)"
        )
    );
    assert_eq!(
        one_error(&with("gap_fraction = 0.25", "gap_fraction = -0.25")),
        error(
            29,
            16,
            "particles[0].gap_fraction",
            "= -0.25 is outside the allowed range [0, inf)"
        )
    );
    // A gap of zero: the spheres touch, 4 mm apart.
    let scene = ok(&with("gap_fraction = 0.25", "gap_fraction = 0.0"));
    let x: Vec<_> = scene.particles.iter().map(|p| p.position.x).collect();
    assert_eq!(x, [0.002, 0.006]);
    // The smallest positive number is positive.
    let scene = ok(&with_run("checkpoint_interval_s = 5e-324"));
    assert_eq!(scene.checkpoint_interval, Some(5e-324));
}

/// A wall's direction must be non-zero; a non-unit one is scaled to length 1.
#[test]
fn a_direction_is_a_non_zero_vector_made_unit() {
    assert_eq!(
        one_error(&with(
            "normal = [0.0, 0.0, 2.0]",
            "normal = [0.0, 0.0, 0.0]"
        )),
        error(36, 10, "walls[0].normal", "must be a non-zero vector")
    );
    let scene = ok(&with(
        "normal = [0.0, 0.0, 2.0]",
        "normal = [0.0, 3.0, 4.0]",
    ));
    match &scene.walls[0].pieces[..] {
        [WallPiece::HalfSpace { normal, .. }] => {
            assert!(
                (normal - Vector3::new(0.0, 0.6, 0.8)).norm() < 1e-16,
                "{normal}"
            );
        }
        other => panic!("{other:?}"),
    }
}

/// A key the placement needs is named when missing; keys it does not use are refused.
#[test]
fn required_and_unused_keys_are_named() {
    let lines: Vec<&str> = SCENE.lines().collect();
    let without = |key: &str| {
        lines
            .iter()
            .filter(|l| !l.starts_with(key))
            .map(|l| format!("{l}\n"))
            .collect::<String>()
    };
    assert_eq!(
        one_error(&without("region_min_m")),
        error(
            22,
            1,
            "particles[0]",
            "missing key `region_min_m` (required by lattice/random placement)"
        )
    );
    assert_eq!(
        one_error(&with(
            "jitter_fraction = 0.0",
            "jitter_fraction = 0.0\nfile = \"a.csv\""
        )),
        error(
            31,
            8,
            "particles[0].file",
            "this key is not used by placement = \"lattice\" / \"random\": remove it"
        )
    );
}

/// A particle file is found next to the scene file; one that is not there is named with the
/// path that was looked for.
#[test]
fn a_particle_file_is_read_next_to_the_scene_file() {
    let dir = common::temp_dir("values_csv");
    common::write(
        &dir,
        "two.csv",
        "x_m,y_m,z_m,radius_m\n0.01,0.02,0.03,0.002\n0.02,0.02,0.03,0.003\n",
    );
    let lattice = "count = 2\nradius_m = 0.002\nplacement = \"lattice\"\n\
                   region_min_m = [0.0, 0.0, 0.0]\nregion_max_m = [0.1, 0.1, 0.1]\n\
                   gap_fraction = 0.25\njitter_fraction = 0.0";
    let csv = |name: &str| with(lattice, &format!("placement = \"csv\"\nfile = \"{name}\""));
    let path = common::write(&dir, "scene.toml", &csv("two.csv"));
    let scene = load_scene(&path).unwrap_or_else(|e| panic!("{e}"));
    let read: Vec<_> = scene
        .particles
        .iter()
        .map(|p| (p.position, p.radius))
        .collect();
    assert_eq!(
        read,
        [
            (Vector3::new(0.01, 0.02, 0.03), 0.002),
            (Vector3::new(0.02, 0.02, 0.03), 0.003)
        ]
    );
    let path = common::write(&dir, "scene.toml", &csv("three.csv"));
    let problems = load_scene(&path).unwrap_err();
    assert_eq!(
        problems.0,
        vec![Problem {
            severity: Severity::Error,
            file: path.clone(),
            line: 25,
            column: 8,
            key: "particles[0].file".into(),
            message: format!("file `{}` not found", dir.join("three.csv").display()),
        }]
    );
}

/// `periodic_x_m` and `periodic_y_m`: both or neither, each a finite `lo < hi`, on the
/// neighbour-list path only.
#[test]
fn a_periodic_box_is_two_finite_ranges_on_the_neighbour_list_path() {
    let both = "periodic_x_m = [0.0, 0.1]\nperiodic_y_m = [-0.05, 0.2]";
    let scene = ok(&with_run(both));
    assert_eq!(scene.periodic, Some([(0.0, 0.1), (-0.05, 0.2)]));
    let on_x = |range: &str| {
        with_run(&format!(
            "periodic_x_m = {range}\nperiodic_y_m = [-0.05, 0.2]"
        ))
    };
    for (range, shown) in [
        ("[0.1, 0.1]", "[0.1, 0.1]"),
        ("[0.1, 0.0]", "[0.1, 0]"),
        ("[-inf, 0.1]", "[-inf, 0.1]"),
        ("[0.0, inf]", "[0, inf]"),
        ("[nan, 0.1]", "[NaN, 0.1]"),
    ] {
        assert_eq!(
            one_error(&on_x(range)),
            error(
                7,
                16,
                "run.periodic_x_m",
                &format!("= {shown} m: needs finite lo < hi (the box's range, m)")
            ),
            "{range}"
        );
    }
    assert_eq!(
        one_error(&with_run("periodic_x_m = [0.0, 0.1]")),
        error(
            7,
            16,
            "run.periodic_x_m",
            "needs periodic_y_m too: the box is periodic in x and y together"
        )
    );
    assert_eq!(
        one_error(&with_run("periodic_y_m = [0.0, 0.1]")),
        error(
            7,
            16,
            "run.periodic_y_m",
            "needs periodic_x_m too: the box is periodic in x and y together"
        )
    );
    let path_only = "applies to the neighbour-list path only (coupling = \"force\", force_path = \
                     \"neighbour_list\")";
    let scene = ok(&with_run(&format!(
        "{both}\nforce_path = \"neighbour_list\""
    )));
    assert_eq!(scene.periodic, Some([(0.0, 0.1), (-0.05, 0.2)]));
    assert_eq!(
        one_error(&with_run(&format!("{both}\nforce_path = \"rapier\""))),
        error(7, 16, "run.periodic_x_m", path_only)
    );
    let problems = refused(&with_run(&format!("{both}\ncoupling = \"restitution\"")));
    assert!(
        problems
            .iter()
            .any(|p| p.key == "run.periodic_x_m" && p.message == path_only),
        "{}",
        Problems(problems.clone())
    );
    assert_eq!(
        one_error(&with_run(&format!("{both}\ndelete_below_m = -1.0"))),
        error(
            7,
            16,
            "run.periodic_x_m",
            "cannot be combined with delete_below_m (removed spheres are parked outside the box)"
        )
    );
}

/// A file written with CRLF line ends (as Windows editors write) is the same scene; an unknown
/// key is blanked from its line's start, so the line before it keeps its `\r\n` (a lone `\r`
/// would be a TOML error of its own).
#[test]
fn a_scene_with_crlf_line_ends_reads_the_same() {
    let crlf = SCENE.replace('\n', "\r\n");
    let scene = ok(&crlf);
    assert_eq!(scene.duration, 0.01);
    assert_eq!(scene.particles.len(), 2);
    let text = crlf.replace(
        "radius_m = 0.002\r\n",
        "radius_m = 0.002\r\nradius_mm = 2.0\r\n",
    );
    assert_eq!(
        one_error(&text),
        error(26, 1, "radius_mm", RADIUS_MM_UNKNOWN)
    );
}
