//! Broken files of the rules settled in issue 49 (round 3): the preload's numbers, the recipe's
//! statements about the other entries, the support against the modes, the zero acceleration
//! fields of a free body (1.8), and a central-directory header that leaves the directory.
use super::*;

/// `text` with the first occurrence of `from` replaced by `to` (which must occur).
fn edit(text: &str, from: &str, to: &str) -> String {
    assert!(text.contains(from), "{from:?} not in the text");
    text.replacen(from, to, 1)
}

/// A preload of the 3-node chain's recipe (numbers that print exactly).
fn preload() -> RecipePreload {
    RecipePreload {
        source: "--preload TIP".into(),
        loads: vec!["TIP".into()],
        max_displacement: 0.25,
        max_displacement_node: 103,
        buckling_factor: Some(2.5),
    }
}

pub fn cases(base: &ReducedBody, add: &mut Add) {
    preload_numbers(base, add);
    recipe_against_entries(base, add);
    geometric_support(add);
    // §9: an optional list present but empty is left out of the summary, as if absent (the
    // Rust reader's Vec and the reference reader agree on it): accepted, summary without it.
    let mut b = base.clone();
    let r = super::super::recipe_3node();
    b.recipe = Some(r.clone());
    let text = String::from_utf8(codec::encode_recipe(&r)).expect("recipe is UTF-8");
    add(
        "recipe_empty_optional_list",
        with_entry(
            &b,
            codec::RECIPE,
            edit(
                &text,
                "\"damping\": \"0-1:0%,1-:2%\"",
                "\"damping\": \"0-1:0%,1-:2%\",\n    \"loads\": []",
            )
            .into_bytes(),
        ),
        None,
    );
    // §7.1 step 1: the last central header's comment runs 10 bytes into the end record, which
    // lies inside the file but outside the directory.
    let mut zip = from_body(base);
    let at = (zip.windows(4).rposition(|w| w == b"PK\x01\x02")).expect("a central header");
    zip[at + 32..at + 34].copy_from_slice(&10u16.to_le_bytes());
    add(
        "central_header_past_directory_end",
        zip,
        Some(("NotZip", "runs past the end of the directory")),
    );
}

/// Rule 13: `preload.max_displacement` finite and ≥ 0, `buckling_factor` finite and > 0.
fn preload_numbers(base: &ReducedBody, add: &mut Add) {
    let mut b = base.clone();
    let mut r = super::super::recipe_3node();
    r.preload = Some(preload());
    b.recipe = Some(r.clone());
    let text = String::from_utf8(codec::encode_recipe(&r)).expect("recipe is UTF-8");
    let with_recipe = |text: String| with_entry(&b, codec::RECIPE, text.into_bytes());
    add(
        "recipe_preload_max_displacement_1e999",
        with_recipe(edit(
            &text,
            "\"max_displacement\": 0.25",
            "\"max_displacement\": 1e999",
        )),
        Some((
            "NonFinite",
            "recipe.json: preload.max_displacement[0] is not finite (inf)",
        )),
    );
    add(
        "recipe_preload_max_displacement_negative",
        with_recipe(edit(
            &text,
            "\"max_displacement\": 0.25",
            "\"max_displacement\": -0.25",
        )),
        Some((
            "Inconsistent",
            "recipe.json: preload.max_displacement -0.25 must be >= 0",
        )),
    );
    add(
        "recipe_preload_buckling_factor_1e999",
        with_recipe(edit(
            &text,
            "\"buckling_factor\": 2.5",
            "\"buckling_factor\": 1e999",
        )),
        Some((
            "NonFinite",
            "recipe.json: preload.buckling_factor[0] is not finite (inf)",
        )),
    );
    add(
        "recipe_preload_buckling_factor_zero",
        with_recipe(edit(
            &text,
            "\"buckling_factor\": 2.5",
            "\"buckling_factor\": 0",
        )),
        Some((
            "Inconsistent",
            "recipe.json: preload.buckling_factor 0 must be > 0",
        )),
    );
}

/// Rule 13, last checks: the recipe's `geometric_stiffness` option and `preload` against the
/// entries and modes, and normal modes that remove only residual vectors.
fn recipe_against_entries(base: &ReducedBody, add: &mut Add) {
    let mut b = base.clone();
    let mut r = super::super::recipe_3node();
    r.options.geometric_stiffness = Some("inertia".into());
    b.recipe = Some(r);
    add(
        "recipe_geometric_stiffness_option_without_entry",
        from_body(&b),
        Some((
            "Inconsistent",
            "recipe.json: options.geometric_stiffness is present but geometric_stiffness.bin is absent",
        )),
    );
    let mut b = super::super::body_3node_geometric_stiffness();
    if let Some(r) = &mut b.recipe {
        r.options.geometric_stiffness = None;
    }
    add(
        "recipe_geometric_stiffness_entry_without_option",
        from_body(&b),
        Some((
            "Inconsistent",
            "recipe.json: options.geometric_stiffness is absent but geometric_stiffness.bin is present",
        )),
    );
    let mut b = super::super::body_3node_geometric_stiffness();
    if let Some(r) = &mut b.recipe {
        r.preload = Some(preload());
    }
    add(
        "recipe_preload_with_geometric_stiffness",
        from_body(&b),
        Some((
            "Inconsistent",
            "recipe.json: a preloaded build has no geometric_stiffness.bin",
        )),
    );
    let mut b = base.clone();
    let mut r = super::super::recipe_3node();
    r.preload = Some(preload());
    b.recipe = Some(r);
    add(
        "recipe_preload_on_free_body",
        from_body(&b),
        Some((
            "Inconsistent",
            "recipe.json: a preload needs a held body, but mode 0 is labelled Rigid",
        )),
    );
    let mut b = super::super::body_3node_residual_vectors();
    if let Some(r) = &mut b.recipe {
        r.options.residual_vectors = None;
    }
    add(
        "normal_modes_removed_without_residual_vectors",
        from_body(&b),
        Some((
            "Inconsistent",
            "recipe.json: counts.removed_dependent = 1 for normal modes without options.residual_vectors",
        )),
    );
}

/// Rule 15: a `Held` body has no `Rigid` mode; since 1.8 a free body's acceleration fields are
/// zero.
fn geometric_support(add: &mut Add) {
    let mut b = super::super::body_3node_geometric_stiffness();
    if let Some(g) = &mut b.geometric_stiffness {
        g.support = StaticSupport::Held;
    }
    add(
        "geometric_held_with_rigid_mode",
        from_body(&b),
        Some((
            "Inconsistent",
            "geometric_stiffness.bin: support is Held, but mode 0 is labelled Rigid",
        )),
    );
    let mut b = super::super::body_3node_geometric_stiffness();
    if let Some(g) = &mut b.geometric_stiffness {
        g.fields[10].matrix[4] = 1e-14;
    }
    add(
        "geometric_acceleration_not_zero_under_inertia_relief",
        from_body(&b),
        Some((
            "Inconsistent",
            "geometric_stiffness.bin: fields[10].matrix[4] = 0.00000000000001: an acceleration field under InertiaRelief is zero",
        )),
    );
    // the same numbers in a file that says 1.7 are accepted: the rule came with 1.8
}
