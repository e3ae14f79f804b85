//! The scene features of the funnel and the hopper sweep, on small scenes: the cone wall, the plug
//! removed at a given time, spheres removed below a height, the funnel's discharge curve, the
//! orifice sweep with its Beverloo fit, and the validation of their keys (file, line, key).

mod common;

use mdr_sim::scene::validate::parse_scene;
use mdr_sim::scene::Problems;
use mdr_sim::{run_scene, RunOptions};
use std::path::Path;

/// A small funnel: a cone (radius 2 cm at z = 2 cm to 4 cm at z = 6 cm) over a spout (radius
/// 1 cm, z = 0..2 cm) plugged at z = 0 until `open_at`; `count` spheres of radius 2 mm fall in
/// from rest; spheres below z = −3 cm are removed.
fn funnel(count: usize, duration: f64, open_at: f64) -> String {
    format!(
        r#"
[run]
name = "funnel"
seed = 3
duration_s = {duration}
dt_s = "auto"
max_speed_m_per_s = 1.5
output_interval_s = 0.01
headline = "funnel"
discharge_height_m = 0.0
delete_below_m = -0.03

[gravity]
acceleration_m_per_s2 = [0.0, 0.0, -9.81]

[[material]]
name = "grain"
youngs_pa = 1.0e7
poisson_ratio = 0.25
density_kg_per_m3 = 2500.0

[contact]
normal = "hertz"
tangential = "mindlin"
friction = 0.3
damping = "stiffness_viscous"
damping_eta = 0.3

[[particles]]
material = "grain"
count = {count}
radius_m = 0.002
placement = "lattice"
region_min_m = [-0.012, -0.012, 0.035]
region_max_m = [0.012, 0.012, 0.09]
gap_fraction = 0.1

[[walls]]
kind = "cone"
material = "grain"
center_m = [0.0, 0.0, 0.02]
radius_m = 0.01
top_radius_m = 0.04
length_m = 0.08
segments = 32
thickness_m = 0.004

[[walls]]
kind = "cylinder"
material = "grain"
center_m = [0.0, 0.0, 0.01]
radius_m = 0.01
length_m = 0.02
segments = 32
thickness_m = 0.004

[[walls]]
kind = "plane"
material = "grain"
point_m = [0.0, 0.0, 0.0]
normal = [0.0, 0.0, 1.0]
removed_at_s = {open_at}
"#
    )
}

fn problems(text: &str) -> Problems {
    match parse_scene(Path::new("scene.toml"), text) {
        Ok(scene) => Problems(scene.warnings),
        Err(p) => p,
    }
}

fn line_of(text: &str, needle: &str) -> usize {
    text.lines()
        .position(|l| l.contains(needle))
        .expect("needle")
        + 1
}

/// The error on `key`, checked to be on the line holding `needle`.
fn refused(text: &str, key: &str, needle: &str) -> String {
    let p = problems(text);
    let e = p
        .errors()
        .find(|e| e.key.ends_with(key))
        .cloned()
        .unwrap_or_else(|| panic!("no error on `{key}`; got:\n{p}"));
    assert_eq!(e.line, line_of(text, needle), "{e}");
    assert!(e.to_string().starts_with("scene.toml:"), "{e}");
    e.message
}

#[test]
fn the_small_funnel_is_valid() {
    let p = problems(&funnel(40, 0.2, 0.1));
    assert!(!p.has_errors() && p.0.is_empty(), "{p}");
}

#[test]
fn bad_funnel_and_sweep_keys_are_refused_with_file_line_and_key() {
    let good = funnel(40, 0.2, 0.1);
    let m = refused(
        &good.replace("removed_at_s = 0.1", "removed_at_s = -1.0"),
        "removed_at_s",
        "removed_at_s = -1.0",
    );
    assert!(m.contains("[0, inf)"), "{m}");
    let m = refused(
        &good.replace("delete_below_m = -0.03", "delete_below_m = nan"),
        "delete_below_m",
        "delete_below_m = nan",
    );
    assert!(m.contains("finite"), "{m}");
    let m = refused(
        &good.replace("delete_below_m = -0.03", "delete_below_m = 0.01"),
        "discharge_height_m",
        "discharge_height_m = 0.0",
    );
    assert!(m.contains("below delete_below_m"), "{m}");
    let m = refused(
        &good.replace("top_radius_m = 0.04", "top_radius_m = 0.0"),
        "top_radius_m",
        "top_radius_m = 0.0",
    );
    assert!(m.contains("(0, inf)"), "{m}");
    // top_radius_m on a cylinder is not a key of that kind.
    let text = good.replace("length_m = 0.02", "length_m = 0.02\ntop_radius_m = 0.02");
    let m = refused(&text, "top_radius_m", "top_radius_m = 0.02");
    assert!(m.contains("not used"), "{m}");
    // A hopper sweep with too few diameters, and on a scene that is not a hopper.
    let text = good.replace(
        "headline = \"funnel\"",
        "headline = \"funnel\"\norifice_sweep_m = [0.01, 0.02]",
    );
    let m = refused(&text, "orifice_sweep_m", "orifice_sweep_m");
    assert!(m.contains("hopper"), "{m}");
    let text = common::column(2, 2, 0.01, 0.3, "").replace(
        "headline = \"column\"",
        "headline = \"hopper\"\norifice_sweep_m = [0.01, 0.02]",
    );
    let m = refused(&text, "orifice_sweep_m", "orifice_sweep_m");
    assert!(m.contains("at least 3"), "{m}");
    let text = text.replace("[0.01, 0.02]", "[0.01, 0.03, 0.02]");
    let m = refused(&text, "orifice_sweep_m", "orifice_sweep_m");
    assert!(m.contains("increase"), "{m}");
    // Radius classes: only with a size distribution, within [2, 255].
    let text = good.replace(
        "radius_m = 0.002\n",
        "radius_m = 0.002\nradius_classes = 8\n",
    );
    let m = refused(&text, "radius_classes", "radius_classes = 8");
    assert!(m.contains("uniform"), "{m}");
    let text = good.replace(
        "radius_m = 0.002\n",
        "size_distribution = \"uniform\"\nradius_min_m = 0.0015\nradius_max_m = 0.002\nradius_classes = 1\n",
    );
    let m = refused(&text, "radius_classes", "radius_classes = 1");
    assert!(m.contains("[2, 255]"), "{m}");
}

/// `exact_surface = true` on the cone and the spout: the spheres touch the smooth surfaces of
/// revolution on the neighbour-list path; they are held until the plug opens (none leaks through
/// a wall: a sphere that did would fall below the sink before the opening) and then drain
/// completely. The key is refused on walls that are not surfaces of revolution (a plane) and off
/// the neighbour-list path.
#[test]
fn exact_cone_and_spout_hold_the_spheres_and_let_them_drain() {
    let exact =
        |text: String| text.replace("segments = 32\n", "segments = 32\nexact_surface = true\n");
    let good = exact(funnel(40, 0.45, 0.2));
    assert_eq!(good.matches("exact_surface = true").count(), 2);
    let dir = common::temp_dir("funnel-exact");
    let path = common::write(&dir, "funnel.toml", &good);
    let scene = mdr_sim::load_scene(&path).unwrap_or_else(|p| panic!("{p}"));
    let summary = run_scene(
        &scene,
        &RunOptions::new(dir.join("out")).quiet(true).no_frames(true),
    )
    .expect("run");
    let h = &summary.headline;
    eprintln!("{}", h.text);
    assert_eq!(
        h.get("spheres_in_funnel_at_opening"),
        Some(40.0),
        "{}",
        h.text
    );
    assert_eq!(h.get("spheres_in_funnel_at_end"), Some(0.0), "{}", h.text);

    let plane = funnel(40, 0.45, 0.2).replace(
        "normal = [0.0, 0.0, 1.0]\n",
        "normal = [0.0, 0.0, 1.0]\nexact_surface = true\n",
    );
    let m = refused(&plane, "exact_surface", "exact_surface = true");
    assert!(m.contains("not used"), "{m}");
    let rapier = good.replace(
        "headline = \"funnel\"",
        "headline = \"funnel\"\nforce_path = \"rapier\"",
    );
    let m = refused(&rapier, "exact_surface", "exact_surface = true");
    assert!(m.contains("neighbour-list path only"), "{m}");
}

#[test]
fn radius_classes_round_every_radius_down_to_its_class() {
    let text = funnel(40, 0.2, 0.1).replace(
        "radius_m = 0.002\n",
        "size_distribution = \"uniform\"\nradius_min_m = 0.0015\nradius_max_m = 0.002\nradius_classes = 4\n",
    );
    let scene = parse_scene(Path::new("scene.toml"), &text).unwrap_or_else(|p| panic!("{p}"));
    let classes = [0.0015, 0.001625, 0.00175, 0.001875, 0.002];
    let mut seen = std::collections::BTreeSet::new();
    for p in &scene.particles {
        let k = classes
            .iter()
            .position(|c| (p.radius - c).abs() < 1e-12)
            .unwrap_or_else(|| panic!("radius {} is not a class", p.radius));
        seen.insert(k);
    }
    assert!(
        seen.len() >= 3,
        "40 uniform draws fill most of 4 classes: {seen:?}"
    );
}

/// The plug holds the spheres until it is removed; then they fall through the spout, leave the
/// funnel and are removed below the sink height: the discharge curve starts at every sphere,
/// stays there while plugged, and ends at none.
#[test]
fn spheres_fall_through_once_the_plug_is_removed_and_are_removed_below_the_sink() {
    let dir = common::temp_dir("funnel-plug");
    let n = 40;
    let text = funnel(n, 0.45, 0.2);
    let path = common::write(&dir, "funnel.toml", &text);
    let scene = mdr_sim::load_scene(&path).unwrap_or_else(|p| panic!("{p}"));
    assert_eq!(scene.particles.len(), n);
    let summary = run_scene(
        &scene,
        &RunOptions::new(dir.join("out")).quiet(true).no_frames(true),
    )
    .expect("run");
    let h = &summary.headline;
    eprintln!("{}", h.text);
    assert_eq!(h.get("spheres_in_funnel_at_opening"), Some(n as f64));
    assert_eq!(h.get("spheres_in_funnel_at_end"), Some(0.0), "{}", h.text);
    assert_eq!(h.get("spheres_remaining_at_end"), Some(0.0), "{}", h.text);
    // Removed spheres are parked at rest below the sink height, apart from each other.
    for p in &summary.particles {
        assert!(p.translation[2] < -0.03, "{:?}", p.translation);
        assert!(p.linvel.iter().all(|v| v.abs() < 1e-9), "{:?}", p.linvel);
    }
    // The CSV: every sphere in the funnel until the plug opens, then non-increasing to zero.
    let csv = std::fs::read_to_string(dir.join("out/funnel_headline.csv")).expect("curve CSV");
    let mut lines = csv.lines();
    assert_eq!(
        lines.next(),
        Some("time_s,spheres_in_funnel,spheres_remaining")
    );
    let rows: Vec<(f64, f64, f64)> = lines
        .map(|l| {
            let f: Vec<f64> = l.split(',').map(|x| x.parse().unwrap()).collect();
            (f[0], f[1], f[2])
        })
        .collect();
    assert!(rows.len() > 40);
    for (t, inside, remaining) in &rows {
        if *t < 0.2 {
            assert_eq!(
                (*inside, *remaining),
                (n as f64, n as f64),
                "t = {t}: plugged"
            );
        }
        assert!(inside <= remaining);
    }
    assert!(rows
        .windows(2)
        .filter(|w| w[0].0 >= 0.2)
        .all(|w| w[1].1 <= w[0].1 + 1.0));
    // The books close with the spheres gone: what they carried out is booked in `removed_j`
    // (their energy at removal, here all of the run's kinetic and gravitational energy).
    let (first, last) = (&summary.energy[0], summary.energy.last().unwrap());
    let drift = last.balance_j - first.balance_j;
    eprintln!(
        "removed {:.4e} J, drift {drift:.3e} J ({:.3} %)",
        last.removed_j,
        100.0 * drift / last.removed_j
    );
    assert!(last.removed_j > 0.0);
    assert!(
        drift.abs() < 0.02 * last.removed_j,
        "drift {drift:e} J against {:e} J removed",
        last.removed_j
    );
}

/// A sphere resting on the plug of a closed funnel that never opens stays: nothing is removed.
#[test]
fn without_removal_the_plug_holds() {
    let dir = common::temp_dir("funnel-closed");
    let text = funnel(20, 0.25, 10.0);
    let scene = parse_scene(&dir.join("funnel.toml"), &text).unwrap_or_else(|p| panic!("{p}"));
    let summary = run_scene(
        &scene,
        &RunOptions::new(dir.join("out")).quiet(true).no_frames(true),
    )
    .expect("run");
    assert_eq!(summary.headline.get("spheres_in_funnel_at_end"), Some(20.0));
    assert!(summary.particles.iter().all(|p| p.translation[2] > 0.0));
}

/// A small flat-bottomed hopper of soft spheres: `count` lattice sites trimmed to a cylinder,
/// run for `duration` s per orifice of `sweep`.
fn hopper(count: usize, duration: f64, sweep: &str) -> String {
    r#"
[run]
name = "hopper"
seed = 3
duration_s = DURATION
dt_s = "auto"
max_speed_m_per_s = 1.5
output_interval_s = 0.005
headline = "hopper"
discharge_height_m = -0.006
delete_below_m = -0.02
orifice_sweep_m = SWEEP

[gravity]
acceleration_m_per_s2 = [0.0, 0.0, -9.81]

[[material]]
name = "grain"
youngs_pa = 1.0e5
poisson_ratio = 0.25
density_kg_per_m3 = 2500.0

[contact]
normal = "hertz"
tangential = "mindlin"
friction = 0.4
damping = "stiffness_viscous"
damping_eta = 0.3

[[particles]]
material = "grain"
count = COUNT
radius_m = 0.001
placement = "lattice"
region_min_m = [-0.011, -0.011, 0.0002]
region_max_m = [0.011, 0.011, 0.06]
region_radius_m = 0.0105
gap_fraction = 0.02
jitter_fraction = 0.5

[[walls]]
kind = "cylinder"
material = "grain"
center_m = [0.0, 0.0, 0.04]
radius_m = 0.0125
length_m = 0.08
segments = 32
thickness_m = 0.003

[[walls]]
kind = "orifice_plate"
material = "grain"
center_m = [0.0, 0.0, 0.0]
outer_radius_m = 0.016
orifice_diameter_m = 0.012
thickness_m = 0.002
segments = 32
"#
    .replace("DURATION", &duration.to_string())
    .replace("SWEEP", sweep)
    .replace("COUNT", &count.to_string())
}

/// The sweep's mechanics, CI-sized (three short runs of ~150 spheres): one run per diameter, each
/// with that orifice, in its own directory, the points and the CSV written, and the fit
/// consistent with the points it was made from.
#[test]
fn hopper_orifice_sweep_runs_once_per_diameter_and_fits_the_rates() {
    let dir = common::temp_dir("hopper-sweep-small");
    let path = common::write(
        &dir,
        "hopper.toml",
        &hopper(200, 0.06, "[0.008, 0.010, 0.012]"),
    );
    let scene = mdr_sim::load_scene(&path).unwrap_or_else(|p| panic!("{p}"));
    let sweep = mdr_sim::run::run_orifice_sweep(
        &scene,
        &RunOptions::new(dir.join("out")).quiet(true).no_frames(true),
    )
    .expect("sweep");
    eprintln!("{}", sweep.text);
    assert_eq!(sweep.points.len(), 3);
    for ((run, point), d) in sweep
        .runs
        .iter()
        .zip(&sweep.points)
        .zip([0.008, 0.010, 0.012])
    {
        assert_eq!(run.headline.get("orifice_diameter_m"), Some(d));
        assert_eq!(point.0, d);
        assert_eq!(Some(point.1), run.headline.get("mass_flow_rate_kg_per_s"));
    }
    let csv = std::fs::read_to_string(dir.join("out/hopper_beverloo.csv")).expect("csv");
    assert_eq!(csv.lines().count(), 4, "{csv}");
    for i in 0..3 {
        assert!(dir
            .join(format!("out/hopper_D{i}/hopper_D{i}_headline.toml"))
            .exists());
    }
    // The fit is always made (three or more points) and must be there: a sweep that silently
    // drops it fails here. The rates of these 0.06 s runs are transients, not Beverloo's
    // steady flow; `small_hopper_discharges_at_beverloo_rate` checks the physics.
    let fit = sweep.fit.expect("the sweep's Beverloo fit");
    let (a, b) = fit.line;
    let rho_b = mdr_sim::headline::BULK_SOLID_FRACTION * 2500.0;
    assert!((fit.c - b.powf(2.5) / (rho_b * 9.81f64.sqrt())).abs() < 1e-12 * fit.c.abs());
    assert!((fit.k + a / (b * 0.002)).abs() < 1e-9 * fit.k.abs().max(1.0));
}

/// `exact_surface = true` on the hopper's cylinder and orifice plate: with an orifice narrower
/// than a sphere the plate holds every sphere (none passes through the top face or the hole's
/// rim), and with an orifice of 6 d the spheres drain through the hole.
#[test]
fn exact_cylinder_and_orifice_plate_hold_the_spheres_and_let_them_drain() {
    let exact = |orifice: &str| {
        let text = hopper(200, 0.1, "[]")
            .replace("orifice_sweep_m = []\n", "")
            .replace(
                "orifice_diameter_m = 0.012",
                &format!("orifice_diameter_m = {orifice}"),
            )
            .replace("segments = 32\n", "segments = 32\nexact_surface = true\n");
        assert_eq!(text.matches("exact_surface = true").count(), 2);
        text
    };
    let dir = common::temp_dir("hopper-exact");
    let mut fractions = Vec::new();
    for (tag, orifice) in [("closed", "0.0015"), ("open", "0.012")] {
        let path = common::write(&dir, &format!("{tag}.toml"), &exact(orifice));
        let scene = mdr_sim::load_scene(&path).unwrap_or_else(|p| panic!("{p}"));
        let summary = run_scene(
            &scene,
            &RunOptions::new(dir.join(tag)).quiet(true).no_frames(true),
        )
        .expect("run");
        eprintln!("{tag}: {}", summary.headline.text);
        fractions.push(
            summary
                .headline
                .get("discharged_fraction")
                .expect("fraction"),
        );
    }
    assert_eq!(
        fractions[0], 0.0,
        "no sphere passes a 1.5 mm hole: {fractions:?}"
    );
    assert!(
        fractions[1] > 0.1,
        "the 12 mm orifice drains: {fractions:?}"
    );
}

/// Least-squares slope of `(x, y)` points.
fn slope(points: &[(f64, f64)]) -> f64 {
    let n = points.len() as f64;
    let mx = points.iter().map(|p| p.0).sum::<f64>() / n;
    let my = points.iter().map(|p| p.1).sum::<f64>() / n;
    points.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum::<f64>()
        / points.iter().map(|p| (p.0 - mx).powi(2)).sum::<f64>()
}

/// The discharge physics at CI size (two runs of ~1,500 soft spheres, 0.25 s each, orifices of
/// 5 d and 6 d in a hopper 12.5 d wide), against Beverloo, Leniger & van de Velde (Chem. Eng. Sci.
/// 15, 260, 1961) with the commonly quoted `C = 0.58`, `k = 1.5`, `ρ_b = 0.6 ρ_p`:
/// - each steady rate within 20 % of `W = C ρ_b √g (D − k d)^{5/2}` (measured 1.130 and 1.002;
///   the correlation's own spread, `C` = 0.55–0.65 and `k` = 1.3–1.7 at `D = 5 d`, is ±15 %);
/// - the flow is steady: the rates over the first and the second half of the fit window agree
///   within 20 % while the fill height falls (measured 2.6 % and 11.7 %; a rate that followed the
///   fill height, as a liquid's `√h` does, or a transient would not).
///
/// Fitting `C` and `k` themselves needs wider orifices and a deeper bed: the ignored test below
/// runs the built-in hopper for them.
#[test]
fn small_hopper_discharges_at_beverloo_rate() {
    let dir = common::temp_dir("hopper-beverloo");
    for orifice in [0.010, 0.012] {
        let text = hopper(2000, 0.25, "[]")
            .replace("orifice_sweep_m = []\n", "")
            .replace(
                "orifice_diameter_m = 0.012",
                &format!("orifice_diameter_m = {orifice}"),
            );
        let tag = format!("D{}", (orifice * 1000.0) as usize);
        let path = common::write(&dir, &format!("{tag}.toml"), &text);
        let scene = mdr_sim::load_scene(&path).unwrap_or_else(|p| panic!("{p}"));
        let summary = run_scene(
            &scene,
            &RunOptions::new(dir.join(&tag)).quiet(true).no_frames(true),
        )
        .expect("run");
        let h = &summary.headline;
        eprintln!("{}", h.text);
        let rate = h.get("mass_flow_rate_kg_per_s").expect("rate");
        let ratio = h.get("ratio_to_beverloo").expect("ratio");
        assert!(
            (ratio - 1.0).abs() < 0.2,
            "D = {orifice}: W = {rate:e} kg/s = {ratio} × Beverloo"
        );
        // Steadiness: the discharged mass in the fit window, split in two halves.
        let start = h.get("fit_window_start_s").expect("window");
        let total: f64 = scene
            .particles
            .iter()
            .map(|p| scene.materials[p.material].1.sphere_mass(p.radius))
            .sum();
        let csv = std::fs::read_to_string(dir.join(format!("{tag}/hopper_headline.csv")))
            .expect("headline CSV");
        let window: Vec<(f64, f64)> = csv
            .lines()
            .skip(1)
            .map(|l| {
                let f: Vec<f64> = l.split(',').map(|x| x.parse().unwrap()).collect();
                (f[0], f[1])
            })
            .filter(|(t, m)| *t >= start && *m > 0.0 && *m <= 0.9 * total)
            .collect();
        assert!(window.len() >= 16, "{} rows in the window", window.len());
        let (first, second) = window.split_at(window.len() / 2);
        let (w1, w2) = (slope(first), slope(second));
        eprintln!("D = {orifice}: window rates {w1:.4e}, {w2:.4e} kg/s");
        assert!(
            (w2 / w1 - 1.0).abs() < 0.2,
            "D = {orifice}: the rate changes within the window: {w1:e} then {w2:e} kg/s"
        );
    }
}

/// Beverloo's `C` and `k` fitted to the built-in hopper's three orifices (6, 8, 10 d; 20,734
/// spheres, 0.8 s each; `cargo test --release -p mdr-sim --test
/// sim_scenes_funnel_hopper -- --ignored`) within the literature's ranges: `C` = 0.55–0.65 and
/// `k` = 1.3–2.9 reported for the correlation (Beverloo, Leniger & van de Velde 1961), and every
/// rate within 10 % of it with `C = 0.58`, `k = 1.5`.
#[test]
#[ignore]
fn builtin_hopper_fits_literature_beverloo_c_and_k() {
    let dir = common::temp_dir("hopper-builtin");
    let path =
        std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../scenes/hopper.toml");
    let scene = mdr_sim::load_scene(&path).unwrap_or_else(|p| panic!("{p}"));
    let sweep = mdr_sim::run::run_orifice_sweep(
        &scene,
        &RunOptions::new(dir.join("out")).quiet(true).no_frames(true),
    )
    .expect("sweep");
    eprintln!("{}", sweep.text);
    for (d, w, beverloo) in &sweep.points {
        assert!(
            (w / beverloo - 1.0).abs() < 0.1,
            "D = {d}: {w} vs {beverloo}"
        );
    }
    let fit = sweep.fit.expect("fit");
    assert!((0.55..=0.65).contains(&fit.c), "C = {}", fit.c);
    assert!((1.3..=2.9).contains(&fit.k), "k = {}", fit.k);
}
