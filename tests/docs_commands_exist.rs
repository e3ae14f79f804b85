//! Every `mdr-dem` command line that README.md and docs/*.md show, in their code blocks and in
//! inline code that starts with `mdr-dem ` or a subcommand, names subcommands and flags that the
//! program has:
//! each subcommand is listed by its parent's `--help` and each `--flag` by the subcommand's
//! `--help`. A made-up flag or subcommand is caught (the negative controls below).

mod common;

use common::mdr_dem;
use std::collections::HashMap;
use std::path::{Path, PathBuf};

fn repo() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// README.md and every docs/*.md.
fn documents() -> Vec<PathBuf> {
    let mut docs: Vec<PathBuf> = std::fs::read_dir(repo().join("docs"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "md"))
        .collect();
    docs.sort();
    docs.insert(0, repo().join("README.md"));
    docs
}

/// The program's subcommands, which inline code may name without the program (`sim run …`).
const TOP_LEVEL: [&str; 4] = ["impact", "sim", "bench", "verify"];

/// The `mdr-dem` invocations of a Markdown text, each as its arguments after the program name:
/// the lines of fenced code blocks (continuation lines joined, `#` comments dropped) and inline
/// code spans starting with `mdr-dem ` or with a subcommand of [`TOP_LEVEL`]. `cargo run [--release] -- ARGS` counts as `mdr-dem
/// ARGS` where it runs the workspace's own program (no `-p`, `--example` or `--bin` of another).
fn invocations(text: &str) -> Vec<Vec<String>> {
    let mut found = Vec::new();
    let mut in_block = false;
    let mut pending = String::new();
    for line in text.lines() {
        if line.trim_start().starts_with("```") {
            in_block = !in_block;
            pending.clear();
            continue;
        }
        if in_block {
            if let Some(head) = line.trim_end().strip_suffix('\\') {
                pending.push_str(head);
                pending.push(' ');
                continue;
            }
            let joined = std::mem::take(&mut pending) + line;
            let code = joined.split(" #").next().unwrap_or("");
            found.extend(invocations_in_command(code));
        } else {
            for (k, span) in line.split('`').enumerate() {
                if k % 2 == 0 {
                    continue;
                }
                if span.starts_with("mdr-dem ") {
                    found.extend(invocations_in_command(span));
                } else if TOP_LEVEL.iter().any(|c| span.starts_with(&format!("{c} "))) {
                    found.extend(invocations_in_command(&format!("mdr-dem {span}")));
                }
            }
        }
    }
    found
}

/// The invocations in one shell command line (several where it chains commands).
fn invocations_in_command(code: &str) -> Vec<Vec<String>> {
    let mut found = Vec::new();
    for part in code
        .split(['|', ';', '>', '<', '(', ')'])
        .flat_map(|p| p.split("&&"))
    {
        let words: Vec<&str> = part.split_whitespace().collect();
        let program = words.iter().position(|w| {
            Path::new(w.trim_matches(['"', '\'']))
                .file_name()
                .is_some_and(|name| name == "mdr-dem")
        });
        let args: Option<&[&str]> = match program {
            Some(i) => Some(&words[i + 1..]),
            None => cargo_run_args(&words),
        };
        if let Some(args) = args {
            found.push(args.iter().map(|s| s.to_string()).collect());
        }
    }
    found
}

/// The program's arguments of `cargo run [--release] [-- ARGS]` of the workspace's own program.
fn cargo_run_args<'a>(words: &'a [&'a str]) -> Option<&'a [&'a str]> {
    let start = words.windows(2).position(|w| w == ["cargo", "run"])?;
    let rest = &words[start + 2..];
    let split = rest.iter().position(|w| *w == "--").unwrap_or(rest.len());
    let cargo_flags = &rest[..split];
    if cargo_flags
        .iter()
        .any(|f| matches!(*f, "-p" | "--package" | "--example" | "--bin"))
    {
        return None;
    }
    Some(rest.get(split + 1..).unwrap_or(&[]))
}

/// The `--help` texts of the subcommands, asked once each.
#[derive(Default)]
struct Help(HashMap<Vec<String>, String>);

impl Help {
    fn of(&mut self, path: &[String]) -> &str {
        self.0.entry(path.to_vec()).or_insert_with(|| {
            let mut args: Vec<&str> = path.iter().map(String::as_str).collect();
            args.push("--help");
            let out = mdr_dem(&args);
            assert!(out.status.success(), "mdr-dem {args:?} failed");
            String::from_utf8(out.stdout).unwrap()
        })
    }
}

/// The subcommand names of a `--help` text (its `Commands:` section).
fn subcommands(help: &str) -> Vec<String> {
    help.lines()
        .skip_while(|l| !l.starts_with("Commands:"))
        .skip(1)
        .take_while(|l| l.starts_with("  "))
        .filter_map(|l| l.split_whitespace().next().map(str::to_owned))
        .collect()
}

/// Whether `help` lists the long flag `flag` (`--name`).
fn lists_flag(help: &str, flag: &str) -> bool {
    help.match_indices(flag).any(|(at, _)| {
        let after = help[at + flag.len()..].chars().next();
        let before = help[..at].chars().next_back();
        !after.is_some_and(|c| c.is_ascii_alphanumeric() || c == '-' || c == '_')
            && !before.is_some_and(|c| c.is_ascii_alphanumeric() || c == '-')
    })
}

/// What one invocation names that the program lacks: a word in subcommand position that no
/// subcommand has where the program requires one, or a flag the subcommand's help does not list.
fn missing(help: &mut Help, args: &[String]) -> Vec<String> {
    let mut path: Vec<String> = Vec::new();
    let mut problems = Vec::new();
    let mut in_subcommands = true;
    for arg in args {
        let arg = arg.trim_matches(['"', '\'', ',', '.']);
        if in_subcommands && !arg.starts_with('-') {
            let known = subcommands(help.of(&path));
            if known.iter().any(|c| c == arg) {
                path.push(arg.to_owned());
                continue;
            }
            // A word where a subcommand is required (a group's help lists commands and takes
            // no positional argument).
            let group = !known.is_empty() && !help.of(&path).contains("Arguments:");
            if group && path.len() < 2 && arg.chars().all(|c| c.is_ascii_lowercase() || c == '-') {
                problems.push(format!(
                    "subcommand `{}`",
                    [&path[..], &[arg.to_owned()]].concat().join(" ")
                ));
                return problems;
            }
            in_subcommands = false;
        }
        if let Some(flag) = arg.strip_prefix("--") {
            let name = format!("--{}", flag.split('=').next().unwrap_or(""));
            if name.len() > 2
                && name[2..]
                    .chars()
                    .all(|c| c.is_ascii_alphanumeric() || c == '-')
                && !lists_flag(help.of(&path), &name)
            {
                problems.push(format!("`mdr-dem {} {name}`", path.join(" ")));
            }
            in_subcommands = false;
        } else if arg.starts_with('-') {
            in_subcommands = false;
        }
    }
    problems
}

#[test]
fn every_documented_command_line_names_existing_subcommands_and_flags() {
    let mut help = Help::default();
    let mut problems = Vec::new();
    let mut checked = 0;
    for doc in documents() {
        let text = std::fs::read_to_string(&doc).unwrap();
        for args in invocations(&text) {
            checked += 1;
            for p in missing(&mut help, &args) {
                let name = doc.strip_prefix(repo()).unwrap().display();
                problems.push(format!("{name}: {p} in `mdr-dem {}`", args.join(" ")));
            }
        }
    }
    // The docs show about 140 command lines; far fewer means the parser lost them.
    assert!(checked > 110, "only {checked} command lines found");
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}

#[test]
fn a_made_up_flag_or_subcommand_is_caught() {
    let mut help = Help::default();
    let text = "```sh\nmdr-dem impact curve --v-max 2 --no-such-flag 3\n```\n\
                Inline: `mdr-dem sim run scenes/drop.toml --frobnicate`, `mdr-dem impact \
                wobble --v0 1` and `verify --plott DIR`.\n```sh\ncargo run --release -- bench bed \
                --not-a-flag\n```\n";
    let found: Vec<Vec<String>> = invocations(text);
    assert_eq!(found.len(), 5, "{found:?}");
    let problems: Vec<String> = found
        .iter()
        .flat_map(|args| missing(&mut help, args))
        .collect();
    assert_eq!(
        problems,
        [
            "`mdr-dem impact curve --no-such-flag`",
            "`mdr-dem sim run --frobnicate`",
            "subcommand `impact wobble`",
            "`mdr-dem verify --plott`",
            "`mdr-dem bench bed --not-a-flag`",
        ]
    );
}

#[test]
fn existing_flags_pass() {
    let mut help = Help::default();
    let text = "```sh\nmdr-dem impact curve --v-max 2 --law mdr \\\n  --qc 1e5\n\
                ./target/release/mdr-dem sim run scenes/drop.toml --out out/drop  # comment --x\n```\n";
    let found = invocations(text);
    assert_eq!(found.len(), 2, "{found:?}");
    for args in &found {
        assert!(missing(&mut help, args).is_empty(), "{args:?}");
    }
}
