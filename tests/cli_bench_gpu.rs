//! `mdr-dem bench bed --device gpu`: the JSON contract (the CPU benchmark's keys, `device`, the
//! GPU's figures and `max_position_difference_diameters` under `--compare-cpu`), and
//! `--compare-cpu` refused without the GPU. Needs a Vulkan device with 64-bit floats (lavapipe
//! on a machine without a GPU, docs/gpu.md); without one the run fails with the error naming
//! what is missing.

use std::process::Command;

fn mdr_dem(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_mdr-dem"))
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .unwrap()
}

#[test]
fn bench_bed_on_the_gpu_keeps_the_json_contract_and_matches_the_cpu_path() {
    let out = mdr_dem(&[
        "bench",
        "bed",
        "--device",
        "gpu",
        "--law",
        "mdr",
        "--steps",
        "5",
        "--warmup",
        "2",
        "--compare-cpu",
        "--json",
    ]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    for key in [
        "particle_steps_per_s",
        "ms_per_step",
        "contacts_per_particle",
        "law",
        "particles",
        "steps",
        "rebuilds",
        "floor_contacts",
        "plastic_contact_fraction",
        "state_checksum",
        "gpu_adapter",
        "device_bytes_per_particle",
    ] {
        assert!(v.get(key).is_some(), "{key} in {v}");
    }
    assert_eq!(v["device"], "gpu");
    assert_eq!(v["particles"], 10_000);
    assert!(v["contacts_per_particle"].as_f64().unwrap() > 4.0, "{v}");
    assert!(
        v["device_bytes_per_particle"].as_f64().unwrap() < 1024.0,
        "{v}"
    );
    // Measured on lavapipe: 0 after 7 steps.
    let d = v["max_position_difference_diameters"].as_f64().unwrap();
    assert!(d < 1e-13, "{v}");
}

#[test]
fn compare_cpu_needs_the_gpu_and_the_cpu_json_names_its_device() {
    let out = mdr_dem(&[
        "bench",
        "bed",
        "--steps",
        "1",
        "--warmup",
        "0",
        "--compare-cpu",
    ]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("--device gpu"));
    let out = mdr_dem(&["bench", "bed", "--steps", "1", "--warmup", "0", "--json"]);
    assert!(out.status.success());
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["device"], "cpu");
}

/// The GPU path's other laws and rolling resistance from the command line: the figures name
/// the law, and the run matches the CPU path of the same contact model.
#[test]
fn bench_bed_on_the_gpu_runs_thornton_adhesion_and_rolling() {
    for (law, extra) in [
        ("thornton", ["--rolling", "0.2"]),
        ("adhesive-mdr", ["--work-of-adhesion", "2"]),
    ] {
        let mut args = vec![
            "bench",
            "bed",
            "--device",
            "gpu",
            "--law",
            law,
            "--steps",
            "5",
            "--warmup",
            "2",
            "--compare-cpu",
            "--json",
        ];
        args.extend(extra);
        let out = mdr_dem(&args);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(out.status.success(), "{law}: {stderr}");
        let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        assert_eq!(v["law"], law, "{v}");
        let d = v["max_position_difference_diameters"].as_f64().unwrap();
        assert!(d < 1e-13, "{law}: {v}");
    }
}

/// A bad law parameter is refused on the GPU path too, naming the flag.
#[test]
fn bad_law_parameters_are_refused_on_the_gpu_by_name() {
    let out = mdr_dem(&[
        "bench",
        "bed",
        "--device",
        "gpu",
        "--law",
        "thornton",
        "--yield-stress=-1",
        "--steps",
        "1",
    ]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert!(stderr.contains("--yield-stress"), "{stderr}");
}
