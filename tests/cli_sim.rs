//! The `mdr-dem sim drop|pair` command line: the CSV contract, the material/law flags
//! and `--config` shared with `mdr-dem impact`, and bad values named by their flag.

mod common;

use common::mdr_dem;

use std::process::Output;

/// The rows of a successful `v0_m_per_s,e_n,steps,stuck,time_step_s` CSV on stdout.
fn rows(output: &Output) -> Vec<Vec<f64>> {
    assert!(
        output.status.success(),
        "failed: {}",
        String::from_utf8_lossy(&output.stderr)
    );
    let text = String::from_utf8(output.stdout.clone()).unwrap();
    let mut lines = text.lines();
    assert_eq!(
        lines.next().unwrap(),
        "v0_m_per_s,e_n,steps,stuck,time_step_s"
    );
    lines
        .map(|l| l.split(',').map(|x| x.parse().unwrap()).collect())
        .collect()
}

/// `e_n` of `mdr-dem impact curve` (the validator) at `v0` with extra flags.
fn validator_e_n(v0: &str, flags: &[&str]) -> f64 {
    let mut args = vec!["impact", "curve", "--velocities", v0, "--csv", "-", "-q"];
    args.extend_from_slice(flags);
    let output = mdr_dem(&args);
    assert!(output.status.success());
    let text = String::from_utf8(output.stdout).unwrap();
    text.lines()
        .nth(1)
        .unwrap()
        .split(',')
        .nth(1)
        .unwrap()
        .parse()
        .unwrap()
}

fn error(args: &[&str]) -> String {
    let output = mdr_dem(args);
    assert!(!output.status.success(), "{args:?} should fail");
    String::from_utf8(output.stderr).unwrap()
}

const FAST: [&str; 2] = ["--steps-per-contact", "200"];

/// Force mode at 200 steps per contact against the validator: measured relative deviations
/// ≤ 9.9·10⁻⁶ (MDR, Thornton, other parameters, elastic); docs/coupling.md.
const FORCE_MODE: f64 = 5e-5;

/// Restitution mode applies the law's closed form: exact up to rounding (measured 2·10⁻¹⁶).
const EXACT: f64 = 1e-12;

#[test]
fn drop_csv_contract_and_agreement_with_the_validator() {
    let mut args = vec!["sim", "drop", "--v0", "0.5,1"];
    args.extend_from_slice(&FAST);
    let table = rows(&mdr_dem(&args));
    assert_eq!(table.len(), 2);
    for row in &table {
        let reference = validator_e_n(&row[0].to_string(), &[]);
        assert!(
            (row[1] - reference).abs() < FORCE_MODE * reference,
            "{row:?} vs {reference}"
        );
        // 200 steps per Hertz contact time; the plastic contact lasts a little longer.
        assert!(row[2] > 150.0 && row[2] < 400.0, "{row:?}");
    }
}

#[test]
fn law_flags_reach_rapier_as_in_impact() {
    for flags in [
        vec!["--law", "thornton"],
        vec!["--law", "thornton", "--yield-stress", "2e9"],
        vec!["--qc", "2e5", "--theta-ratio", "0.5"],
        vec!["--elastic"],
    ] {
        let mut args = vec!["sim", "drop", "--v0", "1"];
        args.extend_from_slice(&FAST);
        args.extend_from_slice(&flags);
        let e_n = rows(&mdr_dem(&args))[0][1];
        let reference = validator_e_n("1", &flags);
        assert!(
            (e_n - reference).abs() < FORCE_MODE * reference,
            "{flags:?}: rapier {e_n} vs validator {reference}"
        );
    }
}

#[test]
fn config_file_keys_are_the_impact_ones_and_flags_override_them() {
    let path = std::env::temp_dir().join(format!("mdr-dem-sim-{}.toml", std::process::id()));
    std::fs::write(&path, "qc = 2e5\nlaw = \"mdr\"\nradius = 0.005\n").unwrap();
    let config = path.to_str().unwrap();
    let from_file = rows(&mdr_dem(&[
        "sim",
        "drop",
        "--v0",
        "1",
        "--mode",
        "restitution",
        "--config",
        config,
    ]))[0][1];
    let reference = validator_e_n("1", &["--qc", "2e5", "--radius", "0.005"]);
    assert!((from_file - reference).abs() < EXACT * reference);
    let overridden = rows(&mdr_dem(&[
        "sim",
        "drop",
        "--v0",
        "1",
        "--mode",
        "restitution",
        "--config",
        config,
        "--qc",
        "3.8e5",
    ]))[0][1];
    let reference = validator_e_n("1", &["--radius", "0.005"]);
    assert!((overridden - reference).abs() < EXACT * reference);
    std::fs::remove_file(&path).unwrap();
}

#[test]
fn pair_target_defaults_to_a_copy_and_takes_target_flags() {
    let mut args = vec!["sim", "pair", "--v0", "1", "--mode", "restitution"];
    let copy = rows(&mdr_dem(&args))[0][1];
    let reference = validator_e_n(
        "1",
        &["--target-radius", "0.00635", "--target-density", "7800"],
    );
    assert!((copy - reference).abs() < EXACT * reference);
    args.extend_from_slice(&["--target-radius", "0.01", "--target-youngs", "2.1e11"]);
    let other = rows(&mdr_dem(&args))[0][1];
    let reference = validator_e_n(
        "1",
        &[
            "--target-radius",
            "0.01",
            "--target-density",
            "7800",
            "--target-youngs",
            "2.1e11",
        ],
    );
    assert!((other - reference).abs() < EXACT * reference);
    assert!(
        (other - copy).abs() > 1e-4,
        "the target flags change the result"
    );
}

#[test]
fn bad_values_name_their_flag() {
    for (args, flag) in [
        (vec!["sim", "drop", "--v0", "-1"], "--v0"),
        (vec!["sim", "drop", "--v0", "1", "--qc", "-3"], "--qc"),
        (
            vec!["sim", "drop", "--v0", "1", "--poisson", "0.7"],
            "--poisson",
        ),
        (vec!["sim", "drop", "--v0", "1", "--angle", "95"], "--angle"),
        (
            vec!["sim", "drop", "--v0", "1", "--target-radius", "0.01"],
            "--target-radius",
        ),
        (
            vec!["sim", "drop", "--v0", "1", "--law", "mdr,hertz"],
            "--law",
        ),
        (
            vec!["sim", "drop", "--v0", "1", "--method", "springs"],
            "--method",
        ),
        (
            vec!["sim", "drop", "--v0", "1", "--steps-per-contact", "3"],
            "--steps-per-contact",
        ),
        (
            vec![
                "sim",
                "drop",
                "--v0",
                "1",
                "--law",
                "thornton",
                "--mode",
                "restitution",
            ],
            "--mode",
        ),
        (
            vec!["sim", "pair", "--v0", "1", "--target-radius", "-2"],
            "--target-radius",
        ),
    ] {
        let message = error(&args);
        assert!(message.contains(flag), "{args:?}: {message}");
    }
}
