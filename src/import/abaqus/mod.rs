//! Abaqus / CalculiX `.inp` reader → [`Model`].
//!
//! Reads the whole file (and every `*INCLUDE`) once, line by line (node lines parse without
//! allocating), into raw records keyed by external ids; one resolve pass then builds the
//! dense model. Keywords are case-insensitive; `**` starts a comment; a keyword line ending in a
//! comma continues on the next line; element data continue on following lines until the
//! element's node count is reached.
//!
//! Supported: *NODE, *ELEMENT (C3D4, C3D10, C3D8(R/I), C3D20(R), C3D6, C3D15, B31, T3D2, S3,
//! S4, S6, S8, MASS, ROTARYI), *NSET/*ELSET (GENERATE; *NSET from ELSET=), *MATERIAL,
//! *ELASTIC, *DENSITY, *SOLID/*BEAM/*SHELL SECTION, *BOUNDARY (dof ranges, ENCASTRE, PINNED,
//! X/Y/ZSYMM), *MASS, *ROTARY INERTIA, *RIGID BODY, *SURFACE (TYPE=NODE), *COUPLING +
//! *KINEMATIC / *DISTRIBUTING, *TRANSFORM (R, C), *INCLUDE; the steps' *CLOAD and *DLOAD
//! (GRAV, P, Pn) as named scene loads (`loads`).
//! Reduced/incompatible-mode variants (C3D8R, C3D8I, C3D10M, B31R, S4R, …) are read as the base
//! type with a warning: their special formulation is not reproduced. Other keywords (steps,
//! outputs, …) are skipped with one warning per keyword and its count.

mod defs;
mod loads;
mod resolve;
mod steps;

use std::collections::{BTreeMap, HashMap};
use std::path::{Path, PathBuf};

use super::error::ImportError;
use super::text::{bad_number, parse_f64, parse_u64, read_text, Builder, Loc};
use defs::{abaqus_shape, element_kind, transform_frame};

use crate::model::{CoordSystem, DofMask, ElementKind, Model, Section, SectionShape};

/// Read an Abaqus/CalculiX input deck (following `*INCLUDE`s) into a [`Model`].
pub fn read(path: &Path) -> Result<Model, ImportError> {
    let mut p = Parser::new(&path.display().to_string());
    p.read_file(path, 0, 0)?;
    p.finish()
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
    e: Option<(f64, f64)>,
    rho: Option<f64>,
    loc: Loc,
}

#[derive(Debug)]
struct RawSection {
    elset: String,
    material: String,
    section: Section,
    orientation: Option<[f64; 3]>,
    loc: Loc,
}

#[derive(Debug)]
enum CouplingKind {
    Kinematic(DofMask),
    Distributing(DofMask),
}

#[derive(Debug)]
struct RawCoupling {
    reference: Target,
    surface: String,
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
    Density,
    SectionLine(usize, usize),
    Boundary,
    Mass(String),
    RotaryInertia(String),
    Surface(String),
    Coupling(usize),
    Transform(String, bool),
    /// `*FREQUENCY` data: the number of eigenvalues.
    Frequency,
    /// `*CLOAD` / `*DLOAD` data lines (loads.rs).
    Load(loads::LoadKeyword),
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
    boundaries: Vec<(Target, DofMask, Loc)>,
    /// `*STEP` blocks and their boundary conditions (steps.rs).
    steps: steps::Steps,
    /// `*CLOAD` / `*DLOAD` lines of the steps (loads.rs).
    loads: Vec<loads::RawLoad>,
    /// MASS / ROTARYI elements: id → (node id, loc).
    mass_elems: HashMap<u64, (u64, Loc)>,
    masses: Vec<(String, f64, Loc)>,
    rotary: Vec<(String, [f64; 6], Loc)>,
    rigid: Vec<(Target, String, Loc)>,
    /// *NSET, NSET=A, ELSET=B requests: (A, B, loc).
    nset_from_elset: Vec<(String, String, Loc)>,
    /// *TRANSFORM: node set and its (resolved) nodal displacement frame.
    transforms: Vec<(String, CoordSystem, Loc)>,
    surfaces: HashMap<String, Vec<(Target, f64, Loc)>>,
    couplings: Vec<RawCoupling>,
    skipped: BTreeMap<String, usize>,
    /// Element types read as a close relative (C3D8I as C3D8, …): "X read as Y" → blocks.
    substituted: BTreeMap<String, usize>,
    /// Elements that listed more node ids than their type takes, by type.
    extra_nodes: BTreeMap<&'static str, usize>,
    /// *SHELL SECTION lines that gave a number of section points (ignored, noted).
    shell_point_notes: Vec<String>,
    /// Bytes of all files read so far (the input budget's base, see `import::budget`).
    input_bytes: u64,
    /// Set members added so far over all sets (bounded by the budget's total).
    set_members: u64,
}

fn upper_norm(s: &str) -> String {
    s.split_whitespace()
        .collect::<Vec<_>>()
        .join(" ")
        .to_ascii_uppercase()
}

/// Split a keyword line into (KEYWORD, [(KEY, value)]).
fn keyword(line: &str) -> (String, Vec<(String, String)>) {
    let mut it = line[1..].split(',');
    let name = upper_norm(it.next().unwrap_or(""));
    let params = it
        .filter(|s| !s.trim().is_empty())
        .map(|s| match s.split_once('=') {
            Some((k, v)) => (upper_norm(k), v.trim().to_owned()),
            None => (upper_norm(s), String::new()),
        })
        .collect();
    (name, params)
}

fn param<'a>(params: &'a [(String, String)], key: &str) -> Option<&'a str> {
    params
        .iter()
        .find(|(k, _)| k == key)
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
            boundaries: Vec::new(),
            steps: steps::Steps::default(),
            loads: Vec::new(),
            mass_elems: HashMap::new(),
            masses: Vec::new(),
            rotary: Vec::new(),
            rigid: Vec::new(),
            transforms: Vec::new(),
            nset_from_elset: Vec::new(),
            shell_point_notes: Vec::new(),
            surfaces: HashMap::new(),
            couplings: Vec::new(),
            skipped: BTreeMap::new(),
            extra_nodes: BTreeMap::new(),
            substituted: BTreeMap::new(),
            input_bytes: 0,
            set_members: 0,
        }
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

    fn start_keyword(
        &mut self,
        name: &str,
        params: &[(String, String)],
        loc: Loc,
    ) -> Result<Block, ImportError> {
        let need = |key: &str| -> Result<String, ImportError> {
            param(params, key)
                .filter(|v| !v.is_empty())
                .map(|v| v.to_ascii_uppercase())
                .ok_or_else(|| self.err(loc, format!("*{name}"), format!("missing {key}=")))
        };
        Ok(match name {
            "NODE" => Block::Node(param(params, "NSET").map(|s| s.to_ascii_uppercase())),
            "ELEMENT" => {
                let t = need("TYPE")?;
                let Some((kind, card)) = element_kind(&t) else {
                    return Err(self.err(loc, "*ELEMENT", format!("unsupported element type {t}")));
                };
                if t != card {
                    *self
                        .substituted
                        .entry(format!("{t} read as {card}"))
                        .or_default() += 1;
                }
                Block::Element {
                    kind,
                    card,
                    elset: param(params, "ELSET").map(|s| s.to_ascii_uppercase()),
                }
            }
            "NSET" | "ELSET" => {
                let node = name == "NSET";
                let name = need(if node { "NSET" } else { "ELSET" })?;
                let map = if node {
                    &mut self.nsets
                } else {
                    &mut self.elsets
                };
                map.entry(name.clone()).or_default();
                if let (true, Some(e)) = (node, param(params, "ELSET")) {
                    // *NSET, NSET=A, ELSET=B: the nodes of B's elements (resolved later).
                    self.nset_from_elset
                        .push((name, e.to_ascii_uppercase(), loc));
                    return Ok(Block::Skip);
                }
                Block::Set {
                    node,
                    name,
                    generate: params.iter().any(|(k, _)| k == "GENERATE"),
                }
            }
            "MATERIAL" => {
                self.materials.push(RawMaterial {
                    name: need("NAME")?,
                    e: None,
                    rho: None,
                    loc,
                });
                Block::Skip
            }
            "ELASTIC" | "DENSITY" => {
                if self.materials.is_empty() {
                    return Err(self.err(loc, format!("*{name}"), "outside a *MATERIAL"));
                }
                if let Some(t) = param(params, "TYPE") {
                    if !t.eq_ignore_ascii_case("ISO") {
                        return Err(self.err(
                            loc,
                            "*ELASTIC",
                            format!("TYPE={t} not supported (isotropic only)"),
                        ));
                    }
                }
                if name == "ELASTIC" {
                    Block::Elastic
                } else {
                    Block::Density
                }
            }
            "SOLID SECTION" | "BEAM SECTION" | "SHELL SECTION" => {
                let elset = need("ELSET")?;
                let material = need("MATERIAL")?;
                let section = match name {
                    "SOLID SECTION" => Section::Solid,
                    "SHELL SECTION" => {
                        // OFFSET= moves the reference surface off the mid-surface: not modelled.
                        if let Some(o) = param(params, "OFFSET") {
                            let zero = o.eq_ignore_ascii_case("SMID")
                                || o.trim().parse::<f64>().is_ok_and(|v| v == 0.0);
                            if !zero {
                                return Err(self.err(
                                    loc,
                                    format!("*SHELL SECTION ELSET={elset}"),
                                    format!("OFFSET={o} not supported (mid-surface shells only)"),
                                ));
                            }
                        }
                        // Material indices are set when the material names are resolved.
                        Section::Shell(crate::model::ShellSection::homogeneous(f64::NAN, 0))
                    }
                    _ => {
                        let s = need("SECTION")?;
                        Section::Beam(crate::model::BeamSection {
                            area: 0.0,
                            i1: 0.0,
                            i2: 0.0,
                            i12: 0.0,
                            j: 0.0,
                            shear_factors: None,
                            nsm: 0.0,
                            shape: Some(SectionShape::Other {
                                name: s,
                                dims: vec![],
                            }),
                        })
                    }
                };
                self.sections.push(RawSection {
                    elset,
                    material,
                    section,
                    orientation: None,
                    loc,
                });
                Block::SectionLine(self.sections.len() - 1, 0)
            }
            "BOUNDARY" => {
                if param(params, "OP").is_some_and(|v| v.eq_ignore_ascii_case("NEW")) {
                    match &mut self.steps.current {
                        Some(step) => {
                            step.op_new = true;
                            step.boundaries.clear();
                        }
                        None => self.boundaries.clear(),
                    }
                }
                Block::Boundary
            }
            "STEP" => {
                self.steps
                    .begin(loc, param(params, "NAME").map(str::to_owned));
                Block::Skip
            }
            "END STEP" => {
                self.steps.finish_current();
                Block::Skip
            }
            p if self.steps.current.is_some() && steps::PROCEDURES.contains(&p) => {
                if let Some(step) = &mut self.steps.current {
                    if step.procedure.is_none() {
                        step.procedure = Some((p.to_owned(), loc));
                    }
                }
                if p == "FREQUENCY" {
                    Block::Frequency
                } else {
                    Block::Skip
                }
            }
            "CLOAD" | "DLOAD" | "DSLOAD" => {
                if self.steps.current.is_none() {
                    return Err(self.err(
                        loc,
                        format!("*{name}"),
                        "a load is history data: it belongs inside a *STEP",
                    ));
                }
                match name {
                    "CLOAD" => Block::Load(loads::LoadKeyword::Cload),
                    "DLOAD" => Block::Load(loads::LoadKeyword::Dload),
                    _ => {
                        return Err(self.err(
                            loc,
                            "*DSLOAD",
                            "loads on element-based surfaces are not supported (element-based *SURFACE is not read): give the pressure with *DLOAD, Pn on the elements",
                        ))
                    }
                }
            }
            "MASS" => Block::Mass(need("ELSET")?),
            "ROTARY INERTIA" => Block::RotaryInertia(need("ELSET")?),
            "TRANSFORM" => {
                let cyl = match param(params, "TYPE")
                    .map(str::to_ascii_uppercase)
                    .as_deref()
                {
                    None | Some("R") => false,
                    Some("C") => true,
                    Some(t) => {
                        return Err(self.err(
                            loc,
                            "*TRANSFORM",
                            format!("TYPE={t} not supported (R, C)"),
                        ))
                    }
                };
                Block::Transform(need("NSET")?, cyl)
            }
            "RIGID BODY" => {
                let nset = need("NSET")?;
                let r = need("REF NODE")?;
                self.rigid.push((target(&r), nset, loc));
                Block::Skip
            }
            "SURFACE" => {
                let t = param(params, "TYPE").unwrap_or("ELEMENT");
                if !t.eq_ignore_ascii_case("NODE") {
                    return self.skip(name, params);
                }
                let n = need("NAME")?;
                self.surfaces.entry(n.clone()).or_default();
                Block::Surface(n)
            }
            "COUPLING" => {
                let r = need("REF NODE")?;
                let s = need("SURFACE")?;
                self.couplings.push(RawCoupling {
                    reference: target(&r),
                    surface: s,
                    kind: None,
                    loc,
                });
                Block::Skip
            }
            "KINEMATIC" | "DISTRIBUTING" => {
                if self.couplings.is_empty() {
                    return Err(self.err(loc, format!("*{name}"), "not after a *COUPLING"));
                }
                let k = self.couplings.len() - 1;
                let c = &mut self.couplings[k];
                c.kind = Some(if name == "KINEMATIC" {
                    CouplingKind::Kinematic(DofMask(0))
                } else {
                    CouplingKind::Distributing(DofMask(0))
                });
                Block::Coupling(k)
            }
            _ => return self.skip(name, params),
        })
    }

    fn skip(&mut self, name: &str, _params: &[(String, String)]) -> Result<Block, ImportError> {
        *self.skipped.entry(name.to_owned()).or_default() += 1;
        Ok(Block::Skip)
    }

    fn data_line(&mut self, line: &str, loc: Loc) -> Result<(), ImportError> {
        let num = |s: &str, ent: &str, p: &Parser| -> Result<f64, ImportError> {
            parse_f64(s).ok_or_else(|| p.err(loc, ent.to_owned(), bad_number(s)))
        };
        match &self.block {
            Block::Skip => {}
            Block::Load(keyword) => {
                let step = (
                    self.steps.done.len(),
                    self.steps.current.as_ref().and_then(|s| s.name.clone()),
                );
                self.loads.push(loads::RawLoad {
                    keyword: *keyword,
                    step,
                    fields: line.split(',').map(|f| f.trim().to_owned()).collect(),
                    loc,
                });
            }
            Block::Frequency => {
                let n = fields(line).next().and_then(parse_u64);
                if let Some(step) = &mut self.steps.current {
                    step.eigenvalues = n.filter(|n| *n > 0).map(|n| n as usize);
                }
                self.block = Block::Skip;
            }
            Block::Node(nset) => {
                let mut f = fields(line);
                let s = f.next().unwrap_or("");
                let id = parse_u64(s)
                    .ok_or_else(|| self.err(loc, "*NODE", format!("bad node id '{s}'")))?;
                let mut x = [0.0; 3];
                for (k, s) in f.enumerate() {
                    if k < 3 && !s.is_empty() {
                        x[k] = parse_f64(s)
                            .ok_or_else(|| self.err(loc, format!("*NODE {id}"), bad_number(s)))?;
                    }
                }
                if let Some(n) = nset {
                    let n = n.clone();
                    self.nsets.entry(n).or_default().push((id, loc));
                }
                self.b.add_node(id, x, loc);
            }
            Block::Element { kind, card, elset } => {
                let (kind, card, elset) = (*kind, *card, elset.clone());
                let (start, mut vals) = self.pending.take().unwrap_or((loc, Vec::new()));
                for s in fields(line) {
                    let id = vals.first().copied();
                    let v = parse_u64(s).ok_or_else(|| {
                        let ent = id.map_or("*ELEMENT".to_owned(), |id| format!("*ELEMENT {id}"));
                        self.err(loc, ent, format!("bad node id '{s}'"))
                    })?;
                    vals.push(v);
                }
                let nn = kind.map_or(1, ElementKind::node_count);
                if vals.len() < nn + 1 {
                    self.pending = Some((start, vals));
                    return Ok(());
                }
                if vals.len() > nn + 1 {
                    // CalculiX reads the nodes the type needs and ignores the rest of the line.
                    vals.truncate(nn + 1);
                    *self.extra_nodes.entry(card).or_default() += 1;
                }
                let id = vals[0];
                if let Some(e) = elset {
                    self.elsets.entry(e).or_default().push((id, start));
                }
                match kind {
                    Some(kind) => {
                        let nodes = vals[1..].iter().map(|&v| v as usize).collect();
                        self.b.add_element(id, kind, nodes, None, card, start);
                    }
                    None => {
                        if let Some((_, first)) = self.mass_elems.insert(id, (vals[1], start)) {
                            let at = format!("{}:{}", self.b.file_name(first), first.line);
                            return Err(self.err(
                                start,
                                format!("*ELEMENT {id}"),
                                format!("duplicate element id (first defined at {at})"),
                            ));
                        }
                    }
                }
            }
            Block::Set {
                node,
                name,
                generate,
            } => {
                let (node, name, generate) = (*node, name.clone(), *generate);
                let kw = if node { "*NSET" } else { "*ELSET" };
                let ent = format!("{kw} {name}");
                let mut add: Vec<(u64, Loc)> = Vec::new();
                let map = if node { &self.nsets } else { &self.elsets };
                let had = map.get(&name).map_or(0, |m| m.len() as u64);
                // The input budget (import::budget), checked before the ids are materialized:
                // per set over all its lines, and over all sets of the deck.
                let budget = |p: &Parser, more: u64, what: &str| -> Result<(), ImportError> {
                    let (per_set, total) = (
                        super::budget::expansion_limit(p.input_bytes),
                        super::budget::total_expansion_limit(p.input_bytes),
                    );
                    if had.saturating_add(more) > per_set
                        || p.set_members.saturating_add(more) > total
                    {
                        return Err(p.err(
                            loc,
                            ent.clone(),
                            format!(
                                "{what} would bring the set to {} members (all sets: {}): more than the input budget allows for {} bytes of input ({per_set} per set, {total} in all; see flexbody::import::budget)",
                                had.saturating_add(more),
                                p.set_members.saturating_add(more),
                                p.input_bytes
                            ),
                        ));
                    }
                    Ok(())
                };
                if generate {
                    let v: Vec<&str> = fields(line).collect();
                    let g: Option<Vec<u64>> = v.iter().map(|s| parse_u64(s)).collect();
                    let (a, b, step) = match g.as_deref() {
                        Some([a, b]) if a <= b => (*a, *b, 1),
                        Some([a, b, s]) if a <= b && *s > 0 => (*a, *b, *s),
                        _ => {
                            return Err(self.err(
                                loc,
                                ent,
                                format!("bad GENERATE line '{}'", line.trim()),
                            ))
                        }
                    };
                    budget(
                        self,
                        ((b - a) / step).saturating_add(1),
                        &format!("GENERATE {a}..{b} step {step}"),
                    )?;
                    add.extend((a..=b).step_by(step as usize).map(|i| (i, loc)));
                } else {
                    for s in fields(line).filter(|s| !s.is_empty()) {
                        let up = s.to_ascii_uppercase();
                        if let Some(id) = parse_u64(s) {
                            add.push((id, loc));
                        } else if up == name {
                            // A set naming itself adds nothing: its members are already in it
                            // (copying them would double the set on every such line).
                        } else if let Some(members) = map.get(&up) {
                            budget(
                                self,
                                add.len() as u64 + members.len() as u64,
                                &format!("adding set {up} ({} members)", members.len()),
                            )?;
                            add.extend_from_slice(members);
                        } else {
                            return Err(self.err(
                                loc,
                                ent,
                                format!("'{s}' is neither an id nor a defined set"),
                            ));
                        }
                    }
                }
                self.set_members += add.len() as u64;
                let map = if node {
                    &mut self.nsets
                } else {
                    &mut self.elsets
                };
                map.entry(name).or_default().extend(add);
            }
            Block::Elastic | Block::Density => {
                let elastic = matches!(self.block, Block::Elastic);
                let k = self.materials.len() - 1;
                let ent = format!("*MATERIAL {}", self.materials[k].name);
                let v: Vec<&str> = fields(line).collect();
                if elastic {
                    if v.len() < 2 {
                        return Err(self.err(loc, ent, "*ELASTIC needs E, nu"));
                    }
                    let e = num(v[0], &ent, self)?;
                    let nu = num(v[1], &ent, self)?;
                    self.materials[k].e = Some((e, nu));
                } else {
                    let rho = num(v[0], &ent, self)?;
                    self.materials[k].rho = Some(rho);
                }
                self.block = Block::Skip;
            }
            Block::SectionLine(k, n) => {
                let (k, n) = (*k, *n);
                let ent = format!("*SECTION ELSET={}", self.sections[k].elset);
                let v: Vec<f64> = fields(line)
                    .filter(|s| !s.is_empty())
                    .map(|s| num(s, &ent, self))
                    .collect::<Result<_, _>>()?;
                self.block = Block::SectionLine(k, n + 1);
                let sec = &mut self.sections[k];
                match &mut sec.section {
                    Section::Solid => {}
                    Section::Shell(sh) if n == 0 => {
                        sh.thickness = *v
                            .first()
                            .ok_or_else(|| self.b.err(loc, ent.clone(), "missing thickness"))?;
                        if v.len() > 1 {
                            // Section points only matter for plasticity output: linear elastic
                            // stiffness is integrated exactly through the thickness.
                            self.shell_point_notes.push(ent.clone());
                        }
                    }
                    Section::Beam(bs) if n == 0 => {
                        let Some(SectionShape::Other { name, .. }) = &bs.shape else {
                            return Ok(());
                        };
                        let shape = abaqus_shape(name, &v).ok_or_else(|| {
                            self.b.err(
                                loc,
                                ent.clone(),
                                format!("SECTION={name} with {} dimensions not supported", v.len()),
                            )
                        })?;
                        let mut s = shape
                            .to_section()
                            .ok_or_else(|| self.b.err(loc, ent.clone(), "unsupported shape"))?;
                        s.nsm = 0.0;
                        *bs = s;
                    }
                    Section::Beam(_) if n == 1 && v.len() >= 3 => {
                        sec.orientation = Some([v[0], v[1], v[2]])
                    }
                    _ => {}
                }
            }
            Block::Boundary => {
                let v: Vec<&str> = fields(line).collect();
                let ent = format!("*BOUNDARY {}", v[0]);
                // Named conditions: ENCASTRE, PINNED, XSYMM, YSYMM, ZSYMM.
                let named = v
                    .get(1)
                    .and_then(|s| match s.to_ascii_uppercase().as_str() {
                        "ENCASTRE" => Some(DofMask::ALL),
                        "PINNED" => Some(DofMask::TRANSLATIONS),
                        "XSYMM" => Some(DofMask(0b11_0001)),
                        "YSYMM" => Some(DofMask(0b10_1010)),
                        "ZSYMM" => Some(DofMask(0b01_1100)),
                        _ => None,
                    });
                if let Some(mask) = named {
                    self.push_boundary((target(v[0]), mask, loc));
                    return Ok(());
                }
                let first = v.get(1).and_then(|s| parse_u64(s));
                let last = match v.get(2) {
                    Some(s) if !s.is_empty() => parse_u64(s),
                    _ => first,
                };
                let mask = match (first, last) {
                    (Some(a), Some(b)) if a <= 6 && b <= 6 => DofMask::from_range(a as u8, b as u8),
                    _ => None,
                };
                let Some(mask) = mask else {
                    return Err(self.err(loc, ent, format!("bad dof range in '{}'", line.trim())));
                };
                if let Some(val) = v.get(3).filter(|s| !s.is_empty()) {
                    if num(val, &ent, self)? != 0.0 {
                        return Err(self.err(
                            loc,
                            ent,
                            "non-zero prescribed displacement not supported",
                        ));
                    }
                }
                self.push_boundary((target(v[0]), mask, loc));
            }
            Block::Mass(set) | Block::RotaryInertia(set) => {
                let set = set.clone();
                let ent = format!("*MASS ELSET={set}");
                let v: Vec<f64> = fields(line)
                    .filter(|s| !s.is_empty())
                    .map(|s| num(s, &ent, self))
                    .collect::<Result<_, _>>()?;
                if matches!(self.block, Block::Mass(_)) {
                    self.masses
                        .push((set, v.first().copied().unwrap_or(0.0), loc));
                } else {
                    let mut r = [0.0; 6];
                    for (k, x) in v.iter().take(6).enumerate() {
                        r[k] = *x;
                    }
                    self.rotary.push((set, r, loc));
                }
                self.block = Block::Skip;
            }
            Block::Transform(nset, cyl) => {
                let (nset, cyl) = (nset.clone(), *cyl);
                let ent = format!("*TRANSFORM NSET={nset}");
                let v: Vec<f64> = fields(line)
                    .filter(|s| !s.is_empty())
                    .map(|s| num(s, &ent, self))
                    .collect::<Result<_, _>>()?;
                let [a1, a2, a3, b1, b2, b3] = v[..] else {
                    return Err(self.err(loc, ent, "needs a1, a2, a3, b1, b2, b3"));
                };
                let id = self.transforms.len() as u64 + 1;
                let cs = transform_frame(id, cyl, [a1, a2, a3], [b1, b2, b3])
                    .ok_or_else(|| self.err(loc, ent.clone(), "degenerate points a, b"))?;
                self.transforms.push((nset, cs, loc));
                self.block = Block::Skip;
            }
            Block::Surface(name) => {
                let name = name.clone();
                let v: Vec<&str> = fields(line).collect();
                let w = match v.get(1).filter(|s| !s.is_empty()) {
                    Some(s) => num(s, &format!("*SURFACE {name}"), self)?,
                    None => 1.0,
                };
                self.surfaces
                    .entry(name)
                    .or_default()
                    .push((target(v[0]), w, loc));
            }
            Block::Coupling(k) => {
                let k = *k;
                let v: Vec<&str> = fields(line).collect();
                let a = parse_u64(v[0]);
                let b = v.get(1).and_then(|s| parse_u64(s)).or(a);
                let m = match (a, b) {
                    (Some(a), Some(b)) if a <= 6 && b <= 6 => DofMask::from_range(a as u8, b as u8),
                    _ => None,
                }
                .ok_or_else(|| {
                    self.err(loc, "*COUPLING", format!("bad dof range '{}'", line.trim()))
                })?;
                match &mut self.couplings[k].kind {
                    Some(CouplingKind::Kinematic(d)) | Some(CouplingKind::Distributing(d)) => {
                        *d = d.union(m)
                    }
                    None => {}
                }
            }
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
    }
}
