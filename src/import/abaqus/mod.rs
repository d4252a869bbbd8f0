//! Abaqus / CalculiX `.inp` reader → [`Model`].
//!
//! Reads the whole file (and every `*INCLUDE`) once, line by line (node lines parse without
//! allocating), into raw records keyed by external ids; one resolve pass then builds the
//! dense model. Keywords are case-insensitive; `**` starts a comment; a keyword line ending in a
//! comma continues on the next line; element data continue on following lines until the
//! element's node count is reached.
//!
//! Supported: *NODE, *ELEMENT (C3D4, C3D10, C3D8, C3D8I, C3D20(R), C3D6, C3D15, B31, B32, B32R,
//! T3D2, S3, S4, S6, S8, S8R, MASS, ROTARYI, SPRINGA, SPRING1, SPRING2; DASHPOTA take no part),
//! *NSET/*ELSET (GENERATE; *NSET from ELSET=), *MATERIAL, *ELASTIC (also TYPE=LAMINA), *DENSITY,
//! *SOLID/*BEAM/*BEAM GENERAL/*SHELL SECTION (also COMPOSITE: materials.rs; B32 and B32R
//! expanded into 20-node bricks as ccx does: `beam_expansion`),
//! *BOUNDARY (dof ranges, ENCASTRE, PINNED, X/Y/ZSYMM), *MASS, *ROTARY INERTIA, *SPRING,
//! *NODAL THICKNESS (`thickness`), *EQUATION, *RIGID BODY (NSET/ELSET, REF NODE, ROT NODE), *SURFACE (TYPE=NODE; element faces
//! for *TIE and *COUPLING, shells' SPOS/SNEG: `faces`), *TIE (`tie`: slave nodes held on the master faces by MPCs), *COUPLING +
//! *KINEMATIC / *DISTRIBUTING, *TRANSFORM (R, C), *INCLUDE; the steps' *CLOAD and *DLOAD
//! (GRAV, P, Pn) as named scene loads (`loads`). C3D8I is the incompatible-mode hexahedron
//! (`ModelParams::solid_bubbles`, model-wide: refused beside C3D8/C3D6); C3D8R is CalculiX's
//! one-point hexahedron with hourglass control (`fe::elements::hex8r`); the variants flexbody
//! does not form (C3D10M, B31R, S3R, S4R: `defs::VARIANTS`, with ccx's measured difference) are
//! refused, and read as their base type only on request (`--ignore S4R=S4`).
//!
//! Every other keyword is a note (it cannot change the body) or refused, by the keyword table
//! (`rules`); unknown element types are refused; all refusals of a deck come in one error, and
//! `ImportOptions::ignore_cards` drops keywords or element types on purpose. Blanks in keyword
//! and parameter names do not matter (as in CalculiX). Only the first `*FREQUENCY` step and what
//! precedes it define the body: every keyword after it is ignored with one warning; a
//! `*FREQUENCY` step that is a PERTURBATION of an earlier `*STATIC` step is built on that step's
//! preload (`steps::Steps::preload`: loads, CENTRIF, temperatures) as ccx perturbs it — the
//! request asks for K + K_G + K_L(u₀) and the spin softening; NLGEOM and other base steps
//! are refused.

mod beam_expansion;
mod connectors;
pub(crate) mod coupling;
mod data;
mod defs;
mod faces;
mod keywords;
mod loads;
mod materials;
mod resolve;
mod rules;
mod sets;
mod shell_equations;
pub mod shell_expansion;
mod shell_nodes;
mod steps;
mod temperature;
mod thickness;
pub(crate) mod tie;
mod tie_search;

use std::collections::{BTreeMap, HashMap};
use std::path::{Path, PathBuf};

use super::error::{ImportError, RefusedCard};
use super::text::{parse_u64, read_text, Builder, Loc};
use super::ImportOptions;

use crate::model::{CoordSystem, DofMask, ElementKind, Model, Section};

/// Read an Abaqus/CalculiX input deck (following `*INCLUDE`s) into a [`Model`].
pub fn read(path: &Path) -> Result<Model, ImportError> {
    read_with_options(path, &ImportOptions::default())
}

/// [`read`] with the keywords and element types to drop on purpose
/// ([`ImportOptions::ignore_cards`]: `*TIE` or `TIE`, `B32R`).
pub fn read_with_options(path: &Path, opts: &ImportOptions) -> Result<Model, ImportError> {
    let mut p = Parser::new(&path.display().to_string());
    p.ignore = opts
        .ignore_cards
        .iter()
        .map(|s| rules::ignore_key(s))
        .collect();
    p.inp_shells = opts.inp_shells;
    p.read_file(path, 0, 0)?;
    if !p.refused.is_empty() {
        return Err(ImportError::Refused {
            file: p.b.files[0].clone(),
            cards: std::mem::take(&mut p.refused),
        });
    }
    let shells = p.shell_elements();
    // the shell sections' OFFSETs by property (a section's property is its index)
    let offsets: Vec<f64> = p.sections.iter().map(|s| s.shell_offset).collect();
    let native_offsets = p.native_shell_offsets();
    let (mut model, expanded_first) = p.finish(&shells, &offsets)?;
    // a CalculiX deck means what ccx makes of it: its C3D4/C3D6 integration (ModelParams)
    model.params.ccx_solid_rules = true;
    anisotropic_c3d8i_warning(&mut model);
    match (opts.inp_shells, expanded_first) {
        (_, Some(x)) => shell_expansion::expand_loads(&mut model, &x, &shells),
        (crate::import::InpShells::Expanded, None) => {
            shell_expansion::expand(&mut model, &shells, &offsets)?
        }
        (crate::import::InpShells::Native, None) => native_offsets.apply(&mut model)?,
    }
    Ok(model)
}

/// The `*SHELL SECTION, OFFSET`s of native shells: Nastran's ZOFFS = −OFFSET·t
/// (`model::shell_offset`: the element formed at its mid-surface, ZOFFS along the normal from its
/// nodes, rigidly linked to them; ccx's mid-surface lies −OFFSET·t along the normal, gen3dfrom2d).
struct NativeOffsets {
    /// Per section (= property): its OFFSET, and where it is for messages.
    sections: Vec<(f64, String, usize, String)>,
}

impl NativeOffsets {
    fn apply(&self, model: &mut Model) -> Result<(), ImportError> {
        let err = |p: usize, msg: String| {
            let (_, file, line, elset) = &self.sections[p];
            ImportError::Parse {
                file: file.clone(),
                line: *line,
                entity: format!("*SHELL SECTION ELSET={elset}"),
                message: msg,
            }
        };
        let mut list = Vec::new();
        for (elem, e) in model.elements.iter().enumerate() {
            let Some(p) = e.property else { continue };
            let Some(&(offset, ..)) = self.sections.get(p).filter(|s| s.0 != 0.0) else {
                continue;
            };
            let Section::Shell(sh) = &model.properties[p].section else {
                continue;
            };
            if model.shell_thickness.contains_key(&elem) {
                return Err(err(
                    p,
                    "OFFSET with *NODAL THICKNESS is not supported".into(),
                ));
            }
            let zoffs = -offset * sh.thickness;
            list.push(crate::model::shell_offset::ShellOffset { elem, zoffs });
        }
        crate::model::shell_offset::offset_shells(model, &list).map_err(|(at, why)| {
            let p = model.elements[list[at].elem].property;
            err(p.unwrap_or_default(), format!("OFFSET: {why}"))
        })?;
        Ok(())
    }
}

/// C3D8I with an anisotropic material keeps massless incompatible modes (Abaqus, ccx 2.11):
/// ccx 2.20 gives them mass (`solid_incompatible::hex8_ccx_matrices`, isotropic only), so its
/// higher modes are lower — a warning naming the elements' count.
fn anisotropic_c3d8i_warning(model: &mut Model) {
    if !model.params.solid_bubbles {
        return;
    }
    let anisotropic = |e: &crate::model::Element| {
        e.kind == crate::model::ElementKind::Hex8
            && e.property
                .and_then(|p| model.properties.get(p))
                .and_then(|p| model.materials.get(p.material))
                .is_some_and(|m| m.stiffness().is_some())
    };
    let count = model.elements.iter().filter(|e| anisotropic(e)).count();
    if count > 0 {
        model.warnings.push(crate::model::ImportWarning {
            file: model.source.clone(),
            message: format!(
                "{count} C3D8I elements with an anisotropic material are formed with massless \
                 incompatible modes (as Abaqus and ccx 2.11); ccx 2.20 gives the modes mass, \
                 which lowers its higher modes (an isotropic 10 × 2 × 2 C3D8I bar: 3.6 % at \
                 mode 7; flexbody forms that for isotropic C3D8I only)"
            ),
        });
    }
}

/// Node reference: a node id or a node-set name.
#[derive(Debug, Clone)]
enum Target {
    Node(u64),
    Set(String),
}

#[derive(Debug)]
struct RawMaterial {
    name: String,
    /// `*ELASTIC` rows (E, ν; temperature) — a table when more than one (temperature.rs).
    elastic: Vec<temperature::Row<2>>,
    /// `*DENSITY` rows (ρ; temperature).
    density: Vec<temperature::Row<1>>,
    /// `*EXPANSION` rows (α; temperature).
    expansion: Vec<temperature::Row<1>>,
    /// A general (orthotropic, anisotropic) `*ELASTIC` instead of `elastic` (materials.rs).
    general: Option<materials::GeneralElastic>,
    loc: Loc,
}

#[derive(Debug)]
struct RawSection {
    elset: String,
    material: String,
    section: Section,
    /// A beam section's dimensions as given (`beam_expansion` needs all of them).
    dims: Vec<f64>,
    /// `*BEAM GENERAL SECTION` (ccx: PIPE and BOX for B32R).
    general: bool,
    /// CalculiX's OFFSET1, OFFSET2 of a beam section.
    offsets: [f64; 2],
    /// `*SHELL SECTION, OFFSET=` in thicknesses (SPOS 0.5, SNEG −0.5).
    shell_offset: f64,
    orientation: Option<[f64; 3]>,
    /// `ORIENTATION=`: the `*ORIENTATION` giving the material axes (materials.rs).
    material_orientation: Option<String>,
    /// `*SHELL SECTION, COMPOSITE`: its plies as read (materials.rs).
    plies: Option<Vec<materials::RawPly>>,
    loc: Loc,
}

#[derive(Debug)]
enum CouplingKind {
    Kinematic(DofMask),
    Distributing(DofMask),
}

/// One `*COUPLING` and the `*KINEMATIC` / `*DISTRIBUTING` after it (coupling.rs).
#[derive(Debug)]
struct RawCoupling {
    reference: Target,
    /// `SURFACE=`, upper case.
    surface: String,
    /// `CONSTRAINT NAME=`, upper case: the reference node's name as an interface.
    name: Option<String>,
    /// `ORIENTATION=`, upper case.
    orientation: Option<String>,
    kind: Option<CouplingKind>,
    loc: Loc,
}

/// What the data lines after the current keyword mean.
#[derive(Debug)]
enum Block {
    Skip,
    Node(Option<String>),
    Element {
        kind: Option<ElementKind>,
        card: &'static str,
        elset: Option<String>,
    },
    Set {
        node: bool,
        name: String,
        generate: bool,
    },
    Elastic,
    /// Data lines of a general `*ELASTIC` (materials.rs).
    ElasticGeneral,
    /// Data line n of `*ORIENTATION` k (materials.rs).
    Orientation(usize, usize),
    Density,
    /// `*EXPANSION` data lines of the current material.
    Expansion,
    /// `*INITIAL CONDITIONS, TYPE=TEMPERATURE` (None) or `*TEMPERATURE` of step k data lines.
    Temperatures(Option<usize>),
    SectionLine(usize, usize),
    /// `*NODAL THICKNESS` data lines (thickness.rs).
    NodalThickness,
    Boundary,
    Mass(String),
    RotaryInertia(String),
    Surface(String),
    /// Data lines of an element-face `*SURFACE` (tie.rs).
    ElementSurface(String),
    /// The data line of `*TIE` k (tie.rs).
    Tie(usize),
    Coupling(usize),
    Transform(String, bool),
    /// `*FREQUENCY` data: the number of eigenvalues.
    Frequency,
    /// `*CLOAD` / `*DLOAD` data lines (loads.rs).
    Load(loads::LoadKeyword),
    /// `*DSLOAD` data lines: pressures on element-face surfaces, read as `*DLOAD` Pn lines.
    SurfaceLoad,
    /// `*SPRING` data lines of spring definition k (connectors.rs).
    Spring(usize),
    /// `*EQUATION` data lines (connectors.rs).
    Equation,
    /// The data lines of an element block that is refused or dropped: the ids are kept so
    /// that sets naming them still resolve (a line ending in a comma continues).
    DroppedElements {
        continued: bool,
    },
}

struct Parser {
    b: Builder,
    block: Block,
    /// Element data split over lines: (entity line loc, values so far).
    pending: Option<(Loc, Vec<u64>)>,
    nsets: HashMap<String, Vec<(u64, Loc)>>,
    elsets: HashMap<String, Vec<(u64, Loc)>>,
    materials: Vec<RawMaterial>,
    sections: Vec<RawSection>,
    /// `*ORIENTATION`s (materials.rs).
    orientations: Vec<materials::RawOrientation>,
    boundaries: Vec<(Target, DofMask, Loc)>,
    /// `*STEP` blocks and their boundary conditions (steps.rs).
    steps: steps::Steps,
    /// `*CLOAD` / `*DLOAD` lines of the steps (loads.rs).
    loads: Vec<loads::RawLoad>,
    /// MASS / ROTARYI elements: id → (node id, loc).
    mass_elems: HashMap<u64, (u64, Loc)>,
    /// Spring and dashpot elements (SPRINGA, SPRING1, SPRING2, DASHPOTA): id → element.
    conn_elems: HashMap<u64, connectors::ConnElement>,
    /// `*SPRING` definitions (connectors.rs).
    springs: Vec<connectors::RawSpring>,
    /// `*EQUATION`s (connectors.rs).
    equations: Vec<connectors::RawEquation>,
    /// Ids of elements of refused or dropped element blocks.
    dropped_elems: std::collections::HashSet<u64>,
    /// C3D8I elements seen (first block), and the first C3D8/C3D6 block: the
    /// incompatible-mode formulation is model-wide (`ModelParams::solid_bubbles`).
    incompatible_hexa: Option<Loc>,
    plain_linear_solid: Option<(Loc, &'static str)>,
    /// Keywords and element types refused (all of them listed in one error).
    refused: Vec<RefusedCard>,
    /// Keywords not read because they cannot change the body: name → (reason, lines).
    notes: BTreeMap<String, (&'static str, Vec<Loc>)>,
    /// Keyword and element-type names dropped on purpose (`ImportOptions::ignore_cards`).
    ignore: Vec<String>,
    /// What was dropped on purpose: name → lines.
    ignored: BTreeMap<String, Vec<Loc>>,
    /// Keywords after the first `*FREQUENCY` step, ignored: name → lines.
    after_frequency: BTreeMap<String, Vec<Loc>>,
    masses: Vec<(String, f64, Loc)>,
    rotary: Vec<(String, [f64; 6], Loc)>,
    rigid: Vec<connectors::RawRigidBody>,
    /// *NSET, NSET=A, ELSET=B requests: (A, B, loc).
    nset_from_elset: Vec<(String, String, Loc)>,
    /// *TRANSFORM: node set and its (resolved) nodal displacement frame.
    transforms: Vec<(String, CoordSystem, Loc)>,
    surfaces: HashMap<String, Vec<(Target, f64, Loc)>>,
    /// Element-face surfaces: name → (element id or set, face number, line) (tie.rs).
    element_surfaces: HashMap<String, Vec<(String, usize, Loc)>>,
    /// `*TIE` definitions (tie.rs).
    ties: Vec<tie::RawTie>,
    /// Initial and step temperatures (temperature.rs).
    temperatures: Vec<temperature::RawTemperature>,
    couplings: Vec<RawCoupling>,
    /// Element variants read as their base type on request (`--ignore S4R=S4`): key → blocks.
    substituted: BTreeMap<String, usize>,
    /// Elements that listed more node ids than their type takes, by type.
    extra_nodes: BTreeMap<&'static str, usize>,
    /// *SHELL SECTION lines that gave a number of section points (ignored, noted).
    shell_point_notes: Vec<String>,
    /// `*NODAL THICKNESS` data lines (thickness.rs).
    nodal_thickness: Vec<thickness::RawNodalThickness>,
    /// Sections with the NODAL THICKNESS parameter (indices into `sections`).
    nodal_thickness_sections: Vec<usize>,
    /// How the shells are formed (`ImportOptions::inp_shells`).
    inp_shells: crate::import::InpShells,
    /// The shell nodes of shells expanded before the ties (`resolve::finish`): a tie's slave
    /// node among them is refused (`tie.rs`).
    expanded_shell_nodes: std::collections::HashSet<usize>,
    /// Bytes of all files read so far (the input budget's base, see `import::budget`).
    input_bytes: u64,
    /// Set members added so far over all sets (bounded by the budget's total).
    set_members: u64,
}

/// Split a keyword line into (KEYWORD, [(KEY, value)]): the keyword by its table name
/// (`rules::canonical`), parameter names upper-cased without blanks (as CalculiX reads them).
fn keyword(line: &str) -> (String, Vec<(String, String)>) {
    let mut it = line[1..].split(',');
    let name = rules::canonical(it.next().unwrap_or(""));
    let params = it
        .filter(|s| !s.trim().is_empty())
        .map(|s| match s.split_once('=') {
            Some((k, v)) => (rules::blankless(k), v.trim().to_owned()),
            None => (rules::blankless(s), String::new()),
        })
        .collect();
    (name, params)
}

/// Parameter `key` (blanks in it do not matter: `REF NODE` = `REFNODE`).
fn param<'a>(params: &'a [(String, String)], key: &str) -> Option<&'a str> {
    let key = rules::blankless(key);
    params
        .iter()
        .find(|(k, _)| *k == key)
        .map(|(_, v)| v.as_str())
}

/// Data-line fields, trailing empty field (line ending in a comma) dropped.
fn fields(line: &str) -> impl Iterator<Item = &str> {
    let line = line.trim_end();
    let line = line.strip_suffix(',').unwrap_or(line);
    line.split(',').map(str::trim)
}

impl Parser {
    fn new(file: &str) -> Parser {
        Parser {
            b: Builder::new(file),
            block: Block::Skip,
            pending: None,
            nsets: HashMap::new(),
            elsets: HashMap::new(),
            materials: Vec::new(),
            sections: Vec::new(),
            orientations: Vec::new(),
            boundaries: Vec::new(),
            steps: steps::Steps::default(),
            loads: Vec::new(),
            mass_elems: HashMap::new(),
            conn_elems: HashMap::new(),
            springs: Vec::new(),
            equations: Vec::new(),
            dropped_elems: Default::default(),
            incompatible_hexa: None,
            plain_linear_solid: None,
            refused: Vec::new(),
            notes: BTreeMap::new(),
            ignore: Vec::new(),
            ignored: BTreeMap::new(),
            after_frequency: BTreeMap::new(),
            masses: Vec::new(),
            rotary: Vec::new(),
            rigid: Vec::new(),
            transforms: Vec::new(),
            nset_from_elset: Vec::new(),
            shell_point_notes: Vec::new(),
            nodal_thickness: Vec::new(),
            nodal_thickness_sections: Vec::new(),
            surfaces: HashMap::new(),
            element_surfaces: HashMap::new(),
            ties: Vec::new(),
            temperatures: Vec::new(),
            couplings: Vec::new(),
            extra_nodes: BTreeMap::new(),
            substituted: BTreeMap::new(),
            inp_shells: crate::import::InpShells::Expanded,
            expanded_shell_nodes: Default::default(),
            input_bytes: 0,
            set_members: 0,
        }
    }

    /// The shell elements read (S3, S4, S4R, S6, S8, S8R) with their type and place, for
    /// `shell_expansion`.
    fn shell_elements(&self) -> shell_expansion::ShellElements {
        let b = &self.b;
        (b.model.elements.iter().zip(&b.elem_card).zip(&b.elem_loc))
            .filter(|((_, card), _)| shell_expansion::SHELL_TYPES.contains(card))
            .map(|((e, card), loc)| {
                let place = shell_expansion::Place {
                    card,
                    file: b.file_name(*loc).to_owned(),
                    line: loc.line as usize,
                };
                (e.id, place)
            })
            .collect()
    }

    /// The sections' OFFSETs for native shells ([`NativeOffsets`]).
    fn native_shell_offsets(&self) -> NativeOffsets {
        let sections = (self.sections.iter())
            .map(|s| {
                let file = self.b.file_name(s.loc).to_owned();
                (s.shell_offset, file, s.loc.line as usize, s.elset.clone())
            })
            .collect();
        NativeOffsets { sections }
    }

    fn err(&self, loc: Loc, entity: impl Into<String>, msg: impl Into<String>) -> ImportError {
        self.b.err(loc, entity, msg)
    }

    fn read_file(&mut self, path: &Path, file: u32, depth: usize) -> Result<(), ImportError> {
        let text = read_text(path)?;
        self.input_bytes += text.len() as u64;
        let mut lines = text.split('\n').enumerate().peekable();
        while let Some((i, raw)) = lines.next() {
            let loc = Loc {
                file,
                line: i as u32 + 1,
            };
            let line = raw.strip_suffix('\r').unwrap_or(raw);
            let t = line.trim_start();
            if t.is_empty() || t.starts_with("**") {
                continue;
            }
            if t.starts_with('*') {
                self.check_pending()?;
                let mut kw = t.trim_end().to_owned();
                while kw.ends_with(',') {
                    match lines.peek() {
                        Some((_, next)) if !next.trim_start().starts_with('*') => {
                            kw.push_str(next.trim_end_matches('\r'));
                            lines.next();
                        }
                        _ => break,
                    }
                }
                let (name, params) = keyword(&kw);
                if name == "INCLUDE" {
                    let Some(inc) = param(&params, "INPUT") else {
                        return Err(self.err(loc, "*INCLUDE", "missing INPUT="));
                    };
                    let inc = inc.trim_matches('"');
                    let dir = path.parent().unwrap_or(Path::new("."));
                    let full: PathBuf = dir.join(inc);
                    if depth >= 16 {
                        return Err(self.err(
                            loc,
                            "*INCLUDE",
                            "includes nested deeper than 16 (cycle?)",
                        ));
                    }
                    self.b.files.push(full.display().to_string());
                    let idx = self.b.files.len() as u32 - 1;
                    self.block = Block::Skip;
                    self.read_file(&full, idx, depth + 1).map_err(|e| match e {
                        ImportError::Io { file, source } => {
                            self.err(loc, "*INCLUDE", format!("cannot read {file}: {source}"))
                        }
                        e => e,
                    })?;
                    continue;
                }
                self.block = self.start_keyword(&name, &params, loc)?;
            } else {
                self.data_line(line, loc)?;
            }
        }
        self.check_pending()
    }

    /// A `*BOUNDARY` line: model data, or the current step's.
    fn push_boundary(&mut self, b: steps::Boundary) {
        match &mut self.steps.current {
            Some(step) => step.boundaries.push(b),
            None => self.boundaries.push(b),
        }
    }

    fn check_pending(&mut self) -> Result<(), ImportError> {
        if let Some((loc, vals)) = self.pending.take() {
            let id = vals.first().copied().unwrap_or(0);
            return Err(self.err(
                loc,
                format!("*ELEMENT {id}"),
                "element data end before all nodes are given (missing continuation line)",
            ));
        }
        Ok(())
    }
}

fn target(s: &str) -> Target {
    match parse_u64(s) {
        Some(id) => Target::Node(id),
        None => Target::Set(s.trim().to_ascii_uppercase()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keyword_split_is_case_insensitive() {
        let (n, p) = keyword("*Solid  section, elset=Solid, material=Steel");
        assert_eq!(n, "SOLID SECTION");
        assert_eq!(param(&p, "ELSET"), Some("Solid"));
        assert_eq!(param(&p, "MATERIAL"), Some("Steel"));
        // CalculiX ignores blanks in keyword and parameter names
        let (n, p) = keyword("*RIGIDBODY, NSET=A, REFNODE=4, Rot Node = 5");
        assert_eq!(n, "RIGID BODY");
        assert_eq!(param(&p, "REF NODE"), Some("4"));
        assert_eq!(param(&p, "ROTNODE"), Some("5"));
    }
}
