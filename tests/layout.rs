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
const LONG_FUNCTIONS: &[(&str, &str, &str)] = &[];

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

// ---------------------------------------------------------------------------------------------
// File-level uses (issue 48): a file's uses are the files its paths resolve to.
//
// A path is `crate::…`, `super::…`, `self::…`, or a child module's name in the file that
// declares it (`stages::file::…` in `pipeline/mod.rs`), `use` groups (`crate::a::{b, c::d}`)
// expanded. It resolves to the deepest module file it names; a name a module re-exports
// (`pub use report::{BuildError, …}`, `pub use pipeline as build`) is followed to the file that
// defines it. `lib.rs` and `main.rs` only declare and call; a file's `#[cfg(test)]` module is
// left out (its `use super::*` is the test's, not the file's). A module's file using the modules
// it declares (`pipeline/mod.rs` calling its stages) is not counted: the children using their
// parent's items is the direction that counts, and a circle is one between siblings.

/// The module tree of `src/`: module path (`["pipeline", "stages", "file"]`) → its file.
fn module_files() -> BTreeMap<Vec<String>, PathBuf> {
    let root = src();
    rust_files(&root)
        .into_iter()
        .filter_map(|file| {
            let rel = file.strip_prefix(&root).ok()?.to_path_buf();
            let mut parts: Vec<String> = rel
                .components()
                .map(|c| c.as_os_str().to_string_lossy().into_owned())
                .collect();
            let last = parts.pop()?;
            match last.as_str() {
                "lib.rs" if parts.is_empty() => {}
                "main.rs" if parts.is_empty() => return None,
                "mod.rs" => {}
                name => parts.push(name.trim_end_matches(".rs").to_owned()),
            }
            Some((parts, file))
        })
        .collect()
}

/// A file's code as its uses are read: comments and its `#[cfg(test)]` module left out.
fn code_of(file: &Path) -> String {
    let text = std::fs::read_to_string(file).expect("a source file");
    let text = match text.find("#[cfg(test)]\nmod ") {
        Some(k) => &text[..k],
        None => &text[..],
    };
    without_comments(text)
}

/// The paths of a `use` tree starting at `code[k..]` (`a::b::{c, d::e}` → `a::b::c`,
/// `a::b::d::e`), each as its segments; `prefix` is what precedes it.
fn path_tree(code: &str, k: usize, prefix: &[String], out: &mut Vec<Vec<String>>) {
    let bytes = code.as_bytes();
    let mut path = prefix.to_vec();
    let mut k = k;
    loop {
        while k < bytes.len() && bytes[k].is_ascii_whitespace() {
            k += 1;
        }
        if k < bytes.len() && bytes[k] == b'{' {
            // a group: its items up to the matching brace, split at top-level commas
            let mut depth = 0;
            let mut start = k + 1;
            for (j, &byte) in bytes.iter().enumerate().skip(k) {
                match byte {
                    b'{' => depth += 1,
                    b'}' | b',' if depth == 1 => {
                        path_tree(code, start, &path, out);
                        start = j + 1;
                        if byte == b'}' {
                            return;
                        }
                    }
                    b'}' => depth -= 1,
                    _ => {}
                }
            }
            return;
        }
        let end = code[k..]
            .find(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
            .map_or(code.len(), |e| k + e);
        if end == k {
            break;
        }
        path.push(code[k..end].to_owned());
        if code[end..].starts_with("::") {
            k = end + 2;
        } else {
            break;
        }
    }
    if !path.is_empty() {
        out.push(path);
    }
}

/// The absolute paths a file's code names: `crate::`, `super::`, `self::` and child-module
/// paths made absolute from `module` (the file's module path).
fn named_paths(code: &str, module: &[String], children: &BTreeSet<String>) -> Vec<Vec<String>> {
    let mut out = Vec::new();
    let bytes = code.as_bytes();
    let word_start = |k: usize| {
        k == 0
            || !(bytes[k - 1].is_ascii_alphanumeric()
                || bytes[k - 1] == b'_'
                || bytes[k - 1] == b':')
    };
    let mut k = 0;
    while k < code.len() {
        if !code.is_char_boundary(k) || !word_start(k) {
            k += 1;
            continue;
        }
        let rest = &code[k..];
        let (base, skip): (Vec<String>, usize) = if rest.starts_with("crate::") {
            (Vec::new(), "crate::".len())
        } else if rest.starts_with("self::") {
            (module.to_vec(), "self::".len())
        } else if rest.starts_with("super::") {
            let mut base = module.to_vec();
            let mut skip = 0;
            while code[k + skip..].starts_with("super::") {
                base.pop();
                skip += "super::".len();
            }
            (base, skip)
        } else if let Some(child) = children
            .iter()
            .find(|c| rest.starts_with(&format!("{c}::")))
        {
            let mut base = module.to_vec();
            base.push(child.clone());
            (base, child.len() + 2)
        } else {
            k += 1;
            continue;
        };
        path_tree(code, k + skip, &base, &mut out);
        k += skip.max(1);
    }
    out
}

/// Module path → (name → the absolute path it re-exports), from each module's `pub use`.
fn re_exports(
    files: &BTreeMap<Vec<String>, PathBuf>,
    children: &BTreeMap<Vec<String>, BTreeSet<String>>,
) -> BTreeMap<Vec<String>, BTreeMap<String, Vec<String>>> {
    let mut out = BTreeMap::new();
    for (module, file) in files {
        let code = code_of(file);
        let mut names = BTreeMap::new();
        for (k, _) in code.match_indices("pub use ") {
            let statement = &code[k + "pub use ".len()..];
            let statement = &statement[..statement.find(';').unwrap_or(statement.len())];
            // `a as b`: the alias names a
            if let Some((used, alias)) = statement.split_once(" as ") {
                let mut target = module.clone();
                target.extend(used.trim().split("::").map(str::to_owned));
                names.insert(alias.trim().to_owned(), target);
                continue;
            }
            let kids = children.get(module).cloned().unwrap_or_default();
            let mut paths = Vec::new();
            // a bare path in a `pub use` is relative to the module (edition 2018: child or crate)
            let with_prefix = if statement.starts_with("crate::")
                || statement.starts_with("super::")
                || statement.starts_with("self::")
            {
                statement.to_owned()
            } else {
                format!("self::{statement}")
            };
            paths.extend(named_paths(&with_prefix, module, &kids));
            for path in paths {
                if let Some(last) = path.last() {
                    names.insert(last.clone(), path);
                }
            }
        }
        out.insert(module.clone(), names);
    }
    out
}

/// The file a path names: the deepest module along it, re-exports followed.
fn resolve(
    path: &[String],
    files: &BTreeMap<Vec<String>, PathBuf>,
    exports: &BTreeMap<Vec<String>, BTreeMap<String, Vec<String>>>,
    depth: usize,
) -> Option<PathBuf> {
    let mut module: Vec<String> = Vec::new();
    for (i, segment) in path.iter().enumerate() {
        let mut next = module.clone();
        next.push(segment.clone());
        if files.contains_key(&next) {
            module = next;
            continue;
        }
        let target = exports.get(&module).and_then(|e| e.get(segment));
        if let (Some(target), true) = (target, depth < 8) {
            let mut followed = target.clone();
            followed.extend(path[i + 1..].iter().cloned());
            if followed != path {
                return resolve(&followed, files, exports, depth + 1);
            }
        }
        break;
    }
    files.get(&module).cloned()
}

/// `file` is the file of a module below `module` (`pipeline/stages/file.rs` below `pipeline`).
fn is_below(file: &Path, module: &[String], files: &BTreeMap<Vec<String>, PathBuf>) -> bool {
    files
        .iter()
        .any(|(m, f)| f == file && m.len() > module.len() && m.starts_with(module))
}

/// File → (file it uses → one path that makes the use), over `src/` (lib.rs and main.rs left
/// out).
fn file_uses() -> BTreeMap<String, BTreeMap<String, String>> {
    let files = module_files();
    let mut children: BTreeMap<Vec<String>, BTreeSet<String>> = BTreeMap::new();
    for module in files.keys().filter(|m| !m.is_empty()) {
        let (name, parent) = module.split_last().expect("a non-empty path");
        children
            .entry(parent.to_vec())
            .or_default()
            .insert(name.clone());
    }
    let exports = re_exports(&files, &children);
    let mut uses: BTreeMap<String, BTreeMap<String, String>> = BTreeMap::new();
    for (module, file) in files.iter().filter(|(m, _)| !m.is_empty()) {
        let from = shown(file);
        let kids = children.get(module).cloned().unwrap_or_default();
        let entry = uses.entry(from.clone()).or_default();
        for path in named_paths(&code_of(file), module, &kids) {
            if let Some(to) = resolve(&path, &files, &exports, 0) {
                if is_below(&to, module, &files) {
                    continue; // a module's file uses the modules it declares: not a circle
                }
                let to = shown(&to);
                if to != from && to != "src/lib.rs" {
                    entry.entry(to).or_insert_with(|| path.join("::"));
                }
            }
        }
    }
    uses
}

/// The circles of `uses`: its strongly connected parts of more than one file (Tarjan).
fn circles(uses: &BTreeMap<String, BTreeMap<String, String>>) -> Vec<Vec<String>> {
    struct Search<'a> {
        uses: &'a BTreeMap<String, BTreeMap<String, String>>,
        index: BTreeMap<&'a str, usize>,
        low: BTreeMap<&'a str, usize>,
        stack: Vec<&'a str>,
        on_stack: BTreeSet<&'a str>,
        parts: Vec<Vec<String>>,
    }
    fn visit<'a>(s: &mut Search<'a>, v: &'a str) {
        let n = s.index.len();
        s.index.insert(v, n);
        s.low.insert(v, n);
        s.stack.push(v);
        s.on_stack.insert(v);
        for w in s.uses.get(v).into_iter().flat_map(|u| u.keys()) {
            let w = w.as_str();
            if !s.index.contains_key(w) {
                visit(s, w);
                let low = s.low[v].min(s.low[w]);
                s.low.insert(v, low);
            } else if s.on_stack.contains(w) {
                let low = s.low[v].min(s.index[w]);
                s.low.insert(v, low);
            }
        }
        if s.low[v] == s.index[v] {
            let mut part = Vec::new();
            while let Some(w) = s.stack.pop() {
                s.on_stack.remove(w);
                part.push(w.to_owned());
                if w == v {
                    break;
                }
            }
            if part.len() > 1 {
                part.sort();
                s.parts.push(part);
            }
        }
    }
    let mut s = Search {
        uses,
        index: BTreeMap::new(),
        low: BTreeMap::new(),
        stack: Vec::new(),
        on_stack: BTreeSet::new(),
        parts: Vec::new(),
    };
    for v in uses.keys() {
        if !s.index.contains_key(v.as_str()) {
            visit(&mut s, v);
        }
    }
    s.parts
}

#[test]
fn file_uses_are_read_from_paths_groups_children_and_re_exports() {
    let uses = file_uses();
    let used = |from: &str, to: &str| uses.get(from).is_some_and(|u| u.contains_key(to));
    // a module's file using the modules it declares is not counted
    assert!(!used(
        "src/pipeline/mod.rs",
        "src/pipeline/stages/reduction.rs"
    ));
    // a re-exported name followed to its file (`pub use spec::{BuildSpec, …}` in pipeline/)
    assert!(used("src/pipeline/plan.rs", "src/pipeline/spec.rs"));
    assert!(used("src/pipeline/plan.rs", "src/pipeline/report.rs"));
    // a `use` group
    assert!(used(
        "src/pipeline/stages/reduction.rs",
        "src/pipeline/scene.rs"
    ));
    // `super::` from a file
    assert!(used("src/cli/build.rs", "src/cli/args.rs"));
    // the circle finder finds a circle
    let mut toy: BTreeMap<String, BTreeMap<String, String>> = BTreeMap::new();
    for (a, b) in [("a", "b"), ("b", "c"), ("c", "a"), ("c", "d")] {
        toy.entry(a.into())
            .or_default()
            .insert(b.into(), String::new());
    }
    assert_eq!(
        circles(&toy),
        vec![vec!["a".to_string(), "b".into(), "c".into()]]
    );
}

/// File-level circles still there, each with its reason: (the files or folders, ending `/`,
/// every file of the circle is in; why). A circle not listed fails, and so does an entry no
/// circle matches any more.
const CIRCLES_LEFT: &[(&[&str], &str)] = &[];

/// Whether every file of `circle` is named by `allowed` (a file, or a folder ending `/`).
fn circle_allowed(circle: &[String], allowed: &[&str]) -> bool {
    circle.iter().all(|file| {
        allowed
            .iter()
            .any(|a| file == a || (a.ends_with('/') && file.starts_with(a)))
    })
}

#[test]
fn no_import_circle_between_files() {
    let uses = file_uses();
    let found = circles(&uses);
    let unlisted: Vec<String> = found
        .iter()
        .filter(|part| !CIRCLES_LEFT.iter().any(|(a, _)| circle_allowed(part, a)))
        .map(|part| {
            let steps: Vec<String> = part
                .iter()
                .flat_map(|from| {
                    uses[from]
                        .iter()
                        .filter(|(to, _)| part.contains(to))
                        .map(move |(to, path)| format!("{from} → {to} ({path})"))
                })
                .collect();
            steps.join("; ")
        })
        .collect();
    assert!(
        unlisted.is_empty(),
        "files use each other in a circle (move the shared type or function below both): \
         {unlisted:#?}"
    );
    let stale: Vec<&str> = CIRCLES_LEFT
        .iter()
        .filter(|(a, _)| !found.iter().any(|part| circle_allowed(part, a)))
        .map(|(_, why)| *why)
        .collect();
    assert!(
        stale.is_empty(),
        "CIRCLES_LEFT lists circles that are gone: take them off the list: {stale:?}"
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

/// The test files `tests/integration.rs` must declare: every `tests/NAME.rs` but itself, and
/// every `tests/NAME/main.rs`, as (module name, path relative to tests/).
fn integration_test_files(tests: &Path) -> Vec<(String, String)> {
    let mut out = Vec::new();
    let mut entries: Vec<PathBuf> = std::fs::read_dir(tests)
        .expect("the tests folder")
        .map(|e| e.expect("a directory entry").path())
        .collect();
    entries.sort();
    for path in entries {
        let name = path
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_default();
        if path.is_dir() && path.join("main.rs").exists() {
            out.push((name.clone(), format!("{name}/main.rs")));
        } else if path.extension().is_some_and(|x| x == "rs") && name != "integration" {
            out.push((name.clone(), format!("{name}.rs")));
        }
    }
    out
}

/// All integration tests are one binary (`autotests = false` in Cargo.toml): a file in tests/
/// that `tests/integration.rs` does not declare would never run, so every one must be declared.
#[test]
fn every_test_file_is_in_the_integration_binary() {
    let tests = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests");
    let root = std::fs::read_to_string(tests.join("integration.rs")).expect("tests/integration.rs");
    let files = integration_test_files(&tests);
    assert!(files.len() > 100, "{files:?}");
    let missing: Vec<&String> = files
        .iter()
        .filter(|(module, path)| {
            let declared = root.lines().any(|l| l.trim() == format!("mod {module};"));
            let by_path =
                path.ends_with("/main.rs") && root.contains(&format!("#[path = \"{path}\"]"));
            !(declared && (by_path || !path.ends_with("/main.rs")))
        })
        .map(|(_, path)| path)
        .collect();
    assert!(
        missing.is_empty(),
        "tests/integration.rs does not declare these test files, so they never run: {missing:?}"
    );
}
