//! `mdr-dem sim run` from the command line. Ctrl-C: SIGINT while the run is under way makes it
//! write a final checkpoint and exit with status 130, printing the command that continues it;
//! that command, run verbatim by a shell, completes the run in the same folder, and its summary
//! counts the steps it ran. Exit statuses of refused input (2) and of a guard (3), the NaN stop
//! among them, with the outputs written before it kept.
//! `--threads`: one and two threads write the same energy books, and 0 is refused by name.

#![cfg(unix)]

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

const DT: f64 = 4.0e-6;

fn scene(duration: f64) -> String {
    format!(
        r#"
[run]
name = "column"
seed = 5
duration_s = {duration:e}
dt_s = {DT:e}
max_speed_m_per_s = 1.0
output_interval_s = 0.002
headline = "column"

[gravity]
acceleration_m_per_s2 = [0.0, 0.0, -9.81]

[[material]]
name = "grain"
youngs_pa = 5.0e7
poisson_ratio = 0.25
density_kg_per_m3 = 2500.0

[contact]
normal = "mdr"
critical_line_load_n_per_m = 100.0
hardening_ratio = 0.37
tangential = "mindlin"
friction = 0.5
rolling_friction = 0.1

[[particles]]
material = "grain"
count = 27
radius_m = 0.002
placement = "lattice"
region_min_m = [-0.0064, -0.0064, 0.0]
region_max_m = [0.0064, 0.0064, 0.0127]
gap_fraction = 0.05
jitter_fraction = 0.8

[[walls]]
kind = "plane"
material = "grain"
point_m = [0.0, 0.0, 0.0]
normal = [0.0, 0.0, 1.0]
"#
    )
}

fn write(path: &Path, text: &str) -> PathBuf {
    std::fs::write(path, text).unwrap();
    path.to_path_buf()
}

#[test]
fn ctrl_c_writes_a_final_checkpoint_and_the_run_resumes_from_it() {
    let dir_guard = tempfile::tempdir().unwrap();
    let dir = dir_guard.path().to_path_buf();
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let out = dir.join("out");
    // 100 s of simulated time: the interrupt always comes first.
    let long = write(&dir.join("long.toml"), &scene(100.0));
    let mut child = Command::new(env!("CARGO_BIN_EXE_mdr-dem"))
        .args(["sim", "run"])
        .arg(&long)
        .arg("--out")
        .arg(&out)
        .arg("--quiet")
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("mdr-dem starts");
    // Wait until the run is under way (its second frame exists), then send SIGINT.
    let second = out.join("frames").join("column_000001.vtp");
    let limit = Instant::now() + Duration::from_secs(300);
    while !second.exists() {
        if let Some(status) = child.try_wait().unwrap() {
            let output = child.wait_with_output().unwrap();
            panic!(
                "mdr-dem ended before the interrupt ({status}): {}",
                String::from_utf8_lossy(&output.stderr)
            );
        }
        assert!(Instant::now() < limit, "no second frame within 300 s");
        std::thread::sleep(Duration::from_millis(10));
    }
    let killed = Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .expect("kill runs");
    assert!(killed.success());
    let output = child.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(
        output.status.code(),
        Some(130),
        "{}: {stderr}",
        output.status
    );
    assert!(stderr.contains("interrupted at t = "), "{stderr}");
    // "interrupted at t = T s (step N) …; continue with:\n  PROGRAM sim run SCENE --out OUT
    // --resume CK --quiet"
    let step: u64 = stderr
        .split("(step ")
        .nth(1)
        .and_then(|s| s.split(')').next())
        .and_then(|s| s.parse().ok())
        .unwrap_or_else(|| panic!("no step in {stderr}"));
    let hint = stderr
        .split("continue with:\n")
        .nth(1)
        .and_then(|s| s.lines().next())
        .unwrap_or_else(|| panic!("no command in {stderr}"))
        .trim()
        .to_owned();
    let checkpoint = PathBuf::from(
        hint.split("--resume ")
            .nth(1)
            .and_then(|s| s.split_whitespace().next())
            .unwrap_or_else(|| panic!("no --resume in {hint}")),
    );
    assert!(checkpoint.exists(), "{}", checkpoint.display());
    assert!(step > 0);
    // No temporary file is left behind.
    for sub in [out.clone(), out.join("frames"), out.join("checkpoints")] {
        for e in std::fs::read_dir(&sub).unwrap() {
            let name = e.unwrap().file_name().to_string_lossy().into_owned();
            assert!(!name.contains(".tmp"), "{name} in {}", sub.display());
        }
    }

    // The scene now ends 50 steps past the stop (only duration_s may change); the hint runs as
    // printed, from another working directory, and continues in the same folder.
    write(&long, &scene((step as f64 + 49.5) * DT));
    let resumed = Command::new("sh")
        .arg("-c")
        .arg(&hint)
        .current_dir(std::env::temp_dir())
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&resumed.stdout);
    assert!(
        resumed.status.success(),
        "{hint}: {}",
        String::from_utf8_lossy(&resumed.stderr)
    );
    assert!(stdout.contains("done: t = "), "{stdout}");
    assert!(stdout.contains(", 50 steps in "), "{stdout}");
    assert!(stdout.contains("energy balance drift"), "{stdout}");
    let pvd = std::fs::read_to_string(out.join("column.pvd")).unwrap();
    let frames = std::fs::read_dir(out.join("frames")).unwrap().count();
    assert_eq!(pvd.matches("<DataSet").count(), frames, "{pvd}");

    // A fresh run into the folder is refused (2) unless --overwrite is given.
    let again = |extra: &[&str]| {
        Command::new(env!("CARGO_BIN_EXE_mdr-dem"))
            .args(["sim", "run"])
            .arg(&long)
            .arg("--out")
            .arg(&out)
            .arg("--quiet")
            .args(extra)
            .output()
            .unwrap()
    };
    let refused = again(&[]);
    let stderr = String::from_utf8_lossy(&refused.stderr);
    assert_eq!(refused.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("--overwrite"), "{stderr}");
    let replaced = again(&["--overwrite"]);
    assert!(
        replaced.status.success(),
        "{}",
        String::from_utf8_lossy(&replaced.stderr)
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn threads_flag_sets_the_pool_and_changes_no_result() {
    let dir_guard = tempfile::tempdir().unwrap();
    let dir = dir_guard.path().to_path_buf();
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let path = write(&dir.join("column.toml"), &scene(400.5 * DT));
    let run = |threads: &str| {
        let out = dir.join(format!("out{threads}"));
        let output = Command::new(env!("CARGO_BIN_EXE_mdr-dem"))
            .args(["sim", "run"])
            .arg(&path)
            .arg("--out")
            .arg(&out)
            .args(["--quiet", "--threads", threads])
            .output()
            .unwrap();
        (output, out.join("column_energy.csv"))
    };
    let (one, one_csv) = run("1");
    assert!(
        one.status.success(),
        "{}",
        String::from_utf8_lossy(&one.stderr)
    );
    let (two, two_csv) = run("2");
    assert!(
        two.status.success(),
        "{}",
        String::from_utf8_lossy(&two.stderr)
    );
    let one_csv = std::fs::read(one_csv).unwrap();
    assert!(one_csv.len() > 200, "energy rows written");
    assert_eq!(one_csv, std::fs::read(two_csv).unwrap());
    let (zero, _) = run("0");
    assert!(!zero.status.success());
    let stderr = String::from_utf8_lossy(&zero.stderr);
    assert!(
        stderr.contains("--threads = 0 is outside the allowed range [1, inf)"),
        "{stderr}"
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn guards_and_refused_input_have_their_exit_statuses() {
    let dir_guard = tempfile::tempdir().unwrap();
    let dir = dir_guard.path().to_path_buf();
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let run = |scene: &Path, extra: &[&str]| {
        Command::new(env!("CARGO_BIN_EXE_mdr-dem"))
            .args(["sim", "run"])
            .arg(scene)
            .arg("--out")
            .arg(dir.join("out"))
            .arg("--quiet")
            .args(extra)
            .output()
            .unwrap()
    };
    // The energy guard set below the round-off drift trips at once: status 3.
    let text = scene(200.5 * DT).replace(
        "headline = \"column\"",
        "headline = \"column\"\nmax_energy_drift = 1e-15",
    );
    let tight = write(&dir.join("tight.toml"), &text);
    let stopped = run(&tight, &[]);
    let stderr = String::from_utf8_lossy(&stopped.stderr);
    assert_eq!(stopped.status.code(), Some(3), "{stderr}");
    assert!(stderr.contains("max_energy_drift"), "{stderr}");
    // `--check` measures the first steps and estimates the run's wall time.
    let checked = run(&tight, &["--check"]);
    let stderr = String::from_utf8_lossy(&checked.stderr);
    assert!(checked.status.success(), "{stderr}");
    assert!(
        stderr.contains("estimate: ") && stderr.contains("steps/s"),
        "{stderr}"
    );
    // A refused scene file: status 2.
    let bad = write(
        &dir.join("bad.toml"),
        &scene(1e-3).replace("seed = 5", "sed = 5"),
    );
    let refused = run(&bad, &[]);
    assert_eq!(refused.status.code(), Some(2));
    // A missing checkpoint: status 2, the system's message once.
    let missing = run(&tight, &["--resume", "no/such.mdrck", "--overwrite"]);
    let stderr = String::from_utf8_lossy(&missing.stderr);
    assert_eq!(missing.status.code(), Some(2), "{stderr}");
    assert_eq!(stderr.matches("No such file").count(), 1, "{stderr}");
    std::fs::remove_dir_all(&dir).ok();
}

/// A state that stops being finite (one sphere under a gravity of 10³⁰⁷ m/s², whose height
/// `z_0 − g dt² k(k+1)/2` passes the largest double at step 5996 of 1 ms) ends the command with
/// the guard's status 3 and a message naming the particle, the step and `dt_s`; the frames of
/// the samples before it (steps 0 to 5500, every 500) and every energy row up to the stop
/// (every 100 steps, the last at step 6000) stay in the output folder.
#[test]
fn a_non_finite_state_exits_with_the_guard_status_and_keeps_what_was_written() {
    let dir_guard = tempfile::tempdir().unwrap();
    let dir = dir_guard.path();
    write(
        &dir.join("one.csv"),
        "x_m,y_m,z_m,radius_m\n0,0,0.0025,0.002\n",
    );
    let text = include_str!("../crates/mdr-sim/tests/data/blowup.toml");
    let scene = write(&dir.join("blowup.toml"), text);
    let out = dir.join("out");
    let output = Command::new(env!("CARGO_BIN_EXE_mdr-dem"))
        .args(["sim", "run"])
        .arg(&scene)
        .arg("--out")
        .arg(&out)
        .arg("--quiet")
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(3), "{stderr}");
    assert!(
        stderr.contains("step 6000")
            && stderr.contains("particle 0 has a non-finite position or velocity: reduce dt_s"),
        "{stderr}"
    );
    let frames = std::fs::read_dir(out.join("frames")).unwrap().count();
    assert_eq!(frames, 12, "{stderr}");
    assert!(out.join("frames").join("blowup_000011.vtp").exists());
    let csv = std::fs::read_to_string(out.join("blowup_energy.csv")).unwrap();
    let last_time: f64 = csv
        .lines()
        .last()
        .and_then(|l| l.split(',').next())
        .unwrap()
        .parse()
        .unwrap();
    assert_eq!(csv.lines().count(), 1 + 61, "{csv}");
    assert!((last_time - 6.0).abs() < 1e-9, "{csv}");
}
