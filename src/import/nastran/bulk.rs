//! The bulk data of a deck, read in three passes: the geometry cards place the nodes; every
//! other card goes through its rule in the card table (`cards`) — honoured by its family's
//! reader into raw records, a note, or refused (every refused card of the deck in one error);
//! then one resolve pass per family builds the [`Model`] (ids → indices, coordinate systems →
//! basic, WTMASS applied, the case control's selections).

use std::collections::BTreeMap;

use super::cards::{self, Rule};
use super::fields::{ThruBudget, C};
use super::geometry::GeometryCards;
use super::lex::{Card, Lexer};
use super::reading::Bulk;
use super::records::{
    BushCards, ElementCards, LoadCards, MassCards, PropertyCards, ScalarCards, SetCards,
    SolutionCards,
};
use super::CardCounts;
use crate::import::error::{ImportError, RefusedCard};
use crate::import::text::{places, Builder, Loc};
use crate::model::{ImportWarning, Model, NodeIndex};

/// Build the model from lexed cards; `subcase` picks the case-control subcase whose SPC and
/// METHOD selections apply; cards named in `ignore` are dropped on purpose (module
/// `cards`: names or `PARAM:NAME`, case-insensitive).
pub(crate) fn build(
    lexer: Lexer,
    subcase: Option<u64>,
    ignore: &[String],
) -> Result<(Model, CardCounts), ImportError> {
    let Lexer {
        files,
        cards: all,
        case_lines,
        has_case_control,
        bytes,
    } = lexer;
    let case = super::case_control::parse(&case_lines, has_case_control, &files)?;
    let ignore: Vec<String> = ignore.iter().map(|s| ignore_key(s)).collect();
    let effective = effective_scope(&case, subcase, &files, &ignore)?;
    let mut b = Builder::new(&files[0]);
    b.files = files.clone();
    b.model.deck.title = case.title.clone();
    b.model.deck.subcase = effective.subcase;

    // Pass 1: cards dropped on purpose set aside; the geometry cards place the nodes.
    let mut ignored: BTreeMap<String, Vec<Loc>> = BTreeMap::new();
    let mut counts = CardCounts::new();
    let mut geometry = GeometryCards::default();
    let mut others: Vec<&Card> = Vec::new();
    for card in &all {
        *counts.entry(card.name.clone()).or_default() += 1;
        let g = C::new(card, &files);
        if !ignore.is_empty() {
            let key = cards::key(&g);
            if ignore.iter().any(|i| *i == key || *i == card.name) {
                ignored.entry(key).or_default().push(card.loc);
                continue;
            }
        }
        match cards::rule(&g) {
            Some(Rule::Geometry) => geometry.take(card, &files)?,
            _ => {
                if matches!(
                    card.name.as_str(),
                    "CELAS3" | "CELAS4" | "CMASS3" | "CMASS4"
                ) {
                    geometry.scalar_users.push(card);
                }
                others.push(card)
            }
        }
    }
    // the defaults of blank CBAR/CBEAM fields are read before any CBAR/CBEAM (`elements`)
    others.sort_by_key(|c| !matches!(c.name.as_str(), "BAROR" | "BEAMOR"));
    let thru = ThruBudget::for_bytes(bytes);
    let (coords, nodes) = super::geometry::place_nodes(&geometry, &files, &thru, &mut b)?;

    // Pass 2: every other card through its rule.
    let mut d = Bulk {
        files: &files,
        b,
        nodes,
        coords,
        thru,
        notes: BTreeMap::new(),
        noted: BTreeMap::new(),
        refused: Vec::new(),
        elements: ElementCards::default(),
        properties: PropertyCards::default(),
        masses: MassCards::default(),
        scalars: ScalarCards::default(),
        bushes: BushCards::default(),
        sets: SetCards::default(),
        solution: SolutionCards::default(),
        loads: LoadCards::default(),
        dmig: Default::default(),
        shear: Default::default(),
    };
    for card in others {
        let g = C::new(card, &files);
        match cards::row(&g) {
            Some((_, _, Rule::Read(read))) => read(&mut d, &g)?,
            Some((_, category, Rule::Note)) => d.note_in(*category, &g, None),
            Some((_, category, Rule::NoteWhy(why))) => d.note_in(*category, &g, Some(why)),
            Some((_, _, Rule::Refuse(why))) => d.refuse(&g, *why),
            Some((_, _, Rule::Geometry | Rule::Command)) | None => d.refuse(&g, cards::NOT_READ),
        }
    }
    super::material_temperature::decide(&mut d)?;
    // the case control's refused commands first: they come first in the deck
    let mut refused: Vec<RefusedCard> = Vec::new();
    for (command, why, loc) in &case.refused {
        if ignore.contains(command) {
            ignored.entry(command.clone()).or_default().push(*loc);
        } else {
            refused.push(RefusedCard {
                file: files[loc.file as usize].clone(),
                line: loc.line as usize,
                entity: format!("{command} (case control)"),
                key: command.clone(),
                reason: (*why).to_owned(),
            });
        }
    }
    if let Some(refusal) = solution(&case, &files, &ignore, &mut ignored, &mut d.b.model) {
        refused.insert(0, refusal);
    }
    d.refused.splice(0..0, refused);
    for (command, why, loc) in &case.noted {
        let entry = (d.notes)
            .entry(format!("{command} (case control)"))
            .or_insert_with(|| (why, Vec::new()));
        entry.1.push(*loc);
    }
    if !d.refused.is_empty() {
        return Err(ImportError::Refused {
            file: files[0].clone(),
            cards: std::mem::take(&mut d.refused),
        });
    }
    ignored_and_notes(&mut d, &ignored, &ignore);

    // Pass 3: resolve, family by family.
    d.b.resolve_element_nodes(&d.nodes)?;
    super::elements::no_scalar_points(&d)?;
    super::elements::check_ids(&mut d)?;
    let (pids, mids) = super::properties::resolve(&mut d)?;
    let element_sets = super::elements::assign_properties(&mut d, &pids, &mids)?;
    super::shear::resolve(&mut d, &mids)?;
    super::elements::orient(&mut d)?;
    super::mass::resolve(&mut d)?;
    super::scalar::resolve(&mut d)?;
    super::bush::resolve(&mut d)?;
    super::dmig::resolve(&mut d, &case, &effective)?;
    super::sets::resolve_spc(&mut d, &case, &effective)?;
    super::sets::resolve_mpc(&mut d, &effective)?;
    super::shell::blank_midsides(&mut d)?;
    super::solution::resolve_method(&mut d, &effective)?;
    super::sets::resolve_dof_sets(&mut d);
    super::properties::warnings(&mut d);
    d.b.model.element_sets = element_sets;
    d.b.model.params.wtmass = d.solution.wtmass;
    let elements = d.b.element_map()?;
    let load_sel = case.load_selections(effective.subcase);
    // masses and springs are in the element id space: their lines are looked up by id too
    let others: Vec<(u64, u32, u32)> = (d.elements.other_ids.iter())
        .map(|(id, c)| (*id, c.loc.file, c.loc.line))
        .collect();
    // rigid elements too, for messages about them (issue 47), where their id names no other
    // element (MSC keeps the two id spaces apart; a shared id keeps the element's line)
    let rigid: Vec<(u64, u32, u32)> = (d.elements.rigid_ids.iter())
        .map(|(id, c)| (*id, c.loc.file, c.loc.line))
        .collect();
    let mut b = d.b;
    b.model.loads =
        super::loads::resolve(&d.loads, &files, &b.model, &d.nodes, &elements, &load_sel)?;
    b.model.deck.preload = statsub_preload(&effective, &b.model.loads, &files)?;
    if let Some(sel) = effective.preload.and_then(|(_, _, scope)| scope.temp_load) {
        let thermal = super::temperature::thermal_preload(
            &d.loads.temperatures,
            &d.properties.mats,
            sel,
            &d.nodes,
            &b.model,
            &files,
        )?;
        if let Some(request) = &mut b.model.deck.preload {
            request.thermal = Some(thermal);
        }
    }
    let load_warnings = crate::model::load::problem_warnings(&b.model.loads, &files[0]);
    b.model.warnings.extend(load_warnings);
    b.model.files = b.files.clone();
    b.record_element_sources();
    let offsets = with_mid_plane_offsets(&b.model, &d.elements.shell_offsets, &d.properties);
    shell_offsets(&mut b.model, &offsets, &files)?;
    b.model.element_sources.extend(others);
    b.model
        .element_sources
        .sort_unstable_by_key(|&(id, _, _)| id);
    let rigid: Vec<(u64, u32, u32)> = (rigid.into_iter())
        .filter(|r| b.model.element_location(r.0).is_none())
        .collect();
    b.model.element_sources.extend(rigid);
    b.model
        .element_sources
        .sort_unstable_by_key(|&(id, _, _)| id);
    Ok((b.model, counts))
}

/// The elements' ZOFFS plus their PCOMP's mid-plane offset Z0 + T/2 (MSC QRG: Z0 is measured
/// from the reference plane, which ZOFFS moves off the grids): one offset per element, at the
/// element card's place, else the PCOMP's.
fn with_mid_plane_offsets(
    model: &Model,
    zoffs: &[(crate::model::shell_offset::ShellOffset, Loc)],
    props: &PropertyCards,
) -> Vec<(crate::model::shell_offset::ShellOffset, Loc)> {
    let mut out = zoffs.to_vec();
    if props.mid_plane_offsets.is_empty() {
        return out;
    }
    let mut at: BTreeMap<usize, usize> = BTreeMap::new();
    for (k, (o, _)) in out.iter().enumerate() {
        at.insert(o.elem, k);
    }
    for (e, el) in model.elements.iter().enumerate() {
        let Some(p) = el.property.and_then(|p| model.properties.get(p)) else {
            continue;
        };
        let Some(&(offset, loc)) = props.mid_plane_offsets.get(&p.id) else {
            continue;
        };
        match at.get(&e) {
            Some(&k) => out[k].0.zoffs += offset,
            None => out.push((
                crate::model::shell_offset::ShellOffset {
                    elem: e,
                    zoffs: offset,
                },
                loc,
            )),
        }
    }
    out
}

/// CQUAD4/CTRIA3 with ZOFFS moved to their reference planes (`model::shell_offset`), with a
/// note saying what was made.
fn shell_offsets(
    model: &mut Model,
    offsets: &[(crate::model::shell_offset::ShellOffset, Loc)],
    files: &[String],
) -> Result<(), ImportError> {
    if offsets.is_empty() {
        return Ok(());
    }
    let list: Vec<_> = offsets.iter().map(|(o, _)| *o).collect();
    let made = crate::model::shell_offset::offset_shells(model, &list).map_err(|(at, why)| {
        let loc = offsets[at].1;
        crate::import::error::parse_err(
            &files[loc.file as usize],
            loc.line as usize,
            format!("element {}", model.elements[offsets[at].0.elem].id),
            why,
        )
    })?;
    let ids = |v: &[NodeIndex]| match (v.first(), v.last()) {
        (Some(&a), Some(&b)) => format!("{} … {}", model.nodes[a].id, model.nodes[b].id),
        _ => String::new(),
    };
    model.deck.notes.push(format!(
        "ZOFFS: {} CQUAD4/CTRIA3 formed at their offset reference planes, on {} nodes (ids {}) \
         each tied to its grid point by an RBE2 on all six dofs (ids {} …), as MSC Nastran's \
         rigid offset",
        made.elements,
        made.nodes.len(),
        ids(&made.nodes),
        made.links.first().copied().unwrap_or_default()
    ));
    Ok(())
}

/// The deck's preload (module `case_control`): the LOAD set of the static subcase that
/// `STATSUB(PRELOAD)` names, by its scene-load name (its TEMP(LOAD) is added by the caller).
fn statsub_preload(
    effective: &super::case_control::Effective,
    loads: &[crate::model::Load],
    files: &[String],
) -> Result<Option<crate::model::deck::PreloadRequest>, ImportError> {
    let Some((id, at, scope)) = effective.preload else {
        return Ok(None);
    };
    let place = |l: Loc| format!("{}:{}", files[l.file as usize], l.line);
    let mut request = crate::model::deck::PreloadRequest {
        source: format!("static subcase {id} (STATSUB(PRELOAD), {})", place(at)),
        ..Default::default()
    };
    if let Some(sel) = scope.load {
        let name = format!("LOAD_{}", sel.id);
        if !loads.iter().any(|l| l.name == name) {
            return Err(sel.undefined(
                files,
                "LOAD",
                "load set",
                "FORCE, MOMENT, GRAV, PLOAD4 or LOAD",
            ));
        }
        request.first_load = format!("{}: LOAD = {}", place(sel.loc), sel.id);
        request.loads.push(name);
    } else if let Some(t) = scope.temp_load {
        request.first_load = format!("{}: TEMP(LOAD) = {}", place(t.loc), t.id);
    }
    Ok(Some(request))
}

/// The case control's selections for `subcase`; when the deck's subcases leave the choice
/// open, a refused solution (SOL 105, 106, 200, …) is the error instead: it outranks the
/// choice among its subcases. `ignore`: the `--ignore` names as [`ignore_key`]s.
fn effective_scope(
    case: &super::case_control::CaseControl,
    subcase: Option<u64>,
    files: &[String],
    ignore: &[String],
) -> Result<super::case_control::Effective, ImportError> {
    case.effective(subcase, files, &files[0]).map_err(|e| {
        let sol = solution(
            case,
            files,
            ignore,
            &mut BTreeMap::new(),
            &mut Model::default(),
        );
        sol.map_or(e, |card| ImportError::Refused {
            file: files[0].clone(),
            cards: vec![card],
        })
    })
}

/// The deck's `SOL` (module `sol`): a normal-modes solution passes; a linear response
/// solution passes with a note; any other is refused (unless ignored as `SOL`).
fn solution(
    case: &super::case_control::CaseControl,
    files: &[String],
    ignore: &[String],
    ignored: &mut BTreeMap<String, Vec<Loc>>,
    model: &mut Model,
) -> Option<RefusedCard> {
    use super::sol::Disposition;
    let (value, loc) = case.sol.as_ref()?;
    match super::sol::disposition(value) {
        Disposition::Modes => None,
        Disposition::Response(what) => {
            model.deck.notes.push(format!(
                "SOL {value} ({what}, {}:{}): the body is the structure's normal modes; the response analysis's own cards are notes",
                files[loc.file as usize], loc.line
            ));
            None
        }
        Disposition::Refused(_) if ignore.iter().any(|i| i == "SOL") => {
            ignored.entry("SOL".to_owned()).or_default().push(*loc);
            None
        }
        Disposition::Refused(why) => Some(RefusedCard {
            file: files[loc.file as usize].clone(),
            line: loc.line as usize,
            entity: format!("SOL {value} (executive control)"),
            key: "SOL".to_owned(),
            reason: why.to_owned(),
        }),
    }
}

/// An `ignore_cards` name as the card table knows it: upper case; a parameter as
/// `PARAM:NAME` whether given as `PARAM:NAME`, `PARAM,NAME` or `PARAM NAME`.
fn ignore_key(name: &str) -> String {
    let up = name.trim().to_ascii_uppercase();
    match up.strip_prefix("PARAM") {
        Some(rest) if !rest.trim_start_matches([':', ',', ' ']).is_empty() => {
            format!("PARAM:{}", rest.trim_start_matches([':', ',', ' ']).trim())
        }
        _ => up,
    }
}

/// One warning per card type dropped on purpose (and per `ignore` name the deck does not
/// have), one note per card type not read because it cannot change the body.
fn ignored_and_notes(d: &mut Bulk, ignored: &BTreeMap<String, Vec<Loc>>, ignore: &[String]) {
    let files = d.files;
    let model = &mut d.b.model;
    if !ignored.is_empty() {
        let list: Vec<String> = ignored
            .iter()
            .map(|(k, locs)| places(k, locs, files))
            .collect();
        model.warnings.push(ImportWarning {
            file: files[0].clone(),
            message: format!(
                "cards dropped on request (--ignore), whatever they carry: {}",
                list.join("; ")
            ),
        });
    }
    for name in ignore {
        let used = ignored
            .keys()
            .any(|k| k == name || k.split(':').next() == Some(name.as_str()));
        if !used {
            model.warnings.push(ImportWarning {
                file: files[0].clone(),
                message: format!("--ignore {name}: the deck has no such card"),
            });
        }
    }
    for (key, (why, locs)) in &d.notes {
        model
            .deck
            .notes
            .push(format!("{} not read: {why}", places(key, locs, files)));
    }
    for (category, cards) in &d.noted {
        let list: Vec<String> = (cards.iter())
            .map(|(key, (why, locs))| match why {
                Some(why) => format!("{} — {why}", places(key, locs, files)),
                None => places(key, locs, files),
            })
            .collect();
        model.deck.notes.push(format!(
            "{} cards not read ({}): {}",
            category.title(),
            category.why(),
            list.join("; ")
        ));
    }
}

#[cfg(test)]
mod tests {
    use super::ignore_key;

    #[test]
    fn ignore_names_are_card_names_or_param_keys() {
        for (given, key) in [
            ("cgap", "CGAP"),
            (" PARAM:snorm", "PARAM:SNORM"),
            ("param,SNORM", "PARAM:SNORM"),
            ("PARAM SNORM", "PARAM:SNORM"),
            ("PARAM", "PARAM"),
        ] {
            assert_eq!(ignore_key(given), key);
        }
    }
}
