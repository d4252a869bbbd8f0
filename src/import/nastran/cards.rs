//! Nastran card interpretation and the resolve pass (ids → indices, coordinate systems → basic,
//! WTMASS applied).

use std::collections::{BTreeMap, HashMap};

use super::coord::{dir_to_basic, from_points, to_basic};
use super::fields::{ThruBudget, C};
use super::lex::{Card, Lexer};
use super::CardCounts;
use crate::import::error::{parse_err, ImportError};
use crate::import::text::{Builder, IdMap, Loc};
use crate::model::{
    BeamSection, ConstraintSource, CoordKind, CoordSystem, DofMask, EigenRequest, ElementKind,
    ImportWarning, InterfaceDofs, Material, Model, PointMass, Property, RigidElement, Section,
    SectionShape, Spc,
};

/// SPCADD: (SID, [(set id, field index)], card).
type SpcAdd<'a> = (u64, Vec<(u64, usize)>, &'a Card);

/// Build the model from lexed cards; `subcase` picks the case-control subcase whose SPC and
/// METHOD selections apply.
pub(crate) fn build(
    lexer: Lexer,
    subcase: Option<u64>,
) -> Result<(Model, CardCounts), ImportError> {
    let mut counts = CardCounts::new();
    let mut unsupported: BTreeMap<String, usize> = BTreeMap::new();
    let files = lexer.files;
    let thru_budget = ThruBudget::for_bytes(lexer.bytes);
    let case = super::case_control::parse(&lexer.case_lines, lexer.has_case_control, &files)?;
    let effective = case.effective(subcase, &files, &files[0])?;
    let mut b = Builder::new(&files[0]);
    b.files = files.clone();
    b.model.deck.title = case.title.clone();
    b.model.deck.subcase = effective.subcase;
    // Gather by kind first: coordinate systems must be known before grids are placed.
    let mut grids = Vec::new();
    let mut coords = Vec::new();
    let mut others = Vec::new();
    let mut grdset: Option<&Card> = None;
    for card in &lexer.cards {
        *counts.entry(card.name.clone()).or_default() += 1;
        match card.name.as_str() {
            "GRID" => grids.push(card),
            "CORD2R" | "CORD2C" | "CORD2S" => coords.push(card),
            "GRDSET" => {
                if let Some(first) = grdset {
                    return Err(cc(card, &files).err_card(format!(
                        "second GRDSET card (the first is on line {})",
                        first.loc.line
                    )));
                }
                grdset = Some(card);
            }
            _ => others.push(card),
        }
    }
    // GRDSET: defaults for the blank CP, CD and PS fields of every GRID.
    let defaults = match grdset {
        Some(card) => {
            let g = cc(card, &files);
            let ps = if g.text(6).is_empty() {
                None
            } else {
                Some(DofMask::from_digits(g.text(6)).ok_or_else(|| g.err(6, "bad PS dof digits"))?)
            };
            (
                g.int(1)?.unwrap_or(0),
                g.int(5)?.unwrap_or(0),
                ps,
                Some(card),
            )
        }
        None => (0, 0, None, None),
    };
    // Coordinate systems.
    let coord_index = resolve_coords(&coords, &files, &mut b.model.coord_systems)?;
    // Grids.
    let mut perm_spc = Vec::new();
    let mut grid_cd = Vec::new();
    for card in &grids {
        let g = cc(card, &files);
        let id = g.id(0, "ID")?;
        let cp = g.int(1)?.unwrap_or(defaults.0);
        let mut x = [g.real_or(2, 0.0)?, g.real_or(3, 0.0)?, g.real_or(4, 0.0)?];
        if cp != 0 {
            let cs = coord_index
                .get(&cp)
                .ok_or_else(|| g.err(1, format!("unknown coordinate system CP {cp}")))?;
            x = to_basic(&b.model.coord_systems[*cs], x);
        }
        let cd = g.int(5)?.unwrap_or(defaults.1);
        if cd > 0 {
            let cs = coord_index
                .get(&cd)
                .ok_or_else(|| g.err(5, format!("unknown coordinate system CD {cd}")))?;
            grid_cd.push((b.model.nodes.len(), *cs));
        }
        if !g.text(6).is_empty() {
            let m = DofMask::from_digits(g.text(6)).ok_or_else(|| g.err(6, "bad PS dof digits"))?;
            perm_spc.push((b.model.nodes.len(), m, *card));
        } else if let (Some(m), Some(gs)) = (defaults.2, defaults.3) {
            perm_spc.push((b.model.nodes.len(), m, gs));
        }
        b.add_node(id, x, card.loc);
    }
    for (n, cs) in grid_cd {
        b.model.nodes[n].displacement_frame = Some(cs);
    }
    let nodes = b.node_map("GRID")?;
    let node = |g: &C, k: usize, id: u64| -> Result<usize, ImportError> {
        nodes
            .get(id)
            .ok_or_else(|| g.err(k, format!("references unknown node {id}")))
    };
    for (n, m, card) in perm_spc {
        if m.0 == 0 {
            continue;
        }
        let at = b.model.spcs.len();
        b.model.spcs.push(Spc {
            node: n,
            dofs: m,
            set_id: 0,
        });
        b.model.constraint_sources.push(ConstraintSource {
            card: format!("{} PS={}", card.name, m.digits()),
            id: format!("GRID {}", b.model.nodes[n].id),
            file: files[card.loc.file as usize].clone(),
            line: card.loc.line as usize,
            set: None,
            spcs: at..at + 1,
            permanent: true,
        });
    }
    // Everything else.
    let mut props: Vec<(u64, u64, Section, &Card)> = Vec::new();
    let mut unsupported_props: HashMap<u64, String> = HashMap::new();
    // Cards of unsupported property types: they share the property id space.
    let mut unsupported_prop_cards: Vec<(u64, &Card)> = Vec::new();
    // CONM2, RBE2 and RBE3 ids: they share the element id space with CBAR, CHEXA, ….
    let mut other_eids: Vec<(u64, &Card)> = Vec::new();
    let mut mats: Vec<(u64, Material, &Card)> = Vec::new();
    let mut elem_pid: Vec<(u64, Loc)> = Vec::new();
    let mut shell_t: Vec<super::shell::ElementThickness> = Vec::new();
    let mut orient: Vec<(usize, Orientation, Loc)> = Vec::new();
    let mut masses: Vec<(PointMass, i64, &Card)> = Vec::new();
    let mut spc_sets: BTreeMap<u64, Vec<(usize, DofMask, &Card)>> = BTreeMap::new();
    let mut spcadd: Vec<SpcAdd> = Vec::new();
    let mut eigen_cards: BTreeMap<u64, &Card> = BTreeMap::new();
    let mut aset_cards: BTreeMap<&str, usize> = BTreeMap::new();
    let mut qset: Vec<(usize, DofMask)> = Vec::new();
    let mut qset_cards: BTreeMap<&str, usize> = BTreeMap::new();
    let mut wtmass = 1.0;
    let mut shear_rigid: Vec<String> = Vec::new();
    // PSOLID ISOP: (FULL, other) property ids — MSC's CHEXA/CPENTA default has bubble modes.
    let mut isop: (Vec<u64>, Vec<u64>) = Default::default();
    let mut load_cards = super::loads::LoadCards::default();
    for card in others {
        let g = cc(card, &files);
        let name = card.name.as_str();
        match name {
            "CTETRA" | "CHEXA" | "CPENTA" | "CBAR" | "CBEAM" | "CROD" | "CQUAD4" | "CTRIA3" => {
                let (kind, ids, o) = element(&g)?;
                let eid = g.id(0, "EID")?;
                let pid = match g.int(1)? {
                    Some(p) if p > 0 => p as u64,
                    Some(_) => return Err(g.err(1, "bad property id")),
                    None => eid,
                };
                if let Some(o) = o {
                    orient.push((b.model.elements.len(), o, card.loc));
                }
                if matches!(name, "CQUAD4" | "CTRIA3") {
                    let k = b.model.elements.len();
                    shell_t.extend(super::shell::element_fields(&g, k)?);
                }
                b.add_element(eid, kind, ids, None, card_name(name), card.loc);
                elem_pid.push((pid, card.loc));
            }
            "PSOLID" | "PSHELL" | "PROD" | "PBAR" | "PBARL" | "PBEAM" | "PBEAML" => {
                let pid = g.id(0, "PID")?;
                if name == "PSOLID" {
                    match g.text(5).to_ascii_uppercase().as_str() {
                        "FULL" | "2" => isop.0.push(pid),
                        _ => isop.1.push(pid),
                    }
                }
                let (mid, section) = match name {
                    "PSHELL" => super::shell::pshell(&g)?,
                    _ => (g.id(1, "MID")?, property(&g)?),
                };
                if let (true, Section::Beam(bs)) = (matches!(name, "PBARL" | "PBEAML"), &section) {
                    if bs.shear_factors.is_none() {
                        shear_rigid.push(format!(
                            "{name} {pid} TYPE {} ({}:{})",
                            g.text(3),
                            g.file,
                            card.loc.line
                        ));
                    }
                }
                props.push((pid, mid, section, card));
            }
            "PCOMP" => {
                let pid = g.id(0, "PID")?;
                let (mid, section) = super::shell::pcomp(&g)?;
                props.push((pid, mid, section, card));
            }
            "CQUAD8" | "CTRIA6" | "CQUADR" | "CTRIAR" => {
                return Err(g.err_card(format!(
                "{name}: quadratic and CQUADR/CTRIAR shells are not supported (use CQUAD4/CTRIA3)"
            )))
            }
            "PCOMPG" | "PELAS" | "PBUSH" | "PSHEAR" | "PDAMP" | "PGAP" | "PMASS" | "PVISC" => {
                let pid = g.id(0, "PID")?;
                unsupported_props.insert(pid, name.to_owned());
                unsupported_prop_cards.push((pid, card));
                *unsupported.entry(name.to_owned()).or_default() += 1;
            }
            "MAT1" => {
                let mid = g.id(0, "MID")?;
                mats.push((mid, mat1(&g, mid)?, card));
            }
            "CONM2" => {
                let eid = g.id(0, "EID")?;
                other_eids.push((eid, card));
                let n = node(&g, 1, g.id(1, "G")?)?;
                let cid = g.int(2)?.unwrap_or(0);
                let m = g.real_or(3, 0.0)?;
                let x = [g.real_or(4, 0.0)?, g.real_or(5, 0.0)?, g.real_or(6, 0.0)?];
                let mut i = [0.0; 6];
                for (k, v) in i.iter_mut().enumerate() {
                    *v = g.real_or(8 + k, 0.0)?;
                }
                let [i11, i21, i22, i31, i32, i33] = i;
                // Nastran CONM2 tensor: [I11 −I21 −I31; −I21 I22 −I32; −I31 −I32 I33].
                let inertia = [[i11, -i21, -i31], [-i21, i22, -i32], [-i31, -i32, i33]];
                masses.push((
                    PointMass {
                        id: eid,
                        node: n,
                        mass: m,
                        offset: x,
                        inertia,
                    },
                    cid,
                    card,
                ));
            }
            "RBE2" => {
                let eid = g.id(0, "EID")?;
                other_eids.push((eid, card));
                let gn = node(&g, 1, g.id(1, "GN")?)?;
                let cm = DofMask::from_digits(g.text(2))
                    .filter(|m| m.0 != 0)
                    .ok_or_else(|| g.err(2, "bad CM dof digits"))?;
                let mut dep = Vec::new();
                for (id, k) in g.id_list(3, &thru_budget)? {
                    dep.push(node(&g, k, id)?);
                }
                if dep.is_empty() {
                    return Err(g.err_card("no dependent grids"));
                }
                b.model.rigid_elements.push(RigidElement::Rbe2 {
                    id: eid,
                    independent: gn,
                    dependent: dep,
                    dofs: cm,
                });
            }
            "RBE3" => {
                other_eids.push((g.id(0, "EID")?, card));
                b.model.rigid_elements.push(rbe3(&g, &node)?)
            }
            "SPC" => {
                let sid = g.id(0, "SID")?;
                for k in [1, 4] {
                    if g.text(k).is_empty() {
                        continue;
                    }
                    let n = node(&g, k, g.id(k, "G")?)?;
                    let m = DofMask::from_digits(g.text(k + 1))
                        .ok_or_else(|| g.err(k + 1, "bad dof digits"))?;
                    if g.real_or(k + 2, 0.0)? != 0.0 {
                        return Err(g.err(k + 2, "enforced displacement not supported"));
                    }
                    spc_sets.entry(sid).or_default().push((n, m, card));
                }
            }
            "SPC1" => {
                let sid = g.id(0, "SID")?;
                let m =
                    DofMask::from_digits(g.text(1)).ok_or_else(|| g.err(1, "bad dof digits"))?;
                let thru = (2..card.fields.len()).any(|k| g.text(k).eq_ignore_ascii_case("THRU"));
                for (id, k) in g.id_list(2, &thru_budget)? {
                    match nodes.get(id) {
                        Some(n) => spc_sets.entry(sid).or_default().push((n, m, card)),
                        None if thru => {}
                        None => return Err(g.err(k, format!("references unknown node {id}"))),
                    }
                }
            }
            "SPCADD" => spcadd.push((g.id(0, "SID")?, g.id_list(1, &thru_budget)?, card)),
            "ASET" | "BSET" | "QSET" => {
                let mut k = 0;
                while !g.text(k).is_empty() {
                    let n = node(&g, k, g.id(k, "G")?)?;
                    let m = DofMask::from_digits(g.text(k + 1))
                        .filter(|m| m.0 != 0)
                        .ok_or_else(|| g.err(k + 1, "bad dof digits"))?;
                    if name == "QSET" {
                        qset.push((n, m));
                    } else {
                        b.model.interface.push(InterfaceDofs { node: n, dofs: m });
                    }
                    k += 2;
                }
                if name == "QSET" {
                    *qset_cards.entry("QSET").or_default() += 1;
                } else {
                    *aset_cards
                        .entry(if name == "ASET" { "ASET" } else { "BSET" })
                        .or_default() += 1;
                }
            }
            "ASET1" | "BSET1" | "QSET1" => {
                let m = DofMask::from_digits(g.text(0))
                    .filter(|m| m.0 != 0)
                    .ok_or_else(|| g.err(0, "bad dof digits"))?;
                let thru = (1..card.fields.len()).any(|k| g.text(k).eq_ignore_ascii_case("THRU"));
                for (id, k) in g.id_list(1, &thru_budget)? {
                    let n = match nodes.get(id) {
                        Some(n) => n,
                        None if thru => continue,
                        None => return Err(g.err(k, format!("references unknown node {id}"))),
                    };
                    if name == "QSET1" {
                        qset.push((n, m));
                    } else {
                        b.model.interface.push(InterfaceDofs { node: n, dofs: m });
                    }
                }
                if name == "QSET1" {
                    *qset_cards.entry("QSET1").or_default() += 1;
                } else {
                    *aset_cards
                        .entry(if name == "ASET1" { "ASET1" } else { "BSET1" })
                        .or_default() += 1;
                }
            }
            "FORCE" | "MOMENT" | "GRAV" | "PLOAD4" | "LOAD" => load_cards.cards.push(card),
            "EIGRL" | "EIGR" => {
                let sid = g.id(0, "SID")?;
                if let Some(prev) = eigen_cards.insert(sid, card) {
                    return Err(g.err(
                        0,
                        format!(
                            "duplicate eigenvalue method id {sid} (also {} on line {})",
                            prev.name, prev.loc.line
                        ),
                    ));
                }
            }
            "PARAM" => {
                let p = g.text(0).to_ascii_uppercase();
                match p.as_str() {
                    "WTMASS" => {
                        wtmass = g
                            .real(1)?
                            .filter(|w| *w > 0.0)
                            .ok_or_else(|| g.err(1, "WTMASS must be > 0"))?;
                    }
                    "COUPMASS" => b.model.params.coupled_mass = Some(g.real_or(1, -1.0)? > 0.0),
                    _ => *unsupported.entry(format!("PARAM,{p}")).or_default() += 1,
                }
            }
            _ => *unsupported.entry(name.to_owned()).or_default() += 1,
        }
    }
    b.resolve_element_nodes(&nodes)?;
    // One element id space (MSC/NX Nastran): structural elements, CONM2 and rigid elements.
    let eids: Vec<(u64, &str, Loc)> = (b.model.elements.iter().enumerate())
        .map(|(k, e)| (e.id, b.elem_card[k], b.elem_loc[k]))
        .chain(
            other_eids
                .iter()
                .map(|(id, c)| (*id, c.name.as_str(), c.loc)),
        )
        .collect();
    unique_ids(
        &eids,
        &files,
        "element id",
        "elements, CONM2 and rigid elements share one id space",
    )?;
    // Materials. Only MAT1 is read; other MATi cards may legally share a MAT1 id (e.g. MAT4
    // holds the thermal data of the same material), so only MAT1 ids must be unique.
    let mat_ids: Vec<(u64, &str, Loc)> = mats.iter().map(|m| (m.0, "MAT1", m.2.loc)).collect();
    unique_ids(&mat_ids, &files, "material id", "MAT1 ids must be unique")?;
    let mids = IdMap::build(mats.iter().map(|m| m.0))
        .map_err(|(_, k)| cc(mats[k].2, &files).err_card("duplicate material id"))?;
    b.model.materials = mats.iter().map(|m| m.1.clone()).collect();
    for m in &mut b.model.materials {
        m.rho *= wtmass;
    }
    // Properties: supported and unsupported types share one id space.
    let prop_ids: Vec<(u64, &str, Loc)> = (props.iter().map(|p| (p.0, p.3)))
        .chain(unsupported_prop_cards.iter().copied())
        .map(|(id, c)| (id, c.name.as_str(), c.loc))
        .collect();
    unique_ids(
        &prop_ids,
        &files,
        "property id",
        "all property cards share one id space",
    )?;
    let pids = IdMap::build(props.iter().map(|p| p.0))
        .map_err(|(_, k)| cc(props[k].3, &files).err_card("duplicate property id"))?;
    for (pid, mid, section, card) in &props {
        let material = mids
            .get(*mid)
            .ok_or_else(|| cc(card, &files).err(1, format!("references unknown material {mid}")))?;
        let mut section = section.clone();
        match &mut section {
            Section::Beam(s) => s.nsm *= wtmass,
            Section::Rod { nsm, .. } => *nsm *= wtmass,
            Section::Shell(s) => {
                s.nsm *= wtmass;
                super::shell::resolve_mids(s, &mids, &cc(card, &files))?;
            }
            _ => {}
        }
        b.model.properties.push(Property {
            id: *pid,
            name: format!("{} {pid}", card.name),
            material,
            section,
        });
    }
    let mut element_sets: BTreeMap<String, Vec<usize>> = BTreeMap::new();
    let mut no_prop: BTreeMap<(&str, String), (usize, u64)> = BTreeMap::new();
    for (k, (pid, loc)) in elem_pid.iter().enumerate() {
        let e = &b.model.elements[k];
        match pids.get(*pid) {
            Some(p) => {
                b.model.elements[k].property = Some(p);
                element_sets
                    .entry(format!("PID_{pid}"))
                    .or_default()
                    .push(k);
            }
            None => match unsupported_props.get(pid) {
                Some(card) => {
                    let entry = no_prop
                        .entry((b.elem_card[k], card.clone()))
                        .or_insert((0, e.id));
                    entry.0 += 1;
                }
                None => {
                    return Err(parse_err(
                        b.file_name(*loc),
                        loc.line as usize,
                        format!("{} {}", b.elem_card[k], e.id),
                        format!("references unknown property {pid}"),
                    ))
                }
            },
        }
    }
    super::shell::apply_thickness(&mut b.model, &shell_t)?;
    for ((elem, card), (n, first)) in no_prop {
        b.model.warnings.push(ImportWarning {
            file: files[0].clone(),
            message: format!(
                "{n} {elem} elements (first: {first}) reference {card} properties (unsupported): no property"
            ),
        });
    }
    // Bar/beam orientation.
    for (k, o, loc) in orient {
        let e = &b.model.elements[k];
        let ga = e.nodes[0];
        let v = match o {
            Orientation::Vector(v) => match b.model.nodes[ga].displacement_frame {
                Some(cs) if b.model.coord_systems[cs].kind == CoordKind::Rectangular => {
                    dir_to_basic(&b.model.coord_systems[cs], v)
                }
                _ => v,
            },
            Orientation::Node(g0) => {
                let n0 = nodes.get(g0).ok_or_else(|| {
                    parse_err(
                        b.file_name(loc),
                        loc.line as usize,
                        format!("{} {}", b.elem_card[k], e.id),
                        format!("orientation node G0 {g0} unknown"),
                    )
                })?;
                let (x0, xa) = (b.model.nodes[n0].x, b.model.nodes[ga].x);
                [x0[0] - xa[0], x0[1] - xa[1], x0[2] - xa[2]]
            }
        };
        b.model.elements[k].orientation = Some(v);
    }
    // Point masses: offsets/inertia to basic, WTMASS.
    for (mut pm, cid, card) in masses {
        let g = cc(card, &files);
        match cid {
            -1 => {
                let xn = b.model.nodes[pm.node].x;
                pm.offset = [
                    pm.offset[0] - xn[0],
                    pm.offset[1] - xn[1],
                    pm.offset[2] - xn[2],
                ];
            }
            0 => {}
            _ => {
                let cs = &b.model.coord_systems[*coord_index
                    .get(&cid)
                    .ok_or_else(|| g.err(2, format!("unknown coordinate system CID {cid}")))?];
                if cs.kind != CoordKind::Rectangular {
                    return Err(g.err(2, "CONM2 in a non-rectangular system not supported"));
                }
                pm.offset = dir_to_basic(cs, pm.offset);
                // I_basic = Aᵀ I A with A's rows the local axes.
                let a = cs.axes;
                let mut ib = [[0.0; 3]; 3];
                for (i, row) in ib.iter_mut().enumerate() {
                    for (j, v) in row.iter_mut().enumerate() {
                        *v = (0..3)
                            .flat_map(|p| (0..3).map(move |q| (p, q)))
                            .map(|(p, q)| a[p][i] * pm.inertia[p][q] * a[q][j])
                            .sum();
                    }
                }
                pm.inertia = ib;
            }
        }
        pm.mass *= wtmass;
        pm.inertia = pm.inertia.map(|r| r.map(|v| v * wtmass));
        b.model.point_masses.push(pm);
    }
    // SPC sets: every set is a node set SPC_<sid>; only the one the case control selects holds.
    let mut node_sets = BTreeMap::new();
    for (sid, list) in &spc_sets {
        let mut ns: Vec<usize> = list.iter().map(|p| p.0).collect();
        ns.sort_unstable();
        ns.dedup();
        node_sets.insert(format!("SPC_{sid}"), ns);
    }
    let mut spcadd_members: BTreeMap<u64, (Vec<u64>, &Card)> = BTreeMap::new();
    for (sid, sets, card) in &spcadd {
        let entry = spcadd_members.entry(*sid).or_insert((Vec::new(), card));
        for &(s, k) in sets {
            if !spc_sets.contains_key(&s) {
                return Err(cc(card, &files).err(k, format!("references unknown SPC set {s}")));
            }
            if !entry.0.contains(&s) {
                entry.0.push(s);
            }
        }
        let mut ns: Vec<usize> = entry
            .0
            .iter()
            .flat_map(|s| spc_sets[s].iter().map(|p| p.0))
            .collect();
        ns.sort_unstable();
        ns.dedup();
        node_sets.insert(format!("SPC_{sid}"), ns);
    }
    for (sid, list) in &spc_sets {
        b.model.deck.spc_sets.insert(
            format!("SPC_{sid}"),
            list.iter().map(|&(n, m, _)| (n, m)).collect(),
        );
    }
    for (sid, (members, _)) in &spcadd_members {
        let all = members
            .iter()
            .flat_map(|s| spc_sets[s].iter().map(|&(n, m, _)| (n, m)))
            .collect();
        b.model.deck.spc_sets.insert(format!("SPC_{sid}"), all);
    }
    let mut applied: Vec<u64> = Vec::new();
    if let Some(sel) = effective.scope.spc {
        let members = match spcadd_members.get(&sel.id) {
            Some((m, _)) => m.clone(),
            None if spc_sets.contains_key(&sel.id) => vec![sel.id],
            None => {
                return Err(parse_err(
                    &files[sel.loc.file as usize],
                    sel.loc.line as usize,
                    format!("SPC = {}", sel.id),
                    format!(
                        "the case control selects SPC set {}, but the bulk data has no SPC, SPC1 or SPCADD with that id",
                        sel.id
                    ),
                ))
            }
        };
        for s in members {
            applied.push(s);
            for &(node, dofs, card) in &spc_sets[&s] {
                let at = b.model.spcs.len();
                b.model.spcs.push(Spc {
                    node,
                    dofs,
                    set_id: sel.id,
                });
                match b.model.constraint_sources.last_mut() {
                    Some(last)
                        if !last.permanent
                            && last.spcs.end == at
                            && last.line == card.loc.line as usize
                            && last.file == files[card.loc.file as usize] =>
                    {
                        last.spcs.end = at + 1;
                    }
                    _ => b.model.constraint_sources.push(ConstraintSource {
                        card: card.name.clone(),
                        id: if s == sel.id {
                            format!("set {s}")
                        } else {
                            format!("set {s} (SPCADD {})", sel.id)
                        },
                        file: files[card.loc.file as usize].clone(),
                        line: card.loc.line as usize,
                        set: Some(format!("SPC_{s}")),
                        spcs: at..at + 1,
                        permanent: false,
                    }),
                }
            }
        }
    }
    let unselected: Vec<String> = spc_sets
        .keys()
        .chain(spcadd_members.keys())
        .filter(|s| !applied.contains(s) && effective.scope.spc.is_none_or(|x| x.id != **s))
        .map(|s| format!("SPC_{s}"))
        .collect();
    if !unselected.is_empty() {
        let why = if !case.present {
            "the file has no case control (bare bulk data), so no SPC set is selected".to_owned()
        } else {
            match effective.scope.spc {
                None => "the case control selects no SPC set (free-free)".to_owned(),
                Some(s) => format!("the case control selects SPC = {}", s.id),
            }
        };
        b.model.deck.notes.push(format!(
            "{}: SPC sets {} in the bulk data are not applied: {why}; their nodes are node sets of these names (for --interface / --reference-conditions)",
            files[0],
            unselected.join(", ")
        ));
    }
    // METHOD → EIGRL/EIGR: the default mode count or band.
    if let Some(sel) = effective.scope.method {
        let card = eigen_cards.get(&sel.id).ok_or_else(|| {
            parse_err(
                &files[sel.loc.file as usize],
                sel.loc.line as usize,
                format!("METHOD = {}", sel.id),
                format!(
                    "the case control selects eigenvalue method {}, but the bulk data has no EIGRL or EIGR with that id",
                    sel.id
                ),
            )
        })?;
        let g = cc(card, &files);
        // EIGRL: SID V1 V2 ND; EIGR: SID METHOD F1 F2 NE ND.
        let (lo, hi, nd) = if card.name == "EIGRL" {
            (g.real(1)?, g.real(2)?, g.int(3)?)
        } else {
            (g.real(2)?, g.real(3)?, g.int(5)?)
        };
        let count = match nd {
            Some(n) if n > 0 => Some(n as usize),
            Some(n) => {
                return Err(g.err(
                    if card.name == "EIGRL" { 3 } else { 5 },
                    format!("ND = {n} must be > 0"),
                ))
            }
            None => None,
        };
        if count.is_none() && hi.is_none() {
            return Err(
                g.err_card("neither ND nor an upper frequency V2/F2 is given: no mode count")
            );
        }
        b.model.deck.eigen = Some(EigenRequest {
            source: format!(
                "METHOD = {} ({}:{}) → {} {} ({}:{})",
                sel.id,
                files[sel.loc.file as usize],
                sel.loc.line,
                card.name,
                sel.id,
                files[card.loc.file as usize],
                card.loc.line
            ),
            count,
            lower_hz: lo,
            upper_hz: hi,
        });
    }
    if !aset_cards.is_empty() {
        let cards: Vec<String> = aset_cards.iter().map(|(c, n)| format!("{n} {c}")).collect();
        let mut ns: Vec<usize> = b.model.interface.iter().map(|i| i.node).collect();
        ns.sort_unstable();
        ns.dedup();
        b.model.deck.interface_source = Some(format!(
            "{} ({} dofs at {} nodes)",
            cards.join(", "),
            b.model
                .interface
                .iter()
                .map(|i| i.dofs.0.count_ones() as usize)
                .sum::<usize>(),
            ns.len()
        ));
    }
    if !qset.is_empty() {
        let cards: Vec<String> = qset_cards.iter().map(|(c, n)| format!("{n} {c}")).collect();
        let mut per_node: BTreeMap<usize, u8> = BTreeMap::new();
        for (n, m) in &qset {
            *per_node.entry(*n).or_default() |= m.0;
        }
        let q = per_node.values().map(|m| m.count_ones() as usize).sum();
        b.model.deck.qset_modes = Some((q, cards.join(", ")));
    }
    if !shear_rigid.is_empty() {
        b.model.warnings.push(ImportWarning {
            file: files[0].clone(),
            message: format!(
                "{}: the shear factors Nastran derives for these cross-section shapes are not implemented here (only ROD's 0.9): shear-rigid bending, stiffer than Nastran's shear-flexible element",
                shear_rigid.join(", ")
            ),
        });
    }
    b.model.node_sets = node_sets;
    b.model.element_sets = element_sets;
    b.model.params.wtmass = wtmass;
    b.model.params.solid_bubbles = isop.0.is_empty();
    if !isop.0.is_empty() && !isop.1.is_empty() {
        b.model.warnings.push(ImportWarning {
            file: files[0].clone(),
            message: format!(
                "PSOLID {:?} ask for full integration (ISOP = FULL), PSOLID {:?} for MSC's default \
                 bubble functions: one formulation per model is implemented, every CHEXA/CPENTA \
                 is fully integrated (stiffer than MSC Nastran on the others)",
                isop.0, isop.1
            ),
        });
    }
    for (name, n) in unsupported {
        b.model.warnings.push(ImportWarning {
            file: files[0].clone(),
            message: format!("unsupported card {name} ignored ({n} cards)"),
        });
    }
    let elements = b.element_map()?;
    let load_sel = case.load_selections(effective.subcase);
    b.model.loads =
        super::loads::resolve(&load_cards, &files, &b.model, &nodes, &elements, &load_sel)?;
    let load_warnings = crate::model::load::problem_warnings(&b.model.loads, &files[0]);
    b.model.warnings.extend(load_warnings);
    b.model.files = b.files.clone();
    b.record_element_sources();
    Ok((b.model, counts))
}

/// Fail on the first id of `items` (id, card name, location) seen twice, naming both places.
fn unique_ids(
    items: &[(u64, &str, Loc)],
    files: &[String],
    what: &str,
    rule: &str,
) -> Result<(), ImportError> {
    IdMap::build(items.iter().map(|i| i.0))
        .map(|_| ())
        .map_err(|(a, k)| {
            let ((id, card, loc), (_, first, floc)) = (items[k], items[a]);
            parse_err(
                &files[loc.file as usize],
                loc.line as usize,
                format!("{card} {id}"),
                format!(
                    "duplicate {what} {id}: also {first} {id} at {}:{} ({rule})",
                    files[floc.file as usize], floc.line
                ),
            )
        })
}

fn cc<'a>(card: &'a Card, files: &'a [String]) -> C<'a> {
    C {
        card,
        file: &files[card.loc.file as usize],
    }
}

fn card_name(name: &str) -> &'static str {
    match name {
        "CTETRA" => "CTETRA",
        "CHEXA" => "CHEXA",
        "CPENTA" => "CPENTA",
        "CBAR" => "CBAR",
        "CBEAM" => "CBEAM",
        "CROD" => "CROD",
        "CQUAD4" => "CQUAD4",
        _ => "CTRIA3",
    }
}

enum Orientation {
    Vector([f64; 3]),
    Node(u64),
}

/// Element card → (kind, external node ids in Abaqus order, orientation).
fn element(g: &C) -> Result<(ElementKind, Vec<usize>, Option<Orientation>), ImportError> {
    use ElementKind::*;
    let name = g.card.name.as_str();
    let (range, kinds): (usize, &[(usize, ElementKind)]) = match name {
        "CTETRA" => (10, &[(4, Tet4), (10, Tet10)]),
        "CHEXA" => (20, &[(8, Hex8), (20, Hex20)]),
        "CPENTA" => (15, &[(6, Prism6), (15, Prism15)]),
        "CBAR" => (2, &[(2, Bar2)]),
        "CBEAM" => (2, &[(2, Beam2)]),
        "CROD" => (2, &[(2, Rod2)]),
        "CQUAD4" => (4, &[(4, Quad4)]),
        _ => (3, &[(3, Tri3)]),
    };
    let mut ids = Vec::with_capacity(range);
    let mut last = 0;
    for k in 2..2 + range {
        if let Some(v) = g.int(k)? {
            if v <= 0 {
                return Err(g.err(k, format!("bad node id {v}")));
            }
            if ids.len() != k - 2 {
                return Err(g.err(
                    k,
                    "blank node field before a given node (partial mid-side nodes not supported)",
                ));
            }
            ids.push(v as usize);
            last = k;
        }
    }
    let Some(&(_, kind)) = kinds.iter().find(|(n, _)| *n == ids.len()) else {
        let want: Vec<String> = kinds.iter().map(|k| k.0.to_string()).collect();
        return Err(g.err(
            last.max(2),
            format!(
                "{name} needs {} nodes, has {} (missing continuation line?)",
                want.join(" or "),
                ids.len()
            ),
        ));
    };
    // Nastran CHEXA20 / CPENTA15: vertical edges before top edges; Abaqus: top edges first.
    if kind == Hex20 {
        ids = [&ids[..12], &ids[16..20], &ids[12..16]].concat();
    } else if kind == Prism15 {
        ids = [&ids[..9], &ids[12..15], &ids[9..12]].concat();
    }
    let orientation = if kind == Beam2 || kind == Bar2 {
        let s = g.text(4);
        if s.is_empty() {
            return Err(g.err(
                4,
                "orientation X1/G0 is blank (BAROR defaults not supported)",
            ));
        }
        if !s.contains('.') && !s.contains(['e', 'E']) {
            Some(Orientation::Node(g.id(4, "G0")?))
        } else {
            Some(Orientation::Vector([
                g.real_or(4, 0.0)?,
                g.real_or(5, 0.0)?,
                g.real_or(6, 0.0)?,
            ]))
        }
    } else {
        None
    };
    Ok((kind, ids, orientation))
}

fn mat1(g: &C, mid: u64) -> Result<Material, ImportError> {
    let (e, gg, nu) = (g.real(1)?, g.real(2)?, g.real(3)?);
    // Two of E, G, ν given → the third from G = E / (2(1+ν)).
    let (e, gg, nu) = match (e, gg, nu) {
        (Some(e), Some(gg), Some(nu)) => (e, gg, nu),
        (Some(e), None, Some(nu)) => (e, e / (2.0 * (1.0 + nu)), nu),
        (Some(e), Some(gg), None) => (e, gg, e / (2.0 * gg) - 1.0),
        (None, Some(gg), Some(nu)) => (2.0 * (1.0 + nu) * gg, gg, nu),
        _ => return Err(g.err_card("MAT1 needs two of E, G, NU")),
    };
    Ok(Material {
        id: mid,
        name: format!("MAT1 {mid}"),
        e,
        nu,
        g: gg,
        rho: g.real_or(4, 0.0)?,
    })
}

/// Beam section from the fields holding [A, I1, I2, I12, J, NSM] (blank = 0).
fn beam(g: &C, at: [usize; 6], k: Option<[f64; 2]>) -> Result<Section, ImportError> {
    let mut v = [0.0; 6];
    for (x, &f) in v.iter_mut().zip(&at) {
        *x = g.real_or(f, 0.0)?;
    }
    let [area, i1, i2, i12, j, nsm] = v;
    Ok(Section::Beam(BeamSection {
        area,
        i1,
        i2,
        i12,
        j,
        shear_factors: k,
        nsm,
        shape: None,
    }))
}

/// Standard shape from PBARL/PBEAML TYPE and dimensions (MSC QRG "PBARL"), with dimension count.
fn nastran_shape(ty: &str, d: &[f64]) -> Option<(SectionShape, usize)> {
    Some(match (ty, d) {
        ("ROD", [r, ..]) => (SectionShape::Circle { radius: *r }, 1),
        ("TUBE", [ro, ri, ..]) => (
            SectionShape::Tube {
                outer_radius: *ro,
                inner_radius: *ri,
            },
            2,
        ),
        ("BAR", [w, h, ..]) => (
            SectionShape::Rectangle {
                width: *w,
                height: *h,
            },
            2,
        ),
        // BOX: DIM1 width, DIM2 height, DIM3 top/bottom wall, DIM4 side walls.
        ("BOX", [w, h, t1, t2, ..]) => (
            SectionShape::Box {
                width: *w,
                height: *h,
                t_web: *t2,
                t_flange: *t1,
            },
            4,
        ),
        ("I", [h, wb, wt, tw, tb, tt, ..]) => (
            SectionShape::I {
                height: *h,
                width_bottom: *wb,
                width_top: *wt,
                t_web: *tw,
                t_bottom: *tb,
                t_top: *tt,
            },
            6,
        ),
        _ => return None,
    })
}

fn property(g: &C) -> Result<Section, ImportError> {
    Ok(match g.card.name.as_str() {
        "PSOLID" => Section::Solid,
        "PROD" => Section::Rod {
            area: g.real_or(2, 0.0)?,
            j: g.real_or(3, 0.0)?,
            nsm: g.real_or(5, 0.0)?,
        },
        "PBAR" => {
            let k = match (g.real(16)?, g.real(17)?) {
                (None, None) => None,
                (k1, k2) => Some([k1.unwrap_or(0.0), k2.unwrap_or(0.0)]),
            };
            beam(g, [2, 3, 4, 18, 5, 6], k)?
        }
        "PBEAM" => {
            // End A values; skip the stress-point line and any intermediate/end-B stations.
            let mut k = 8;
            let so = |k: usize| {
                matches!(
                    g.text(k).to_ascii_uppercase().as_str(),
                    "YES" | "YESA" | "NO"
                )
            };
            if !so(k) && g.card.fields.len() > k {
                k += 8;
            }
            while so(k) {
                k += 16;
            }
            // Nastran PBEAM: K1, K2 default 1.0 (shear flexible); 0.0 means shear-rigid.
            let kf = Some([g.real(k)?.unwrap_or(1.0), g.real(k + 1)?.unwrap_or(1.0)]);
            beam(g, [2, 3, 4, 5, 6, 7], kf)?
        }
        _ => {
            // PBARL / PBEAML: TYPE in field 5, dimensions from the first continuation.
            let ty = g.text(3).to_ascii_uppercase();
            let mut d = Vec::new();
            for k in 8..g.card.fields.len().min(8 + 7) {
                match g.real(k)? {
                    Some(v) => d.push(v),
                    None => break,
                }
            }
            let (shape, n) = nastran_shape(&ty, &d).ok_or_else(|| {
                g.err(3, format!("cross-section TYPE {ty} with {} dimensions not supported (ROD, TUBE, BAR, BOX, I)", d.len()))
            })?;
            let nsm = d.get(n).copied().unwrap_or(0.0);
            let mut s = shape
                .to_section()
                .ok_or_else(|| g.err(3, "unsupported shape"))?;
            s.nsm = nsm;
            // The shear factors Nastran derives for the shape (its equivalent PBAR/PBEAM).
            s.shear_factors = shape.nastran_shear_factors();
            Section::Beam(s)
        }
    })
}

fn rbe3(
    g: &C,
    node: &dyn Fn(&C, usize, u64) -> Result<usize, ImportError>,
) -> Result<RigidElement, ImportError> {
    let eid = g.id(0, "EID")?;
    let reference = node(g, 2, g.id(2, "REFGRID")?)?;
    let ref_dofs = DofMask::from_digits(g.text(3))
        .filter(|m| m.0 != 0)
        .ok_or_else(|| g.err(3, "bad REFC dof digits"))?;
    let mut independent = Vec::new();
    let mut k = 4;
    let n = g.card.fields.len();
    let (mut w, mut c) = (None, None);
    while k < n {
        let s = g.text(k);
        if s.is_empty() {
            k += 1;
            continue;
        }
        let up = s.to_ascii_uppercase();
        if up == "UM" {
            return Err(g.err(k, "RBE3 UM (user-selected dependent dofs) not supported"));
        }
        if up == "ALPHA" {
            break;
        }
        if s.contains('.') || s.contains(['e', 'E']) {
            w = Some(g.real(k)?.unwrap_or(1.0));
            c = None;
        } else if c.is_none() {
            if w.is_none() {
                return Err(g.err(k, "component before a weight"));
            }
            c = Some(DofMask::from_digits(s).ok_or_else(|| g.err(k, "bad dof digits"))?);
        } else {
            let id = g.id(k, "G")?;
            independent.push((
                node(g, k, id)?,
                w.unwrap_or(1.0),
                c.unwrap_or(DofMask::TRANSLATIONS),
            ));
        }
        k += 1;
    }
    if independent.is_empty() {
        return Err(g.err_card("no independent grids"));
    }
    Ok(RigidElement::Rbe3 {
        id: eid,
        reference,
        ref_dofs,
        independent,
    })
}

/// Resolve CORD2R/C/S chains into `out`; returns CID → index. Errors: unknown RID, cycles,
/// duplicate CID, degenerate points.
fn resolve_coords(
    cards: &[&Card],
    files: &[String],
    out: &mut Vec<CoordSystem>,
) -> Result<HashMap<i64, usize>, ImportError> {
    let mut by_id: HashMap<i64, usize> = HashMap::new();
    for (k, card) in cards.iter().enumerate() {
        let g = C {
            card,
            file: &files[card.loc.file as usize],
        };
        let cid = g.req_int(0, "CID")?;
        if cid <= 0 {
            return Err(g.err(0, "CID must be > 0"));
        }
        if by_id.insert(cid, k).is_some() {
            return Err(g.err(0, "duplicate coordinate system id"));
        }
    }
    let mut index: HashMap<i64, usize> = HashMap::new();
    for start in 0..cards.len() {
        let mut chain = vec![start];
        // Walk down to a resolved system or the basic frame.
        loop {
            let card = cards[*chain.last().unwrap_or(&start)];
            let g = C {
                card,
                file: &files[card.loc.file as usize],
            };
            let rid = g.int(1)?.unwrap_or(0);
            if rid == 0 || index.contains_key(&rid) {
                break;
            }
            let next = *by_id.get(&rid).ok_or_else(|| {
                g.err(1, format!("unknown reference coordinate system RID {rid}"))
            })?;
            if chain.contains(&next) {
                return Err(g.err(1, format!("cycle of coordinate systems through RID {rid}")));
            }
            chain.push(next);
        }
        for &k in chain.iter().rev() {
            let card = cards[k];
            let g = C {
                card,
                file: &files[card.loc.file as usize],
            };
            let cid = g.req_int(0, "CID")?;
            if index.contains_key(&cid) {
                continue;
            }
            let rid = g.int(1)?.unwrap_or(0);
            let mut p = [[0.0; 3]; 3];
            for (i, pt) in p.iter_mut().enumerate() {
                for (d, v) in pt.iter_mut().enumerate() {
                    *v = g.real_or(2 + 3 * i + d, 0.0)?;
                }
            }
            if rid != 0 {
                let r = &out[index[&rid]];
                p = p.map(|q| to_basic(r, q));
            }
            let kind = match card.name.as_str() {
                "CORD2R" => CoordKind::Rectangular,
                "CORD2C" => CoordKind::Cylindrical,
                _ => CoordKind::Spherical,
            };
            let cs = from_points(cid as u64, kind, p[0], p[1], p[2])
                .ok_or_else(|| g.err_card("degenerate points A, B, C"))?;
            out.push(cs);
            index.insert(cid, out.len() - 1);
        }
    }
    Ok(index)
}
