//! The repository is whole on its own (issue 31): a fresh clone runs the README's two commands
//! with nothing beside it. These tests read the repository's own files.

use std::path::{Path, PathBuf};

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

fn read(rel: &str) -> String {
    std::fs::read_to_string(root().join(rel)).unwrap_or_else(|e| panic!("{rel}: {e}"))
}

/// The first lines of README.md's first code block: the commands a new user runs.
fn readme_commands() -> Vec<String> {
    let readme = read("README.md");
    let block = readme
        .split("```sh\n")
        .nth(1)
        .and_then(|b| b.split("```").next())
        .expect("README.md opens with a ```sh block");
    block.lines().map(str::to_owned).collect()
}

/// `pip install ./python` works from a copy of the folder: the package holds the reference
/// reader as a file (not a link out of the folder), byte for byte the spec's.
#[test]
fn the_python_package_holds_the_reference_reader_itself() {
    let spec = root().join("python/flexbody/_spec.py");
    let meta = std::fs::symlink_metadata(&spec).unwrap();
    assert!(
        !meta.file_type().is_symlink(),
        "{} is a link",
        spec.display()
    );
    assert!(
        std::fs::read(&spec).unwrap()
            == std::fs::read(root().join("format-spec/reference_reader.py")).unwrap(),
        "python/flexbody/_spec.py differs from format-spec/reference_reader.py: copy it again"
    );
}

/// README's second command is the test command `.ci/run` runs; the file the first command
/// writes is ignored by git.
#[test]
fn readme_commands_are_what_ci_runs_and_leave_the_tree_clean() {
    let cmds = readme_commands();
    assert!(cmds.len() >= 2, "{cmds:?}");
    assert!(
        cmds[0].starts_with("cargo run --release -- build "),
        "{}",
        cmds[0]
    );
    assert_eq!(cmds[1], "cargo test --workspace --release");
    let ci = read(".ci/run");
    assert!(
        ci.lines().any(|l| l.trim() == cmds[1]),
        ".ci/run does not run `{}`",
        cmds[1]
    );
    let output = cmds[0]
        .split_whitespace()
        .skip_while(|w| *w != "-o")
        .nth(1)
        .expect("the first command names its output with -o");
    let ignore = read(".gitignore");
    let ignored = ignore.lines().any(|l| {
        let l = l.trim();
        l == format!("/{output}")
            || (l.starts_with("/*.") && output.ends_with(&l[2..]) && !output.contains('/'))
    });
    assert!(ignored, ".gitignore does not cover {output}");
}

/// Test data lives in the repository; outside data (not redistributable) is reached only
/// through `tests/common`'s `external_reference`, which says SKIPPED without it.
#[test]
fn tests_reach_outside_data_only_through_the_skipping_helper() {
    let mut offenders = Vec::new();
    let mut stack: Vec<PathBuf> = vec![root().join("tests"), root().join("src")];
    while let Some(dir) = stack.pop() {
        for entry in std::fs::read_dir(&dir).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                stack.push(path);
            } else if path.extension().is_some_and(|e| e == "rs")
                && !path.ends_with("tests/common/mod.rs")
                && !path.ends_with("tests/repository_files.rs")
            {
                let text = std::fs::read_to_string(&path).unwrap();
                for (k, line) in text.lines().enumerate() {
                    if line.contains("\"../shared") || line.contains("\"/work/shared") {
                        offenders.push(format!("{}:{}", path.display(), k + 1));
                    }
                }
            }
        }
    }
    assert!(
        offenders.is_empty(),
        "paths outside the repository: {offenders:?}"
    );
}

/// Every skip goes through `tests/common`'s `skipped` / `skipped_install` (printed past the
/// harness's capture, counted by `.ci/run`, a failure under `CI=true` for what `.ci/run`
/// installs): no test prints its own skip line with `println!`/`eprintln!`, which a passing run
/// never shows.
#[test]
fn skips_go_through_the_common_helper() {
    let mut offenders = Vec::new();
    for entry in std::fs::read_dir(root().join("tests")).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_none_or(|e| e != "rs") || path.ends_with("repository_files.rs") {
            continue;
        }
        let text = std::fs::read_to_string(&path).unwrap();
        for (at, _) in text.match_indices("println!(") {
            // the macro's arguments: up to the first `);` after it
            let call = &text[at..];
            let call = &call[..call.find(");").unwrap_or(call.len())];
            if call.to_ascii_lowercase().contains("skip") {
                let line = text[..at].matches('\n').count() + 1;
                offenders.push(format!("{}:{line}", path.display()));
            }
        }
    }
    assert!(
        offenders.is_empty(),
        "skips printed without crate::common::skipped: {offenders:?}"
    );
}
