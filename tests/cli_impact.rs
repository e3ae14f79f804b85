//! The `mdr-dem impact …` command line: output contracts (CSV headers, JSON keys, files) and
//! every bad flag value exiting non-zero with a message that names the flag.

mod common;

use common::{mdr_dem, scratch, stdout};

use std::process::Command;

#[test]
fn curve_csv_contract() {
    let text = stdout(&mdr_dem(&[
        "impact",
        "curve",
        "--velocities",
        "0.1,1,3",
        "--csv",
        "-",
        "--quiet",
    ]));
    let mut lines = text.lines();
    assert_eq!(
        lines.next().unwrap(),
        "v0_m_per_s,e_n,e_n_scaled,d_max_m,d_residual_m,contact_time_s,f_max_n,stuck"
    );
    let rows: Vec<Vec<f64>> = lines
        .map(|l| l.split(',').map(|x| x.parse().unwrap()).collect())
        .collect();
    assert_eq!(rows.len(), 3);
    assert_eq!(rows[0][1], 1.0, "0.1 m/s is below the yield speed");
    for row in &rows {
        assert!((row[2] - 0.95 * row[1]).abs() < 1e-12);
    }
    assert!(rows[2][1] < rows[1][1] && rows[1][1] < 1.0);
}

#[test]
fn springs_curve_agrees_with_closed() {
    let closed = stdout(&mdr_dem(&[
        "impact",
        "curve",
        "--velocities",
        "1",
        "--csv",
        "-",
    ]));
    let springs = stdout(&mdr_dem(&[
        "impact",
        "curve",
        "--velocities",
        "1",
        "--csv",
        "-",
        "--method",
        "springs",
    ]));
    let e = |t: &str| -> f64 {
        t.lines()
            .nth(1)
            .unwrap()
            .split(',')
            .nth(1)
            .unwrap()
            .parse()
            .unwrap()
    };
    assert!((e(&closed) - e(&springs)).abs() < 1e-3);
}

#[test]
fn trace_and_oblique_csv_contracts() {
    let trace = stdout(&mdr_dem(&[
        "impact", "trace", "--v0", "1", "--steps", "100",
    ]));
    assert_eq!(
        trace.lines().next().unwrap(),
        "t_s,d_m,v_m_per_s,f_n,contact_radius_m,plastic_work_j"
    );
    assert!(trace.lines().count() > 100);
    let oblique = stdout(&mdr_dem(&[
        "impact",
        "oblique",
        "--speed",
        "1",
        "--angles",
        "10,45,80",
        "--springs",
        "200",
        "--steps",
        "400",
    ]));
    let mut lines = oblique.lines();
    assert_eq!(
        lines.next().unwrap(),
        "angle_deg,e_n,e_t,rebound_angle_deg,omega_rad_per_s,stuck"
    );
    assert_eq!(lines.count(), 3);
}

#[test]
fn fit_json_contract() {
    let dir = scratch("fit");
    let data = dir.path().join("data.csv");
    // Points from the model itself (paper values), so the fit must land on them.
    let curve = stdout(&mdr_dem(&[
        "impact", "curve", "--v-min", "0.1", "--v-max", "10", "--points", "12", "--csv", "-",
    ]));
    let mut csv = String::from("v0_m_per_s,e_n\n");
    for line in curve.lines().skip(1) {
        let cells: Vec<&str> = line.split(',').collect();
        csv.push_str(&format!("{},{}\n", cells[0], cells[2]));
    }
    std::fs::write(&data, csv).unwrap();
    let text = stdout(&mdr_dem(&[
        "impact",
        "fit",
        "--data",
        data.to_str().unwrap(),
        "--free",
        "qc,theta_ratio",
        "--json",
    ]));
    let value: serde_json::Value = serde_json::from_str(text.trim()).unwrap();
    for key in ["q_c", "theta_ratio", "scale", "rmse", "n_points"] {
        assert!(value.get(key).is_some(), "missing key {key}: {text}");
    }
    assert!((value["q_c"].as_f64().unwrap() / 3.8e5 - 1.0).abs() < 1e-3);
    assert!((value["theta_ratio"].as_f64().unwrap() / 0.37 - 1.0).abs() < 1e-3);
    assert_eq!(value["n_points"].as_u64(), Some(12));
    // Too few points for three parameters: refused with a message.
    std::fs::write(&data, "v0_m_per_s,e_n\n1,0.7\n2,0.65\n").unwrap();
    let output = mdr_dem(&["impact", "fit", "--data", data.to_str().unwrap()]);
    assert!(!output.status.success());
    assert!(String::from_utf8_lossy(&output.stderr).contains("at least 4 points"));
}

#[test]
fn fig2_writes_table_csv_svg_png() {
    let dir = scratch("fig2");
    let data = dir.path().join("measured.csv");
    std::fs::write(&data, "v0_m_per_s,e_n\n0.1,0.95\n1,0.7\n").unwrap();
    let output = Command::new(env!("CARGO_BIN_EXE_mdr-dem"))
        .args([
            "impact",
            "fig2",
            "--quiet",
            "--data",
            data.to_str().unwrap(),
        ])
        .current_dir(&dir)
        .output()
        .unwrap();
    let text = stdout(&output);
    assert!(text.contains("yield speed"));
    let csv = std::fs::read_to_string(dir.path().join("results/fig2.csv")).unwrap();
    assert!(csv.starts_with("v0_m_per_s,e_n,e_n_scaled,"));
    assert_eq!(csv.lines().count(), 201);
    let svg = std::fs::read_to_string(dir.path().join("results/fig2.svg")).unwrap();
    assert!(svg.contains("<svg") && svg.contains("yield speed"));
    let png = std::fs::read(dir.path().join("results/fig2.png")).unwrap();
    assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n");
    // No arguments runs the same job.
    let dir = scratch("default");
    let output = Command::new(env!("CARGO_BIN_EXE_mdr-dem"))
        .current_dir(&dir)
        .output()
        .unwrap();
    stdout(&output);
    assert!(dir.path().join("results/fig2.csv").exists());
}

#[test]
fn config_file_keys_and_flag_override() {
    let dir = scratch("config");
    let config = dir.path().join("impact.toml");
    std::fs::write(&config, "theta-ratio = 0.8\nlaw = \"mdr\"\nscale = 0.9\n").unwrap();
    let run = |extra: &[&str]| {
        let mut args = vec![
            "impact",
            "curve",
            "--velocities",
            "5",
            "--csv",
            "-",
            "--config",
        ];
        args.push(config.to_str().unwrap());
        args.extend_from_slice(extra);
        let text = stdout(&mdr_dem(&args));
        let row: Vec<f64> = text
            .lines()
            .nth(1)
            .unwrap()
            .split(',')
            .map(|x| x.parse().unwrap())
            .collect();
        (row[1], row[2])
    };
    let (from_file, scaled) = run(&[]);
    assert!((scaled / from_file - 0.9).abs() < 1e-12);
    let (overridden, _) = run(&["--theta-ratio", "0.37"]);
    assert!(
        from_file > overridden + 0.05,
        "Θ/E* = 0.8 gives a higher e_n than 0.37"
    );
    std::fs::write(&config, "radius = -1\n").unwrap();
    let output = mdr_dem(&["impact", "curve", "--config", config.to_str().unwrap()]);
    assert!(!output.status.success());
    assert!(String::from_utf8_lossy(&output.stderr).contains("--radius"));
    std::fs::write(&config, "radios = 1\n").unwrap();
    let output = mdr_dem(&["impact", "curve", "--config", config.to_str().unwrap()]);
    assert!(!output.status.success());
    assert!(String::from_utf8_lossy(&output.stderr).contains("--config"));
}

/// Every bad value exits non-zero and the message names the flag.
#[test]
fn bad_flag_values_name_the_flag() {
    let cases: &[(&[&str], &str)] = &[
        (&["impact", "curve", "--radius", "-1"], "--radius"),
        (&["impact", "curve", "--radius", "abc"], "--radius"),
        (&["impact", "curve", "--density", "0"], "--density"),
        (&["impact", "curve", "--youngs", "-2e11"], "--youngs"),
        (&["impact", "curve", "--poisson", "0.7"], "--poisson"),
        (
            &["impact", "curve", "--target-youngs", "0"],
            "--target-youngs",
        ),
        (
            &["impact", "curve", "--target-poisson", "-1.5"],
            "--target-poisson",
        ),
        (
            &[
                "impact",
                "curve",
                "--target-radius",
                "-0.01",
                "--target-density",
                "7800",
            ],
            "--target-radius",
        ),
        (
            &["impact", "curve", "--target-radius", "0.01"],
            "--target-radius",
        ),
        (
            &["impact", "curve", "--target-density", "7800"],
            "--target-density",
        ),
        (
            &[
                "impact",
                "curve",
                "--target-radius",
                "0.01",
                "--target-density",
                "-5",
            ],
            "--target-density",
        ),
        (&["impact", "curve", "--qc", "-5"], "--qc"),
        (
            &["impact", "curve", "--theta-ratio", "1.5"],
            "--theta-ratio",
        ),
        (&["impact", "curve", "--law", "foo"], "--law"),
        (
            &[
                "impact",
                "curve",
                "--law",
                "thornton",
                "--yield-stress",
                "-1",
            ],
            "--yield-stress",
        ),
        (&["impact", "curve", "--mu", "-0.1"], "--mu"),
        (&["impact", "curve", "--scale", "0"], "--scale"),
        (&["impact", "curve", "--velocities", "1,-2"], "--velocities"),
        (&["impact", "curve", "--velocities", "1,x"], "--velocities"),
        (&["impact", "curve", "--v-min", "-1"], "--v-min"),
        (
            &["impact", "curve", "--v-min", "5", "--v-max", "1"],
            "--v-max",
        ),
        (&["impact", "curve", "--points", "1"], "--points"),
        (&["impact", "curve", "--method", "magic"], "--method"),
        (
            &["impact", "curve", "--method", "springs", "--springs", "1"],
            "--springs",
        ),
        (
            &[
                "impact",
                "curve",
                "--method",
                "springs",
                "--springs",
                "100000001",
            ],
            "--springs",
        ),
        (
            &["impact", "curve", "--method", "springs", "--law", "hertz"],
            "--method",
        ),
        (&["impact", "curve", "--steps", "2"], "--steps"),
        (
            &["impact", "curve", "--plot", "out.bmpx", "--velocities", "1"],
            "--plot",
        ),
        (
            &["impact", "curve", "--config", "/nonexistent/x.toml"],
            "--config",
        ),
        (&["impact", "trace", "--v0", "0"], "--v0"),
        (&["impact", "trace", "--v0", "nan"], "--v0"),
        (
            &["impact", "fit", "--data", "/nonexistent/data.csv"],
            "--data",
        ),
        (
            &[
                "impact",
                "fit",
                "--data",
                "/nonexistent/data.csv",
                "--free",
                "qc,bogus",
            ],
            "--free",
        ),
        (&["impact", "oblique", "--speed", "-1"], "--speed"),
        (
            &["impact", "oblique", "--speed", "1", "--angles", "10,95"],
            "--angles",
        ),
        (
            &[
                "impact",
                "oblique",
                "--speed",
                "1",
                "--tangential",
                "springs",
                "--method",
                "closed",
            ],
            "--tangential",
        ),
    ];
    for (args, flag) in cases {
        let output = mdr_dem(args);
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert!(!output.status.success(), "{args:?} succeeded");
        assert!(
            stderr.contains(flag),
            "{args:?}: message does not name {flag}: {stderr}"
        );
    }
}

/// Yield speed of the paper's ball from docs/theory.md §4, written out (independent of the
/// code): `m v_y²/2 = (8/15) E* √R u_c^{5/2}`, `u_c = π q_c/(2E*)`, `E* = E/(2(1 − ν²))`.
fn paper_yield_speed() -> f64 {
    let (e, nu, rho, r, q_c) = (2.0e11_f64, 0.286_f64, 7800.0_f64, 0.635e-2_f64, 3.8e5_f64);
    let e_star = e / (2.0 * (1.0 - nu * nu));
    let mass = 4.0 / 3.0 * std::f64::consts::PI * r.powi(3) * rho;
    let u_c = std::f64::consts::PI * q_c / (2.0 * e_star);
    (2.0 * 8.0 / 15.0 * e_star * r.sqrt() * u_c.powf(2.5) / mass).sqrt()
}

/// `impact curve --law mdr,thornton,hertz`: one CSV per law, each the law it names (Hertz
/// elastic, Thornton his eq. 31 with the MDR law's yield speed, MDR the single-law curve), and
/// one figure with the three.
#[test]
fn curve_with_several_laws_writes_one_file_per_law() {
    let dir = scratch("laws");
    let csv = dir.path().join("laws.csv");
    let svg = dir.path().join("laws.svg");
    stdout(&mdr_dem(&[
        "impact",
        "curve",
        "--law",
        "mdr,thornton,hertz",
        "--velocities",
        "1,3",
        "--csv",
        csv.to_str().unwrap(),
        "--plot",
        svg.to_str().unwrap(),
        "--quiet",
    ]));
    let e_n = |law: &str| -> Vec<f64> {
        let text = std::fs::read_to_string(dir.path().join(format!("laws_{law}.csv")))
            .unwrap_or_else(|e| panic!("laws_{law}.csv: {e}"));
        text.lines()
            .skip(1)
            .map(|l| l.split(',').nth(1).unwrap().parse().unwrap())
            .collect()
    };
    // Hertz is time-integrated: e_n = 1 to the integrator's 3.1e-9 (measured).
    for e in e_n("hertz") {
        assert!((e - 1.0).abs() < 1e-8, "Hertz e_n = {e}");
    }
    let v_y = paper_yield_speed();
    for (v, e) in [1.0, 3.0].into_iter().zip(e_n("thornton")) {
        let x = v_y / v;
        let published = (6.0 * 3f64.sqrt() / 5.0 * (1.0 - x * x / 6.0)).sqrt()
            * (x / (x + 2.0 * (6.0 / 5.0 - x * x / 5.0).sqrt())).powf(0.25);
        // Time integration against his eq. 31: measured 8.9e-8 (tests of mdr-impact).
        assert!(
            (e - published).abs() < 3e-7,
            "Thornton at {v} m/s: {e} vs {published}"
        );
    }
    let single = stdout(&mdr_dem(&[
        "impact",
        "curve",
        "--velocities",
        "1,3",
        "--csv",
        "-",
        "--quiet",
    ]));
    let single: Vec<f64> = single
        .lines()
        .skip(1)
        .map(|l| l.split(',').nth(1).unwrap().parse().unwrap())
        .collect();
    assert_eq!(e_n("mdr"), single);
    let figure = std::fs::read_to_string(&svg).unwrap();
    for law in ["MDR", "Thornton", "Hertz"] {
        assert!(figure.contains(law), "{law} missing from the figure");
    }
}

/// `fig2 --data`: every measured point is drawn (one filled circle per point, plus the legend's).
#[test]
fn fig2_draws_the_measured_points() {
    let dir = scratch("fig2-points");
    let data = dir.path().join("measured.csv");
    std::fs::write(&data, "v0_m_per_s,e_n\n0.1,0.95\n0.5,0.8\n1,0.7\n3,0.62\n").unwrap();
    let run = |extra: &[&str]| {
        let output = Command::new(env!("CARGO_BIN_EXE_mdr-dem"))
            .args(["impact", "fig2", "--quiet"])
            .args(extra)
            .current_dir(&dir)
            .output()
            .unwrap();
        stdout(&output);
        std::fs::read_to_string(dir.path().join("results/fig2.svg")).unwrap()
    };
    let without = run(&[]);
    let with = run(&["--data", data.to_str().unwrap()]);
    let circles = |svg: &str| svg.matches("<circle").count();
    assert_eq!(
        circles(&with) - circles(&without),
        4 + 1,
        "4 points and a legend marker"
    );
}
