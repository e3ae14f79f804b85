//! The repository stands alone: no document, source file or script sends the reader outside it
//! (`../shared`, a `model.md` that is not in the repository) or cites a work-item number
//! (`issue 8`, `(#6)`, `#13`) that means nothing to someone reading the code; and
//! `mdr-dem bench bed` runs with its defaults in a copy of the repository that has nothing
//! beside it.

use std::path::{Path, PathBuf};
use std::process::Command;

/// The repository root (this package's manifest directory).
fn repo() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// The files of the repository, relative to its root: `git ls-files` where git and the history
/// are available, else a walk that skips `target/` and `.git/`.
fn repository_files() -> Vec<PathBuf> {
    let listed = Command::new("git")
        .args(["ls-files", "-z"])
        .current_dir(repo())
        .output();
    if let Ok(out) = listed {
        if out.status.success() && !out.stdout.is_empty() {
            return out
                .stdout
                .split(|&b| b == 0)
                .filter(|name| !name.is_empty())
                .map(|name| PathBuf::from(String::from_utf8_lossy(name).into_owned()))
                .filter(|p| repo().join(p).is_file())
                .collect();
        }
    }
    let mut files = Vec::new();
    walk(repo(), Path::new(""), &mut files);
    files
}

fn walk(root: &Path, rel: &Path, files: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(root.join(rel)) else {
        return;
    };
    for entry in entries.flatten() {
        let name = entry.file_name();
        if rel.as_os_str().is_empty() && (name == "target" || name == ".git") {
            continue;
        }
        let path = rel.join(&name);
        match entry.file_type() {
            Ok(t) if t.is_dir() => walk(root, &path, files),
            Ok(t) if t.is_file() => files.push(path),
            _ => {}
        }
    }
}

/// Documents, sources, tests and scripts: everything under these roots except pictures, fonts
/// and data files.
fn is_checked_text(path: &Path) -> bool {
    const ROOTS: [&str; 7] = [
        "docs", "crates", "src", "tests", "benches", "examples", "scenes",
    ];
    const SKIPPED: [&str; 13] = [
        "svg", "png", "jpg", "gif", "ttf", "otf", "woff", "data", "csv", "lock", "mdrck", "stl",
        "obj",
    ];
    let first = path
        .components()
        .next()
        .and_then(|c| c.as_os_str().to_str());
    let in_scope = path == Path::new("README.md") || first.is_some_and(|f| ROOTS.contains(&f));
    let extension = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    in_scope && !extension.is_some_and(|e| SKIPPED.contains(&e.as_str()))
}

/// What a line names that it should not, if anything.
fn offence(line: &str) -> Option<&'static str> {
    if line.contains("../shared") || line.contains("shared/bench/") {
        return Some("a path outside the repository (`../shared`)");
    }
    if line.contains("model.md") {
        return Some("`model.md`, which is not in the repository (use `docs/theory.md` §n)");
    }
    if cites_issue_number(line) {
        return Some("a work-item number (`issue N`)");
    }
    if cites_hash_number(line) {
        return Some("a work-item number (`#N`)");
    }
    None
}

/// `issue 8`, `Issue 7`, `issues 3`, `issue #6`, `issue-6`.
fn cites_issue_number(line: &str) -> bool {
    let lower = line.to_ascii_lowercase();
    let bytes = lower.as_bytes();
    lower.match_indices("issue").any(|(at, _)| {
        let mut i = at + "issue".len();
        if bytes.get(i) == Some(&b's') {
            i += 1;
        }
        while matches!(bytes.get(i), Some(b' ' | b'-' | b'\t')) {
            i += 1;
        }
        if bytes.get(i) == Some(&b'#') {
            i += 1;
        }
        bytes.get(i).is_some_and(u8::is_ascii_digit)
    })
}

/// `#13` or `(#6)` in prose: a `#` not preceded by a word character, `&`, `#`, `$`, `/` or `\`
/// and followed by digits that end the word (so `#[derive]`, `#!`, `## Heading`, `&#123;`, `$#`
/// and hex colours such as `#1f77b4` do not count).
fn cites_hash_number(line: &str) -> bool {
    let bytes = line.as_bytes();
    bytes.iter().enumerate().any(|(at, &b)| {
        if b != b'#' {
            return false;
        }
        let before_ok = at == 0 || {
            let p = bytes[at - 1];
            !(p.is_ascii_alphanumeric() || matches!(p, b'_' | b'&' | b'#' | b'$' | b'/' | b'\\'))
        };
        let digits = bytes[at + 1..]
            .iter()
            .take_while(|c| c.is_ascii_digit())
            .count();
        let after = bytes.get(at + 1 + digits);
        before_ok && digits > 0 && !after.is_some_and(|c| c.is_ascii_alphanumeric() || *c == b'_')
    })
}

#[test]
fn the_matchers_catch_citations_and_spare_code() {
    for cited in [
        "see issue 8",
        "(Issue 7)",
        "issues 3 and 4",
        "issue #6",
        "the issue-6 changes",
        "fixed in (#6)",
        "#13 in prose",
        "the reference is `../shared/bench/lammps/`",
        "Path::new(\"shared/bench/lammps/settled.data\")",
        "closed form (model.md §4)",
    ] {
        assert!(offence(cited).is_some(), "missed: {cited}");
    }
    for clean in [
        "#[derive(Debug)]",
        "#![warn(missing_docs)]",
        "## 4. Closed form",
        "fill=\"#1f77b4\"",
        "echo $#",
        "the issue is the time step",
        "an issue with 2 threads",
        "docs/theory.md §4",
        "println!(\"{:#?}\", x)",
    ] {
        assert!(offence(clean).is_none(), "false positive: {clean}");
    }
}

#[test]
fn no_file_names_shared_or_a_work_item_number() {
    let mut found = Vec::new();
    // This file spells out the patterns it looks for, so it is the one file not checked.
    let this_file = Path::new(file!());
    for path in repository_files()
        .into_iter()
        .filter(|p| is_checked_text(p) && p != this_file)
    {
        let Ok(text) = std::fs::read_to_string(repo().join(&path)) else {
            continue; // not UTF-8 text: a binary file
        };
        for (number, line) in text.lines().enumerate() {
            if let Some(what) = offence(line) {
                found.push(format!(
                    "{}:{}: names {what}: {}",
                    path.display(),
                    number + 1,
                    line.trim()
                ));
            }
        }
    }
    assert!(
        found.is_empty(),
        "{} lines send the reader outside the repository or cite a work-item number (name the \
         feature instead):\n{}",
        found.len(),
        found.join("\n")
    );
}

/// A fresh directory under the system's temporary directory, removed on drop.
struct TempDir(PathBuf);

impl TempDir {
    fn new(tag: &str) -> TempDir {
        let nanos = std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .map_or(0, |d| d.as_nanos());
        let path =
            std::env::temp_dir().join(format!("mdr-dem-{tag}-{}-{nanos}", std::process::id()));
        std::fs::create_dir_all(&path).expect("create a temporary directory");
        TempDir(path)
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

#[test]
fn bench_bed_runs_with_its_defaults_in_a_lone_copy() {
    let outside = TempDir::new("stands-alone");
    // The copy sits alone in its own directory: nothing beside it, nothing above it but /tmp.
    let copy = outside.0.join("mdr-dem");
    let files = repository_files();
    assert!(
        files
            .iter()
            .any(|f| f == Path::new("benches/lammps/settled.data")),
        "benches/lammps/settled.data is not part of the repository"
    );
    for file in &files {
        let target = copy.join(file);
        std::fs::create_dir_all(target.parent().unwrap()).unwrap();
        std::fs::copy(repo().join(file), &target)
            .unwrap_or_else(|e| panic!("copying {}: {e}", file.display()));
    }
    let output = Command::new(env!("CARGO_BIN_EXE_mdr-dem"))
        .args(["bench", "bed", "--steps", "10"])
        .current_dir(&copy)
        .output()
        .expect("run mdr-dem");
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(
        output.status.success(),
        "`mdr-dem bench bed --steps 10` failed in a lone copy of the repository:\n{}{}",
        stdout,
        String::from_utf8_lossy(&output.stderr)
    );
    // The default input is the reference bed of benches/lammps: 10,000 spheres.
    assert!(
        stdout.starts_with("bench bed: 10000 spheres"),
        "unexpected output: {stdout}"
    );
}
