//! The code base's layout, read from `src/` (issue 33; ARCHITECTURE.md's invariants):
//!
//! * `src/` holds only `lib.rs` and `main.rs` besides its folders;
//! * the top-level modules (`cli`, `pipeline`, the stages `import`, `model`, `fe`, `solve`,
//!   `reduce`, `body`, `write`, and `export`) use each other without a circle; the pipeline
//!   never uses the command line, and no stage reaches up into the pipeline or the command line
//!   (`export` converts finished files, downstream of the pipeline: its `mtx` target rebuilds
//!   the model through the pipeline, as `check --model` does);
//! * no function is longer than [`MAX_FUNCTION_LINES`] lines, but those in
//!   [`LONG_FUNCTIONS`], each with its reason;
//! * no `match` over element kinds has a catch-all arm (`_ =>`, `other =>`): a new
//!   `ElementKind` then fails to compile at every place that must know it (issue 48).
//!
//! A module's uses are its `crate::NAME` paths outside comments, a crate-root re-export of
//! `lib.rs` (`pub use body::{stress, …}`, `pub use pipeline as build`) counting as its module. A
//! function's length is the lines from its `fn` line to the brace that closes its body.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// The longest a function in `src/` may be, in lines.
const MAX_FUNCTION_LINES: usize = 200;

/// Functions allowed to be longer than [`MAX_FUNCTION_LINES`]: (file, function, why).
const LONG_FUNCTIONS: &[(&str, &str, &str)] = &[(
    // ~200 lines: SPCs, rigid elements, T by substitution, the automatic SPCs, in one pass.
    // src/fe/ is being extended concurrently (spring, mass, bush elements): split after.
    "src/fe/constraints.rs",
    "eliminate",
    "in src/fe/, which concurrent element work is changing; split after it lands",
)];

/// The stages: they may use each other, never the pipeline or the command line.
const STAGES: &[&str] = &["import", "model", "fe", "solve", "reduce", "body", "write"];

fn src() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("src")
}

/// Every `.rs` file under `dir`, sorted.
fn rust_files(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    let mut entries: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|e| e.expect("a directory entry").path())
        .collect();
    entries.sort();
    for path in entries {
        if path.is_dir() {
            out.extend(rust_files(&path));
        } else if path.extension().is_some_and(|x| x == "rs") {
            out.push(path);
        }
    }
    out
}

/// `path` relative to the package, `/`-separated (`src/fe/assembly.rs`).
fn shown(path: &Path) -> String {
    let rel = path
        .strip_prefix(env!("CARGO_MANIFEST_DIR"))
        .unwrap_or(path);
    rel.components()
        .map(|c| c.as_os_str().to_string_lossy().into_owned())
        .collect::<Vec<_>>()
        .join("/")
}

/// The top-level module a file belongs to: `src/fe/assembly.rs` → `fe`, `src/lib.rs` → `lib`.
fn top_module(path: &Path) -> String {
    let rel = path.strip_prefix(src()).expect("a file under src/");
    let first = rel.components().next().expect("a path under src/");
    first
        .as_os_str()
        .to_string_lossy()
        .trim_end_matches(".rs")
        .to_owned()
}

/// The text with `//` comments (doc comments included) removed, line by line; string literals
/// are kept as they are (a `//` inside one ends the line early, which only loses text).
fn without_comments(text: &str) -> String {
    text.lines()
        .map(|l| match l.find("//") {
            Some(k) => &l[..k],
            None => l,
        })
        .collect::<Vec<_>>()
        .join("\n")
}

/// The identifiers that follow `prefix` in `code` (`crate::` → `fe`, `pipeline`, …).
fn names_after<'a>(code: &'a str, prefix: &str) -> Vec<&'a str> {
    code.match_indices(prefix)
        .map(|(k, _)| {
            let rest = &code[k + prefix.len()..];
            let end = rest
                .find(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
                .unwrap_or(rest.len());
            &rest[..end]
        })
        .filter(|name| !name.is_empty())
        .collect()
}

/// `lib.rs`'s crate-root re-exports: alias → the top-level module it names
/// (`pub use pipeline as build;`, `pub use body::{damping, …};`, `pub use cli::check;`).
fn root_aliases() -> BTreeMap<String, String> {
    let code = without_comments(&std::fs::read_to_string(src().join("lib.rs")).expect("lib.rs"));
    let mut aliases = BTreeMap::new();
    for statement in code.split(';') {
        let Some(start) = statement.find("pub use ") else {
            continue;
        };
        let used: String = statement[start + "pub use ".len()..]
            .split_whitespace()
            .collect::<Vec<_>>()
            .join(" ");
        if let Some((module, alias)) = used.split_once(" as ") {
            aliases.insert(alias.trim().to_owned(), module.trim().to_owned());
        } else if let Some((module, items)) = used.split_once("::") {
            let items = items.trim_start_matches('{').trim_end_matches('}');
            for item in items.split(',').map(str::trim).filter(|i| !i.is_empty()) {
                let alias = item.rsplit("::").next().unwrap_or(item).trim();
                aliases.insert(alias.to_owned(), module.trim().to_owned());
            }
        }
    }
    aliases
}

/// Module → (module it uses → the files that use it), over the top-level modules of `src/`
/// (`lib.rs` and `main.rs` left out: they only declare and call).
fn module_uses() -> BTreeMap<String, BTreeMap<String, BTreeSet<String>>> {
    let files = rust_files(&src());
    let modules: BTreeSet<String> = files.iter().map(|f| top_module(f)).collect();
    let aliases = root_aliases();
    let mut uses: BTreeMap<String, BTreeMap<String, BTreeSet<String>>> = BTreeMap::new();
    for file in &files {
        let from = top_module(file);
        if from == "lib" || from == "main" {
            continue;
        }
        let code = without_comments(&std::fs::read_to_string(file).expect("a source file"));
        let entry = uses.entry(from.clone()).or_default();
        for name in names_after(&code, "crate::") {
            let to = aliases.get(name).map_or(name, String::as_str);
            if to != from && modules.contains(to) {
                entry.entry(to.to_owned()).or_default().insert(shown(file));
            }
        }
    }
    uses
}

/// A circle in `uses`, as the modules along it (first = last), if there is one.
fn find_circle(uses: &BTreeMap<String, BTreeMap<String, BTreeSet<String>>>) -> Option<Vec<String>> {
    // Depth-first search; `path` is the chain being explored.
    fn visit(
        module: &str,
        uses: &BTreeMap<String, BTreeMap<String, BTreeSet<String>>>,
        path: &mut Vec<String>,
        done: &mut BTreeSet<String>,
    ) -> Option<Vec<String>> {
        if let Some(k) = path.iter().position(|m| m == module) {
            let mut circle = path[k..].to_vec();
            circle.push(module.to_owned());
            return Some(circle);
        }
        if done.contains(module) {
            return None;
        }
        path.push(module.to_owned());
        for next in uses.get(module).into_iter().flat_map(|u| u.keys()) {
            if let Some(circle) = visit(next, uses, path, done) {
                return Some(circle);
            }
        }
        path.pop();
        done.insert(module.to_owned());
        None
    }
    let mut done = BTreeSet::new();
    uses.keys()
        .find_map(|m| visit(m, uses, &mut Vec::new(), &mut done))
}

#[test]
fn src_root_holds_only_lib_and_main() {
    let mut loose: Vec<String> = std::fs::read_dir(src())
        .expect("src/")
        .map(|e| e.expect("a directory entry").path())
        .filter(|p| p.is_file())
        .map(|p| shown(&p))
        .filter(|p| p != "src/lib.rs" && p != "src/main.rs")
        .collect();
    loose.sort();
    assert!(
        loose.is_empty(),
        "src/ holds files besides lib.rs and main.rs (put each in the folder of its stage, \
         pipeline/ or cli/): {loose:?}"
    );
}

#[test]
fn no_import_circle_between_cli_pipeline_and_stages() {
    let uses = module_uses();
    for module in ["cli", "pipeline", "import", "fe", "reduce"] {
        assert!(
            uses.contains_key(module),
            "no module {module} found in src/"
        );
    }
    if let Some(circle) = find_circle(&uses) {
        let steps: Vec<String> = circle
            .windows(2)
            .map(|w| {
                let files = &uses[&w[0]][&w[1]];
                format!("{} → {} (in {files:?})", w[0], w[1])
            })
            .collect();
        panic!(
            "the modules use each other in a circle: {}",
            steps.join("; ")
        );
    }
    let reaching_up: Vec<String> = uses
        .iter()
        .flat_map(|(from, to)| to.iter().map(move |(to, files)| (from, to, files)))
        .filter(|(from, to, _)| {
            (from.as_str() == "pipeline" && to.as_str() == "cli")
                || (STAGES.contains(&from.as_str()) && matches!(to.as_str(), "pipeline" | "cli"))
        })
        .map(|(from, to, files)| format!("{from} → {to} (in {files:?})"))
        .collect();
    assert!(
        reaching_up.is_empty(),
        "a stage reaches up into the pipeline or the command line, or the pipeline into the \
         command line: {reaching_up:?}"
    );
}

/// The functions of `text`: (name, first line, lines from the `fn` line to its closing brace).
/// Bodiless declarations (`fn f();`) are left out.
fn functions(text: &str) -> Vec<(String, usize, usize)> {
    let lines: Vec<&str> = text.lines().collect();
    let mut out = Vec::new();
    for (start, line) in lines.iter().enumerate() {
        let Some(name) = fn_name(line) else {
            continue;
        };
        let mut depth = 0usize;
        let mut opened = false;
        let mut in_string = false;
        'lines: for (k, l) in lines.iter().enumerate().skip(start) {
            for c in code_chars(l, &mut in_string) {
                match c {
                    '{' => {
                        depth += 1;
                        opened = true;
                    }
                    '}' => {
                        depth = depth.saturating_sub(1);
                        if opened && depth == 0 {
                            out.push((name.clone(), start + 1, k - start + 1));
                            break 'lines;
                        }
                    }
                    ';' if !opened => break 'lines,
                    _ => {}
                }
            }
        }
    }
    out
}

/// The function a line declares: `[pub[(…)]] [const] [async] [unsafe] [extern "C"] fn NAME`.
fn fn_name(line: &str) -> Option<String> {
    let mut rest = line.trim_start();
    loop {
        let before = rest;
        if let Some(r) = rest.strip_prefix("pub") {
            rest = r.trim_start();
            if let Some(r) = rest.strip_prefix('(') {
                rest = r.split_once(')')?.1.trim_start();
            }
        }
        for word in ["const ", "async ", "unsafe ", "extern \"C\" "] {
            if let Some(r) = rest.strip_prefix(word) {
                rest = r.trim_start();
            }
        }
        if rest == before {
            break;
        }
    }
    let rest = rest.strip_prefix("fn ")?;
    let end = rest
        .find(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
        .unwrap_or(rest.len());
    (end > 0).then(|| rest[..end].to_owned())
}

/// The characters of a line that are code: string and character literals and `//` comments
/// dropped (enough to count braces). `in_string` carries a string literal over line ends.
fn code_chars(line: &str, in_string: &mut bool) -> Vec<char> {
    let chars: Vec<char> = line.chars().collect();
    let mut out = Vec::new();
    let mut k = 0;
    while k < chars.len() {
        if *in_string {
            match chars[k] {
                '\\' => k += 1,
                '"' => *in_string = false,
                _ => {}
            }
            k += 1;
            continue;
        }
        match chars[k] {
            '/' if chars.get(k + 1) == Some(&'/') => break,
            '"' => *in_string = true,
            // a character literal ('{', '"'), not a lifetime ('a)
            '\'' if chars.get(k + 2) == Some(&'\'') => k += 2,
            // an escaped one ('\n', '\'', '\u{7b}')
            '\'' if chars.get(k + 1) == Some(&'\\') => {
                k += 2;
                while k + 1 < chars.len() && chars[k + 1] != '\'' {
                    k += 1;
                }
                k += 1;
            }
            c => out.push(c),
        }
        k += 1;
    }
    out
}

#[test]
fn function_length_counter_reads_bodies_declarations_and_literals() {
    let text = "pub(crate) fn a() {\n    let c = '{';\n    let s = \"}}\\\n  {\";\n    \
                let q = '\\'';\n}\nfn b();\nimpl X {\n    \
                pub const fn c<'a>(x: &'a str) -> &'a str { x }\n}\n";
    let found = functions(text);
    assert_eq!(
        found,
        vec![("a".into(), 1, 6), ("c".into(), 9, 1)],
        "{found:?}"
    );
}

#[test]
fn no_function_over_200_lines_but_the_listed_ones() {
    let mut long = Vec::new();
    let mut listed_found = BTreeSet::new();
    for file in rust_files(&src()) {
        let text = std::fs::read_to_string(&file).expect("a source file");
        let path = shown(&file);
        for (name, line, length) in functions(&text) {
            if length <= MAX_FUNCTION_LINES {
                continue;
            }
            if LONG_FUNCTIONS
                .iter()
                .any(|(f, n, _)| *f == path && *n == name)
            {
                listed_found.insert((path.clone(), name));
            } else {
                long.push(format!("{path}:{line} fn {name}: {length} lines"));
            }
        }
    }
    assert!(
        long.is_empty(),
        "functions over {MAX_FUNCTION_LINES} lines (split them by what they do, or list them in \
         LONG_FUNCTIONS with the reason): {long:#?}"
    );
    // The list keeps only what is still long: a function split since is taken off it.
    let stale: Vec<&(&str, &str, &str)> = LONG_FUNCTIONS
        .iter()
        .filter(|(f, n, _)| !listed_found.contains(&(f.to_string(), n.to_string())))
        .collect();
    assert!(
        stale.is_empty(),
        "LONG_FUNCTIONS lists functions that are no longer over {MAX_FUNCTION_LINES} lines (or \
         no longer exist): take them off the list: {stale:?}"
    );
}

/// The variants of `ElementKind`, read from `src/model/mod.rs`.
fn element_kinds() -> Vec<String> {
    let text = std::fs::read_to_string(src().join("model/mod.rs")).expect("model/mod.rs");
    let code = without_comments(&text);
    let start = code
        .find("pub enum ElementKind {")
        .expect("the ElementKind enum");
    let body = &code[start..];
    let body = &body[body.find('{').expect("its brace") + 1..body.find('}').expect("its end")];
    body.split(',')
        .map(|v| v.trim().to_owned())
        .filter(|v| !v.is_empty())
        .collect()
}

/// The arm of a catch-all: `_ =>`, `_ if … =>` or a lone binding (`other =>`).
fn is_catch_all_arm(line: &str) -> bool {
    let head = line.split("=>").next().unwrap_or("");
    let pattern = head.split(" if ").next().unwrap_or("").trim();
    line.contains("=>")
        && !pattern.is_empty()
        && pattern
            .chars()
            .all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || c == '_')
        && pattern.starts_with(|c: char| c.is_ascii_lowercase() || c == '_')
}

/// Does this arm line name an element kind (`ElementKind::Tet4`, `| Hex8`, or a bare variant
/// under `use ElementKind::*`)?
fn names_element_kind(line: &str, kinds: &[String]) -> bool {
    let t = line.trim_start().trim_start_matches('|').trim_start();
    t.starts_with("ElementKind::")
        || kinds.iter().any(|k| {
            t.strip_prefix(k.as_str())
                .is_some_and(|rest| rest.starts_with([' ', '|', '=', ',']) || rest.is_empty())
        })
}

/// The catch-all arms over element kinds in `text`: a catch-all arm line whose sibling arms
/// (the lines at its indentation up to the enclosing lines of smaller indentation) name an
/// element kind. Reads rustfmt's layout: arms, their `|` continuations and closing braces at
/// one indentation.
fn element_kind_catch_alls(text: &str, kinds: &[String]) -> Vec<usize> {
    let code = without_comments(text);
    let lines: Vec<&str> = code.lines().collect();
    let indent = |l: &str| l.len() - l.trim_start().len();
    let mut found = Vec::new();
    for (i, line) in lines.iter().enumerate() {
        if line.trim().is_empty() || !is_catch_all_arm(line) {
            continue;
        }
        let level = indent(line);
        let mut siblings = Vec::new();
        for range in [
            &mut (0..i).rev() as &mut dyn Iterator<Item = usize>,
            &mut (i + 1..lines.len()),
        ] {
            for j in range {
                let l = lines[j];
                if l.trim().is_empty() || indent(l) > level {
                    continue;
                }
                if indent(l) < level {
                    break;
                }
                siblings.push(l);
            }
        }
        if siblings.iter().any(|l| names_element_kind(l, kinds)) {
            found.push(i + 1);
        }
    }
    found
}

#[test]
fn catch_all_reader_finds_arms_over_element_kinds_only() {
    let kinds = vec!["Tet4".to_owned(), "Hex8".to_owned()];
    let over_kinds =
        "fn f(k: ElementKind) -> u8 {\n    match k {\n        ElementKind::Tet4\n        \
                      | ElementKind::Hex8 => 1,\n        _ => 0,\n    }\n}\n";
    assert_eq!(element_kind_catch_alls(over_kinds, &kinds), vec![5]);
    let bare = "match k {\n    Tet4 => {\n        1\n    }\n    other => g(other),\n}\n";
    assert_eq!(element_kind_catch_alls(bare, &kinds), vec![5]);
    let other_enum = "match s {\n    Section::Rod { a } => a,\n    _ => 0,\n}\n";
    assert!(element_kind_catch_alls(other_enum, &kinds).is_empty());
    let exhaustive = "match k {\n    ElementKind::Tet4 => 1,\n    ElementKind::Hex8 => 2,\n}\n";
    assert!(element_kind_catch_alls(exhaustive, &kinds).is_empty());
}

#[test]
fn no_catch_all_arm_over_element_kinds() {
    let kinds = element_kinds();
    assert!(kinds.len() > 10, "{kinds:?}");
    let mut found = Vec::new();
    for file in rust_files(&src()) {
        let text = std::fs::read_to_string(&file).expect("a source file");
        for line in element_kind_catch_alls(&text, &kinds) {
            found.push(format!("{}:{line}", shown(&file)));
        }
    }
    assert!(
        found.is_empty(),
        "catch-all arms over ElementKind (list the kinds, so that a new kind fails to compile \
         where it must be handled): {found:#?}"
    );
}
