//! `mdr-dem verify`: `--test N` runs one test, `--quick` the CI resolution (coarser than the
//! default), `--plot DIR` writes the figures, and a bad test number is refused by its flag.

mod common;

use common::mdr_dem;

use std::process::Output;

fn passed(output: &Output) -> String {
    let text = String::from_utf8_lossy(&output.stdout).into_owned();
    assert!(
        output.status.success(),
        "{text}\n{}",
        String::from_utf8_lossy(&output.stderr)
    );
    text
}

#[test]
fn verify_runs_one_test_writes_its_figures_and_honours_quick() {
    let dir_guard = tempfile::tempdir().unwrap();
    let dir = dir_guard.path().to_path_buf();
    let _ = std::fs::remove_dir_all(&dir);
    let quick = passed(&mdr_dem(&[
        "verify",
        "--test",
        "1",
        "--quick",
        "--plot",
        dir.to_str().unwrap(),
    ]));
    assert!(
        quick.contains("Test 1:") && quick.contains("PASSED"),
        "{quick}"
    );
    assert!(
        !quick.contains("Test 2:"),
        "--test 1 ran another test: {quick}"
    );
    let figures: Vec<_> = std::fs::read_dir(&dir)
        .expect("--plot folder")
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .collect();
    assert!(!figures.is_empty());
    for name in &figures {
        assert!(
            name.starts_with("verify_test1_") && name.ends_with(".svg"),
            "{name}"
        );
        let svg = std::fs::read_to_string(dir.join(name)).unwrap();
        assert!(svg.contains("<svg"), "{name}");
        assert!(quick.contains(name.as_str()), "figure {name} not reported");
    }
    // The default (full) resolution integrates with more steps: other errors, same verdict.
    let full = passed(&mdr_dem(&["verify", "--test", "1"]));
    assert!(full.contains("PASSED"), "{full}");
    let checks = |text: &str| -> Vec<String> {
        text.lines()
            .filter(|l| !l.contains("figure:"))
            .map(str::to_owned)
            .collect()
    };
    assert_ne!(checks(&quick), checks(&full), "--quick changed nothing");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn verify_refuses_a_test_number_outside_one_to_eight() {
    for bad in ["0", "9"] {
        let output = mdr_dem(&["verify", "--test", bad, "--quick"]);
        assert!(!output.status.success(), "--test {bad} was accepted");
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert!(stderr.contains("--test"), "{stderr}");
    }
}
