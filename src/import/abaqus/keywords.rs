//! Keyword lines of the Abaqus reader: `*NAME, KEY=value, …` → the [`Block`] its data lines
//! fill ([`super::data`]). [`Parser::start_keyword`] is the table: one reader per honoured
//! keyword family; every other keyword is a note or refused by the keyword table
//! ([`super::rules`]). Keywords after the first `*FREQUENCY` step are ignored (one warning):
//! only that step and what precedes it define the body.

use super::connectors::{RawRigidBody, RawSpring};
use super::defs::element_kind;
use super::rules::{self, Rule};
use super::{
    loads, param, steps, target, Block, CouplingKind, Parser, RawCoupling, RawMaterial, RawSection,
};
use crate::import::error::{ImportError, RefusedCard};
use crate::import::text::Loc;
use crate::model::{DofMask, Section, SectionShape};

/// The note of `*RESTART, WRITE`.
const OUTPUT_RESTART: &str = "writing restart data does not change the body";

/// A keyword line: its name, its parameters and where it is.
pub(super) struct Keyword<'a> {
    name: &'a str,
    params: &'a [(String, String)],
    pub(super) loc: Loc,
}

impl Keyword<'_> {
    pub(super) fn param(&self, key: &str) -> Option<&str> {
        param(self.params, key)
    }

    /// The parameter `key`, upper-cased; an error naming the keyword when it is missing or empty.
    pub(super) fn need(&self, key: &str, p: &Parser) -> Result<String, ImportError> {
        self.param(key)
            .filter(|v| !v.is_empty())
            .map(|v| v.to_ascii_uppercase())
            .ok_or_else(|| {
                p.err(
                    self.loc,
                    format!("*{}", self.name),
                    format!("missing {key}="),
                )
            })
    }
}

impl Parser {
    /// The keyword table: the block that the data lines after keyword `name` fill.
    pub(super) fn start_keyword(
        &mut self,
        name: &str,
        params: &[(String, String)],
        loc: Loc,
    ) -> Result<Block, ImportError> {
        let kw = Keyword { name, params, loc };
        if self.steps.after_frequency() {
            // only the first *FREQUENCY step and what precedes it define the body
            self.after_frequency
                .entry(name.to_owned())
                .or_default()
                .push(loc);
            return Ok(Block::Skip);
        }
        let key = rules::blankless(name);
        if self.ignore.contains(&key) {
            self.ignored
                .entry(format!("*{name}"))
                .or_default()
                .push(loc);
            return Ok(Block::Skip);
        }
        Ok(match name {
            "NODE" => Block::Node(kw.param("NSET").map(|s| s.to_ascii_uppercase())),
            "ELEMENT" => self.element_keyword(&kw)?,
            "NSET" | "ELSET" => self.set_keyword(&kw)?,
            "MATERIAL" => {
                self.materials.push(RawMaterial {
                    name: kw.need("NAME", self)?,
                    elastic: Vec::new(),
                    density: Vec::new(),
                    expansion: Vec::new(),
                    general: None,
                    loc,
                });
                Block::Skip
            }
            "ELASTIC" | "DENSITY" | "EXPANSION" => self.material_data_keyword(&kw)?,
            "ORIENTATION" => self.orientation_keyword(&kw)?,
            "SOLID SECTION" | "BEAM SECTION" | "BEAM GENERAL SECTION" | "SHELL SECTION" => {
                self.section_keyword(&kw)?
            }
            "BOUNDARY" => self.boundary_keyword(&kw),
            "NODAL THICKNESS" => Block::NodalThickness,
            "STEP" => {
                let nlgeom = kw
                    .param("NLGEOM")
                    .is_some_and(|v| !v.eq_ignore_ascii_case("NO"));
                let perturbation = kw.param("PERTURBATION").is_some();
                (self.steps).begin(
                    loc,
                    kw.param("NAME").map(str::to_owned),
                    perturbation,
                    nlgeom,
                );
                Block::Skip
            }
            "TEMPERATURE" if self.steps.current.is_some() => self.temperature_keyword(&kw),
            "END STEP" => {
                self.steps.finish_current();
                Block::Skip
            }
            p if self.steps.current.is_some() && steps::PROCEDURES.contains(&p) => {
                self.procedure_keyword(&kw)
            }
            "CLOAD" | "DLOAD" | "DSLOAD" => self.load_keyword(&kw)?,
            "MASS" => Block::Mass(kw.need("ELSET", self)?),
            "ROTARY INERTIA" => Block::RotaryInertia(kw.need("ELSET", self)?),
            "TRANSFORM" => self.transform_keyword(&kw)?,
            "RIGID BODY" => self.rigid_body_keyword(&kw)?,
            "SPRING" => self.spring_keyword(&kw)?,
            "RESTART" if kw.param("READ").is_some() => {
                self.refuse(
                    loc,
                    name,
                    "a restart reads a model this importer cannot see",
                );
                Block::Skip
            }
            "RESTART" => {
                self.note(&kw, OUTPUT_RESTART);
                Block::Skip
            }
            "EQUATION" => Block::Equation,
            "SURFACE" => self.surface_keyword(&kw)?,
            "TIE" => self.tie_keyword(&kw)?,
            "COUPLING" => {
                let r = kw.need("REF NODE", self)?;
                let s = kw.need("SURFACE", self)?;
                let upper = |k: &str| kw.param(k).map(str::to_ascii_uppercase);
                self.couplings.push(RawCoupling {
                    reference: target(&r),
                    surface: s,
                    name: upper("CONSTRAINT NAME"),
                    orientation: upper("ORIENTATION"),
                    kind: None,
                    loc,
                });
                Block::Skip
            }
            "KINEMATIC" | "DISTRIBUTING" => self.coupling_kind_keyword(&kw)?,
            "INITIAL CONDITIONS" => self.initial_conditions_keyword(&kw),
            _ => self.table_keyword(&kw),
        })
    }

    /// `*INITIAL CONDITIONS, TYPE=…`: velocities and displacements start a dynamic or static
    /// step and cannot change the modes of the linear frequency step (a note); temperatures
    /// are read (temperature.rs: the rows of temperature tables, the reference of a thermal
    /// strain); stresses and every other type are refused.
    fn initial_conditions_keyword(&mut self, kw: &Keyword) -> Block {
        let t = kw.param("TYPE").map(rules::blankless).unwrap_or_default();
        match t.as_str() {
            "VELOCITY" | "DISPLACEMENT" => self.note(
                kw,
                "initial velocities and displacements start a dynamic or static step: they do \
                 not change the modes of the linear frequency step",
            ),
            // temperature.rs: they pick the rows of temperature tables and are the reference
            // of a thermal strain
            "TEMPERATURE" => return Block::Temperatures(None),
            "STRESS" => self.refuse(
                kw.loc,
                kw.name,
                "TYPE=STRESS: an initial stress preloads the part (its stress stiffness changes \
                 the modes) and is not read; give the preload as a *STATIC step before a \
                 *FREQUENCY, PERTURBATION step",
            ),
            other => self.refuse(
                kw.loc,
                kw.name,
                &format!(
                    "TYPE={other} is not read and may change the body (VELOCITY and \
                     DISPLACEMENT are notes, TEMPERATURE is read)"
                ),
            ),
        }
        Block::Skip
    }

    /// A keyword that is not honoured: a note, or refused (listed or not).
    fn table_keyword(&mut self, kw: &Keyword) -> Block {
        match rules::rule(kw.name) {
            Some(Rule::Note(why)) => self.note(kw, why),
            Some(Rule::Refuse(why)) => self.refuse(kw.loc, kw.name, why),
            None => self.refuse(kw.loc, kw.name, rules::NOT_READ),
        }
        Block::Skip
    }

    /// Keyword `kw` is not read because it cannot change the body, for `why`.
    fn note(&mut self, kw: &Keyword, why: &'static str) {
        let entry = (self.notes)
            .entry(kw.name.to_owned())
            .or_insert_with(|| (why, Vec::new()));
        entry.1.push(kw.loc);
    }

    /// Keyword (or element type `TYPE=…` when `name` is one) `name` at `loc` is refused.
    pub(super) fn refuse(&mut self, loc: Loc, name: &str, why: &str) {
        let element_type = name.starts_with("TYPE=");
        self.refused.push(RefusedCard {
            file: self.b.file_name(loc).to_owned(),
            line: loc.line as usize,
            entity: if element_type {
                format!("*ELEMENT, {name}")
            } else {
                format!("*{name}")
            },
            key: if element_type {
                name.trim_start_matches("TYPE=").to_owned()
            } else {
                format!("*{name}")
            },
            reason: why.to_owned(),
        });
    }

    /// `*RIGID BODY, NSET=… | ELSET=…, REF NODE=…, ROT NODE=…`.
    fn rigid_body_keyword(&mut self, kw: &Keyword) -> Result<Block, ImportError> {
        let (node_set, set) = match (kw.param("NSET"), kw.param("ELSET")) {
            (Some(n), None) if !n.is_empty() => (true, n.to_ascii_uppercase()),
            (None, Some(e)) if !e.is_empty() => (false, e.to_ascii_uppercase()),
            _ => return Err(self.err(kw.loc, "*RIGID BODY", "needs one of NSET= or ELSET=")),
        };
        let node = |key: &str| kw.param(key).filter(|v| !v.is_empty()).map(target);
        self.rigid.push(RawRigidBody {
            node_set,
            set,
            reference: node("REF NODE"),
            rotation: node("ROT NODE"),
            loc: kw.loc,
        });
        Ok(Block::Skip)
    }

    /// `*SPRING, ELSET=…` (linear; ORIENTATION and NONLINEAR refused).
    fn spring_keyword(&mut self, kw: &Keyword) -> Result<Block, ImportError> {
        let elset = kw.need("ELSET", self)?;
        for p in ["NONLINEAR", "ORIENTATION"] {
            if kw.param(p).is_some() {
                return Err(self.err(
                    kw.loc,
                    format!("*SPRING ELSET={elset}"),
                    format!("{p} is not supported (linear springs in global directions)"),
                ));
            }
        }
        self.springs.push(RawSpring {
            elset,
            lines: Vec::new(),
            loc: kw.loc,
        });
        Ok(Block::Spring(self.springs.len() - 1))
    }

    /// `*ELEMENT, TYPE=…`: the element kind; a variant flexbody does not form is refused, or read
    /// as its base type when `--ignore VARIANT=BASE` asks for it (`defs::VARIANTS`).
    fn element_keyword(&mut self, kw: &Keyword) -> Result<Block, ImportError> {
        let t = rules::blankless(&kw.need("TYPE", self)?);
        let dropped = Block::DroppedElements { continued: false };
        if self.ignore.contains(&t) {
            (self.ignored.entry(t)).or_default().push(kw.loc);
            return Ok(dropped);
        }
        // expanded as ccx does, S4R is a C3D8R layer (`shell_expansion`), not a variant
        let expanded_s4r = t == "S4R" && self.inp_shells == crate::import::InpShells::Expanded;
        let variant = (super::defs::VARIANTS.iter()).find(|v| v.0 == t && !expanded_s4r);
        let t = match variant {
            Some(&(variant, base, why)) => {
                let key = format!("{variant}={base}");
                if !self.ignore.contains(&key) {
                    self.refuse(
                        kw.loc,
                        &format!("TYPE={t}"),
                        &format!(
                            "element type {variant} is not formed ({why}): --ignore {key} reads \
                             them as {base} on purpose"
                        ),
                    );
                    if let Some(r) = self.refused.last_mut() {
                        r.key = key;
                    }
                    return Ok(dropped);
                }
                *self.substituted.entry(key).or_default() += 1;
                base.to_owned()
            }
            None => t,
        };
        let Some((kind, card)) = element_kind(&t) else {
            self.refuse(
                kw.loc,
                &format!("TYPE={t}"),
                &format!("unsupported element type {t}"),
            );
            return Ok(dropped);
        };
        match card {
            "C3D8I" => {
                self.incompatible_hexa.get_or_insert(kw.loc);
            }
            "C3D8" | "C3D6" => {
                self.plain_linear_solid.get_or_insert((kw.loc, card));
            }
            _ => {}
        }
        Ok(Block::Element {
            kind,
            card,
            elset: kw.param("ELSET").map(|s| s.to_ascii_uppercase()),
        })
    }

    /// `*NSET` / `*ELSET` (GENERATE; `*NSET, NSET=A, ELSET=B`: the nodes of B's elements).
    fn set_keyword(&mut self, kw: &Keyword) -> Result<Block, ImportError> {
        let node = kw.name == "NSET";
        let name = kw.need(if node { "NSET" } else { "ELSET" }, self)?;
        let map = if node {
            &mut self.nsets
        } else {
            &mut self.elsets
        };
        map.entry(name.clone()).or_default();
        if let (true, Some(e)) = (node, kw.param("ELSET")) {
            // *NSET, NSET=A, ELSET=B: the nodes of B's elements (resolved later).
            self.nset_from_elset
                .push((name, e.to_ascii_uppercase(), kw.loc));
            return Ok(Block::Skip);
        }
        Ok(Block::Set {
            node,
            name,
            generate: kw.params.iter().any(|(k, _)| k == "GENERATE"),
        })
    }

    /// `*ELASTIC` (isotropic; other types: materials.rs) / `*DENSITY` inside a `*MATERIAL`.
    fn material_data_keyword(&mut self, kw: &Keyword) -> Result<Block, ImportError> {
        if self.materials.is_empty() {
            return Err(self.err(kw.loc, format!("*{}", kw.name), "outside a *MATERIAL"));
        }
        if let Some(t) = kw.param("TYPE") {
            let iso = ["ISO", "ISOTROPIC"].contains(&t.trim().to_ascii_uppercase().as_str());
            if kw.name == "ELASTIC" && !iso {
                return self.general_elastic_keyword(kw, t);
            }
            if !iso {
                return Err(self.err(
                    kw.loc,
                    "*ELASTIC",
                    format!("TYPE={t} not supported (isotropic only)"),
                ));
            }
        }
        Ok(match kw.name {
            "ELASTIC" => Block::Elastic,
            "DENSITY" => Block::Density,
            _ => Block::Expansion,
        })
    }

    /// `*SOLID SECTION` / `*SHELL SECTION` (mid-surface only) / `*BEAM SECTION`.
    fn section_keyword(&mut self, kw: &Keyword) -> Result<Block, ImportError> {
        let elset = kw.need("ELSET", self)?;
        // COMPOSITE: the plies name their materials (materials.rs).
        let composite = kw.name == "SHELL SECTION" && kw.param("COMPOSITE").is_some();
        let material = match composite {
            true => String::new(),
            false => kw.need("MATERIAL", self)?,
        };
        // OFFSET=: the reference surface (the shell's nodes) OFFSET·t above the mid-surface
        // (SPOS: its top, 0.5; SNEG: its bottom, −0.5); shell_expansion and faces.rs
        let mut shell_offset = 0.0;
        let section = match kw.name {
            "SOLID SECTION" => Section::Solid,
            "SHELL SECTION" => {
                if let Some(o) = kw.param("OFFSET") {
                    shell_offset = match o.trim().to_ascii_uppercase().as_str() {
                        "SMID" => 0.0,
                        "SPOS" => 0.5,
                        "SNEG" => -0.5,
                        v => v
                            .parse::<f64>()
                            .ok()
                            .filter(|v| v.is_finite())
                            .ok_or_else(|| {
                                self.err(
                                    kw.loc,
                                    format!("*SHELL SECTION ELSET={elset}"),
                                    format!("OFFSET={o}: a number (in thicknesses), SPOS or SNEG"),
                                )
                            })?,
                    };
                }
                if kw.param("NODALTHICKNESS").is_some() {
                    self.nodal_thickness_sections.push(self.sections.len());
                }
                // Material indices are set when the material names are resolved.
                Section::Shell(crate::model::ShellSection::homogeneous(f64::NAN, 0))
            }
            _ => {
                let s = kw.need("SECTION", self)?;
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
                    taper: None,
                })
            }
        };
        // CalculiX's OFFSET1, OFFSET2 (section offsets of expanded beams, in section sizes)
        let mut offsets = [0.0; 2];
        for (o, key) in offsets.iter_mut().zip(["OFFSET1", "OFFSET2"]) {
            if let Some(v) = kw.param(key) {
                *o = v.trim().parse().map_err(|_| {
                    self.err(
                        kw.loc,
                        format!("*{} ELSET={elset}", kw.name),
                        format!("bad {key}={v}"),
                    )
                })?;
            }
        }
        self.sections.push(RawSection {
            elset,
            material,
            section,
            dims: Vec::new(),
            general: kw.name == "BEAM GENERAL SECTION",
            offsets,
            shell_offset,
            orientation: None,
            material_orientation: kw.param("ORIENTATION").map(str::to_owned),
            plies: composite.then(Vec::new),
            loc: kw.loc,
        });
        Ok(Block::SectionLine(self.sections.len() - 1, 0))
    }

    /// `*BOUNDARY` (OP=NEW clears the conditions before it).
    fn boundary_keyword(&mut self, kw: &Keyword) -> Block {
        if kw
            .param("OP")
            .is_some_and(|v| v.eq_ignore_ascii_case("NEW"))
        {
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

    /// A step's procedure (`*FREQUENCY`, `*STATIC`, …): the first one is the step's.
    fn procedure_keyword(&mut self, kw: &Keyword) -> Block {
        let p = kw.name;
        if let Some(step) = &mut self.steps.current {
            if step.procedure.is_none() {
                step.procedure = Some((p.to_owned(), kw.loc));
            }
            if kw.param("PERTURBATION").is_some() {
                step.perturbation = true;
            }
        }
        if p == "FREQUENCY" {
            Block::Frequency
        } else {
            Block::Skip
        }
    }

    /// `*CLOAD` / `*DLOAD` / `*DSLOAD` inside a step.
    fn load_keyword(&mut self, kw: &Keyword) -> Result<Block, ImportError> {
        if self.steps.current.is_none() {
            return Err(self.err(
                kw.loc,
                format!("*{}", kw.name),
                "a load is history data: it belongs inside a *STEP",
            ));
        }
        if let Some(step) = &mut self.steps.current {
            step.loads.push((format!("*{}", kw.name), kw.loc));
        }
        match kw.name {
            "CLOAD" => Ok(Block::Load(loads::LoadKeyword::Cload)),
            "DLOAD" => Ok(Block::Load(loads::LoadKeyword::Dload)),
            _ => Ok(Block::SurfaceLoad),
        }
    }

    /// `*TEMPERATURE` inside a step: a thermal load of the step (steps.rs: a preload of a
    /// perturbation step).
    fn temperature_keyword(&mut self, kw: &Keyword) -> Block {
        if let Some(step) = &mut self.steps.current {
            step.loads.push(("*TEMPERATURE".to_owned(), kw.loc));
        }
        Block::Temperatures(Some(self.steps.done.len()))
    }

    /// `*TRANSFORM, NSET=…, TYPE=R|C`.
    fn transform_keyword(&mut self, kw: &Keyword) -> Result<Block, ImportError> {
        let cyl = match kw.param("TYPE").map(str::to_ascii_uppercase).as_deref() {
            None | Some("R") => false,
            Some("C") => true,
            Some(t) => {
                return Err(self.err(
                    kw.loc,
                    "*TRANSFORM",
                    format!("TYPE={t} not supported (R, C)"),
                ))
            }
        };
        Ok(Block::Transform(kw.need("NSET", self)?, cyl))
    }

    /// `*SURFACE, TYPE=NODE`, or of element faces (read for `*TIE`, tie.rs).
    fn surface_keyword(&mut self, kw: &Keyword) -> Result<Block, ImportError> {
        let t = kw.param("TYPE").unwrap_or("ELEMENT");
        if !t.eq_ignore_ascii_case("NODE") {
            let n = kw.need("NAME", self)?.to_ascii_uppercase();
            self.element_surfaces.entry(n.clone()).or_default();
            return Ok(Block::ElementSurface(n));
        }
        let n = kw.need("NAME", self)?;
        self.surfaces.entry(n.clone()).or_default();
        Ok(Block::Surface(n))
    }

    /// `*KINEMATIC` / `*DISTRIBUTING` after a `*COUPLING`.
    fn coupling_kind_keyword(&mut self, kw: &Keyword) -> Result<Block, ImportError> {
        if self.couplings.is_empty() {
            return Err(self.err(kw.loc, format!("*{}", kw.name), "not after a *COUPLING"));
        }
        let k = self.couplings.len() - 1;
        let c = &mut self.couplings[k];
        c.kind = Some(if kw.name == "KINEMATIC" {
            CouplingKind::Kinematic(DofMask(0))
        } else {
            CouplingKind::Distributing(DofMask(0))
        });
        Ok(Block::Coupling(k))
    }
}
