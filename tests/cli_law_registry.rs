//! The law registry on the command line: `mdr-dem sim laws` lists what the laws declare, and a
//! law added as one file and one registry line (the demo linear spring, `demo-laws` feature,
//! which `cargo test` builds this program with) runs from `mdr-dem sim run`, `sim drop`,
//! `sim pair` and `impact` as its analytic solution, its scene key's and flag's range errors
//! derived from its declaration.

mod common;

use common::{mdr_dem, stdout};

use std::path::Path;

/// The built-in drop scene with a linear spring `k_n = 10⁴ N/m` on a 5 mm sphere (1 mm fall).
fn spring_drop(dir: &Path, stiffness: &str) -> std::path::PathBuf {
    let text =
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/drop.toml"))
            .unwrap();
    let text = text
        .replace("duration_s = 0.2", "duration_s = 0.03")
        .replace("dt_s = \"auto\"", "dt_s = 1.0e-6")
        .replace("max_speed_m_per_s = 1.0", "max_speed_m_per_s = 0.5")
        .replace("checkpoint_interval_s = 0.1", "")
        .replace(
            "normal = \"mdr\"\ncritical_line_load_n_per_m = 3.8e5   # q_c, eq. (7)\nhardening_ratio = 0.37               # Θ/E*, eq. (12)",
            &format!("normal = \"linear_spring\"\nnormal_stiffness_n_per_m = {stiffness}"),
        )
        .replace("youngs_pa = 2.0e11", "youngs_pa = 1.0e9")
        .replace("density_kg_per_m3 = 7800.0", "density_kg_per_m3 = 2500.0")
        .replace("radius_m = 0.00635", "radius_m = 0.005")
        .replace(
            "region_min_m = [-0.00635, -0.00635, 0.05]",
            "region_min_m = [-0.005, -0.005, 0.001]",
        )
        .replace(
            "region_max_m = [0.00636, 0.00636, 0.0628]",
            "region_max_m = [0.00501, 0.00501, 0.01101]",
        );
    assert!(text.contains("linear_spring") && text.contains("0.001]"));
    let path = dir.join("spring.toml");
    std::fs::write(&path, text).unwrap();
    path
}

#[test]
fn sim_laws_lists_every_registered_law_with_its_declared_parameters() {
    let text = stdout(&mdr_dem(&["sim", "laws"]));
    for line in [
        "normal = \"mdr\"",
        "critical_line_load_n_per_m = …  q_c (N/m, in [0, inf)",
        "hardening_ratio = …  Θ/E* (1, in [0, 1])",
        "normal = \"hertz\"",
        "yield_pressure_pa = …  p_y (Pa, in (0, inf))",
        "normal = \"linear_spring\"",
        "normal_stiffness_n_per_m = …  k_n (N/m, in (0, inf))",
    ] {
        assert!(text.contains(line), "missing `{line}` in\n{text}");
    }
    let json: serde_json::Value =
        serde_json::from_str(&stdout(&mdr_dem(&["sim", "laws", "--json"]))).unwrap();
    let mdr = &json[0];
    assert_eq!(mdr["name"], "mdr");
    // The derived names reproduce the published flags and Python keywords.
    assert_eq!(mdr["parameters"][0]["flag"], "--qc");
    assert_eq!(mdr["parameters"][1]["flag"], "--theta-ratio");
    assert_eq!(mdr["parameters"][1]["python"], "theta_ratio");
    assert_eq!(json[2]["parameters"][0]["flag"], "--yield-stress");
    let by_name = |name: &str| {
        json.as_array()
            .unwrap()
            .iter()
            .find(|l| l["name"] == name)
            .unwrap_or_else(|| panic!("no law `{name}` in {json}"))
    };
    let spring = &by_name("linear_spring")["parameters"][0];
    assert_eq!(
        by_name("adhesive_mdr")["parameters"][2]["flag"],
        "--work-of-adhesion"
    );
    assert_eq!(spring["flag"], "--normal-stiffness-n-per-m");
    assert_eq!(spring["lammps"], "kn");
}

/// `e_n = 1` (no damping, an elastic spring) and the impact speed of a 1 mm fall.
#[test]
fn sim_run_runs_the_demo_law() {
    let dir = tempfile::tempdir().unwrap();
    let scene = spring_drop(dir.path(), "1.0e4");
    let out = dir.path().join("out");
    let text = stdout(&mdr_dem(&[
        "sim",
        "run",
        scene.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--quiet",
    ]));
    let e_n: f64 = text
        .split("e_n = ")
        .nth(1)
        .and_then(|s| s.split_whitespace().next())
        .unwrap_or_else(|| panic!("no e_n in {text}"))
        .parse()
        .unwrap();
    assert!((e_n - 1.0).abs() < 2e-3, "{text}");
    assert!(text.contains("impact speed 0.14"), "{text}");
    // The MDR closed form is not quoted for another law.
    assert!(!text.contains("energy route"), "{text}");
}

/// The demo spring scene with the demo damping law `c` (N·s/m), without gravity: the 5 mm
/// sphere is thrown at 0.1 m/s onto the plane 0.1 mm away.
fn dashpot_throw(dir: &Path, coefficient: f64) -> std::path::PathBuf {
    let spring = spring_drop(dir, "1.0e4");
    let text = std::fs::read_to_string(&spring).unwrap();
    let text = text
        .replace("duration_s = 0.03", "duration_s = 0.004")
        .replace("[0.0, 0.0, -9.81]", "[0.0, 0.0, 0.0]")
        .replace(
            "normal_stiffness_n_per_m = 1.0e4",
            &format!(
                "normal_stiffness_n_per_m = 1.0e4\ndamping = \"linear_dashpot\"\ndamping_coefficient_n_s_per_m = {coefficient}"
            ),
        )
        .replace("-0.005, 0.001]", "-0.005, 0.0001]")
        .replace(
            "0.00501, 0.01101]",
            "0.00501, 0.01011]\nvelocity_m_per_s = [0.0, 0.0, -0.1]",
        );
    assert!(text.contains("linear_dashpot") && text.contains("-0.1]"));
    let path = dir.join("dashpot.toml");
    std::fs::write(&path, text).unwrap();
    path
}

/// `mdr-dem sim run` runs the demo damping law (its file and one registry line): the rebound is
/// the linear spring–dashpot's whose contact only pushes, `e_n = exp(−β t_e)` with
/// `ω_d t_e = π − 2 arctan(β/ω_d)` (`β = c/(2m)`, `ω_d = √(k/m − β²)`; Schwager & Pöschel,
/// Granular Matter 9 (2007) 465), at damping ratio 0.2; a coefficient 5 % larger is told
/// apart.
#[test]
fn sim_run_runs_the_demo_damping_law_as_its_analytic_restitution() {
    let m = 4.0 / 3.0 * std::f64::consts::PI * 0.005_f64.powi(3) * 2500.0;
    let k = 1.0e4;
    let restitution = |c: f64| {
        let beta = c / (2.0 * m);
        let omega_d = (k / m - beta * beta).sqrt();
        let t_e = (std::f64::consts::PI - 2.0 * (beta / omega_d).atan()) / omega_d;
        (-beta * t_e).exp()
    };
    let c = 2.0 * 0.2 * (m * k).sqrt();
    let dir = tempfile::tempdir().unwrap();
    let scene = dashpot_throw(dir.path(), c);
    let out = dir.path().join("out");
    let text = stdout(&mdr_dem(&[
        "sim",
        "run",
        scene.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--quiet",
    ]));
    let e_n: f64 = text
        .split("e_n = ")
        .nth(1)
        .and_then(|s| s.split_whitespace().next())
        .unwrap_or_else(|| panic!("no e_n in {text}"))
        .trim_end_matches(',')
        .parse()
        .unwrap();
    // Symplectic Euler at ω₀ dt = 2.8e-3: e_n − e = −4e-4.
    assert!((e_n - restitution(c)).abs() < 1.2e-3, "{text}");
    assert!((e_n - restitution(1.05 * c)).abs() > 5e-3, "{text}");
    // Its range error is its declaration's.
    let scene = dashpot_throw(dir.path(), -1.0);
    let output = mdr_dem(&["sim", "run", scene.to_str().unwrap(), "--quiet"]);
    assert_eq!(output.status.code(), Some(2));
    let err = String::from_utf8_lossy(&output.stderr);
    assert!(
        err.contains("damping_coefficient_n_s_per_m") && err.contains("[0, inf)"),
        "{err}"
    );
}

#[test]
fn sim_run_refuses_a_demo_law_value_outside_its_declared_range() {
    let dir = tempfile::tempdir().unwrap();
    let scene = spring_drop(dir.path(), "-1.0");
    let output = mdr_dem(&["sim", "run", scene.to_str().unwrap(), "--quiet"]);
    assert_eq!(output.status.code(), Some(2));
    let err = String::from_utf8_lossy(&output.stderr);
    assert!(
        err.contains("normal_stiffness_n_per_m") && err.contains("(0, inf)"),
        "{err}"
    );
}

/// The paper's steel ball (R = 0.635 cm, 7800 kg/m³) on a half-space: the reduced mass is the
/// ball's mass.
fn paper_ball_mass() -> f64 {
    4.0 / 3.0 * std::f64::consts::PI * 0.635e-2_f64.powi(3) * 7800.0
}

/// `mdr-dem impact curve` runs the demo law by its registered name, its stiffness given by the
/// flag its declaration derives: an undamped linear spring returns every impact (`e_n = 1`)
/// after half a period, `t_c = π √(m*/k_n)`, with the peak force `F = v₀ √(k_n m*)`, whatever
/// the speed.
#[test]
fn impact_curve_runs_the_demo_law_as_its_analytic_solution() {
    let k = 1.0e4;
    let text = stdout(&mdr_dem(&[
        "impact",
        "curve",
        "--law",
        "linear-spring",
        "--normal-stiffness-n-per-m",
        "1e4",
        "--velocities",
        "0.1,1",
        "--csv",
        "-",
        "--quiet",
    ]));
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let column = |name: &str| header.iter().position(|h| *h == name).unwrap();
    let m = paper_ball_mass();
    let contact_time = std::f64::consts::PI * (m / k).sqrt();
    let rows: Vec<Vec<f64>> = lines
        .map(|l| l.split(',').map(|x| x.parse().unwrap()).collect())
        .collect();
    assert_eq!(rows.len(), 2);
    for row in rows {
        let v0 = row[column("v0_m_per_s")];
        let e_n = row[column("e_n")];
        let t_c = row[column("contact_time_s")];
        let f_max = row[column("f_max_n")];
        assert!((e_n - 1.0).abs() < 1e-4, "e_n = {e_n} at {v0} m/s");
        assert!(
            (t_c / contact_time - 1.0).abs() < 1e-3,
            "t_c = {t_c} vs {contact_time}"
        );
        assert!(
            (f_max / (v0 * (k * m).sqrt()) - 1.0).abs() < 1e-3,
            "F_max = {f_max}"
        );
    }
    // The law is named by its underscore name too; the help lists its derived flag.
    let help = stdout(&mdr_dem(&["impact", "curve", "--help"]));
    assert!(
        help.contains("--normal-stiffness-n-per-m") && help.contains("k_n (N/m, in (0, inf))"),
        "{help}"
    );
}

/// A missing, out-of-range or misplaced demo-law parameter is refused naming its flag, and
/// restitution mode (the MDR law's `e(v)`) refuses the law naming `--mode`.
#[test]
fn impact_refuses_demo_law_parameters_by_their_derived_flag() {
    let fails = |args: &[&str], needles: &[&str]| {
        let output = mdr_dem(args);
        assert!(!output.status.success(), "{args:?} succeeded");
        let err = String::from_utf8_lossy(&output.stderr);
        for needle in needles {
            assert!(err.contains(needle), "{args:?}: no `{needle}` in {err}");
        }
    };
    fails(
        &[
            "impact",
            "curve",
            "--law",
            "linear_spring",
            "--velocities",
            "1",
        ],
        &["--law", "--normal-stiffness-n-per-m", "k_n"],
    );
    fails(
        &[
            "impact",
            "trace",
            "--law",
            "linear_spring",
            "--normal-stiffness-n-per-m",
            "-5",
            "--v0",
            "1",
        ],
        &["invalid value for --normal-stiffness-n-per-m", "(0, inf)"],
    );
    fails(
        &[
            "impact",
            "curve",
            "--normal-stiffness-n-per-m",
            "1e4",
            "--velocities",
            "1",
        ],
        &[
            "invalid value for --normal-stiffness-n-per-m",
            "none of the laws",
        ],
    );
    fails(
        &[
            "sim",
            "pair",
            "--law",
            "linear_spring",
            "--normal-stiffness-n-per-m",
            "-5",
            "--v0",
            "1",
        ],
        &[
            "invalid value for --normal-stiffness-n-per-m",
            "(0, inf)",
            "k_n",
        ],
    );
    fails(
        &[
            "sim",
            "drop",
            "--law",
            "linear_spring",
            "--normal-stiffness-n-per-m",
            "1e4",
            "--mode",
            "restitution",
            "--v0",
            "1",
        ],
        &["invalid value for --mode", "force mode"],
    );
}

/// `mdr-dem sim drop|pair` run the demo law in rapier's impact scene by its registered name,
/// its stiffness given by its derived flag: an undamped linear spring returns the approach
/// speed (`e_n = 1` to the integrator's step error, of order `(π dt / t_c)²`) after half a
/// period, `t_c = π √(m*/k_n)` (`steps × time_step_s`, to a step), with the reduced mass of
/// the pair (a 1 cm steel target sphere of 7850 kg/m³).
#[test]
fn sim_drop_and_pair_run_the_demo_law_as_its_analytic_solution() {
    let k = 1.0e6;
    let ball = paper_ball_mass();
    let target = 4.0 / 3.0 * std::f64::consts::PI * 0.01_f64.powi(3) * 7850.0;
    for (command, mass, extra) in [
        ("drop", ball, &[][..]),
        (
            "pair",
            ball * target / (ball + target),
            &["--target-radius", "0.01", "--target-density", "7850"][..],
        ),
    ] {
        let mut args = vec![
            "sim",
            command,
            "--law",
            "linear-spring",
            "--normal-stiffness-n-per-m",
            "1e6",
            "--v0",
            "0.1,1",
        ];
        args.extend_from_slice(extra);
        let text = stdout(&mdr_dem(&args));
        let mut lines = text.lines();
        assert_eq!(
            lines.next().unwrap(),
            "v0_m_per_s,e_n,steps,stuck,time_step_s"
        );
        let contact_time = std::f64::consts::PI * (mass / k).sqrt();
        let rows: Vec<Vec<f64>> = lines
            .map(|l| l.split(',').map(|x| x.parse().unwrap()).collect())
            .collect();
        assert_eq!(rows.len(), 2, "{text}");
        for row in rows {
            let (e_n, steps, stuck, dt) = (row[1], row[2], row[3], row[4]);
            let step_error = (std::f64::consts::PI * dt / contact_time).powi(2);
            assert!(
                (e_n - 1.0).abs() < 0.5 * step_error + 1e-12,
                "{command}: e_n = {e_n} (dt {dt})"
            );
            assert!(
                (steps * dt - contact_time).abs() <= 1.01 * dt,
                "{command}: contact time {} vs {contact_time}",
                steps * dt
            );
            assert_eq!(stuck, 0.0);
        }
    }
}
