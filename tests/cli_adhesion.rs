//! `--work-of-adhesion` on the `mdr-dem impact …` command line: the `stuck` column, the
//! `impact trace --json` keys, the fit of Δγ, and bad values refused naming the flag in every
//! command that takes it.

mod common;

use common::{mdr_dem, stdout};

const GLASS: [&str; 8] = [
    "--radius",
    "5e-6",
    "--youngs",
    "63e9",
    "--poisson",
    "0.2",
    "--density",
    "2500",
];

fn with_glass<'a>(args: &[&'a str]) -> Vec<&'a str> {
    args.iter().copied().chain(GLASS).collect()
}

#[test]
fn curve_marks_stuck_impacts() {
    let text = stdout(&mdr_dem(&with_glass(&[
        "impact",
        "curve",
        "--elastic",
        "--work-of-adhesion",
        "0.1",
        "--velocities",
        "0.01,1",
        "--csv",
        "-",
        "--quiet",
    ])));
    let mut lines = text.lines();
    assert!(lines.next().unwrap().ends_with(",f_max_n,stuck"));
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    assert_eq!((rows[0][1], rows[0][7]), ("0", "1"));
    assert_eq!(rows[1][7], "0");
    assert!(rows[1][1].parse::<f64>().unwrap() > 0.9);
}

/// `--law adhesive_mdr` (or `adhesive-mdr`) runs the adhesive law with `--work-of-adhesion` as
/// its Δγ: the same curve as `--law mdr --work-of-adhesion`, plastic and elastic, with the slow
/// impact stuck (so Δγ reached the law); without the flag it is refused naming it.
#[test]
fn adhesive_mdr_by_name_takes_the_work_of_adhesion() {
    let curve = |law: &str, elastic: bool| {
        let mut args = vec![
            "impact",
            "curve",
            "--law",
            law,
            "--work-of-adhesion",
            "0.1",
            "--velocities",
            "0.01,0.3,1,20",
            "--csv",
            "-",
            "--quiet",
        ];
        if elastic {
            args.push("--elastic");
        }
        stdout(&mdr_dem(&with_glass(&args)))
    };
    for elastic in [false, true] {
        let mdr = curve("mdr", elastic);
        let rows: Vec<&str> = mdr.lines().skip(1).collect();
        assert_eq!(rows.len(), 4);
        assert!(
            rows[0].starts_with("0.01,0,") && rows[0].ends_with(",1"),
            "{mdr}"
        );
        for name in ["adhesive_mdr", "adhesive-mdr"] {
            assert_eq!(curve(name, elastic), mdr, "--law {name}, elastic {elastic}");
        }
    }
    let output = mdr_dem(&with_glass(&["impact", "curve", "--law", "adhesive_mdr"]));
    assert!(!output.status.success());
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        stderr.contains("`adhesive_mdr` needs --work-of-adhesion"),
        "{stderr}"
    );
    // Adhesion stays the MDR laws': another law beside them is refused.
    let output = mdr_dem(&with_glass(&[
        "impact",
        "curve",
        "--law",
        "adhesive_mdr,hertz",
        "--work-of-adhesion",
        "0.1",
    ]));
    assert!(!output.status.success());
    assert!(String::from_utf8_lossy(&output.stderr).contains("--law adhesive_mdr"));
}

#[test]
fn trace_json_reports_pull_off_and_release() {
    let dir = std::env::temp_dir().join(format!("mdr-dem-cli-adhesion-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let csv = dir.join("trace.csv");
    let text = stdout(&mdr_dem(&with_glass(&[
        "impact",
        "trace",
        "--elastic",
        "--work-of-adhesion",
        "0.1",
        "--v0",
        "0.3",
        "--csv",
        csv.to_str().unwrap(),
        "--json",
        "-",
    ])));
    let json: serde_json::Value = serde_json::from_str(&text).unwrap();
    let pull_off = json["pull_off_force_n"].as_f64().unwrap();
    let expected = 1.5 * std::f64::consts::PI * 0.1 * 5e-6;
    assert!((pull_off - expected).abs() < 1e-3 * expected);
    assert!(json["release_overlap_m"].as_f64().unwrap() < 0.0);
    assert_eq!(json["stuck"], false);
    // The trace goes through negative overlap with tensile forces.
    let trace = std::fs::read_to_string(&csv).unwrap();
    assert!(trace
        .lines()
        .skip(1)
        .any(|l| l.split(',').nth(3).unwrap().parse::<f64>().unwrap() < 0.0));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn bad_work_of_adhesion_is_refused_by_every_command() {
    let commands: [&[&str]; 5] = [
        &["impact", "curve", "--velocities", "1", "--quiet"],
        &["impact", "trace", "--v0", "1"],
        &["impact", "oblique", "--speed", "1", "--angles", "30"],
        &["impact", "fit", "--data", "missing.csv"],
        &["impact", "fig2"],
    ];
    for command in commands {
        for bad in ["-0.1", "nan", "inf"] {
            let mut args = command.to_vec();
            args.extend(["--work-of-adhesion", bad]);
            let output = mdr_dem(&args);
            let stderr = String::from_utf8_lossy(&output.stderr);
            assert!(!output.status.success(), "{args:?} accepted");
            assert!(stderr.contains("--work-of-adhesion"), "{args:?}: {stderr}");
        }
    }
    // Adhesion is the MDR law's.
    let hertz = mdr_dem(&[
        "impact",
        "curve",
        "--law",
        "hertz",
        "--work-of-adhesion",
        "0.1",
    ]);
    assert!(String::from_utf8_lossy(&hertz.stderr).contains("--work-of-adhesion"));
    for command in ["drop", "pair"] {
        for bad in ["-0.1", "nan", "inf"] {
            let args = ["sim", command, "--v0", "1", "--work-of-adhesion", bad];
            let output = mdr_dem(&args);
            assert!(!output.status.success(), "{args:?} accepted");
            assert!(String::from_utf8_lossy(&output.stderr).contains("--work-of-adhesion"));
        }
    }
}

/// `sim drop` and `sim pair` run the adhesive law in both rapier coupling modes: the slow
/// impact sticks (`e_n = 0`, `stuck` 1) and the fast one rebounds with the validator's `e_n`
/// (`impact curve`, an integration of the law without rapier) to the coupling's step error
/// (measured below 1.3e-4 at 1000 steps per contact, crates/mdr-rapier/tests/adhesion.rs).
#[test]
fn sim_drop_and_pair_stick_and_rebound_with_adhesion() {
    let curve = stdout(&mdr_dem(&with_glass(&[
        "impact",
        "curve",
        "--elastic",
        "--work-of-adhesion",
        "0.2",
        "--velocities",
        "0.02,0.5",
        "--csv",
        "-",
        "--quiet",
    ])));
    let reference: Vec<f64> = curve
        .lines()
        .skip(1)
        .map(|l| l.split(',').nth(1).unwrap().parse().unwrap())
        .collect();
    assert_eq!(reference[0], 0.0);
    for command in ["drop", "pair"] {
        for mode in ["force", "restitution"] {
            let text = stdout(&mdr_dem(&with_glass(&[
                "sim",
                command,
                "--elastic",
                "--work-of-adhesion",
                "0.2",
                "--mode",
                mode,
                "--v0",
                "0.02,0.5",
            ])));
            let mut lines = text.lines();
            assert_eq!(
                lines.next().unwrap(),
                "v0_m_per_s,e_n,steps,stuck,time_step_s"
            );
            let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
            assert_eq!((rows[0][1], rows[0][3]), ("0", "1"), "{command} {mode}");
            assert_eq!(rows[1][3], "0", "{command} {mode}");
            if command == "drop" {
                let e: f64 = rows[1][1].parse().unwrap();
                assert!(
                    (e - reference[1]).abs() < 5e-4,
                    "{command} {mode}: {e} vs {}",
                    reference[1]
                );
            }
        }
    }
}
