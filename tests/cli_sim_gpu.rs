//! `mdr-dem sim run --device gpu` from the command line: a sphere dropped onto a plane run on
//! both devices prints the same headline and writes the same files, checkpoints included; a
//! CPU checkpoint continues on the GPU with `--resume` (the scene made longer) and a GPU run
//! writes the checkpoints `checkpoint_interval_s` asks for, none with `--no-checkpoints`; the
//! shipped hopper, its orifice sweep included, is accepted, and a contact network and
//! `--no-checkpoints` on the CPU are refused by name (exit 2). A small orifice sweep on the GPU
//! prints the CPU sweep's table and writes its CSV and run folders; `--resume` of a sweep is
//! refused on the GPU as on the CPU; Ctrl-C stops a GPU sweep in its run with a message whose
//! instructions resume that run alone. Needs a Vulkan device with 64-bit floats (lavapipe on a
//! machine without a GPU, docs/gpu.md).

#[path = "../crates/mdr-gpu/tests/common/hopper_sweep.rs"]
mod hopper_sweep;

use hopper_sweep::{hopper_sweep_text, write_hopper_sweep, DIAMETERS, NAME};
use std::path::Path;
use std::process::{Command, Output};

fn mdr_dem(args: &[&str], dir: &Path) -> Output {
    Command::new(env!("CARGO_BIN_EXE_mdr-dem"))
        .args(args)
        .current_dir(dir)
        .output()
        .unwrap()
}

/// The steel sphere of `scenes/drop.toml` 10 µm above the plane, approaching it at 0.5 m/s:
/// 250 steps cover the bounce.
const DROP: &str = r#"
[run]
name = "drop"
duration_s = 2.0e-4
dt_s = 8.0e-7
max_speed_m_per_s = 0.6
output_interval_s = 5.0e-5
energy_interval_s = 1.0e-5
headline = "drop"

[gravity]
acceleration_m_per_s2 = [0.0, 0.0, -9.81]

[[material]]
name = "steel"
youngs_pa = 2.0e11
poisson_ratio = 0.286
density_kg_per_m3 = 7800.0

[contact]
normal = "mdr"
critical_line_load_n_per_m = 3.8e5
hardening_ratio = 0.37

[[particles]]
material = "steel"
placement = "csv"
file = "drop.csv"

[[walls]]
kind = "plane"
material = "steel"
point_m = [0.0, 0.0, 0.0]
normal = [0.0, 0.0, 1.0]
"#;

fn drop_dir() -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("drop.csv"),
        "x_m,y_m,z_m,radius_m,vx_m_per_s,vy_m_per_s,vz_m_per_s\n\
         0.0,0.0,0.00636,0.00635,0.0,0.0,-0.5\n",
    )
    .unwrap();
    std::fs::write(dir.path().join("drop.toml"), DROP).unwrap();
    dir
}

fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

/// The files of a run's folder, relative to it, sorted.
fn files(dir: &Path) -> Vec<String> {
    let mut names = Vec::new();
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        if path.is_dir() {
            names.extend(files(&path).into_iter().map(|f| format!("{name}/{f}")));
        } else {
            names.push(name);
        }
    }
    names.sort();
    names
}

#[test]
fn sim_run_on_the_gpu_prints_the_cpu_runs_headline_and_refuses_what_it_lacks() {
    let dir = drop_dir();
    let path = dir.path();
    let cpu = mdr_dem(
        &["sim", "run", "drop.toml", "--quiet", "--out", "cpu"],
        path,
    );
    assert!(cpu.status.success(), "{}", text(&cpu.stderr));
    let gpu = mdr_dem(
        &[
            "sim",
            "run",
            "drop.toml",
            "--quiet",
            "--out",
            "gpu",
            "--device",
            "gpu",
        ],
        path,
    );
    let (stdout, stderr) = (text(&gpu.stdout), text(&gpu.stderr));
    assert!(gpu.status.success(), "{stderr}");
    // The energy guard applies on the GPU as on the CPU: no warning that it does not.
    assert!(!stderr.contains("energy guard"), "{stderr}");
    // The headline's lines (the impact, the rebound, e_n and the law's closed form) are the
    // CPU run's to the printed digits.
    let headline = |out: &str| -> Vec<String> {
        out.lines()
            .filter(|l| l.contains("e_n"))
            .map(str::to_owned)
            .collect()
    };
    let cpu_headline = headline(&text(&cpu.stdout));
    assert_eq!(cpu_headline.len(), 2, "{}", text(&cpu.stdout));
    assert_eq!(headline(&stdout), cpu_headline, "{stdout}");
    // `done: t = …, N steps` as on the CPU (then the wall time and the adapter).
    let done = |out: &str| -> String {
        let line = out.lines().find(|l| l.starts_with("done: ")).unwrap_or("");
        line[..line.find(" in ").unwrap_or(0)].to_owned()
    };
    assert!(!done(&stdout).is_empty(), "{stdout}");
    assert_eq!(done(&stdout), done(&text(&cpu.stdout)));
    // The same files, the end checkpoint included.
    let cpu_files = files(&path.join("cpu"));
    assert!(
        cpu_files.iter().any(|f| f.starts_with("checkpoints/")),
        "{cpu_files:?}"
    );
    assert_eq!(files(&path.join("gpu")), cpu_files);

    // The CPU run's end checkpoint continues on the GPU, the scene made longer.
    std::fs::write(
        path.join("longer.toml"),
        DROP.replace("duration_s = 2.0e-4", "duration_s = 3.0e-4"),
    )
    .unwrap();
    let checkpoint = cpu_files
        .iter()
        .find(|f| f.starts_with("checkpoints/"))
        .unwrap();
    let resumed = mdr_dem(
        &[
            "sim",
            "run",
            "longer.toml",
            "--quiet",
            "--out",
            "cpu",
            "--device",
            "gpu",
            "--resume",
            &format!("cpu/{checkpoint}"),
        ],
        path,
    );
    let (stdout, stderr) = (text(&resumed.stdout), text(&resumed.stderr));
    assert!(resumed.status.success(), "{stderr}");
    // From the CPU run's end checkpoint (step 251 of 251) to the longer scene's end.
    assert!(stdout.contains("(from step 251 to 375)"), "{stdout}");

    // The checkpoints a scene asks for, on the GPU (every 125 steps, and at the end of the
    // scene's 251 steps); none with --no-checkpoints.
    std::fs::write(
        path.join("ckpt.toml"),
        DROP.replace(
            "headline = \"drop\"",
            "headline = \"drop\"\ncheckpoint_interval_s = 1.0e-4",
        ),
    )
    .unwrap();
    let run = mdr_dem(
        &[
            "sim",
            "run",
            "ckpt.toml",
            "--quiet",
            "--out",
            "ckpt",
            "--device",
            "gpu",
        ],
        path,
    );
    assert!(run.status.success(), "{}", text(&run.stderr));
    let written: Vec<_> = files(&path.join("ckpt"))
        .into_iter()
        .filter(|f| f.starts_with("checkpoints/"))
        .collect();
    assert_eq!(
        written,
        [
            "checkpoints/drop_step000000000125.mdrck",
            "checkpoints/drop_step000000000250.mdrck",
            "checkpoints/drop_step000000000251.mdrck"
        ],
    );
    let run = mdr_dem(
        &[
            "sim",
            "run",
            "ckpt.toml",
            "--quiet",
            "--out",
            "none",
            "--device",
            "gpu",
            "--no-checkpoints",
        ],
        path,
    );
    assert!(run.status.success(), "{}", text(&run.stderr));
    assert!(!path.join("none/checkpoints").exists());
    let cpu_flag = mdr_dem(
        &["sim", "run", "drop.toml", "--check", "--no-checkpoints"],
        path,
    );
    let stderr = text(&cpu_flag.stderr);
    assert_eq!(cpu_flag.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("--no-checkpoints"), "{stderr}");

    // The shipped hopper, its orifice sweep included, runs on the GPU; a contact network is
    // refused by its key.
    let hopper = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/hopper.toml");
    let checked = mdr_dem(
        &[
            "sim",
            "run",
            &hopper.display().to_string(),
            "--device",
            "gpu",
            "--check",
            "--no-checkpoints",
        ],
        path,
    );
    let stderr = text(&checked.stderr);
    assert!(checked.status.success(), "{stderr}");
    assert!(stderr.contains("the GPU path runs this scene"), "{stderr}");
    std::fs::write(
        path.join("network.toml"),
        DROP.replace(
            "headline = \"drop\"",
            "headline = \"drop\"\ncontact_network = true",
        ),
    )
    .unwrap();
    let refused = mdr_dem(
        &["sim", "run", "network.toml", "--device", "gpu", "--check"],
        path,
    );
    let stderr = text(&refused.stderr);
    assert_eq!(refused.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("contact_network"), "{stderr}");
}

/// The rows of a sweep's `NAME_beverloo.csv`: its header and its numbers.
fn beverloo_csv(path: &Path) -> (String, Vec<Vec<f64>>) {
    let csv = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut lines = csv.lines();
    let header = lines.next().unwrap_or_default().to_owned();
    let rows = lines
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect();
    (header, rows)
}

/// A small hopper sweep (three diameters, 166 spheres) with `--device gpu` prints what the
/// CPU sweep prints (each run's headline, the sweep's table and fit), writes the same run
/// folders and the CSV with the CPU's columns and rates: the same bits, as
/// `crates/mdr-gpu/tests/gpu_sweep.rs` measures (the trajectories differ by 10⁻¹³ diameters,
/// which moves no sphere across the discharge height at a sample); `--resume` is refused for a
/// sweep.
#[test]
fn an_orifice_sweep_on_the_gpu_prints_the_cpu_sweeps_table_and_writes_its_csv() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path();
    write_hopper_sweep(path, &DIAMETERS);
    let cpu = mdr_dem(
        &["sim", "run", "hopper.toml", "--quiet", "--out", "cpu"],
        path,
    );
    assert!(cpu.status.success(), "{}", text(&cpu.stderr));
    let gpu = mdr_dem(
        &[
            "sim",
            "run",
            "hopper.toml",
            "--quiet",
            "--out",
            "gpu",
            "--device",
            "gpu",
        ],
        path,
    );
    let (stdout, stderr) = (text(&gpu.stdout), text(&gpu.stderr));
    assert!(gpu.status.success(), "{stderr}");
    let cpu_stdout = text(&cpu.stdout);
    assert!(cpu_stdout.contains("orifice sweep:\n"), "{cpu_stdout}");
    assert!(cpu_stdout.contains("fitted W = C"), "{cpu_stdout}");
    assert_eq!(stdout, cpu_stdout);
    for i in 0..DIAMETERS.len() {
        let run = format!("{NAME}_D{i}");
        let cpu_files = files(&path.join("cpu").join(&run));
        assert!(
            cpu_files.contains(&format!("{run}_headline.toml")),
            "{cpu_files:?}"
        );
        assert_eq!(files(&path.join("gpu").join(&run)), cpu_files, "{run}");
    }
    let csv = format!("{NAME}_beverloo.csv");
    let (cpu_header, cpu_rows) = beverloo_csv(&path.join("cpu").join(&csv));
    let (gpu_header, gpu_rows) = beverloo_csv(&path.join("gpu").join(&csv));
    assert_eq!(
        cpu_header,
        "orifice_diameter_m,mass_flow_rate_kg_per_s,beverloo_kg_per_s"
    );
    assert_eq!(gpu_header, cpu_header);
    let diameters: Vec<f64> = cpu_rows.iter().map(|r| r[0]).collect();
    assert_eq!(diameters, DIAMETERS);
    assert!(cpu_rows.iter().all(|r| r[1] > 0.0), "{cpu_rows:?}");
    assert_eq!(gpu_rows, cpu_rows);

    // A sweep is not resumed as a whole, on either device.
    let refused = mdr_dem(
        &[
            "sim",
            "run",
            "hopper.toml",
            "--out",
            "gpu",
            "--device",
            "gpu",
            "--resume",
            "hopper.toml",
        ],
        path,
    );
    let stderr = text(&refused.stderr);
    assert_eq!(refused.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("--resume continues one run"), "{stderr}");
}

/// Ctrl-C during a GPU sweep's first run (the sweep made 2 s long so the interrupt comes
/// first): exit status 130 and a message naming the run, the diameter and name to write and
/// the checkpoint; followed as it says (the scene with that run's diameter and name, without the
/// sweep, 5 ms past the interrupt), `--resume` continues the run on the GPU from the checkpoint.
/// The checkpoint refuses the scene without the run's name (its fingerprint holds `run.name`):
/// a message that left the name out would fail here.
#[cfg(unix)]
#[test]
fn ctrl_c_stops_a_gpu_sweep_with_a_message_that_resumes_its_run() {
    use std::process::Stdio;
    use std::time::{Duration, Instant};
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path();
    let long = hopper_sweep_text(&DIAMETERS).replace("duration_s = 0.06", "duration_s = 2.0");
    std::fs::write(path.join("long.toml"), &long).unwrap();
    let mut child = Command::new(env!("CARGO_BIN_EXE_mdr-dem"))
        .args([
            "sim",
            "run",
            "long.toml",
            "--quiet",
            "--out",
            "gpu",
            "--device",
            "gpu",
        ])
        .current_dir(path)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    // The first run is under way once its second frame is written.
    let second = path.join(format!("gpu/{NAME}_D0/frames/{NAME}_D0_000001.vtp"));
    let limit = Instant::now() + Duration::from_secs(300);
    while !second.exists() {
        if let Some(status) = child.try_wait().unwrap() {
            let output = child.wait_with_output().unwrap();
            panic!(
                "ended before the interrupt ({status}): {}",
                text(&output.stderr)
            );
        }
        assert!(Instant::now() < limit, "no second frame within 300 s");
        std::thread::sleep(Duration::from_millis(10));
    }
    let killed = Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(killed.success());
    let output = child.wait_with_output().unwrap();
    let stderr = text(&output.stderr);
    assert_eq!(output.status.code(), Some(130), "{stderr}");
    let message = stderr
        .lines()
        .find(|l| l.starts_with("interrupted at t = "))
        .unwrap_or_else(|| panic!("{stderr}"));
    assert!(message.contains("of run 1 of the sweep"), "{message}");
    assert!(
        message.contains(&format!("its name `{NAME}_D0` into name")),
        "{message}"
    );
    let time: f64 = message["interrupted at t = ".len()..]
        .split(' ')
        .next()
        .and_then(|t| t.parse().ok())
        .unwrap_or_else(|| panic!("{message}"));
    let checkpoint = message
        .split("--resume ")
        .nth(1)
        .unwrap_or_else(|| panic!("{message}"))
        .trim();
    assert!(
        checkpoint.starts_with(&format!("gpu/{NAME}_D0/checkpoints/")),
        "{message}"
    );
    // As the message says: the run's diameter (the scene's orifice_diameter_m is the first) and
    // name, the sweep removed.
    let alone: String = long
        .replace(
            "duration_s = 2.0",
            &format!("duration_s = {:?}", time + 0.005),
        )
        .replace(
            &format!("name = \"{NAME}\""),
            &format!("name = \"{NAME}_D0\""),
        )
        .lines()
        .filter(|l| !l.starts_with("orifice_sweep_m"))
        .map(|l| format!("{l}\n"))
        .collect();
    assert!(alone.contains(&format!("orifice_diameter_m = {:?}", DIAMETERS[0])));
    std::fs::write(path.join("alone.toml"), alone).unwrap();
    let resumed = mdr_dem(
        &[
            "sim",
            "run",
            "alone.toml",
            "--quiet",
            "--device",
            "gpu",
            "--resume",
            checkpoint,
        ],
        path,
    );
    let (stdout, stderr) = (text(&resumed.stdout), text(&resumed.stderr));
    assert!(resumed.status.success(), "{stderr}");
    assert!(stdout.contains("(from step "), "{stdout}");
    assert!(
        stdout.contains("hopper discharge: D = 1.0000e-2 m"),
        "{stdout}"
    );
}
