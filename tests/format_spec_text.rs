//! SPEC.md names what the readers implement (issue 37 items 12, 13, 15): every entry in §2's
//! table with the version that introduced it, every record that holds strings under §7.2's
//! 16 MiB bound, every element's smallest encoding, the bottom-fibre checks in §6, every
//! member of the `inspect --json` summary in §9, and the version in the title, the history and
//! the golden folders.
use std::path::Path;

use flexbody_reader::codec::{ENTRIES, RECIPE, STRESS_SHAPES_BOTTOM, STRING_RECORDS};
use flexbody_reader::FORMAT_VERSION;

fn spec() -> String {
    std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("format-spec/SPEC.md"))
        .expect("SPEC.md")
}

/// The text of section `heading` (a line starting with it) up to the next heading of its level.
fn section(text: &str, heading: &str) -> String {
    let level = heading.split(' ').next().expect("#s").len();
    let start = text
        .find(&format!("\n{heading}"))
        .unwrap_or_else(|| panic!("no section {heading}"));
    let rest = &text[start + 1..];
    let end = rest[1..]
        .find(&format!("\n{} ", "#".repeat(level)))
        .map_or(rest.len(), |e| e + 1);
    rest[..end].to_string()
}

#[test]
fn every_entry_is_in_the_table_with_its_version() {
    let table = section(&spec(), "## 2.");
    for (name, required, minor) in ENTRIES {
        let row = table
            .lines()
            .find(|l| l.contains(&format!("| `{name}` |")))
            .unwrap_or_else(|| panic!("{name} not in §2's table"));
        assert_eq!(row.contains("| yes |"), required, "{row}");
        assert_eq!(
            row.contains(&format!("(since 1.{minor})")),
            minor > 0,
            "{row}: introduced in 1.{minor}"
        );
    }
}

#[test]
fn the_string_records_and_smallest_encodings_are_in_section_7_2() {
    let limits = section(&spec(), "### 7.2");
    let bound = limits
        .split("\n\n")
        .find(|p| p.contains("16 MiB"))
        .expect("§7.2 states the 16 MiB bound");
    for name in STRING_RECORDS.iter().chain([&RECIPE]) {
        assert!(
            bound.contains(&format!("`{name}`")),
            "§7.2's bound omits {name}"
        );
    }
    for element in [
        "`InterfaceInfo` 25",
        "`ModalLoad` 24",
        "`GeometricField` 13",
        "`EigenProblem` 33",
        "`Node` 33",
        "`Face` 16",
    ] {
        assert!(limits.contains(element), "§7.2 omits {element}");
    }
}

#[test]
fn the_bottom_fibre_checks_are_a_rule_of_section_6() {
    let rules = section(&spec(), "## 6.");
    let rule9 = rules
        .lines()
        .skip_while(|l| !l.starts_with("9. "))
        .take_while(|l| !l.starts_with("10. "))
        .collect::<Vec<_>>()
        .join(" ");
    assert!(
        rule9.contains(&format!("`{STRESS_SHAPES_BOTTOM}`")),
        "{rule9}"
    );
    assert!(rule9.contains("top entry"), "{rule9}");
}

#[test]
fn every_summary_member_is_named_in_section_9() {
    let text = section(&spec(), "## 9.");
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures/golden");
    let mut seen = 0;
    for dir in std::fs::read_dir(&root).expect("golden").flatten() {
        for f in std::fs::read_dir(dir.path())
            .expect("version folder")
            .flatten()
        {
            if f.path().extension().is_some_and(|x| x == "json") {
                let v: serde_json::Value =
                    serde_json::from_slice(&std::fs::read(f.path()).expect("read")).expect("json");
                for key in v.as_object().expect("object").keys() {
                    assert!(text.contains(&format!("`{key}`")), "§9 omits `{key}`");
                    seen += 1;
                }
            }
        }
    }
    assert!(seen > 100);
    assert!(
        text.contains("1.2–1.7"),
        "§9 says which flags `optional` holds"
    );
}

#[test]
fn title_history_and_golden_folders_have_the_format_version() {
    let text = spec();
    let (major, minor) = (FORMAT_VERSION.major, FORMAT_VERSION.minor);
    assert!(text.starts_with(&format!(
        "# flexbody reduced-body file format — version {major}.{minor}\n"
    )));
    let history = section(&text, "### 7.3");
    for m in 0..=minor {
        assert!(
            history.contains(&format!("{major}.{m} —")),
            "§7.3 history omits 1.{m}"
        );
    }
    let golden =
        Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("fixtures/golden/v{major}.{minor}"));
    assert!(golden.is_dir(), "{} missing", golden.display());
}
