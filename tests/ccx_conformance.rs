//! CalculiX's own frequency tests (Debian's `calculix-ccx-test`), as users write decks, through
//! the CLI against ccx run on the same deck (issue 32): every `*FREQUENCY` deck of the suite in
//! scope — structural; not cyclic symmetry, contact, heat transfer, 2-D elements or plasticity —
//! either builds and matches ccx's frequencies (the same number of rigid-body modes; elastic
//! modes within 1e-5), or is refused (exit 2) with a message naming the keyword or element it
//! does not honour. A build with exit 0 whose frequencies differ from ccx's — a silently wrong
//! body — fails the test.
//!
//! Shells are expanded into one layer of bricks as ccx does (`--inp-shells expanded`, the
//! default), B32/B32R beams into 20-node bricks with ccx's section integration
//! (`beam_expansion`). Where an element is formulated differently from ccx's by design, the
//! deck is listed in `BY_DESIGN` with the reason and must stay within 0.2 % on its first ten
//! modes.
//!
//! The suite is read from `FLEXBODY_CCX_TESTS` (default: the Debian package's folder
//! `/usr/share/doc/calculix-ccx-test/examples/test`) and needs `ccx` on the PATH; without them
//! the test says SKIPPED. `FLEXBODY_WRITE_CONFORMANCE=1` writes the table to
//! `docs/conformance.md`.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;

use crate::common::{scratch, skipped_install};
use flexbody_reader as file;

const SUITE_ENV: &str = "FLEXBODY_CCX_TESTS";
const DEBIAN_SUITE: &str = "/usr/share/doc/calculix-ccx-test/examples/test";

/// Relative agreement of a match (ccx prints 7 significant digits).
const MATCH: f64 = 1e-5;
/// Agreement of a deck whose elements differ from ccx's by design, first ten modes.
const BY_DESIGN_LIMIT: f64 = 2e-3;

/// Decks whose elements flexbody formulates differently from ccx on purpose, and why (none
/// since C3D8I keeps its incompatible modes as ccx does: dloadlinIf matches, measured 1.6e-6).
const BY_DESIGN: &[(&str, &str)] = &[];

/// Decks compared with the suite's own reference output (`<deck>.dat.ref`, written by the ccx
/// version of the suite, 2.11) instead of the installed ccx, and why.
const SUITE_REFERENCE: &[(&str, &str)] = &[];

/// Decks with a *FREQUENCY step that is a perturbation of a preceding *STATIC step whose
/// preload flexbody cannot apply, refused by name: rotor's static step is NLGEOM (issue 35).
const PRELOADED: &[&str] = &["rotor"];

/// Decks the issue requires to build and match that do not yet, and why (the test fails when
/// one of them starts matching, so that it moves to `MUST_MATCH`).
const KNOWN_GAPS: &[(&str, &str)] = &[];

/// Decks that build and match ccx: every deck `docs/conformance.md` lists as matching
/// (`must_match_is_every_deck_the_conformance_table_lists_as_matching` holds the two equal; a
/// run with `FLEXBODY_WRITE_CONFORMANCE=1` prints this list from the table it writes). A deck
/// that stops matching fails the test; one that starts matching is added here and in the table.
const MUST_MATCH: &[&str] = &[
    "acou3",
    "beam8f",
    "beamdy1",
    "beamdy10",
    "beamdy11",
    "beamdy12",
    "beamdy13",
    "beamdy14",
    "beamdy15",
    "beamdy16",
    "beamdy17",
    "beamdy18",
    "beamdy19",
    "beamdy2",
    "beamdy3",
    "beamdy4",
    "beamdy5",
    "beamdy6",
    "beamdy7",
    "beamdy8",
    "beamdy9",
    "beamf",
    "beamf2",
    "beamfsh1",
    "beamft",
    "beampsensfreq",
    "boxprofile",
    "damper1",
    "dashpot1",
    "dashpot2",
    "dashpot3",
    "dloadlinIf",
    "shellf",
    "shellf2",
    "simplebeampipe3",
    "spring3",
    "spring5",
    "uprofile",
];

#[derive(Debug, Clone, PartialEq)]
enum Outcome {
    OutOfScope(String),
    CcxFails(String),
    Matches {
        modes: usize,
        worst: f64,
    },
    /// Matches the suite's own reference output (`SUITE_REFERENCE`), not the installed ccx.
    MatchesSuiteReference {
        modes: usize,
        worst: f64,
        why: String,
    },
    ByDesign {
        modes: usize,
        worst: f64,
        why: String,
    },
    Refused(String),
    /// Exit 2 without naming a keyword (or element) and its line: loud, but not yet a useful
    /// refusal.
    FailsUnnamed(String),
    /// Exit 0 with frequencies other than ccx's: a silently wrong body.
    Mismatch(String),
}

impl Outcome {
    fn column(&self) -> &'static str {
        match self {
            Outcome::OutOfScope(_) => "out of scope",
            Outcome::CcxFails(_) => "ccx fails",
            Outcome::Matches { .. } => "matches",
            Outcome::MatchesSuiteReference { .. } => "matches the suite's reference",
            Outcome::ByDesign { .. } => "within 0.2 % (by design)",
            Outcome::Refused(_) => "refused",
            Outcome::FailsUnnamed(_) => "fails (no keyword and line named)",
            Outcome::Mismatch(_) => "MISMATCH",
        }
    }

    fn detail(&self) -> String {
        match self {
            Outcome::Matches { modes, worst } => format!("{modes} modes, worst {worst:.1e}"),
            Outcome::MatchesSuiteReference { modes, worst, why } => {
                format!("{modes} modes, worst {worst:.1e}: {why}")
            }
            Outcome::ByDesign { modes, worst, why } => {
                format!("{modes} modes, worst {worst:.1e}: {why}")
            }
            Outcome::OutOfScope(s)
            | Outcome::CcxFails(s)
            | Outcome::Refused(s)
            | Outcome::FailsUnnamed(s)
            | Outcome::Mismatch(s) => s.clone(),
        }
    }
}

/// The suite's folder, or `None` (SKIPPED) without it or without ccx.
fn suite() -> Option<PathBuf> {
    let dir = std::env::var_os(SUITE_ENV)
        .filter(|d| !d.is_empty())
        .map_or_else(|| PathBuf::from(DEBIAN_SUITE), PathBuf::from);
    if !dir.is_dir() {
        skipped_install(
            &format!(
                "ccx_conformance: no CalculiX test suite at {} (or set {SUITE_ENV})",
                dir.display()
            ),
            "apt-get install calculix-ccx-test",
        );
        return None;
    }
    if Command::new("ccx").arg("-v").output().is_err() {
        skipped_install(
            "ccx_conformance: ccx is not on the PATH",
            "apt-get install calculix-ccx",
        );
        return None;
    }
    Some(dir)
}

/// A deck's text, decompressing `.inp.gz`.
fn deck_text(path: &Path) -> String {
    if path.extension().is_some_and(|e| e == "gz") {
        let o = Command::new("gzip")
            .arg("-dc")
            .arg(path)
            .output()
            .expect("gzip runs");
        assert!(o.status.success(), "gzip -dc {}", path.display());
        String::from_utf8_lossy(&o.stdout).into_owned()
    } else {
        String::from_utf8_lossy(&std::fs::read(path).unwrap()).into_owned()
    }
}

/// Keyword lines as CalculiX reads them: upper case, blanks removed.
fn keywords(text: &str) -> Vec<String> {
    text.lines()
        .filter(|l| l.starts_with('*') && !l.starts_with("**"))
        .map(|l| l.to_ascii_uppercase().replace([' ', '\t'], ""))
        .collect()
}

/// Why a deck is outside the scope, if it is.
fn out_of_scope(kw: &[String]) -> Option<String> {
    let has = |p: &str| kw.iter().any(|k| k.starts_with(p));
    let element_types: Vec<&str> = kw
        .iter()
        .filter(|k| k.starts_with("*ELEMENT,"))
        .filter_map(|k| k.split(',').find_map(|p| p.strip_prefix("TYPE=")))
        .collect();
    if has("*CYCLICSYMMETRYMODEL") {
        return Some("cyclic symmetry".into());
    }
    if has("*CONTACTPAIR") || has("*SURFACEINTERACTION") {
        return Some("contact".into());
    }
    if has("*HEATTRANSFER") || has("*COUPLEDTEMPERATURE") || has("*UNCOUPLEDTEMPERATURE") {
        return Some("heat transfer".into());
    }
    if has("*PLASTIC") || has("*CREEP") || has("*HYPERELASTIC") {
        return Some("plasticity / non-linear material".into());
    }
    if let Some(t) = element_types.iter().find(|t| {
        ["CPS", "CPE", "CAX", "M3D"]
            .iter()
            .any(|p| t.starts_with(p))
    }) {
        return Some(format!("2-D elements ({t})"));
    }
    None
}

/// The frequencies (cycles/time) of the first EIGENVALUE OUTPUT table of a ccx `.dat`.
fn dat_frequencies(text: &str) -> Vec<f64> {
    let mut out = Vec::new();
    let mut inside = false;
    for line in text.lines() {
        if line.contains("E I G E N V A L U E   O U T P U T") {
            if !out.is_empty() {
                break;
            }
            inside = true;
            continue;
        }
        if inside && (line.contains("P A R T I C I P A T I O N") || line.contains("E F F E C T")) {
            inside = false;
        }
        let f: Vec<&str> = line.split_whitespace().collect();
        if inside && f.len() == 5 && f[0].parse::<usize>().is_ok() {
            out.push(f[3].parse().unwrap_or(f64::NAN));
        }
    }
    out
}

/// ccx's frequencies of `deck` in `dir`, or why it has none.
fn run_ccx(dir: &Path, name: &str) -> Result<Vec<f64>, String> {
    let o = Command::new("ccx")
        .args(["-i", name])
        .current_dir(dir)
        .env("OMP_NUM_THREADS", "1")
        .output()
        .map_err(|e| format!("ccx does not run: {e}"))?;
    let dat = std::fs::read_to_string(dir.join(format!("{name}.dat"))).unwrap_or_default();
    let f = dat_frequencies(&dat);
    if f.is_empty() {
        let log = String::from_utf8_lossy(&o.stdout);
        let why = log
            .lines()
            .find(|l| l.contains("ERROR"))
            .map_or("no eigenvalue output", str::trim);
        return Err(format!("ccx 2.20: {why}"));
    }
    Ok(f)
}

/// Whether a refusal names what it refuses and where: `FILE:LINE` of a keyword line of the deck
/// (or of a file it includes), and that line's keyword (`*STEP`) or element type (`TYPE=B31R`).
/// `files`: (file name, text) of the deck and its includes.
fn names_keyword_and_line(message: &str, files: &[(String, String)]) -> bool {
    let upper = message.to_ascii_uppercase();
    files.iter().any(|(file_name, text)| {
        let lines: Vec<&str> = text.lines().collect();
        let tag = format!("{file_name}:");
        message.match_indices(&tag).any(|(at, _)| {
            let digits: String = (message[at + tag.len()..].chars())
                .take_while(char::is_ascii_digit)
                .collect();
            let line = (digits.parse::<usize>().ok())
                .and_then(|n| n.checked_sub(1))
                .and_then(|k| lines.get(k));
            let Some(line) = line.filter(|l| l.starts_with('*') && !l.starts_with("**")) else {
                return false;
            };
            let card = line.to_ascii_uppercase();
            let mut fields = card.split(',').map(str::trim);
            let keyword = fields.next().unwrap_or_default();
            let element =
                fields.find_map(|p| p.replace(' ', "").strip_prefix("TYPE=").map(String::from));
            upper.contains(keyword) || element.is_some_and(|t| !t.is_empty() && upper.contains(&t))
        })
    })
}

fn classify(suite: &Path, deck: &Path) -> (String, Outcome) {
    let file_name = deck.file_name().unwrap().to_string_lossy().into_owned();
    let name = file_name
        .trim_end_matches(".gz")
        .trim_end_matches(".inp")
        .to_owned();
    let text = deck_text(deck);
    let kw = keywords(&text);
    if !kw.iter().any(|k| k.starts_with("*FREQUENCY")) {
        return (name, Outcome::OutOfScope("no *FREQUENCY step".into()));
    }
    if let Some(why) = out_of_scope(&kw) {
        return (name, Outcome::OutOfScope(why));
    }
    let dir = scratch(&format!("ccx-{name}"));
    std::fs::write(dir.join(format!("{name}.inp")), &text).unwrap();
    // the deck and the *INCLUDE files beside it (plain or gzipped), for the refusals' lines
    let mut files = vec![(format!("{name}.inp"), text.clone())];
    for k in kw.iter().filter(|k| k.starts_with("*INCLUDE")) {
        if let Some(inc) = k.split(',').find_map(|p| p.strip_prefix("INPUT=")) {
            for cand in [suite.join(inc.to_ascii_lowercase()), suite.join(inc)] {
                for path in [
                    cand.clone(),
                    PathBuf::from(format!("{}.gz", cand.display())),
                ] {
                    if path.exists() {
                        let included = deck_text(&path);
                        std::fs::write(dir.join(inc.to_ascii_lowercase()), &included).unwrap();
                        files.push((inc.to_ascii_lowercase(), included));
                    }
                }
            }
        }
    }
    let reference = SUITE_REFERENCE.iter().find(|(n, _)| *n == name);
    let ccx = match reference {
        Some(_) => {
            let plain = suite.join(format!("{name}.dat.ref"));
            let zipped = suite.join(format!("{name}.dat.ref.gz"));
            let path = if plain.exists() { plain } else { zipped };
            dat_frequencies(&deck_text(&path))
        }
        None => match run_ccx(&dir, &name) {
            Ok(f) => f,
            Err(why) => return (name, Outcome::CcxFails(why)),
        },
    };
    let out = dir.join(format!("{name}.flexbody"));
    let o = crate::common::build_as_ccx(&dir.join(format!("{name}.inp")), &["-q"], &out);
    let stderr = String::from_utf8_lossy(&o.stderr).into_owned();
    let outcome = if !o.status.success() {
        // the error, and for a refusal its list of keywords (one per line), without the
        // closing hint on how to drop them
        let message = stderr
            .lines()
            .map(|l| l.trim().trim_start_matches("flexbody: "))
            .filter(|l| !l.is_empty() && !l.starts_with("to drop them on purpose"))
            // the warnings and notes a failing build prints too are not its reason
            .filter(|l| !l.starts_with("warning: ") && !l.starts_with("note: "))
            .collect::<Vec<_>>()
            .join(" ")
            .replace(&format!("{}/", dir.display()), "");
        if names_keyword_and_line(&message, &files) {
            Outcome::Refused(message)
        } else {
            Outcome::FailsUnnamed(message)
        }
    } else {
        match compare(&name, &ccx, &file::read(&out).unwrap()) {
            Outcome::Matches { modes, worst } => match reference {
                Some((_, why)) => Outcome::MatchesSuiteReference {
                    modes,
                    worst,
                    why: format!("against the suite's .dat.ref: {why}"),
                },
                None => Outcome::Matches { modes, worst },
            },
            o => o,
        }
    };
    let _ = std::fs::remove_dir_all(&dir);
    (name, outcome)
}

/// Our frequencies against ccx's: rigid-body counts, then the elastic modes pairwise.
fn compare(name: &str, ccx: &[f64], body: &file::ReducedBody) -> Outcome {
    let ours = &body.modes.frequency_hz;
    let rigid_ours = body
        .modes
        .labels
        .iter()
        .filter(|l| **l == file::ModeLabel::Rigid)
        .count();
    let top = ccx.iter().cloned().fold(0.0, f64::max);
    let rigid_ccx = ccx.iter().filter(|f| **f < 1e-4 * top).count();
    if rigid_ours != rigid_ccx {
        return Outcome::Mismatch(format!(
            "{rigid_ours} rigid-body modes, ccx {rigid_ccx} (ccx {:?}, ours {:?})",
            &ccx[..ccx.len().min(8)],
            &ours[..ours.len().min(8)]
        ));
    }
    // the mode counts first: a build that lost a mode does not match on the rest
    let rel = match crate::common::frequency_differences(ours, ccx, rigid_ours) {
        Ok(rel) => rel,
        Err(why) => return Outcome::Mismatch(format!("{why}; exit 0")),
    };
    if rel.is_empty() {
        return Outcome::Mismatch(format!("no elastic mode to compare (ours {ours:?})"));
    }
    let worst = rel.iter().cloned().fold(0.0, f64::max);
    if rel.iter().all(|r| *r <= MATCH) {
        return Outcome::Matches {
            modes: rel.len(),
            worst,
        };
    }
    if let Some((_, why)) = BY_DESIGN.iter().find(|(n, _)| *n == name) {
        let worst10 = rel.iter().take(10).cloned().fold(0.0, f64::max);
        if rel.iter().take(10).all(|r| *r <= BY_DESIGN_LIMIT) {
            return Outcome::ByDesign {
                modes: rel.len().min(10),
                worst: worst10,
                why: (*why).to_owned(),
            };
        }
    }
    let k = (0..rel.len())
        .max_by(|x, y| rel[*x].total_cmp(&rel[*y]))
        .unwrap_or(0);
    let (a, b) = (ours[rigid_ours + k], ccx[rigid_ours + k]);
    Outcome::Mismatch(format!(
        "elastic mode {}: {a:.6e} against ccx {b:.6e} ({:+.2e}); exit 0",
        k + 1,
        (a - b) / b
    ))
}

fn table(results: &BTreeMap<String, Outcome>) -> String {
    let mut counts: BTreeMap<&str, usize> = BTreeMap::new();
    for o in results.values() {
        *counts.entry(o.column()).or_default() += 1;
    }
    let mut s = String::from(
        "# Conformance: CalculiX's frequency tests\n\n\
         Made by `FLEXBODY_WRITE_CONFORMANCE=1 cargo test --release --test integration ccx_conformance::` \
         (`tests/ccx_conformance.rs`): every deck of Debian's `calculix-ccx-test` with a \
         `*FREQUENCY` step, run by ccx 2.20 and built by `flexbody build DECK --units si \
         --method normal --mass consistent`. In scope: structural decks, not cyclic symmetry, \
         contact, heat transfer, 2-D elements or plasticity. A deck in scope either matches \
         ccx (as many modes, the same rigid-body modes, elastic frequencies within 1e-5) or is refused naming the \
         keyword and its line; a deck whose elements differ from ccx's by design stays within 0.2 % on ten \
         modes; shells (S3, S4R, S6, S8, S8R) are expanded into one layer of bricks joined to \
         the shell nodes as ccx does (`--inp-shells expanded`, the default; \
         `src/import/abaqus/shell_expansion.rs`); a deck listed with a reason is compared with the suite's own reference output \
         (ccx 2.11) instead. A MISMATCH (exit 0, other frequencies) fails the test, and so does \
         a failure that names no keyword and line, but for the known gaps listed with their reason. \
         Decks whose *FREQUENCY step is a perturbation of a *STATIC step are built as ccx \
         perturbs the linear static state, K + K_G(σ₀) + K_L(u₀) (issue 35), or refused naming \
         why (NLGEOM).\n\n\
         No deck here builds its *FREQUENCY step on an element variant; our own decks in \
         `fixtures/ccx_elements/` (`tests/abaqus_element_variants.rs`) do: C3D8R, formed as \
         ccx forms it (one-point integration, hourglass control), matches ccx on a regular and \
         a distorted cantilever to its printed digits; S4R, expanded into one layer of C3D8R \
         bricks as ccx does, matches ccx's plate (9.26, 60.1, 143.7 Hz; 8.54, 36.9, 53.7 Hz \
         as flexbody's S4, `--inp-shells native`, which refuses S4R); B31R, which ccx expands \
         into one layer of C3D8R bricks (a B31R cantilever's first mode 6.89 Hz against \
         41.86 Hz as B31), is refused with those figures, as are C3D10M and S3R, which ccx \
         2.20 refuses itself; `--ignore B31R=B31` (C3D10M=C3D10, …) reads them as the base \
         type on purpose. B32 and \
         B32R beams are expanded into 20-node bricks as ccx does (section integration of \
         RECT, CIRC, PIPE and BOX, the beam node tied to its section; \
         `src/import/abaqus/beam_expansion.rs`); our own decks in `fixtures/ccx_beams/` \
         (`tests/ccx_beams.rs`) check them against ccx without the suite.\n\n",
    );
    s += "| outcome | decks |\n|---|---|\n";
    for (k, v) in &counts {
        s += &format!("| {k} | {v} |\n");
    }
    s += "\n| deck | outcome | detail |\n|---|---|---|\n";
    for (name, o) in results {
        let mut detail = o.detail();
        if let Some((_, why)) = KNOWN_GAPS.iter().find(|(n, _)| n == name) {
            detail = format!("known gap: {why} ({detail})");
        }
        if PRELOADED.contains(&name.as_str()) {
            detail = format!("preload of a *STATIC step, issue 35: {detail}");
        }
        s += &format!(
            "| {name} | {} | {} |\n",
            o.column(),
            detail.replace('|', "\\|")
        );
    }
    s + ANSYS_SECTION
}

/// The ANSYS section of `docs/conformance.md` (its checks are `tests/ansys_archive.rs`'s).
const ANSYS_SECTION: &str = "\n## ANSYS: ansys-mapdl-reader's example files\n\n\
    `tests/ansys_archive.rs`, on the files the PyPI package `ansys-mapdl-reader` ships (written by \
    ANSYS; see `docs/ansys.md`).\n\n\
    | file | outcome | detail |\n|---|---|---|\n\
    | HexBeam.cdb + file.full | equal | K and M dof by dof: 3.2e-13 (K), 5.1e-12 (M) of \
    sqrt(a_ii a_jj); 20 clamped modes from the archive 1.4e-12, from the full file 4.7e-11 of \
    the package's frequencies (the mesh with file.rst's material) |\n\
    | TetBeam.cdb | equal | 3913 SOLID187 on corner nodes = the same mesh as CTETRA 4: 0 |\n\
    | sector.cdb | builds | 105 SOLID185 KEYOPT(2)=0 (B-bar; bricks and collapsed wedges), \
    `--material`: six rigid modes, 7th/6th frequency 3.3e6 |\n\
    | cyclic_v182.rst (the repository's tests/testfiles/cyclic_reader, as an archive + element \
    forces) | equal | SOLID185 KEYOPT(2)=0: K u − ω² M r + Σ ENF is 4.2e-8 of max \\|Σ ENF\\| \
    over 65 elements (`tests/ansys_solids.rs`) |\n\
    | cyc_stress.rst (the repository's tests/testfiles, as an archive + solution) | equal | \
    SOLID185 KEYOPT(2)=3: K u − F_reaction − ω² M r is 1.1e-8 of max \\|K u\\| \
    (`tests/ansys_solids.rs`) |\n";

#[test]
fn calculix_frequency_tests_build_and_match_or_are_refused_by_name() {
    let Some(suite) = suite() else {
        return;
    };
    let mut decks: Vec<PathBuf> = std::fs::read_dir(&suite)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| {
            let n = p.file_name().unwrap().to_string_lossy();
            n.ends_with(".inp") || n.ends_with(".inp.gz")
        })
        .collect();
    decks.sort();
    let mut results = BTreeMap::new();
    for deck in &decks {
        let (name, outcome) = classify(&suite, deck);
        if outcome != Outcome::OutOfScope("no *FREQUENCY step".into()) {
            println!("{name:<16} {:<24} {}", outcome.column(), outcome.detail());
            results.insert(name, outcome);
        }
    }
    let text = table(&results);
    if std::env::var_os("FLEXBODY_WRITE_CONFORMANCE").is_some() {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/conformance.md");
        std::fs::write(&path, &text).unwrap();
        // past the harness's capture, as the list to paste into MUST_MATCH
        use std::io::Write;
        let _ = writeln!(
            std::io::stderr(),
            "wrote {}; MUST_MATCH for the decks it lists as matching:\n{:#?}",
            path.display(),
            matching_decks(&text)
        );
    }
    let bad: Vec<String> = results
        .iter()
        .filter(|(_, o)| matches!(o, Outcome::Mismatch(_) | Outcome::FailsUnnamed(_)))
        .map(|(n, o)| format!("{n}: {} {}", o.column(), o.detail()))
        .collect();
    let missing: Vec<&str> = MUST_MATCH
        .iter()
        .filter(|n| !matches!(results.get(**n), Some(Outcome::Matches { .. })))
        .copied()
        .collect();
    let not_refused: Vec<&str> = PRELOADED
        .iter()
        .filter(|n| !matches!(results.get(**n), Some(Outcome::Refused(_))))
        .copied()
        .collect();
    let gaps_closed: Vec<&str> = KNOWN_GAPS
        .iter()
        .filter(|(n, _)| !matches!(results.get(*n), Some(Outcome::FailsUnnamed(_))))
        .map(|(n, _)| *n)
        .collect();
    let bad: Vec<String> = bad
        .into_iter()
        .filter(|b| {
            !KNOWN_GAPS
                .iter()
                .any(|(n, _)| b.starts_with(&format!("{n}:")))
        })
        .collect();
    assert!(
        bad.is_empty() && missing.is_empty() && not_refused.is_empty() && gaps_closed.is_empty(),
        "silently wrong or unnamed failures: {bad:#?}\nrequired to match but do not: {missing:?}\n\
         preloaded decks not refused by *STEP, PERTURBATION: {not_refused:?}\n\
         known gaps that changed (move them to MUST_MATCH?): {gaps_closed:?}"
    );
}

/// The decks a conformance table (`docs/conformance.md`) lists as matching ccx, sorted.
fn matching_decks(table: &str) -> Vec<String> {
    let mut decks: Vec<String> = (table.lines())
        .filter_map(|l| {
            let cells: Vec<&str> = l.split('|').map(str::trim).collect();
            (cells.len() > 3 && cells[2] == "matches").then(|| cells[1].to_owned())
        })
        .collect();
    decks.sort();
    decks
}

/// `MUST_MATCH` is the list `docs/conformance.md` gives as matching: no deck that matched when
/// the table was written can regress unnoticed (runs without ccx or the suite too).
#[test]
fn must_match_is_every_deck_the_conformance_table_lists_as_matching() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/conformance.md");
    let documented = matching_decks(&std::fs::read_to_string(path).unwrap());
    let mut must: Vec<String> = MUST_MATCH.iter().map(|s| s.to_string()).collect();
    must.sort();
    assert_eq!(must, documented, "MUST_MATCH against docs/conformance.md");
    assert!(documented.len() >= 38, "{documented:?}");
}
