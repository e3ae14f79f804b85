//! The scene validation of `[[particles]]` held to hand-written scenes: the count's bounds per
//! group and for the whole scene, placement from a file, the lattice's sites, `jitter_fraction`'s
//! range, the region, `region_radius_m`'s cylinder, `radius_classes`, the size distributions'
//! bounds and the millimetre hint; each with the error (key and text) or the spheres it must
//! give. Parsing only: no scene is run.

mod common;

use mdr_sim::scene::validate::parse_scene;
use mdr_sim::scene::{Problem, Problems, Scene};
use std::path::Path;

/// The reference column (one material `grain`, a floor at `z = 0`) with its `[[particles]]`
/// table replaced by `particles`.
fn with_particles(particles: &str) -> String {
    let text = common::column(2, 2, 0.01, 0.0, "");
    let start = text.find("[[particles]]").unwrap();
    let end = text.find("[[walls]]").unwrap();
    format!("{}{particles}\n{}", &text[..start], &text[end..])
}

/// A lattice group of `count` spheres of radius `radius_m` in the box `lo`–`hi` (m) with the
/// gap fraction `gap` and no jitter, and `extra` lines.
fn lattice(count: u64, radius_m: f64, lo: [f64; 3], hi: [f64; 3], gap: f64, extra: &str) -> String {
    format!(
        "[[particles]]\nmaterial = \"grain\"\ncount = {count}\nradius_m = {radius_m:?}\n\
         placement = \"lattice\"\nregion_min_m = {lo:?}\nregion_max_m = {hi:?}\n\
         gap_fraction = {gap:?}\n{extra}\n"
    )
}

/// The column's own group (8 spheres of 2 mm) with `extra` lines.
fn column_group(extra: &str) -> String {
    lattice(
        8,
        0.002,
        [-0.0043, -0.0043, 0.0],
        [0.0043, 0.0043, 0.0085],
        0.05,
        extra,
    )
}

fn parse_at(path: &Path, text: &str) -> Result<Scene, Problems> {
    parse_scene(path, text)
}

fn parsed(text: &str) -> Scene {
    parse_at(Path::new("scene.toml"), text).unwrap_or_else(|e| panic!("{e}\n{text}"))
}

/// The scene's only error; panics when it is taken or has other errors.
fn the_error(text: &str) -> Problem {
    let problems = parse_at(Path::new("scene.toml"), text)
        .err()
        .unwrap_or_else(|| panic!("taken:\n{text}"));
    let errors: Vec<_> = problems.errors().cloned().collect();
    assert_eq!(errors.len(), 1, "{problems}");
    errors.into_iter().next().unwrap()
}

/// A group's `count` lies in `[1, 10⁶]` and the scene holds at most 10⁶ spheres. Counts of 10⁶
/// exactly, for a group and for the scene, pass the bound and reach the lattice, which says the
/// region is too small (an error of its own, so nothing is placed); one more is refused by the
/// bound.
#[test]
fn the_count_is_bounded_per_group_and_for_the_whole_scene() {
    let e = the_error(&with_particles(
        &column_group("").replace("count = 8", "count = 0"),
    ));
    assert_eq!(e.key, "particles[0].count");
    assert_eq!(
        e.message,
        "= 0 is outside the allowed range [1, 1000000]: a group needs particles"
    );
    let bound = |n: u64| {
        format!("= {n} is outside the allowed range [1, 1000000] (whole scene at most 1000000)")
    };
    let e = the_error(&with_particles(
        &column_group("").replace("count = 8", "count = 1000000"),
    ));
    assert_eq!(e.key, "particles[0].count");
    assert!(
        e.message
            .starts_with("the region holds only 8 lattice sites")
            && e.message.contains("for 1000000 particles"),
        "{e}"
    );
    let e = the_error(&with_particles(
        &column_group("").replace("count = 8", "count = 1000001"),
    ));
    assert_eq!(
        (e.key.as_str(), e.message),
        ("particles[0].count", bound(1_000_001))
    );
    // A second group beside the first's 8 spheres: 999 992 makes the scene's 10⁶.
    let second = |n: u64| lattice(n, 0.002, [0.01, 0.01, 0.0], [0.02, 0.02, 0.0085], 0.05, "");
    let e = the_error(&with_particles(&(column_group("") + &second(999_992))));
    assert_eq!(e.key, "particles[1].count");
    assert!(e.message.contains("for 999992 particles"), "{e}");
    let e = the_error(&with_particles(&(column_group("") + &second(999_993))));
    assert_eq!(
        (e.key.as_str(), e.message),
        ("particles[1].count", bound(999_993))
    );
    // Both groups placed.
    assert_eq!(
        parsed(&with_particles(&(column_group("") + &second(8))))
            .particles
            .len(),
        16
    );
}

/// A lattice fills its region from the corner `lo + r` at the spacing `2r(1 + gap)`, x first
/// (without jitter); random placement takes neither `gap_fraction` nor `jitter_fraction`; the
/// region's upper corner must exceed the lower one in every component.
#[test]
fn a_lattice_fills_from_the_corner_and_random_placement_takes_no_lattice_keys() {
    let (r, gap) = (0.01, 0.05);
    let spacing = 2.0 * r * (1.0 + gap);
    let scene = parsed(&with_particles(&lattice(
        4,
        r,
        [0.0, 0.0, 0.0],
        [0.1, 0.1, 0.1],
        gap,
        "",
    )));
    let got: Vec<[f64; 3]> = scene.particles.iter().map(|p| p.position.into()).collect();
    let want = [
        [r, r, r],
        [r + spacing, r, r],
        [r + 2.0 * spacing, r, r],
        [r + 3.0 * spacing, r, r],
    ];
    for (g, w) in got.iter().zip(&want) {
        for c in 0..3 {
            assert!((g[c] - w[c]).abs() <= 1e-15, "{got:?} vs {want:?}");
        }
    }
    assert_eq!(got.len(), 4);

    let random = |extra: &str| {
        with_particles(
            &lattice(4, r, [0.0, 0.0, 0.0], [0.1, 0.1, 0.1], gap, extra)
                .replace("placement = \"lattice\"", "placement = \"random\"")
                .replace(&format!("gap_fraction = {gap:?}\n"), ""),
        )
    };
    let scene = parsed(&random(""));
    assert_eq!(scene.particles.len(), 4);
    for p in &scene.particles {
        assert!(
            p.position.iter().all(|&x| (r..=0.1 - r).contains(&x)),
            "{p:?}"
        );
    }
    for key in ["gap_fraction", "jitter_fraction"] {
        let e = the_error(&random(&format!("{key} = 0.5")));
        assert_eq!(e.key, format!("particles[0].{key}"));
        assert_eq!(
            e.message,
            "this key is not used by placement = \"random\": remove it"
        );
    }

    let e = the_error(&with_particles(&lattice(
        4,
        r,
        [0.0, 0.0, 0.0],
        [0.1, 0.1, 0.0],
        gap,
        "",
    )));
    assert_eq!(e.key, "particles[0].region_max_m");
    assert!(
        e.message
            .starts_with("must exceed region_min_m in every component"),
        "{e}"
    );
}

/// `jitter_fraction` lies in `[0, 1]`, both ends included.
#[test]
fn jitter_fraction_lies_in_zero_to_one() {
    for taken in ["0.0", "1.0"] {
        parsed(&with_particles(&column_group(&format!(
            "jitter_fraction = {taken}"
        ))));
    }
    let e = the_error(&with_particles(&column_group("jitter_fraction = 1.5")));
    assert_eq!(
        (e.key.as_str(), e.message.as_str()),
        (
            "particles[0].jitter_fraction",
            "is outside the allowed range [0, 1]"
        )
    );
    let e = the_error(&with_particles(&column_group("jitter_fraction = -0.1")));
    assert_eq!(e.key, "particles[0].jitter_fraction");
    assert!(e.message.contains("[0, inf)"), "{e}");
}

/// A lattice or random group needs `count`; a group read from a file takes every sphere of it,
/// or its first `count` where `count` is given.
#[test]
fn the_count_is_required_by_a_lattice_and_limits_a_file() {
    let e = the_error(&with_particles(
        &column_group("").replace("count = 8\n", ""),
    ));
    assert_eq!(e.key, "particles[0]");
    assert_eq!(
        e.message,
        "missing key `count` (required by placement = \"lattice\" / \"random\")"
    );

    let dir = common::temp_dir("particles-csv");
    common::write(
        &dir,
        "spheres.csv",
        "x_m,y_m,z_m,radius_m\n0.0,0.0,0.01,0.002\n0.01,0.0,0.01,0.003\n0.02,0.0,0.01,0.004\n",
    );
    let group = |count: &str| {
        with_particles(&format!(
            "[[particles]]\nmaterial = \"grain\"\n{count}placement = \"csv\"\nfile = \"spheres.csv\"\n"
        ))
    };
    let read = |count: &str| {
        let text = group(count);
        let path = common::write(&dir, "scene.toml", &text);
        let scene = parse_at(&path, &text).unwrap_or_else(|e| panic!("{e}\n{text}"));
        scene
            .particles
            .iter()
            .map(|p| (p.position.x, p.radius))
            .collect::<Vec<_>>()
    };
    let all = vec![(0.0, 0.002), (0.01, 0.003), (0.02, 0.004)];
    assert_eq!(read(""), all);
    assert_eq!(read("count = 3\n"), all);
    assert_eq!(read("count = 4\n"), all);
    assert_eq!(read("count = 2\n"), all[..2]);
}

/// `region_radius_m` keeps the spheres whose centres lie within that distance of the region's
/// central line parallel to z. A 3 × 3 lattice of spheres of 1 cm at the spacing 2.1 cm in
/// `[0, 6.21 cm]²`: centres at x, y = 1, 3.1, 5.2 cm around the line at 3.105 cm; a radius of
/// 2.5 cm keeps the middle one and its four neighbours (2.1 cm away), not the corners (2.97 cm).
#[test]
fn region_radius_keeps_the_spheres_within_its_distance_of_the_central_line() {
    let group = |extra: &str| {
        with_particles(&lattice(
            9,
            0.01,
            [0.0, 0.0, 0.0],
            [0.0621, 0.0621, 0.0201],
            0.05,
            extra,
        ))
    };
    assert_eq!(parsed(&group("")).particles.len(), 9);
    let scene = parsed(&group("region_radius_m = 0.025"));
    let mut kept: Vec<(f64, f64)> = scene
        .particles
        .iter()
        .map(|p| (p.position.x, p.position.y))
        .collect();
    kept.sort_by(|a, b| a.partial_cmp(b).unwrap());
    let want = [
        (0.01, 0.031),
        (0.031, 0.01),
        (0.031, 0.031),
        (0.031, 0.052),
        (0.052, 0.031),
    ];
    assert_eq!(kept.len(), want.len(), "{kept:?}");
    for (g, w) in kept.iter().zip(&want) {
        assert!(
            (g.0 - w.0).abs() < 1e-12 && (g.1 - w.1).abs() < 1e-12,
            "{kept:?}"
        );
    }
    // The middle sphere is 7.1·10⁻⁵ m off the line.
    assert_eq!(
        parsed(&group("region_radius_m = 0.0001")).particles.len(),
        1
    );
    let e = the_error(&group("region_radius_m = 0.00005"));
    assert_eq!(
        (e.key.as_str(), e.message.as_str()),
        (
            "particles[0].region_radius_m",
            "= 0.00005 m leaves no sphere of the group in the region"
        )
    );
    let e = the_error(&group("region_radius_m = -0.01"));
    assert_eq!(e.key, "particles[0].region_radius_m");
    assert!(e.message.contains("(0, inf)"), "{e}");
}

/// A uniform or normal size distribution of `count` spheres between `lo` and `hi` (m), mean
/// `mean` and deviation `std` for the normal one, with `extra` lines.
fn distributed(kind: &str, mean: f64, std: f64, lo: f64, hi: f64, extra: &str) -> String {
    let normal = if kind == "normal" {
        format!("radius_m = {mean:?}\nradius_std_m = {std:?}\n")
    } else {
        String::new()
    };
    with_particles(&format!(
        "[[particles]]\nmaterial = \"grain\"\ncount = 8\nsize_distribution = \"{kind}\"\n{normal}\
         radius_min_m = {lo:?}\nradius_max_m = {hi:?}\nplacement = \"lattice\"\n\
         region_min_m = [0.0, 0.0, 0.0]\nregion_max_m = [0.1, 0.1, 0.1]\n{extra}\n"
    ))
}

/// `radius_classes = n` rounds each radius down to one of `n` classes of width
/// `(r_max − r_min)/n` from `r_min`; `n` in `[2, 255]`, only with a uniform or normal size
/// distribution whose bounds differ.
#[test]
fn radius_classes_round_down_to_n_classes() {
    let (lo, hi) = (0.001, 0.002);
    for n in [2_u32, 4, 255] {
        let scene = parsed(&distributed(
            "uniform",
            0.0,
            0.0,
            lo,
            hi,
            &format!("radius_classes = {n}"),
        ));
        let width = (hi - lo) / f64::from(n);
        for p in &scene.particles {
            let k = ((p.radius - lo) / width).round();
            assert!(
                (p.radius - (lo + k * width)).abs() < 1e-15 && (0.0..f64::from(n)).contains(&k),
                "n = {n}: {}",
                p.radius
            );
        }
        let distinct = scene
            .particles
            .windows(2)
            .filter(|w| w[0].radius != w[1].radius)
            .count();
        assert!(distinct > 0, "n = {n}: one class only");
    }
    for n in [1, 256] {
        let e = the_error(&distributed(
            "uniform",
            0.0,
            0.0,
            lo,
            hi,
            &format!("radius_classes = {n}"),
        ));
        assert_eq!(
            (e.key.as_str(), e.message),
            (
                "particles[0].radius_classes",
                format!("= {n} is outside the allowed range [2, 255]")
            )
        );
    }
    // One radius has no classes: refused, not a group dropped without a word.
    let e = the_error(&distributed(
        "uniform",
        0.0,
        0.0,
        0.0015,
        0.0015,
        "radius_classes = 4",
    ));
    assert_eq!(
        (e.key.as_str(), e.message.as_str()),
        (
            "particles[0].radius_classes",
            "= 4 needs radius_max_m > radius_min_m (both are 0.0015 m: one radius): remove it"
        )
    );
    // Inverted bounds are radius_law's one error, at radius_max_m.
    let e = the_error(&distributed(
        "uniform",
        0.0,
        0.0,
        0.002,
        0.001,
        "radius_classes = 4",
    ));
    assert_eq!(e.key, "particles[0].radius_max_m");
    let e = the_error(&with_particles(&column_group("radius_classes = 4")));
    assert_eq!(
        (e.key.as_str(), e.message.as_str()),
        (
            "particles[0].radius_classes",
            "is used only with size_distribution = \"uniform\" or \"normal\": remove it"
        )
    );
}

/// A uniform distribution needs `radius_min_m ≤ radius_max_m` (equal: one radius); a normal one
/// its mean in `[radius_min_m, radius_max_m]`, both ends included.
#[test]
fn size_distributions_hold_their_bounds() {
    let radii =
        |text: &str| -> Vec<f64> { parsed(text).particles.iter().map(|p| p.radius).collect() };
    assert!(radii(&distributed("uniform", 0.0, 0.0, 0.0015, 0.0015, ""))
        .iter()
        .all(|&r| r == 0.0015));
    let e = the_error(&distributed("uniform", 0.0, 0.0, 0.002, 0.001, ""));
    assert_eq!(
        (e.key.as_str(), e.message.as_str()),
        (
            "particles[0].radius_max_m",
            "= 0.001 must be ≥ radius_min_m = 0.002"
        )
    );
    for mean in [0.001, 0.0015, 0.002] {
        let r = radii(&distributed("normal", mean, 0.0003, 0.001, 0.002, ""));
        assert!(
            r.iter().all(|r| (0.001..=0.002).contains(r)),
            "{mean}: {r:?}"
        );
    }
    for mean in [0.0009, 0.0021] {
        let e = the_error(&distributed("normal", mean, 0.0003, 0.001, 0.002, ""));
        assert_eq!(
            (e.key.as_str(), e.message),
            (
                "particles[0].radius_m",
                format!("= {mean} must lie in [radius_min_m, radius_max_m] = [0.001, 0.002]")
            )
        );
    }
}

/// A radius of a metre or more is warned about at its key (most often millimetres written in
/// metres); below a metre nothing is said.
#[test]
fn spheres_of_a_metre_or_more_are_warned_about() {
    let big = |radius: f64| {
        parsed(&with_particles(&lattice(
            1,
            radius,
            [0.0, 0.0, 0.0],
            [3.0, 3.0, 3.0],
            0.05,
            "",
        )))
        .warnings
    };
    let warnings = big(1.0);
    let hint: Vec<_> = warnings
        .iter()
        .filter(|w| w.key == "particles[0].radius_m")
        .collect();
    assert_eq!(hint.len(), 1, "{warnings:?}");
    assert!(
        hint[0]
            .message
            .starts_with("= 1 m: spheres of a metre or more?")
            && hint[0].message.ends_with("write 1e-3"),
        "{}",
        hint[0].message
    );
    for radius in [0.999, 0.002] {
        let warnings = big(radius);
        assert!(
            warnings
                .iter()
                .all(|w| !w.message.contains("a metre or more")),
            "{radius}: {warnings:?}"
        );
    }
}

/// Every error of the scene as `(key, message)`, in the order reported.
fn the_errors(path: &Path, text: &str) -> Vec<(String, String)> {
    let problems = parse_at(path, text)
        .err()
        .unwrap_or_else(|| panic!("taken:\n{text}"));
    problems
        .errors()
        .map(|e| (e.key.clone(), e.message.clone()))
        .collect()
}

/// A group read from a file without `count` takes every sphere of it only where the scene has
/// room for them: the scene's 10⁶ counts the groups before it. After a lattice of 999 999
/// spheres (100³ sites of spheres of 1 mm at the spacing 2.1 mm in 21 cm, filled but one) a
/// file of one sphere is taken, one of two refused at its `file`, and one of two with
/// `count = 1` cut to its first. The run's negative `duration_s` is an error of its own, which
/// keeps the overlap check of 10⁶ spheres (run only on a scene without errors) out of the test.
/// A file group that took every sphere up to 10⁶ whatever the groups before it held makes the
/// two-sphere file a scene of 1 000 001; `len > limit` → `>=` refuses the one-sphere file.
#[test]
fn a_file_without_count_takes_what_the_scene_has_room_for() {
    let dir = common::temp_dir("particles-room");
    common::write(&dir, "one.csv", "x_m,y_m,z_m,radius_m\n0.5,0.5,0.5,0.001\n");
    common::write(
        &dir,
        "two.csv",
        "x_m,y_m,z_m,radius_m\n0.5,0.5,0.5,0.001\n0.6,0.5,0.5,0.001\n",
    );
    let full = lattice(
        999_999,
        0.001,
        [0.0, 0.0, 0.0],
        [0.21, 0.21, 0.21],
        0.05,
        "",
    );
    let errors = |file: &str, count: &str| {
        let text = with_particles(&format!(
            "{full}[[particles]]\nmaterial = \"grain\"\n{count}placement = \"csv\"\nfile = \"{file}\"\n"
        ))
        .replace("duration_s = 0.01", "duration_s = -0.01");
        let path = common::write(&dir, "scene.toml", &text);
        the_errors(&path, &text)
    };
    let duration = || {
        (
            "run.duration_s".to_owned(),
            "= -0.01 is outside the allowed range (0, inf)".to_owned(),
        )
    };
    assert_eq!(errors("one.csv", ""), [duration()]);
    assert_eq!(
        errors("two.csv", ""),
        [
            duration(),
            (
                "particles[1].file".to_owned(),
                "the file holds 2 particles, more than the allowed 1 (whole scene at most 1000000)"
                    .to_owned()
            )
        ]
    );
    assert_eq!(errors("two.csv", "count = 1\n"), [duration()]);
}

/// `radius_classes` leaves equal bounds that are not a radius (zero, infinite) to the size
/// distribution's own errors at `radius_min_m` and `radius_max_m`: no third error at
/// `radius_classes` (`lo > 0` → `lo >= 0` gives one at zero).
#[test]
fn radius_classes_leave_equal_bounds_that_are_no_radius_to_the_distribution() {
    for (bound, message) in [
        (0.0, "= 0 is outside the allowed range (0, inf)"),
        (f64::INFINITY, "must be a finite number, got inf"),
    ] {
        let text = distributed("uniform", 0.0, 0.0, bound, bound, "radius_classes = 4");
        let errors = the_errors(Path::new("scene.toml"), &text);
        let want: Vec<(String, String)> = ["radius_min_m", "radius_max_m"]
            .iter()
            .map(|k| (format!("particles[0].{k}"), message.to_owned()))
            .collect();
        assert_eq!(errors, want, "{bound}");
    }
}
