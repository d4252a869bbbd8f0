//! ANSYS Mechanical APDL archives (`.cdb`, as `CDWRITE` writes them) and full files (`.full`,
//! [`full`]).
//!
//! The archive is read line by line ([`blocks`]): every command and element type has a row in
//! the catalogue ([`catalogue`], `docs/ansys-commands.md`) — honoured, a note (one per command,
//! with its lines) or refused; a name in no table is refused by its line, and every refusal of
//! the archive is listed in one error (`ImportOptions::ignore_cards` drops a name on purpose).
//! Elements are formed by type and KEYOPT ([`elements`], [`form`]), materials from
//! `MPTEMP`/`MPDATA` ([`materials`]), the section commands in [`sections`] (shell and beam
//! sections in [`shells`] and [`beams`]), `D`/`CE`/`CP`/`F`/`ACEL` in [`constraints`], `SFE`
//! pressures in [`surface`], the `NBLOCK`'s nodal coordinate systems in [`nodal`], `LOCAL`
//! systems and the elements' ESYS (orthotropic material axes) in [`esys`]; contact
//! pairs (remote points, bonded contact) in [`contact`] and [`bonded`]; node and element
//! components (`CMBLOCK`) become the model's named sets.

mod beams;
mod blocks;
mod bonded;
pub mod catalogue;
mod connections;
mod constraints;
mod contact;
mod elements;
mod esys;
mod form;
pub mod full;
mod legacy;
mod materials;
mod nodal;
mod sections;
mod segments;
mod shells;
mod surface;

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

use self::blocks::{Command, ElementRecord, Lines, NodeRecord};
use self::catalogue::Disposition;
use self::connections::free_dependents;
use self::elements::{ElementType, LinkSection};
use super::error::{parse_err, ImportError, RefusedCard};
use super::text::IdMap;
use super::ImportOptions;
use crate::model::deck::EigenRequest;
use crate::model::{Model, Node, Property, Section};

/// The archive's materials into `model`, each with a solid property: material number →
/// property index.
fn solid_properties(
    materials: &BTreeMap<i64, crate::model::Material>,
    model: &mut Model,
) -> BTreeMap<i64, usize> {
    let mut property_of = BTreeMap::new();
    for (mat, m) in materials {
        model.materials.push(m.clone());
        model.properties.push(Property {
            id: (*mat).max(0) as u64,
            name: format!("MAT{mat}"),
            material: model.materials.len() - 1,
            section: Section::Solid,
        });
        property_of.insert(*mat, model.properties.len() - 1);
    }
    property_of
}

/// Read an archive with default options.
pub fn read(path: &Path) -> Result<Model, ImportError> {
    read_with_options(path, &ImportOptions::default())
}

/// Whether a line (upper case, trimmed) is one only an ANSYS archive has: an `NBLOCK` or
/// `EBLOCK` header (for format detection by content).
pub(crate) fn is_block_header(line: &str) -> bool {
    let head = line.get(..7).unwrap_or("");
    head.eq_ignore_ascii_case("NBLOCK,") || head.eq_ignore_ascii_case("EBLOCK,")
}

/// Read an archive.
pub fn read_with_options(path: &Path, opts: &ImportOptions) -> Result<Model, ImportError> {
    let file = path.display().to_string();
    let text = super::text::read_text(path)?;
    let ignored: BTreeSet<String> = opts
        .ignore_cards
        .iter()
        .map(|s| s.trim().to_ascii_uppercase())
        .collect();
    let mut archive = Archive::default();
    archive.read(&file, &text, &ignored)?;
    archive.resolve(&file, &ignored)
}

/// What the archive holds, by external ids, before the resolve pass.
#[derive(Debug, Default)]
struct Archive {
    nodes: Vec<NodeRecord>,
    elements: Vec<ElementRecord>,
    types: BTreeMap<i64, ElementType>,
    materials: materials::Tables,
    tref: f64,
    components: Vec<(usize, String, bool, Vec<u64>)>,
    raw: constraints::Raw,
    /// `SFE` pressures.
    pressures: Vec<surface::Pressure>,
    /// `LOCAL`/`CLOCAL` systems and the active one (`CSYS`).
    locals: esys::LocalSystems,
    lumped: Option<(usize, bool)>,
    /// LINK sections by id, and the section the last SECTYPE opened (`None`: not a LINK one).
    sections: BTreeMap<i64, LinkSection>,
    section_now: Option<i64>,
    /// Shell sections by id, and the one the last SECTYPE opened (`None`: not a shell one).
    shell_sections: BTreeMap<i64, shells::ShellSection>,
    shell_now: Option<i64>,
    /// Beam sections by id, and the one the last SECTYPE opened (`None`: not a beam one).
    beam_sections: BTreeMap<i64, beams::BeamSection>,
    beam_now: Option<i64>,
    /// The MPC184 rigid links' MPCs (indices into the model's).
    links: Vec<usize>,
    /// Real constant sets (`R`, `RLBLOCK`).
    reals: BTreeMap<i64, Vec<f64>>,
    eigen: Option<EigenRequest>,
    /// Command name → lines of the commands noted.
    noted: BTreeMap<String, Vec<usize>>,
    /// Names dropped by `--ignore` → lines.
    dropped: BTreeMap<String, Vec<usize>>,
    /// (line, entity, key, reason).
    refused: Vec<(usize, String, String, String)>,
}

/// Commands refused only when a field is nonzero (a rotating frame): all zero is a note.
const REFUSED_WHEN_NONZERO: [&str; 5] = ["OMEGA", "DOMEGA", "CGLOC", "CGOMEGA", "DCGOMG"];

impl Archive {
    fn refuse(&mut self, line: usize, key: &str, reason: impl Into<String>) {
        self.refused
            .push((line, key.to_owned(), key.to_owned(), reason.into()));
    }

    /// Every line, in order: commands dispatched by the catalogue, blocks read whole.
    fn read(
        &mut self,
        file: &str,
        text: &str,
        ignored: &BTreeSet<String>,
    ) -> Result<(), ImportError> {
        let mut lines = Lines::new(file, text);
        // `CDWRITE,DB,…,IGES` writes the solid model as an IGES file (its S, G, D, P and T
        // sections, with sequence numbers in columns 73–80) before the label `:CDWRITE`, and
        // the archive after it: the geometry is not the mesh
        let iges_end = (text.lines().position(|l| l.starts_with(":CDWRITE"))).map(|k| k + 1);
        if let Some(end) = iges_end {
            self.noted
                .entry("IGES geometry (before :CDWRITE)".into())
                .or_default()
                .push(end);
        }
        while let Some((n, line)) = lines.next_line() {
            if iges_end.is_some_and(|end| n <= end) {
                continue;
            }
            let Some(c) = blocks::command(line, n) else {
                continue;
            };
            if c.name.contains('=') {
                self.noted
                    .entry("parameter assignment".into())
                    .or_default()
                    .push(n);
                continue;
            }
            if ignored.contains(&c.name) {
                self.dropped.entry(c.name.clone()).or_default().push(n);
                // a dropped block's records are still skipped as the block
                self.skip_block(&mut lines, &c)?;
                continue;
            }
            match catalogue::command(&c.name) {
                None => self.refuse(
                    n,
                    &c.name,
                    format!(
                        "command {} is not in the catalogue (docs/ansys-commands.md)",
                        c.name
                    ),
                ),
                Some((_, Disposition::Note(_))) => {
                    self.noted.entry(c.name.clone()).or_default().push(n)
                }
                Some((_, Disposition::Refused(why))) => {
                    let zero = REFUSED_WHEN_NONZERO.contains(&c.name.as_str())
                        && (0..c.fields.len()).all(|k| c.real(file, k).is_ok_and(|v| v == 0.0));
                    if zero {
                        self.noted.entry(c.name.clone()).or_default().push(n);
                    } else {
                        self.refuse(n, &c.name, why);
                        self.skip_block(&mut lines, &c)?;
                    }
                }
                Some((_, Disposition::Honoured(_))) => self.honour(file, &mut lines, &c)?,
            }
        }
        Ok(())
    }

    /// The records of a block command not read (dropped or refused), so that they are not
    /// taken for commands.
    fn skip_block(&mut self, lines: &mut Lines, c: &Command) -> Result<(), ImportError> {
        match c.name.as_str() {
            "NBLOCK" => drop(lines.nblock(c.line)?),
            "EBLOCK" => drop(lines.eblock(c.line, c.field(1).eq_ignore_ascii_case("SOLID"))?),
            "CMBLOCK" => drop(lines.cmblock(c.line, c.int(&lines.file, 2)?.max(0) as usize)?),
            "RLBLOCK" => drop(lines.rlblock(c.line, c.int(&lines.file, 0)?.max(0) as usize)?),
            "SFEBLOCK" => lines.skip_sfeblock(),
            "SFE" | "SECBLOCK" => lines.skip_data_lines(),
            _ => {}
        }
        Ok(())
    }

    /// A command the catalogue honours.
    fn honour(&mut self, file: &str, lines: &mut Lines, c: &Command) -> Result<(), ImportError> {
        let mut refused = Vec::new();
        match c.name.as_str() {
            "NBLOCK" => {
                let nodes = lines.nblock(c.line)?;
                self.nodes.extend(nodes);
            }
            "EBLOCK" => {
                let solid = c.field(1).eq_ignore_ascii_case("SOLID");
                let els = lines.eblock(c.line, solid)?;
                self.elements.extend(els);
            }
            "N" | "EN" => {} // block end lines outside a block: nothing to end
            "ET" | "ETBLOCK" | "KEYOPT" | "KEYOP" => {
                self.honour_element_types(file, lines, c, &mut refused)?
            }
            "DBLOCK" => {
                // (i9,a6,2(pg16.9)): node, dof label, value, imaginary value — each a D command
                for (n, cols) in lines.records(c.line, "DBLOCK")? {
                    let fields = (0..4).map(|k| cols.get(k).copied().flatten().unwrap_or(""));
                    let d = Command {
                        line: n,
                        name: "D".into(),
                        fields: fields.collect(),
                    };
                    self.raw.d(file, &d, &mut refused)?;
                }
            }
            "CMDEL" => {
                let name = c.field(0);
                self.components
                    .retain(|comp| !comp.1.eq_ignore_ascii_case(name));
            }
            "PSTRES" => {
                let on =
                    c.field(0).eq_ignore_ascii_case("ON") || c.int(file, 0).is_ok_and(|v| v == 1);
                if on {
                    refused.push((
                        c.line,
                        "PSTRES,ON: prestress effects of the archive's own static solution; an \
                         ANSYS archive's preload is not formed here (the body would be built \
                         without it)"
                            .into(),
                    ));
                } else {
                    self.noted.entry(c.name.clone()).or_default().push(c.line);
                }
            }
            "TB" => {
                let lab = c.field(0).to_ascii_uppercase();
                match materials::table_effect(&lab) {
                    Ok(()) => self
                        .noted
                        .entry(format!("TB,{lab}"))
                        .or_default()
                        .push(c.line),
                    Err(why) => refused.push((c.line, format!("TB,{lab}: {why}"))),
                }
            }
            "SFEBLOCK" => {
                let (pressures, noted) = (&mut self.pressures, &mut self.noted);
                surface::sfeblock(file, c, lines, pressures, noted, &mut refused)?;
            }
            "MPTEMP" => self.materials.mptemp(file, c)?,
            "MPDATA" | "MP" => self.materials.mpdata(file, c, &mut refused)?,
            "TREF" => self.tref = c.real(file, 0)?,
            "CMBLOCK" => {
                let count = c.int(file, 2)?.max(0) as usize;
                let items = lines.cmblock(c.line, count)?;
                let node = c.field(1).eq_ignore_ascii_case("NODE");
                if !node && !c.field(1).eq_ignore_ascii_case("ELEM") {
                    refused.push((
                        c.line,
                        format!(
                            "component of {}: only NODE and ELEM components are read",
                            c.field(1)
                        ),
                    ));
                }
                self.components
                    .push((c.line, c.field(0).to_owned(), node, items));
            }
            "R" => {
                let values = (1..c.fields.len().max(1))
                    .map(|k| c.real(file, k))
                    .collect::<Result<Vec<_>, _>>()?;
                self.reals.insert(c.int(file, 0)?, values);
            }
            "RLBLOCK" => {
                let sets = lines.rlblock(c.line, c.int(file, 0)?.max(0) as usize)?;
                self.reals.extend(sets);
            }
            "SECTYPE" | "SECDATA" | "SECCONTROL" | "SECBLOCK" | "SECOFFSET" => {
                self.honour_section(file, lines, c, &mut refused)?
            }
            "D" => self.raw.d(file, c, &mut refused)?,
            "CE" => {
                if c.field(1).eq_ignore_ascii_case("DEFI") {
                    let count = c.int(file, 2)?.clamp(0, 100_000) as usize;
                    let constant = c.real(file, 4)?;
                    let terms = lines.ce_terms(c.line, count)?;
                    self.raw.ce(c.line, terms, constant, &mut refused);
                } else {
                    refused.push((
                        c.line,
                        "CE: only the archive's CE,R5.0,DEFI form is read".into(),
                    ));
                }
            }
            "CP" => self.raw.cp(file, c, &mut refused)?,
            "F" => self.raw.f(file, c, &mut refused)?,
            "SFE" => {
                // the archive's form SFE,Elem,LKEY,Lab,KVAL,R5.0 has its values on the next line
                let record = if blocks::archive_form(c.field(4)) {
                    let (n, text) = lines.record(c.line, "SFE")?;
                    // MAPDL 2022 writes the values alone; a format line before them is skipped
                    if text.trim_start().starts_with('(') {
                        Some(lines.record(c.line, "SFE")?)
                    } else {
                        Some((n, text))
                    }
                } else {
                    None
                };
                let (pressures, noted) = (&mut self.pressures, &mut self.noted);
                surface::sfe(file, c, record, pressures, noted, &mut refused)?;
            }
            // LOCAL,KCN,… or the archive's LOCAL,R5.0,LOC|ANG|PRM,KCN,… (three lines)
            "LOCAL" | "CLOCAL" => drop(self.locals.define(file, c)?),
            "CSYS" => self.locals.csys(file, c)?,
            "ACEL" => self.raw.acel(file, c)?,
            "LUMPM" => {
                let on = c.field(0).eq_ignore_ascii_case("ON") || c.field(0) == "1";
                self.lumped = Some((c.line, on));
            }
            "MODOPT" => {
                let count = c.int(file, 1)?;
                let (lo, hi) = (c.real(file, 2)?, c.real(file, 3)?);
                self.eigen = Some(EigenRequest {
                    source: format!("MODOPT,{},{count} (line {})", c.field(0), c.line),
                    count: (count > 0).then_some(count as usize),
                    lower_hz: (lo > 0.0).then_some(lo),
                    upper_hz: (hi > 0.0).then_some(hi),
                });
            }
            _ => return Err(unread_honoured(file, c)),
        }
        for (line, why) in refused {
            self.refuse(line, &c.name, why);
        }
        Ok(())
    }

    /// `ET`, `ETBLOCK` and `KEYOPT`: the element types and their options.
    fn honour_element_types(
        &mut self,
        file: &str,
        lines: &mut Lines,
        c: &Command,
        refused: &mut Vec<(usize, String)>,
    ) -> Result<(), ImportError> {
        match c.name.as_str() {
            "ET" => {
                let t = c.int(file, 0)?;
                self.types.insert(t, ElementType::new(c.line, c.field(1)));
            }
            "ETBLOCK" => {
                // (2i9,19a9): type number, element number, KEYOPT(1)…KEYOPT(18) and a 19th
                // column (Workbench's SOLID186 records carry its KEYOPT(2)=1 in the fourth
                // column, the full integration its ds.dat sets with keyo,…,2,1)
                for (n, cols) in lines.records(c.line, "ETBLOCK")? {
                    let t = blocks::int_col(file, n, "ETBLOCK", cols[0])?;
                    let name = cols.get(1).copied().flatten().unwrap_or("");
                    let mut et = ElementType::new(n, name);
                    for (k, col) in cols.iter().enumerate().skip(2) {
                        let v = blocks::int_col(file, n, "ETBLOCK", *col)?;
                        match k - 1 {
                            _ if v == 0 => {}
                            key @ 1..=18 => drop(et.keyopts.insert(key as u32, v)),
                            _ => refused.push((
                                n,
                                format!(
                                    "ETBLOCK record of type {t}: column {} = {v} (past KEYOPT(18)) \
                                     is not described in the documentation at hand",
                                    k + 1
                                ),
                            )),
                        }
                    }
                    self.types.insert(t, et);
                }
            }
            "KEYOPT" | "KEYOP" => {
                let (t, k, v) = (c.int(file, 0)?, c.int(file, 1)?, c.int(file, 2)?);
                match self.types.get_mut(&t) {
                    Some(et) if (1..=18).contains(&k) => {
                        if v == 0 {
                            et.keyopts.remove(&(k as u32));
                        } else {
                            et.keyopts.insert(k as u32, v);
                        }
                    }
                    _ => refused.push((
                        c.line,
                        format!(
                            "KEYOPT of element type {t} (no ET before it) or KEYOPT number {k}"
                        ),
                    )),
                }
            }
            _ => return Err(unread_honoured(file, c)),
        }
        Ok(())
    }

    /// The model: nodes, formed elements, materials, sets, constraints and loads; or every
    /// refusal of the archive in one error.
    fn resolve(mut self, file: &str, ignored: &BTreeSet<String>) -> Result<Model, ImportError> {
        let mut refused_materials = Vec::new();
        let materials = self.materials.resolve(self.tref, &mut refused_materials);
        for (line, why) in refused_materials {
            self.refuse(line, "MPDATA", why);
        }
        for (lab, lines) in std::mem::take(&mut self.materials.noted) {
            self.noted.insert(format!("MPDATA {lab}"), lines);
        }
        let mut model = Model {
            source: file.to_owned(),
            ..Default::default()
        };
        model.params.ansys_solid_rules = true;
        let node_map = self.place_nodes(file, &mut model, None)?;
        let elements = self.form_elements(file, ignored, &node_map, &materials, &mut model)?;
        self.archived_solid_rules(&elements, &mut model);
        self.constraints(file, &node_map, &mut model)?;
        self.surface_loads(file, &node_map, &elements, &mut model)?;
        self.element_systems();
        free_dependents(&mut model, &self.links);
        self.components(file, &node_map, &elements, &mut model)?;
        self.refusals(file)?;
        if model.elements.is_empty() && model.point_masses.is_empty() {
            let line = self.elements.first().map_or(1, |r| r.line);
            return Err(parse_err(
                file,
                line,
                "EBLOCK",
                format!(
                    "no element with stiffness or mass: the archive's {} element record(s) form \
                     none (a mesher's MESH200 elements carry neither: give them a structural \
                     element type with ET)",
                    self.elements.len()
                ),
            ));
        }
        if let Some((line, true)) = self.lumped {
            if let Some(why) =
                beams::lumped_refusal(&model).or_else(|| shells::lumped_refusal(&model))
            {
                self.refuse(line, "LUMPM", why);
                self.refusals(file)?;
            }
        }
        model.params.coupled_mass = Some(match self.lumped {
            Some((line, true)) => crate::model::DeckMass {
                consistent: false,
                asked_by: format!("LUMPM,ON at {file}:{line}"),
            },
            Some((line, false)) => crate::model::DeckMass {
                consistent: true,
                asked_by: format!("LUMPM,OFF at {file}:{line}"),
            },
            None => crate::model::DeckMass {
                consistent: true,
                asked_by: "an ANSYS archive without LUMPM,ON (ANSYS's default)".into(),
            },
        });
        model.deck.eigen = self.eigen.take();
        let mut groups: BTreeMap<&str, Vec<String>> = BTreeMap::new();
        for (name, lines) in &self.noted {
            let command = name.split([' ', ',']).next().unwrap_or(name);
            let title = catalogue::command(command).map_or("other lines", |(c, _)| c.title());
            groups.entry(title).or_default().push(format!(
                "{} {name} ({})",
                lines.len(),
                list(lines)
            ));
        }
        let beam_note = beams::note(&model);
        let notes = &mut model.deck.notes;
        notes.push(format!(
            "ANSYS archive: {} mass (ANSYS's default is consistent mass, LUMPM,ON lumped; SOLID186's \
             consistent mass with ANSYS's 14-point rule)",
            if self.lumped.is_some_and(|l| l.1) { "lumped" } else { "consistent" }
        ));
        if model.params.ansys_shell181 {
            notes.push(
                "ANSYS archive: SHELL181 (KEYOPT(3)=2; K = L its degenerate triangle) formed with \
                 ANSYS's transverse shear factor and drilling penalty, its strain energy (but for \
                 the drilling penalty's) and consistent mass shown against ANSYS's on flat \
                 elements with ν = 0.3; ANSYS's drilling penalty is flexbody's for elements larger \
                 than 100 t² and stiffer for smaller ones (a warning counts them), and ANSYS puts \
                 no inertia on the drilling rotation (flexbody 10⁻⁴ of ρt³/12) (docs/ansys.md)"
                    .into(),
            );
        }
        if !model.ansys_shell281.is_empty() {
            notes.push(
                "ANSYS archive: SHELL281 formed as the 8-node shell on 2 × 2 points with its \
                 section's offset and transverse shear, shown against ANSYS's element forces of \
                 one flat offset mesh; its drilling penalty (10⁻⁴ of the transverse shear \
                 stiffness) and its mass (consistent, 2 × 2 points) are not shown against \
                 ANSYS (docs/ansys.md)"
                    .into(),
            );
        }
        notes.extend(beam_note);
        for (title, items) in groups {
            notes.push(format!(
                "ANSYS archive, {title}: not read, no effect on the body (docs/ansys-commands.md \
                 says why): {}",
                items.join("; ")
            ));
        }
        for (name, lines) in &self.dropped {
            notes.push(format!(
                "ANSYS archive: {} {name} ({}) dropped as --ignore asks",
                lines.len(),
                list(lines)
            ));
        }
        Ok(model)
    }

    /// The archive's nodes into `model` (its source and files too); a node's rotation angles
    /// become its displacement frame ([`nodal`]), or with `refuse_rotations` (the full file's
    /// mesh) a refusal naming `why`.
    fn place_nodes(
        &mut self,
        file: &str,
        model: &mut Model,
        refuse_rotations: Option<&str>,
    ) -> Result<IdMap, ImportError> {
        model.params.wtmass = 1.0;
        model.files.push(file.to_owned());
        let mut frames = nodal::NodalFrames::default();
        for r in &self.nodes {
            let mut displacement_frame = None;
            if let (Some(why), true) = (refuse_rotations, r.angles != [0.0; 3]) {
                self.refused.push((
                    r.line,
                    format!("NBLOCK node {}", r.id),
                    "NBLOCK".into(),
                    why.to_owned(),
                ));
            } else {
                displacement_frame = frames.frame(r.angles, model);
            }
            model.nodes.push(Node {
                id: r.id,
                x: r.x,
                displacement_frame,
            });
        }
        IdMap::build(model.nodes.iter().map(|n| n.id)).map_err(|(_, b)| {
            parse_err(
                file,
                self.nodes[b].line,
                format!("node {}", self.nodes[b].id),
                "duplicate node id",
            )
        })
    }

    /// Every refusal gathered, as one error (none: `Ok`).
    fn refusals(&self, file: &str) -> Result<(), ImportError> {
        if self.refused.is_empty() {
            return Ok(());
        }
        let cards = self
            .refused
            .iter()
            .map(|(line, entity, key, reason)| RefusedCard {
                file: file.to_owned(),
                line: *line,
                entity: entity.clone(),
                key: key.clone(),
                reason: reason.clone(),
            })
            .collect();
        Err(ImportError::Refused {
            file: file.to_owned(),
            cards,
        })
    }

    /// CMBLOCK components → node and element sets.
    fn components(
        &mut self,
        file: &str,
        node_map: &IdMap,
        elements: &BTreeMap<u64, Option<usize>>,
        model: &mut Model,
    ) -> Result<(), ImportError> {
        for (line, name, is_node, items) in &self.components {
            if *is_node {
                let mut set = Vec::with_capacity(items.len());
                for &id in items {
                    set.push(node_map.get(id).ok_or_else(|| {
                        parse_err(
                            file,
                            *line,
                            format!("CMBLOCK {name}"),
                            format!("unknown node {id}"),
                        )
                    })?);
                }
                model.node_sets.insert(name.clone(), set);
            } else {
                let mut set = Vec::with_capacity(items.len());
                for &id in items {
                    match elements.get(&id) {
                        Some(Some(i)) => set.push(*i),
                        Some(None) => {}
                        None => {
                            return Err(parse_err(
                                file,
                                *line,
                                format!("CMBLOCK {name}"),
                                format!("unknown element {id}"),
                            ))
                        }
                    }
                }
                model.element_sets.insert(name.clone(), set);
            }
        }
        Ok(())
    }
}

/// A command the catalogue honours reached a reader that does not read it (an importer defect,
/// never the archive's).
fn unread_honoured(file: &str, c: &Command) -> ImportError {
    parse_err(
        file,
        c.line,
        &c.name,
        "honoured by the catalogue but read by no reader",
    )
}

/// "12, 14, 15, …": the first lines of a list.
fn list(lines: &[usize]) -> String {
    let mut s: Vec<String> = lines.iter().take(8).map(usize::to_string).collect();
    if lines.len() > 8 {
        s.push("…".into());
    }
    s.join(", ")
}
