//! The scene validation of `[run]` and of what the scene builder checks across sections, held
//! to hand-written scenes: the run's name, `duration_s`'s upper bound, the output interval
//! against the run, the energy interval's default, `steps_per_contact`'s lower bound,
//! restitution coupling's law and what it ignores, `neighbour_skin_m`, `discharge_height_m`
//! against the headline and `delete_below_m`, `orifice_sweep_m`, the materials' names,
//! `exact_surface` against the path, `max_initial_overlap_fraction`'s range and a radius on a
//! class boundary; each with the error, warning (key and text) or radius it must give. Parsing
//! only: no scene is run.

mod common;

use mdr_sim::scene::validate::parse_scene;
use mdr_sim::scene::{Problem, Severity};
use std::path::Path;

/// The reference column (one material `grain`, 8 spheres of 2 mm on a floor at `z = 0`,
/// Mindlin friction 0.3, `duration_s = 0.01`, `output_interval_s = 0.005`,
/// `energy_interval_s = 0.0005`) with `extra_run` appended to `[run]`.
fn column(extra_run: &str) -> String {
    common::column(2, 2, 0.01, 0.3, extra_run)
}

/// `(key, message)` of an expected error.
fn err(key: &str, message: &str) -> (String, String) {
    (key.to_owned(), message.to_owned())
}

const NONE: [String; 0] = [];

/// Every problem of the scene, errors and warnings.
fn problems(text: &str) -> Vec<Problem> {
    match parse_scene(Path::new("scene.toml"), text) {
        Ok(scene) => scene.warnings,
        Err(p) => p.0,
    }
}

/// The messages of the problems of `severity` at `key`.
fn at(text: &str, severity: Severity, key: &str) -> Vec<String> {
    problems(text)
        .into_iter()
        .filter(|p| p.severity == severity && p.key == key)
        .map(|p| p.message)
        .collect()
}

fn errors_at(text: &str, key: &str) -> Vec<String> {
    at(text, Severity::Error, key)
}

fn warnings_at(text: &str, key: &str) -> Vec<String> {
    at(text, Severity::Warning, key)
}

/// The scene's errors as `(key, message)`.
fn errors(text: &str) -> Vec<(String, String)> {
    problems(text)
        .into_iter()
        .filter(|p| p.severity == Severity::Error)
        .map(|p| (p.key, p.message))
        .collect()
}

/// `[run] name` names the output files: empty or blank, with `/` or `\`, or with a control
/// character it is refused at its key.
#[test]
fn the_run_name_must_be_a_file_name() {
    let named = |name: &str| column("").replace("name = \"column\"", &format!("name = {name}"));
    let refused = "must be a non-empty file-name-safe string (no `/`)";
    for name in [r#""""#, r#""  ""#, r#""a/b""#, r#""a\\b""#, r#""a\u0007b""#] {
        assert_eq!(errors(&named(name)), [err("run.name", refused)], "{name}");
    }
    assert!(errors(&named(r#""column 2.b""#)).is_empty());
}

/// `duration_s` lies in `(0, 1e9]` s: at 10⁹ s the bound holds and the run's step count
/// (10⁹ s over a step of microseconds, above 10¹⁰ steps) is the error; above it the bound.
#[test]
fn the_duration_is_at_most_a_billion_seconds() {
    let lasting = |d: &str| column("").replace("duration_s = 0.01", &format!("duration_s = {d}"));
    let at_bound = errors_at(&lasting("1.0e9"), "run.duration_s");
    assert_eq!(at_bound.len(), 1, "{at_bound:?}");
    assert!(
        at_bound[0].starts_with("the run would take") && at_bound[0].contains("steps"),
        "{at_bound:?}"
    );
    assert_eq!(
        errors(&lasting("1.5e9")),
        [err(
            "run.duration_s",
            "is outside the allowed range (0, 1e9] s"
        )]
    );
}

/// An output interval longer than the run is a warning (only the first and last frames); one
/// as long as the run or shorter is not.
#[test]
fn an_output_interval_longer_than_the_run_is_warned_about() {
    let every = |o: &str| {
        column("").replace(
            "output_interval_s = 0.005",
            &format!("output_interval_s = {o}"),
        )
    };
    for o in ["0.005", "0.01"] {
        assert_eq!(warnings_at(&every(o), "run.output_interval_s"), NONE, "{o}");
    }
    assert_eq!(
        warnings_at(&every("0.02"), "run.output_interval_s"),
        ["= 0.02 s is longer than the run (0.01 s): only the first and last frames are written"]
    );
}

/// Without `energy_interval_s` the energy books take a row every tenth of the output interval
/// (docs/user-guide.md, the `[run]` table); given, it is taken as it is.
#[test]
fn the_energy_interval_defaults_to_a_tenth_of_the_output_interval() {
    let text = column("");
    let default = text.replace("energy_interval_s = 0.0005\n", "");
    let scene = parse_scene(Path::new("scene.toml"), &default).unwrap();
    assert!(
        (scene.energy_interval - 5e-4).abs() < 1e-18,
        "{}",
        scene.energy_interval
    );
    let given = text.replace("energy_interval_s = 0.0005", "energy_interval_s = 0.002");
    let scene = parse_scene(Path::new("scene.toml"), &given).unwrap();
    assert_eq!(scene.energy_interval, 0.002);
}

/// `steps_per_contact` lies in `[5, inf)`: 5 is taken, 4.99 refused at its key.
#[test]
fn steps_per_contact_is_at_least_five() {
    let steps = |s: &str| {
        column("").replace(
            "steps_per_contact = 50",
            &format!("steps_per_contact = {s}"),
        )
    };
    assert_eq!(errors_at(&steps("5.0"), "run.steps_per_contact"), NONE);
    assert_eq!(
        errors_at(&steps("4.99"), "run.steps_per_contact"),
        ["is outside the allowed range [5, inf)"]
    );
}

/// The column with `[contact]`'s normal law block `normal` in place of its MDR block.
fn with_normal(text: &str, normal: &str) -> String {
    text.replace(
        "normal = \"mdr\"\ncritical_line_load_n_per_m = 100.0\nhardening_ratio = 0.37",
        normal,
    )
}

/// Restitution coupling takes its restitution from the MDR energy route: `normal = "hertz"` is
/// refused at `contact.normal` there, and taken with force coupling.
#[test]
fn restitution_coupling_needs_the_mdr_law() {
    let law = "restitution coupling needs normal = \"mdr\" or \"adhesive_mdr\" (its restitution \
               comes from the MDR energy route)";
    let restitution = column("coupling = \"restitution\"");
    assert_eq!(errors_at(&restitution, "contact.normal"), NONE);
    assert_eq!(
        errors_at(
            &with_normal(&restitution, "normal = \"hertz\""),
            "contact.normal"
        ),
        [law]
    );
    assert!(errors(&with_normal(&column(""), "normal = \"hertz\"")).is_empty());
}

/// Restitution coupling ignores damping and rolling resistance: a damping law other than
/// `"none"` or a rolling friction above 0 is a warning at `contact`; `damping = "none"` and
/// `rolling_friction = 0` are not, nor either with force coupling.
#[test]
fn restitution_coupling_warns_about_what_it_ignores() {
    let warning = "restitution coupling ignores damping and rolling resistance (only e_n(v) and \
                   μ enter the impulses)";
    let contact = |coupling: &str, extra: &str| {
        column(coupling).replace(
            "hardening_ratio = 0.37",
            &format!("hardening_ratio = 0.37\n{extra}"),
        )
    };
    let restitution = "coupling = \"restitution\"";
    for (extra, warned) in [
        ("", false),
        ("damping = \"none\"", false),
        ("rolling_friction = 0.0", false),
        ("damping = \"stiffness_viscous\"\ndamping_eta = 0.3", true),
        ("rolling_friction = 0.1", true),
    ] {
        let text = contact(restitution, extra);
        assert!(errors(&text).is_empty(), "{extra}: {:?}", errors(&text));
        let want: &[&str] = if warned { &[warning] } else { &[] };
        assert_eq!(warnings_at(&text, "contact"), want, "{extra}");
        let force = contact("", extra);
        assert_eq!(warnings_at(&force, "contact"), NONE, "{extra}");
    }
}

/// `neighbour_skin_m` lies in `(0, inf)` m (zero and infinity refused) and applies to the
/// neighbour-list path only (refused with restitution coupling).
#[test]
fn the_neighbour_skin_is_positive_and_finite_on_the_neighbour_list_path() {
    for (skin, shown) in [("0.0", "0"), ("inf", "inf")] {
        assert_eq!(
            errors(&column(&format!("neighbour_skin_m = {skin}"))),
            [err(
                "run.neighbour_skin_m",
                &format!("= {shown} m is outside the allowed range (0, inf) m")
            )],
            "{skin}"
        );
    }
    assert_eq!(
        errors_at(
            &column("coupling = \"restitution\"\nneighbour_skin_m = 0.001"),
            "run.neighbour_skin_m"
        ),
        ["applies to the neighbour-list path only (coupling = \"force\", force_path = \"neighbour_list\")"]
    );
}

/// `discharge_height_m` is used only by the hopper and funnel headlines, and must not lie below
/// `delete_below_m` (a sphere would be removed before it counts as discharged); equal is taken.
#[test]
fn the_discharge_height_needs_a_hopper_or_funnel_and_lies_above_the_deletion() {
    assert_eq!(
        errors(&column("discharge_height_m = -0.01")),
        [err(
            "run.discharge_height_m",
            "is used only with headline = \"hopper\" or \"funnel\""
        )]
    );
    let funnel =
        |extra: &str| column(extra).replace("headline = \"column\"", "headline = \"funnel\"");
    assert!(errors(&funnel("discharge_height_m = -0.01")).is_empty());
    for d in ["-0.1", "0.0"] {
        let text = funnel(&format!("discharge_height_m = {d}\ndelete_below_m = -0.1"));
        assert!(errors(&text).is_empty(), "{d}: {:?}", errors(&text));
    }
    assert_eq!(
        errors(&funnel("discharge_height_m = -0.2\ndelete_below_m = -0.1")),
        [err(
            "run.discharge_height_m",
            "= -0.2 m is below delete_below_m = -0.1 m: a sphere is removed before it counts as \
             discharged"
        )]
    );
}

/// The column as a hopper with `orifice_sweep_m = sweep` and `plates` orifice plates below its
/// floor (2 cm apart, far from every sphere).
fn hopper(sweep: &str, plates: usize) -> String {
    let mut text = column(&format!("orifice_sweep_m = {sweep}"))
        .replace("headline = \"column\"", "headline = \"hopper\"");
    for k in 1..=plates {
        text += &format!(
            "\n[[walls]]\nkind = \"orifice_plate\"\nmaterial = \"grain\"\n\
             center_m = [0.0, 0.0, {:?}]\nouter_radius_m = 0.06\norifice_diameter_m = 0.024\n\
             thickness_m = 0.003\nsegments = 64\n",
            -0.02 * k as f64
        );
    }
    text
}

/// `orifice_sweep_m`: only with the hopper headline; at least 3 diameters, each in `(0, inf)`
/// m, increasing strictly, with exactly one orifice plate to sweep.
#[test]
fn an_orifice_sweep_needs_three_increasing_diameters_and_one_plate() {
    let key = "run.orifice_sweep_m";
    assert_eq!(
        errors(&column("orifice_sweep_m = [0.024, 0.032, 0.040]")),
        [err(key, "is used only with headline = \"hopper\"")]
    );
    let taken = hopper("[0.024, 0.032, 0.040]", 1);
    assert!(errors(&taken).is_empty(), "{:?}", errors(&taken));
    for (sweep, message) in [
        (
            "[0.024, 0.032]",
            "has 2 diameter(s): at least 3 are needed to fit Beverloo's C and k",
        ),
        (
            "[0.024, 0.0, 0.040]",
            "= [0.024, 0.0, 0.04]: every diameter must be in (0, inf) m",
        ),
        (
            "[0.024, inf, 0.040]",
            "= [0.024, inf, 0.04]: every diameter must be in (0, inf) m",
        ),
        (
            "[0.024, 0.040, 0.032]",
            "= [0.024, 0.04, 0.032]: the diameters must increase",
        ),
        (
            "[0.024, 0.024, 0.040]",
            "= [0.024, 0.024, 0.04]: the diameters must increase",
        ),
    ] {
        assert_eq!(errors(&hopper(sweep, 1)), [err(key, message)], "{sweep}");
    }
    for plates in [0, 2] {
        assert_eq!(
            errors(&hopper("[0.024, 0.032, 0.040]", plates)),
            [err(
                key,
                "needs exactly one wall of kind orifice_plate (its diameter is swept)"
            )],
            "{plates} plates"
        );
    }
}

/// A second `[[material]]` named `name`, inserted after the first.
fn second_material(text: &str, name: &str) -> String {
    text.replace(
        "[contact]",
        &format!(
            "[[material]]\nname = \"{name}\"\nyoungs_pa = 5.0e7\npoisson_ratio = 0.25\n\
             density_kg_per_m3 = 2500.0\n\n[contact]"
        ),
    )
}

/// Material names are unique; a sphere group or wall naming no material is refused at its
/// `material` (listing the defined ones), except where a material is itself refused (its
/// error says why, and the names it would have defined are unknown).
#[test]
fn materials_are_named_once_and_named_materials_must_exist() {
    assert_eq!(
        errors(&second_material(&column(""), "grain")),
        [err("material[1].name", "material `grain` is defined twice")]
    );
    let two = second_material(&column(""), "glass");
    assert!(errors(&two).is_empty(), "{:?}", errors(&two));
    let sand = column("").replacen("material = \"grain\"", "material = \"sand\"", 1);
    assert_eq!(
        errors(&sand),
        [err(
            "particles[0].material",
            "unknown material `sand` (defined: grain)"
        )]
    );
    let keys: Vec<String> =
        errors(&column("").replace("poisson_ratio = 0.25", "poisson_ratio = 0.7"))
            .into_iter()
            .map(|(k, _)| k)
            .collect();
    assert_eq!(keys, ["material[0].poisson_ratio"]);
}

/// `exact_surface = true` applies to the neighbour-list path only: refused at the wall's key
/// with `force_path = "rapier"` or restitution coupling, taken on the neighbour-list path;
/// `exact_surface = false` is taken on every path.
#[test]
fn an_exact_surface_needs_the_neighbour_list_path() {
    let plate = |run: &str, exact: bool| {
        column(run)
            + &format!(
                "\n[[walls]]\nkind = \"orifice_plate\"\nmaterial = \"grain\"\n\
                 center_m = [0.0, 0.0, -0.02]\nouter_radius_m = 0.06\norifice_diameter_m = 0.024\n\
                 thickness_m = 0.003\nsegments = 64\nexact_surface = {exact}\n"
            )
    };
    let refused = "applies to the neighbour-list path only (coupling = \"force\", force_path = \
                   \"neighbour_list\"): remove it or set it to false";
    for path in ["", "force_path = \"neighbour_list\""] {
        let text = plate(path, true);
        assert!(errors(&text).is_empty(), "{path}: {:?}", errors(&text));
    }
    for path in ["force_path = \"rapier\"", "coupling = \"restitution\""] {
        assert_eq!(
            errors(&plate(path, true)),
            [err("walls[1].exact_surface", refused)],
            "{path}"
        );
        let text = plate(path, false);
        assert!(errors(&text).is_empty(), "{path}: {:?}", errors(&text));
    }
}

/// `max_initial_overlap_fraction` lies in `[0, 0.5]`, both ends included.
#[test]
fn the_initial_overlap_allowance_lies_in_zero_to_a_half() {
    let allowed = |f: &str| {
        column("").replace(
            "placement = \"lattice\"",
            &format!("placement = \"lattice\"\nmax_initial_overlap_fraction = {f}"),
        )
    };
    for f in ["0.0", "0.5"] {
        assert!(
            errors(&allowed(f)).is_empty(),
            "{f}: {:?}",
            errors(&allowed(f))
        );
    }
    for (f, shown) in [("0.6", "0.6"), ("-0.1", "-0.1")] {
        assert_eq!(
            errors(&allowed(f)),
            [err(
                "particles[0].max_initial_overlap_fraction",
                &format!("= {shown} is outside the allowed range [0, 0.5]")
            )],
            "{f}"
        );
    }
}

/// A radius on a class boundary keeps its class (`radius_classes` rounds down with a margin of
/// 10⁻⁹ class widths against the quotient's round-off): a normal distribution of deviation
/// 10⁻¹⁵ m around 1.5 mm, the boundary between the two classes of [1, 2] mm, gives every
/// sphere 1.5 mm, not the lower class's 1 mm.
#[test]
fn a_radius_on_a_class_boundary_keeps_its_class() {
    let text = column("").replace(
        "radius_m = 0.002\n",
        "size_distribution = \"normal\"\nradius_m = 0.0015\nradius_std_m = 1e-15\n\
         radius_min_m = 0.001\nradius_max_m = 0.002\nradius_classes = 2\n",
    );
    let scene = parse_scene(Path::new("scene.toml"), &text).unwrap_or_else(|e| panic!("{e}"));
    assert!(!scene.particles.is_empty());
    for p in &scene.particles {
        assert!((p.radius - 0.0015).abs() < 1e-15, "{}", p.radius);
    }
}
