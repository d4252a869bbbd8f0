//! Data lines of the Abaqus reader, read by the block their keyword opened
//! ([`super::keywords`]): [`Parser::data_line`] is the table, one reader per block.

use super::defs::{abaqus_shape, transform_frame};
use super::{fields, loads, target, Block, CouplingKind, Parser};
use crate::import::error::ImportError;
use crate::import::text::{bad_number, parse_f64, parse_u64, Loc};
use crate::model::{DofMask, ElementKind, Section, SectionShape};

impl Parser {
    /// The data-line table: `line` read by the current block's reader.
    pub(super) fn data_line(&mut self, line: &str, loc: Loc) -> Result<(), ImportError> {
        match &self.block {
            Block::Skip => Ok(()),
            Block::Load(keyword) => {
                let keyword = *keyword;
                self.load_line(keyword, line, loc);
                Ok(())
            }
            Block::SurfaceLoad => self.surface_load_line(line, loc),
            Block::Frequency => {
                self.frequency_line(line);
                Ok(())
            }
            Block::Node(nset) => {
                let nset = nset.clone();
                self.node_line(nset, line, loc)
            }
            Block::Element { kind, card, elset } => {
                let (kind, card, elset) = (*kind, *card, elset.clone());
                self.element_line(kind, card, elset, line, loc)
            }
            Block::Set {
                node,
                name,
                generate,
            } => {
                let (node, name, generate) = (*node, name.clone(), *generate);
                self.set_line(node, name, generate, line, loc)
            }
            Block::Elastic => self.material_line(0, line, loc),
            Block::ElasticGeneral => self.general_elastic_line(line, loc),
            Block::Orientation(k, n) => {
                let (k, n) = (*k, *n);
                self.orientation_line(k, n, line, loc)
            }
            Block::Density => self.material_line(1, line, loc),
            Block::Expansion => self.material_line(2, line, loc),
            Block::Temperatures(step) => {
                let step = *step;
                self.temperature_line(step, line, loc)
            }
            Block::SectionLine(k, n) => {
                let (k, n) = (*k, *n);
                self.section_line(k, n, line, loc)
            }
            Block::Boundary => self.boundary_line(line, loc),
            Block::NodalThickness => self.nodal_thickness_line(line, loc),
            Block::Mass(set) => {
                let set = set.clone();
                self.mass_line(set, true, line, loc)
            }
            Block::RotaryInertia(set) => {
                let set = set.clone();
                self.mass_line(set, false, line, loc)
            }
            Block::Transform(nset, cyl) => {
                let (nset, cyl) = (nset.clone(), *cyl);
                self.transform_line(nset, cyl, line, loc)
            }
            Block::Surface(name) => {
                let name = name.clone();
                self.surface_line(name, line, loc)
            }
            Block::ElementSurface(name) => {
                let name = name.clone();
                self.element_surface_line(name, line, loc)
            }
            Block::Tie(k) => {
                let k = *k;
                self.tie_line(k, line, loc)
            }
            Block::Coupling(k) => {
                let k = *k;
                self.coupling_line(k, line, loc)
            }
            Block::Spring(k) => {
                let k = *k;
                self.spring_line(k, line, loc);
                Ok(())
            }
            Block::Equation => self.equation_line(line, loc),
            Block::DroppedElements { continued } => {
                if !*continued {
                    if let Some(id) = fields(line).next().and_then(parse_u64) {
                        self.dropped_elems.insert(id);
                    }
                }
                self.block = Block::DroppedElements {
                    continued: line.trim_end().ends_with(','),
                };
                Ok(())
            }
        }
    }

    /// A real number of entity `ent` at `loc`.
    pub(super) fn real(&self, s: &str, ent: &str, loc: Loc) -> Result<f64, ImportError> {
        parse_f64(s).ok_or_else(|| self.err(loc, ent.to_owned(), bad_number(s)))
    }

    /// The non-empty fields of `line` as real numbers of entity `ent`.
    pub(super) fn reals(&self, line: &str, ent: &str, loc: Loc) -> Result<Vec<f64>, ImportError> {
        fields(line)
            .filter(|s| !s.is_empty())
            .map(|s| self.real(s, ent, loc))
            .collect()
    }

    /// A `*CLOAD`/`*DLOAD` line, kept raw with its step for loads.rs.
    fn load_line(&mut self, keyword: loads::LoadKeyword, line: &str, loc: Loc) {
        let step = (
            self.steps.done.len(),
            self.steps.current.as_ref().and_then(|s| s.name.clone()),
        );
        self.loads.push(loads::RawLoad {
            keyword,
            step,
            fields: line.split(',').map(|f| f.trim().to_owned()).collect(),
            loc,
        });
    }

    /// `*DSLOAD`: surface, P, magnitude — one `*DLOAD` line `element or set, Pn, magnitude` per
    /// line of the element-face surface (ccx's `dloads.f` reads both alike: face loads Pn).
    fn surface_load_line(&mut self, line: &str, loc: Loc) -> Result<(), ImportError> {
        let f: Vec<String> = fields(line).map(str::to_owned).collect();
        let surface = f
            .first()
            .map(|s| s.to_ascii_uppercase())
            .unwrap_or_default();
        let ent = format!("*DSLOAD {surface}");
        if !f.get(1).is_some_and(|t| t.eq_ignore_ascii_case("P")) || f.len() != 3 {
            return Err(self.err(
                loc,
                ent,
                "only uniform pressure is supported: surface, P, magnitude",
            ));
        }
        let Some(faces) = self.element_surfaces.get(&surface) else {
            return Err(self.err(
                loc,
                ent,
                format!("unknown element-face surface {surface} (a *DSLOAD needs element faces)"),
            ));
        };
        let lines: Vec<Vec<String>> = (faces.iter())
            .map(|(target, face, _)| vec![target.clone(), format!("P{face}"), f[2].clone()])
            .collect();
        for fields in lines {
            self.load_line(loads::LoadKeyword::Dload, &fields.join(","), loc);
        }
        Ok(())
    }

    /// `*FREQUENCY`: the number of eigenvalues of the step.
    fn frequency_line(&mut self, line: &str) {
        let n = fields(line).next().and_then(parse_u64);
        if let Some(step) = &mut self.steps.current {
            step.eigenvalues = n.filter(|n| *n > 0).map(|n| n as usize);
        }
        self.block = Block::Skip;
    }

    /// `*NODE`: id, x, y, z.
    fn node_line(&mut self, nset: Option<String>, line: &str, loc: Loc) -> Result<(), ImportError> {
        let mut f = fields(line);
        let s = f.next().unwrap_or("");
        let id =
            parse_u64(s).ok_or_else(|| self.err(loc, "*NODE", format!("bad node id '{s}'")))?;
        let mut x = [0.0; 3];
        for (k, s) in f.enumerate() {
            if k < 3 && !s.is_empty() {
                x[k] = parse_f64(s)
                    .ok_or_else(|| self.err(loc, format!("*NODE {id}"), bad_number(s)))?;
            }
        }
        if let Some(n) = nset {
            self.nsets.entry(n).or_default().push((id, loc));
        }
        self.b.add_node(id, x, loc);
        Ok(())
    }

    /// `*ELEMENT`: id and node ids, continued on the next lines until the type's node count.
    fn element_line(
        &mut self,
        kind: Option<ElementKind>,
        card: &'static str,
        elset: Option<String>,
        line: &str,
        loc: Loc,
    ) -> Result<(), ImportError> {
        let (start, mut vals) = self.pending.take().unwrap_or((loc, Vec::new()));
        for s in fields(line) {
            let id = vals.first().copied();
            let v = parse_u64(s).ok_or_else(|| {
                let ent = id.map_or("*ELEMENT".to_owned(), |id| format!("*ELEMENT {id}"));
                self.err(loc, ent, format!("bad node id '{s}'"))
            })?;
            vals.push(v);
        }
        let nn = kind.map_or_else(
            || super::connectors::connector_node_count(card).unwrap_or(1),
            ElementKind::node_count,
        );
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
                let first = if matches!(card, "MASS" | "ROTARYI") {
                    self.mass_elems.insert(id, (vals[1], start)).map(|f| f.1)
                } else {
                    let e = super::connectors::ConnElement {
                        card,
                        nodes: vals[1..].to_vec(),
                        loc: start,
                    };
                    self.conn_elems.insert(id, e).map(|f| f.loc)
                };
                if let Some(first) = first {
                    let at = format!("{}:{}", self.b.file_name(first), first.line);
                    return Err(self.err(
                        start,
                        format!("*ELEMENT {id}"),
                        format!("duplicate element id (first defined at {at})"),
                    ));
                }
            }
        }
        Ok(())
    }

    /// `*NSET`/`*ELSET`: ids, sets, or a GENERATE range, within the input budget.
    fn set_line(
        &mut self,
        node: bool,
        name: String,
        generate: bool,
        line: &str,
        loc: Loc,
    ) -> Result<(), ImportError> {
        let kw = if node { "*NSET" } else { "*ELSET" };
        let ent = format!("{kw} {name}");
        let mut add: Vec<(u64, Loc)> = Vec::new();
        let map = if node { &self.nsets } else { &self.elsets };
        let had = map.get(&name).map_or(0, |m| m.len() as u64);
        // The input budget (import::budget), checked before the ids are materialized:
        // per set over all its lines, and over all sets of the deck.
        let budget = |p: &Parser, more: u64, what: &str| -> Result<(), ImportError> {
            let (per_set, total) = (
                crate::import::budget::expansion_limit(p.input_bytes),
                crate::import::budget::total_expansion_limit(p.input_bytes),
            );
            if had.saturating_add(more) > per_set || p.set_members.saturating_add(more) > total {
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
                    return Err(self.err(loc, ent, format!("bad GENERATE line '{}'", line.trim())))
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
        Ok(())
    }

    /// A row of `*ELASTIC` (`what` 0: E, ν[, T]), `*DENSITY` (1: ρ[, T]) or `*EXPANSION`
    /// (2: α[, T]) of the current material; several rows are a temperature table
    /// (temperature.rs).
    fn material_line(&mut self, what: usize, line: &str, loc: Loc) -> Result<(), ImportError> {
        let k = self.materials.len() - 1;
        let ent = format!("*MATERIAL {}", self.materials[k].name);
        let v: Vec<&str> = fields(line).filter(|s| !s.is_empty()).collect();
        let need = if what == 0 { 2 } else { 1 };
        if v.len() < need {
            let keyword = [
                "*ELASTIC needs E, nu",
                "*DENSITY needs rho",
                "*EXPANSION needs alpha",
            ];
            return Err(self.err(loc, ent, keyword[what]));
        }
        let t = match v.get(need) {
            Some(s) => Some(self.real(s, &ent, loc)?),
            None => None,
        };
        let a = self.real(v[0], &ent, loc)?;
        let nu = match what {
            0 => self.real(v[1], &ent, loc)?,
            _ => 0.0,
        };
        let m = &mut self.materials[k];
        match what {
            0 => m.elastic.push(([a, nu], t, loc)),
            1 => m.density.push(([a], t, loc)),
            _ => m.expansion.push(([a], t, loc)),
        }
        Ok(())
    }

    /// A temperature data line (node or node set, T) of `*INITIAL CONDITIONS` (`step` None) or
    /// of step `step`'s `*TEMPERATURE` (temperature.rs).
    fn temperature_line(
        &mut self,
        step: Option<usize>,
        line: &str,
        loc: Loc,
    ) -> Result<(), ImportError> {
        let v: Vec<&str> = fields(line).collect();
        let ent = format!("*TEMPERATURE {}", v[0]);
        let t = match v.get(1) {
            Some(s) if !s.is_empty() => self.real(s, &ent, loc)?,
            _ => return Err(self.err(loc, ent, "needs a node or node set and a temperature")),
        };
        self.temperatures.push(super::temperature::RawTemperature {
            step,
            target: target(v[0]),
            t,
            loc,
        });
        Ok(())
    }

    /// Section data: a shell's thickness, a beam's dimensions (line 1) and orientation (line 2).
    fn section_line(
        &mut self,
        k: usize,
        n: usize,
        line: &str,
        loc: Loc,
    ) -> Result<(), ImportError> {
        if self.sections[k].plies.is_some() {
            return self.composite_line(k, line, loc);
        }
        let ent = format!("*SECTION ELSET={}", self.sections[k].elset);
        let v = self.reals(line, &ent, loc)?;
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
                sec.dims.clone_from(&v);
                let Some(SectionShape::Other { name, .. }) = &bs.shape else {
                    return Ok(());
                };
                // a general section (B32R only) is integrated over its own walls by
                // `beam_expansion`, which reads `dims`: its beam constants are not used, so an
                // uneven BOX stands in with its first two walls
                let even = |mut d: Vec<f64>| {
                    if sec.general && name == "BOX" && d.len() >= 6 {
                        (d[4], d[5]) = (d[2], d[3]);
                    }
                    d
                };
                let shape = abaqus_shape(name, &even(v.clone()))
                    .map_err(|why| self.b.err(loc, ent.clone(), why))?;
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
        Ok(())
    }

    /// `*BOUNDARY`: node or set, a dof range (or ENCASTRE, PINNED, X/Y/ZSYMM), zero value only.
    fn boundary_line(&mut self, line: &str, loc: Loc) -> Result<(), ImportError> {
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
            if self.real(val, &ent, loc)? != 0.0 {
                return Err(self.err(loc, ent, "non-zero prescribed displacement not supported"));
            }
        }
        self.push_boundary((target(v[0]), mask, loc));
        Ok(())
    }

    /// `*MASS` (m) or `*ROTARY INERTIA` (I11, I22, I33, I12, I13, I23) of an element set.
    fn mass_line(
        &mut self,
        set: String,
        mass: bool,
        line: &str,
        loc: Loc,
    ) -> Result<(), ImportError> {
        let ent = format!("*MASS ELSET={set}");
        let v = self.reals(line, &ent, loc)?;
        if mass {
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
        Ok(())
    }

    /// `*TRANSFORM`: points a and b of the nodal frame.
    fn transform_line(
        &mut self,
        nset: String,
        cyl: bool,
        line: &str,
        loc: Loc,
    ) -> Result<(), ImportError> {
        let ent = format!("*TRANSFORM NSET={nset}");
        let v = self.reals(line, &ent, loc)?;
        let [a1, a2, a3, b1, b2, b3] = v[..] else {
            return Err(self.err(loc, ent, "needs a1, a2, a3, b1, b2, b3"));
        };
        let id = self.transforms.len() as u64 + 1;
        let cs = transform_frame(id, cyl, [a1, a2, a3], [b1, b2, b3])
            .ok_or_else(|| self.err(loc, ent.clone(), "degenerate points a, b"))?;
        self.transforms.push((nset, cs, loc));
        self.block = Block::Skip;
        Ok(())
    }

    /// `*SURFACE, TYPE=NODE`: node or set, weight.
    fn surface_line(&mut self, name: String, line: &str, loc: Loc) -> Result<(), ImportError> {
        let v: Vec<&str> = fields(line).collect();
        let w = match v.get(1).filter(|s| !s.is_empty()) {
            Some(s) => self.real(s, &format!("*SURFACE {name}"), loc)?,
            None => 1.0,
        };
        self.surfaces
            .entry(name)
            .or_default()
            .push((target(v[0]), w, loc));
        Ok(())
    }

    /// `*KINEMATIC`/`*DISTRIBUTING`: a dof range of the coupling.
    fn coupling_line(&mut self, k: usize, line: &str, loc: Loc) -> Result<(), ImportError> {
        let v: Vec<&str> = fields(line).collect();
        let a = parse_u64(v[0]);
        let b = v.get(1).and_then(|s| parse_u64(s)).or(a);
        let m = match (a, b) {
            (Some(a), Some(b)) if a <= 6 && b <= 6 => DofMask::from_range(a as u8, b as u8),
            _ => None,
        }
        .ok_or_else(|| self.err(loc, "*COUPLING", format!("bad dof range '{}'", line.trim())))?;
        match &mut self.couplings[k].kind {
            Some(CouplingKind::Kinematic(d)) | Some(CouplingKind::Distributing(d)) => {
                *d = d.union(m)
            }
            None => {}
        }
        Ok(())
    }
}
