//! Broken files of the JSON entries (SPEC §4.1; issue 37 items 8, 9, 14): numbers beyond
//! binary64, member names twice, nesting too deep, optional recipe members of the wrong type.
use super::*;

/// `text` with the first occurrence of `from` replaced by `to` (which must occur).
fn edit(text: &str, from: &str, to: &str) -> String {
    assert!(text.contains(from), "{from:?} not in the text");
    text.replacen(from, to, 1)
}

/// `depth` nested arrays.
fn nested(depth: usize) -> String {
    format!("{}{}", "[".repeat(depth), "]".repeat(depth))
}

pub fn cases(base: &ReducedBody, add: &mut Add) {
    let good = entries(base);
    let manifest_text =
        serde_json::to_string_pretty(&manifest(base, &good)).expect("manifest json");
    let with_manifest = |text: String| pack_raw(Some(text.into_bytes()), &good);

    // Item 8: 1e999 is the binary64 +∞ (nearest), which rule 2 refuses.
    add(
        "manifest_si_1e999",
        with_manifest(edit(&manifest_text, "\"si\": 1.0", "\"si\": 1e999")),
        Some((
            "Inconsistent",
            "manifest.json: units.force.si must be finite and > 0, got inf",
        )),
    );
    // Item 9: a member twice; a first-copy reader would see version 1.0, a last-copy one 1.6.
    add(
        "manifest_duplicate_member",
        with_manifest(edit(
            &manifest_text,
            "\"generator\"",
            "\"version\": { \"major\": 1, \"minor\": 6 },\n  \"generator\"",
        )),
        Some(("Manifest", "member \"version\" occurs twice")),
    );
    // Item 14: 65 levels (an unknown member holding 64 nested arrays).
    add(
        "manifest_nested_too_deep",
        with_manifest(edit(
            &manifest_text,
            "\"generator\"",
            &format!("\"later\": {},\n  \"generator\"", nested(64)),
        )),
        Some(("Manifest", "nested deeper than 64")),
    );

    let mut b = base.clone();
    b.recipe = Some(super::super::recipe_3node());
    let recipe = String::from_utf8(codec::encode_recipe(&super::super::recipe_3node()))
        .expect("recipe is UTF-8");
    let with_recipe = |text: String| with_entry(&b, codec::RECIPE, text.into_bytes());
    // Item 8: beyond binary64 in recipe.json too, written with an exponent or as an integer:
    // rule 13 refuses the +∞ (NonFinite), the parser does not.
    add(
        "recipe_fmax_1e999",
        with_recipe(edit(&recipe, "\"fmax_hz\": null", "\"fmax_hz\": 1e999")),
        Some((
            "NonFinite",
            "recipe.json: options.fmax_hz[0] is not finite (inf)",
        )),
    );
    add(
        "recipe_fmax_huge_integer",
        with_recipe(edit(
            &recipe,
            "\"fmax_hz\": null",
            &format!("\"fmax_hz\": 1{}", "0".repeat(400)),
        )),
        Some((
            "NonFinite",
            "recipe.json: options.fmax_hz[0] is not finite (inf)",
        )),
    );
    // Item 9: duplicates are refused at every level, unknown members included.
    add(
        "recipe_duplicate_member",
        with_recipe(edit(
            &recipe,
            "\"tool\"",
            "\"later\": { \"note\": 1, \"note\": 2 },\n  \"tool\"",
        )),
        Some((
            "Decode",
            "recipe.json: cannot decode (not JSON: member \"note\" occurs twice",
        )),
    );
    // Item 14: an optional member (`name?: T`) present is a T, null is not; `select` likewise.
    add(
        "recipe_thickness_null",
        with_recipe(edit(
            &recipe,
            "\"damping\":",
            "\"thickness\": null,\n    \"damping\":",
        )),
        Some(("Decode", "recipe.json: cannot decode (not a valid recipe")),
    );
    add(
        "recipe_select_not_a_string",
        with_recipe(edit(
            &recipe,
            "\"damping\":",
            "\"select\": 0.01,\n    \"damping\":",
        )),
        Some(("Decode", "recipe.json: cannot decode (not a valid recipe")),
    );
    add(
        "recipe_nested_too_deep",
        with_recipe(edit(
            &recipe,
            "\"tool\"",
            &format!("\"later\": {},\n  \"tool\"", nested(64)),
        )),
        Some(("Decode", "nested deeper than 64")),
    );
}
