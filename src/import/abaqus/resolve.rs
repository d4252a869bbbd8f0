//! Resolve pass of the Abaqus reader: external ids → dense indices, sets, materials, sections,
//! boundary conditions, point masses, rigid bodies and couplings.

use std::collections::{BTreeMap, HashMap};

use super::sets::Sets;
use super::shell_expansion::{expand_elements, Expansion, ShellElements};
use super::temperature::{at_temperature, depends_on_temperature, Row, TemperatureState};
use super::{Parser, Target};
use crate::import::error::ImportError;
use crate::import::text::Loc;
use crate::model::deck::PreloadRequest;
use crate::model::{
    ConstraintSource, DofMask, EigenRequest, ImportWarning, Material, Model, PointMass, Property,
    Section, SectionShape, Spc,
};

impl Parser {
    /// The resolve pass: ids → indices and sets, then materials, sections, boundary
    /// conditions, point masses, frames, rigid elements, notes and loads, in that order.
    /// When a `*TIE` or `*COUPLING` names faces of shells expanded as ccx expands them, the
    /// expansion runs before the ties (their faces are the bricks'), and its [`Expansion`] is
    /// returned for the loads (`shell_expansion::expand_loads`).
    pub(super) fn finish(
        mut self,
        shells: &ShellElements,
        offsets: &[f64],
    ) -> Result<(Model, Option<Expansion>), ImportError> {
        let sets = self.resolve_sets()?;
        self.steps.finish_current();
        let base = {
            let at = |loc: Loc| format!("{}:{}", self.b.file_name(loc), loc.line);
            self.steps.preload(&at).ok().flatten()
        };
        let temps = self.temperature_state(&sets, self.b.model.nodes.len(), base)?;
        let mat_index = self.resolve_materials(&temps)?;
        self.resolve_sections(&mat_index, &sets)?;
        self.resolve_nodal_thickness(&sets)?;
        self.resolve_boundaries(&sets, &temps)?;
        self.resolve_point_masses(&sets)?;
        self.resolve_transforms(&sets)?;
        self.resolve_connectors(&sets.nodes, &sets.node_sets, &sets.element_sets)?;
        self.resolve_incompatible_modes()?;
        let expanded_first =
            self.inp_shells == crate::import::InpShells::Expanded && self.shell_faces_in_use(&sets);
        let expansion = match expanded_first {
            true => Some(expand_elements(&mut self.b.model, shells, offsets, true)?),
            false => None,
        };
        if let Some(x) = &expansion {
            self.expanded_shell_nodes = x.shell_nodes().collect();
        }
        let (mpcs, rigid) = (self.b.model.mpcs.len(), self.b.model.rigid_elements.len());
        let tie_loc = self.ties.first().map(|t| t.loc);
        self.resolve_ties(&sets)?;
        let reference_names = self.resolve_couplings(&sets)?;
        if let Some(x) = &expansion {
            self.refuse_shell_nodes_after_expansion(x, (mpcs, rigid), tie_loc)?;
        }
        self.import_notes();
        self.b.model.loads = self.resolve_loads(&sets)?;
        self.expand_quadratic_beams()?;
        self.b.model.node_sets = sets.node_sets;
        for (name, node) in reference_names {
            // a coupling's CONSTRAINT NAME names its reference node, unless a set has the name
            self.b
                .model
                .node_sets
                .entry(name)
                .or_insert_with(|| vec![node]);
        }
        self.b.model.element_sets = sets.element_sets;
        self.b.model.files = self.b.files.clone();
        self.b.record_element_sources();
        Ok((self.b.model, expansion))
    }

    /// Node and element ids → indices (mass elements checked against both), the node and
    /// element sets, and node sets made from element sets.
    fn resolve_sets(&mut self) -> Result<Sets, ImportError> {
        let nodes = self.b.node_map("*NODE")?;
        self.b.resolve_element_nodes(&nodes)?;
        let elems = self.b.element_map()?;
        for (id, e) in &self.conn_elems {
            if let Some(k) = elems.get(*id) {
                let first = self.b.elem_loc[k];
                let at = format!("{}:{}", self.b.file_name(first), first.line);
                return Err(self.err(
                    e.loc,
                    format!("*ELEMENT {id}"),
                    format!("duplicate element id (first defined at {at})"),
                ));
            }
        }
        for (id, (node, loc)) in &self.mass_elems {
            if let Some(k) = elems.get(*id) {
                let first = self.b.elem_loc[k];
                let at = format!("{}:{}", self.b.file_name(first), first.line);
                return Err(self.err(
                    *loc,
                    format!("*ELEMENT {id}"),
                    format!("duplicate element id (first defined at {at})"),
                ));
            }
            if nodes.get(*node).is_none() {
                return Err(self.err(
                    *loc,
                    format!("*ELEMENT {id}"),
                    format!("references unknown node {node}"),
                ));
            }
        }
        // Node sets.
        let mut node_sets = BTreeMap::new();
        for (name, members) in &self.nsets {
            let mut idx = Vec::with_capacity(members.len());
            for &(id, loc) in members {
                idx.push(nodes.get(id).ok_or_else(|| {
                    self.err(loc, format!("*NSET {name}"), format!("unknown node {id}"))
                })?);
            }
            idx.sort_unstable();
            idx.dedup();
            node_sets.insert(name.clone(), idx);
        }
        // Element sets (mass elements are not in `Model::elements` and are left out).
        let mut element_sets = BTreeMap::new();
        for (name, members) in &self.elsets {
            let mut idx = Vec::with_capacity(members.len());
            for &(id, loc) in members {
                match elems.get(id) {
                    Some(i) => idx.push(i),
                    None if self.mass_elems.contains_key(&id)
                        || self.conn_elems.contains_key(&id)
                        || self.dropped_elems.contains(&id) => {}
                    None => {
                        return Err(self.err(
                            loc,
                            format!("*ELSET {name}"),
                            format!("unknown element {id}"),
                        ))
                    }
                }
            }
            idx.sort_unstable();
            idx.dedup();
            element_sets.insert(name.clone(), idx);
        }
        for (nset, elset, loc) in &self.nset_from_elset {
            let members = element_sets.get(elset).ok_or_else(|| {
                self.err(
                    *loc,
                    format!("*NSET {nset}"),
                    format!("unknown element set {elset}"),
                )
            })?;
            let set: &mut Vec<usize> = node_sets.entry(nset.clone()).or_default();
            for &e in members {
                set.extend_from_slice(&self.b.model.elements[e].nodes);
            }
            set.sort_unstable();
            set.dedup();
        }
        Ok(Sets {
            nodes,
            elems,
            node_sets,
            element_sets,
        })
    }

    /// `*MATERIAL`s → the model's materials, temperature tables evaluated at the state's
    /// temperature (temperature.rs); returns name → index.
    fn resolve_materials(
        &mut self,
        temps: &TemperatureState,
    ) -> Result<HashMap<String, usize>, ImportError> {
        let mut mat_index = HashMap::new();
        let mut notes = Vec::new();
        for (k, m) in self.materials.iter().enumerate() {
            let ent = format!("*MATERIAL {}", m.name);
            // Names are case-insensitive (upper-cased on reading): STEEL and Steel are one.
            if let Some(first) = mat_index.insert(m.name.clone(), k) {
                let at = self.materials[first].loc;
                return Err(self.err(
                    m.loc,
                    ent,
                    format!(
                        "duplicate material name (first defined at {}:{})",
                        self.b.file_name(at),
                        at.line
                    ),
                ));
            }
            let general = match &m.general {
                None => None,
                Some(g) => Some(self.general_material(g, &m.elastic, temps, &ent, &mut notes)?),
            };
            let [e, nu] = match general {
                Some(_) => [0.0; 2],
                None => (self.at_state(&m.elastic, temps, (&ent, "*ELASTIC", 2), &mut notes)?)
                    .ok_or_else(|| self.err(m.loc, ent.clone(), "no *ELASTIC given"))?,
            };
            let rho =
                (self.at_state(&m.density, temps, (&ent, "*DENSITY", 1), &mut notes)?).map(|[r]| r);
            if rho.is_none() {
                self.b.model.warnings.push(ImportWarning {
                    file: self.b.file_name(m.loc).to_owned(),
                    message: format!("material {} has no *DENSITY: density 0", m.name),
                });
            }
            if let Some(g) = general {
                let rho = rho.unwrap_or(0.0);
                let mat = match g {
                    Ok(d) => Material::anisotropic(k as u64 + 1, &m.name, d, rho),
                    Err(p) => Material::plane_stress_material(k as u64 + 1, &m.name, p, rho),
                };
                self.b.model.materials.push(mat);
                continue;
            }
            self.b.model.materials.push(Material {
                id: k as u64 + 1,
                name: m.name.clone(),
                e,
                nu,
                g: e / (2.0 * (1.0 + nu)),
                rho: rho.unwrap_or(0.0),
                elasticity: crate::model::Elasticity::Isotropic,
            });
        }
        self.b.model.deck.notes.extend(notes);
        Ok(mat_index)
    }

    /// The D of a general `*ELASTIC` (materials.rs) at the state's temperature, or (`Err`) the
    /// plane-stress lamina of `TYPE=LAMINA`.
    fn general_material(
        &self,
        g: &super::materials::GeneralElastic,
        iso_rows: &[Row<2>],
        temps: &TemperatureState,
        ent: &str,
        notes: &mut Vec<String>,
    ) -> Result<Result<crate::model::Stiffness6, crate::model::PlaneStress>, ImportError> {
        if let Some(r) = iso_rows.first() {
            return Err(self.err(r.2, ent.to_owned(), "a second *ELASTIC in one material"));
        }
        if !g.pending.is_empty() {
            return Err(self.err(
                g.loc,
                ent.to_owned(),
                format!("*ELASTIC: a row ends after {} constants", g.pending.len()),
            ));
        }
        let v = (self.at_state(&g.rows, temps, (ent, "*ELASTIC", g.kind.count()), notes)?)
            .ok_or_else(|| {
                self.err(
                    g.loc,
                    ent.to_owned(),
                    "*ELASTIC has no complete row of constants",
                )
            })?;
        if g.kind == super::materials::ElasticKind::Lamina {
            return Ok(Err(self.lamina(&v, (ent, g.loc))?));
        }
        Ok(Ok(self.general_stiffness(
            g.kind,
            &v,
            (ent, g.loc),
            notes,
        )?))
    }

    /// A material table's values in the state the modes are taken in (temperature.rs): a
    /// table is read at the part's one temperature (a note naming the first `shown` values), and
    /// refused without one.
    fn at_state<const N: usize>(
        &self,
        rows: &[Row<N>],
        temps: &TemperatureState,
        (ent, keyword, shown): (&str, &str, usize),
        notes: &mut Vec<String>,
    ) -> Result<Option<[f64; N]>, ImportError> {
        if !depends_on_temperature(rows) {
            return Ok(rows.first().map(|r| r.0));
        }
        let loc = rows[0].2;
        if let Some(other) = temps.other_step {
            return Err(self.err(loc, ent.to_owned(), format!("{keyword} is a temperature table and a *TEMPERATURE at {}:{} changes the temperature in a step the modes do not perturb: which temperature the table is read at is not modelled", self.b.file_name(other), other.line)));
        }
        let t = match temps.uniform() {
            Ok(Some(t)) => t,
            Ok(None) => return Err(self.err(loc, ent.to_owned(), format!("{keyword} is a temperature table, and the deck gives the part no temperature (*INITIAL CONDITIONS, TYPE=TEMPERATURE, or a *TEMPERATURE in the static step a *FREQUENCY, PERTURBATION step perturbs)"))),
            Err((lo, hi)) => return Err(self.err(loc, ent.to_owned(), format!("{keyword} is a temperature table over a temperature field that is not uniform ({lo} to {hi}, or nodes without a temperature): reading it per element is not supported"))),
        };
        let v = at_temperature(rows, Some(t));
        if let Some(v) = v {
            let at = temps.first.map_or(String::new(), |l| {
                format!(" ({}:{})", self.b.file_name(l), l.line)
            });
            let file = self.b.file_name(loc).to_owned();
            notes.push(format!(
                "{file}:{}: {ent}: {keyword} table read at the part's temperature {t}{at}: {}",
                loc.line,
                v.iter()
                    .take(shown)
                    .map(|x| format!("{x:.7e}"))
                    .collect::<Vec<_>>()
                    .join(", ")
            ));
        }
        Ok(v)
    }

    /// The thermal strain of a preload whose step changes the temperatures (temperature.rs):
    /// α (T − T₀) with each material's constant `*EXPANSION`; none with zero expansion or
    /// unchanged temperatures — then a preload of temperatures alone is no preload (a note).
    fn thermal_strain(
        &mut self,
        mut request: PreloadRequest,
        temps: &TemperatureState,
    ) -> Result<Option<PreloadRequest>, ImportError> {
        let changed = (temps.state.iter().zip(&temps.initial)).any(|(s, i)| s.is_some() && s != i);
        // a mechanical preload, or temperatures that do not change: no thermal strain
        let mut alpha = Vec::with_capacity(self.materials.len());
        if changed {
            for m in &self.materials {
                let a = m.expansion.first().map_or(0.0, |r| r.0[0]);
                if m.expansion.iter().any(|r| r.0[0] != a) {
                    let loc = m.expansion[0].2;
                    return Err(self.err(loc, format!("*MATERIAL {}", m.name), "*EXPANSION is a temperature table and the modes' step changes the temperature: a temperature-dependent expansion coefficient is not supported (give one α)"));
                }
                alpha.push(a);
            }
        }
        if changed && alpha.iter().any(|&a| a != 0.0) {
            let mut dt = Vec::with_capacity(temps.state.len());
            for (n, (s, i)) in temps.state.iter().zip(&temps.initial).enumerate() {
                dt.push(match (s, i) {
                    (Some(s), Some(i)) => s - i,
                    (None, _) => 0.0,
                    (Some(_), None) => {
                        let loc = temps.first.unwrap_or(self.materials[0].loc);
                        let id = self.b.model.nodes[n].id;
                        return Err(self.err(loc, "*TEMPERATURE".to_owned(), format!("node {id} has a temperature in the preload step but no initial temperature (*INITIAL CONDITIONS, TYPE=TEMPERATURE): the thermal strain has no reference")));
                    }
                });
            }
            request.thermal = Some((dt, alpha));
            return Ok(Some(request));
        }
        if request.loads.is_empty() {
            self.b.model.deck.notes.push(format!(
                "{}: its *TEMPERATURE strains nothing (zero *EXPANSION or unchanged temperatures): no preload; the temperatures set the material tables only",
                request.source
            ));
            return Ok(None);
        }
        Ok(Some(request))
    }

    /// A shell section's material axis and, for `COMPOSITE`, its plies (material names to
    /// indices, thickness their sum).
    fn shell_plies(
        &self,
        s: &super::RawSection,
        sh: &mut crate::model::ShellSection,
        mat_index: &HashMap<String, usize>,
    ) -> Result<(), ImportError> {
        let plane = |m: usize| self.b.model.materials[m].plane_stress().is_some();
        let needs_axis = s.plies.is_some() || plane(sh.bending.map_or(0, |b| b.0));
        if needs_axis {
            sh.material_axis = self.shell_axis(s.material_orientation.as_deref(), s.loc)?;
        }
        let Some(raw) = &s.plies else {
            return Ok(());
        };
        let ent = format!("*SHELL SECTION ELSET={}", s.elset);
        if raw.is_empty() {
            return Err(self.err(s.loc, ent, "COMPOSITE without ply lines"));
        }
        for p in raw {
            let material = *mat_index.get(&p.material).ok_or_else(|| {
                self.err(
                    p.loc,
                    ent.clone(),
                    format!("unknown material {}", p.material),
                )
            })?;
            sh.plies.push(crate::model::Ply {
                material,
                thickness: p.thickness,
                angle_deg: p.angle_deg,
            });
        }
        sh.thickness = sh.plies.iter().map(|p| p.thickness).sum();
        Ok(())
    }

    /// Sections → properties, assigned to the elements of their set.
    fn resolve_sections(
        &mut self,
        mat_index: &HashMap<String, usize>,
        sets: &Sets,
    ) -> Result<(), ImportError> {
        for (k, s) in self.sections.iter().enumerate() {
            let ent = format!("*SECTION ELSET={}", s.elset);
            let material = *mat_index.get(&s.material).ok_or_else(|| {
                self.err(
                    s.loc,
                    ent.clone(),
                    format!("unknown material {}", s.material),
                )
            })?;
            let members = sets.element_sets.get(&s.elset).ok_or_else(|| {
                self.err(
                    s.loc,
                    ent.clone(),
                    format!("unknown element set {}", s.elset),
                )
            })?;
            if let Section::Beam(b) = &s.section {
                if matches!(b.shape, Some(SectionShape::Other { .. })) {
                    return Err(self.err(s.loc, ent, "missing section dimensions line"));
                }
            }
            let mut section = s.section.clone();
            if let Section::Shell(sh) = &mut section {
                if s.plies.as_ref().is_some_and(|p| !p.is_empty()) {
                    sh.thickness = 0.0;
                }
                if sh.thickness.is_nan() {
                    return Err(self.err(s.loc, ent, "missing thickness line"));
                }
                *sh = crate::model::ShellSection::homogeneous(sh.thickness, material);
                self.shell_plies(s, sh, mat_index)?;
            }
            let plane = self.b.model.materials[material].plane_stress().is_some();
            if plane && !matches!(section, Section::Shell(_)) {
                return Err(self.err(
                    s.loc,
                    ent,
                    format!(
                        "material {} is *ELASTIC, TYPE=LAMINA (plane stress): only *SHELL \
                         SECTION takes it",
                        s.material
                    ),
                ));
            }
            if let Some(name) = &s.material_orientation {
                let axes = self.material_axes(name, s.loc)?;
                let prop = self.b.model.properties.len();
                self.b.model.property_axes.insert(prop, axes);
            }
            self.b.model.properties.push(Property {
                id: k as u64 + 1,
                name: s.elset.clone(),
                material,
                section,
            });
            for &e in members {
                let el = &self.b.model.elements[e];
                if el.property.is_some() {
                    return Err(self.err(
                        s.loc,
                        ent,
                        format!("element {} already has a section", el.id),
                    ));
                }
                let orientation = self.beam_direction(s, e)?;
                let el = &mut self.b.model.elements[e];
                el.property = Some(k);
                el.orientation = orientation;
            }
        }
        Ok(())
    }

    /// The 1-direction of a beam section's element `e`: the section's direction line, or
    /// without it ccx's default (0, 0, −1) (ccx User's Manual, "Beam element"), refused when
    /// that is parallel to the element's axis.
    fn beam_direction(
        &self,
        s: &super::RawSection,
        e: usize,
    ) -> Result<Option<[f64; 3]>, ImportError> {
        if s.orientation.is_some() || !matches!(s.section, Section::Beam(_)) {
            return Ok(s.orientation);
        }
        const CCX_DEFAULT: [f64; 3] = [0.0, 0.0, -1.0];
        let el = &self.b.model.elements[e];
        if let [a, b, ..] = el.nodes[..] {
            let (xa, xb) = (self.b.model.nodes[a].x, self.b.model.nodes[b].x);
            let d = [0, 1, 2].map(|k| xb[k] - xa[k]);
            let len = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
            if len > 0.0 && (d[0] * d[0] + d[1] * d[1]).sqrt() <= 1e-6 * len {
                return Err(self.err(
                    s.loc,
                    format!("*BEAM SECTION ELSET={}", s.elset),
                    format!(
                        "no direction line (the section's second data line): ccx's default \
                         1-direction (0, 0, -1) is parallel to the axis of element {}; give \
                         the direction",
                        el.id
                    ),
                ));
            }
        }
        Ok(Some(CCX_DEFAULT))
    }

    /// `*BOUNDARY`: the model data's, and those of the `*FREQUENCY` step (steps.rs), as SPCs
    /// with their source; the step's ignored keywords as warnings, its mode count.
    fn resolve_boundaries(
        &mut self,
        sets: &Sets,
        temps: &TemperatureState,
    ) -> Result<(), ImportError> {
        self.steps.finish_current();
        let at = |loc: Loc| format!("{}:{}", self.b.file_name(loc), loc.line);
        let preload = (self.steps.preload(&at))
            .map_err(|(loc, kw, msg)| self.err(loc, kw, msg))?
            .map(|k| self.steps.preload_request(k, &at));
        let applied = self.steps.applied(&at);
        let mut bcs: Vec<(Target, DofMask, Loc, String)> = self
            .boundaries
            .iter()
            .map(|(t, d, l)| (t.clone(), *d, *l, "model data".to_owned()))
            .collect();
        bcs.extend(
            applied
                .boundaries
                .iter()
                .map(|(b, what)| (b.0.clone(), b.1, b.2, what.clone())),
        );
        let ignored = applied.ignored;
        let frequency = applied.frequency;
        for (t, dofs, loc, what) in &bcs {
            let first = self.b.model.spcs.len();
            for node in sets.target(t, *loc, "*BOUNDARY", self)? {
                self.b.model.spcs.push(Spc {
                    node,
                    dofs: *dofs,
                    set_id: 0,
                });
            }
            let (name, set) = match t {
                Target::Node(id) => (format!("node {id}"), None),
                Target::Set(s) => (s.clone(), Some(s.clone())),
            };
            self.b.model.constraint_sources.push(ConstraintSource {
                card: "*BOUNDARY".into(),
                id: format!("{name} dofs {} ({what})", dofs.digits()),
                file: self.b.file_name(*loc).to_owned(),
                line: loc.line as usize,
                set,
                spcs: first..self.b.model.spcs.len(),
                permanent: false,
            });
        }
        for (loc, message) in ignored {
            self.b.model.warnings.push(ImportWarning {
                file: self.b.file_name(loc).to_owned(),
                message,
            });
        }
        self.b.model.deck.preload = match preload {
            Some(request) => self.thermal_strain(request, temps)?,
            None => None,
        };
        if let Some((what, count)) = frequency {
            self.b.model.deck.eigen = count.map(|n| EigenRequest {
                source: format!("*FREQUENCY of {what}"),
                count: Some(n),
                lower_hz: None,
                upper_hz: None,
            });
        }
        Ok(())
    }

    /// Point masses from MASS / ROTARYI elements.
    fn resolve_point_masses(&mut self, sets: &Sets) -> Result<(), ImportError> {
        let mut pm: BTreeMap<u64, PointMass> = BTreeMap::new();
        let set_mass_elems =
            |set: &str, loc: Loc, p: &Parser| -> Result<Vec<(u64, usize)>, ImportError> {
                let m = p.elsets.get(set).ok_or_else(|| {
                    p.err(loc, format!("*MASS ELSET={set}"), "unknown element set")
                })?;
                Ok(m.iter()
                    .filter_map(|(id, _)| {
                        p.mass_elems
                            .get(id)
                            .and_then(|(n, _)| sets.nodes.get(*n))
                            .map(|n| (*id, n))
                    })
                    .collect())
            };
        for (set, mass, loc) in &self.masses {
            for (id, node) in set_mass_elems(set, *loc, self)? {
                pm.entry(id).or_insert_with(|| empty_mass(id, node)).mass = *mass;
            }
        }
        for (set, r, loc) in &self.rotary {
            for (id, node) in set_mass_elems(set, *loc, self)? {
                let p = pm.entry(id).or_insert_with(|| empty_mass(id, node));
                // Abaqus order I11, I22, I33, I12, I13, I23 (I_ij = −∫ x_i x_j dm for i ≠ j).
                p.inertia = [[r[0], r[3], r[4]], [r[3], r[1], r[5]], [r[4], r[5], r[2]]];
            }
        }
        self.b.model.point_masses = pm.into_values().collect();
        Ok(())
    }

    /// `*TRANSFORM`: nodal displacement frames.
    fn resolve_transforms(&mut self, sets: &Sets) -> Result<(), ImportError> {
        for (nset, cs, loc) in &self.transforms {
            let ent = format!("*TRANSFORM NSET={nset}");
            let members = sets.target(&Target::Set(nset.clone()), *loc, &ent, self)?;
            self.b.model.coord_systems.push(cs.clone());
            let k = self.b.model.coord_systems.len() - 1;
            for n in members {
                self.b.model.nodes[n].displacement_frame = Some(k);
            }
        }
        Ok(())
    }

    /// What the reader did not reproduce, as warnings: substituted element types, extra node
    /// ids, section points, ignored keywords.
    fn import_notes(&mut self) {
        for (key, count) in &self.substituted {
            let (variant, base) = key.split_once('=').unwrap_or((key, key));
            self.b.model.warnings.push(ImportWarning {
                file: self.b.files[0].clone(),
                message: format!(
                    "element type {variant} read as {base} on request (--ignore {key}; {count} \
                     *ELEMENT blocks): {variant}'s own formulation is not reproduced"
                ),
            });
        }
        for (card, count) in &self.extra_nodes {
            self.b.model.warnings.push(ImportWarning {
                file: self.b.files[0].clone(),
                message: format!(
                    "{count} {card} elements list more node ids than the type takes; the extra ids were ignored (as CalculiX does)"
                ),
            });
        }
        let quadratic_shells = (self.b.model.elements.iter())
            .filter(|e| {
                matches!(
                    e.kind,
                    crate::model::ElementKind::Quad8 | crate::model::ElementKind::Tri6
                )
            })
            .count();
        if quadratic_shells > 0 && self.inp_shells == crate::import::InpShells::Native {
            self.b.model.warnings.push(ImportWarning {
                file: self.b.files[0].clone(),
                message: format!(
                    "{quadratic_shells} S8/S8R/S6 shells are formed as curved shells (MITC9/MITC6, \
                     as Abaqus forms shells; --inp-shells native); CalculiX expands them into \
                     one layer of C3D20/C3D20R/C3D15 bricks (the default, --inp-shells \
                     expanded), which is stiffer on coarse meshes (its test shellf, 2×2 S8: \
                     ccx +11 … +84 % against Leissa's plate, flexbody's shells −0.4 … +4.8 %), \
                     so ccx's frequencies of this deck may be higher"
                ),
            });
        }
        for ent in &self.shell_point_notes {
            self.b.model.warnings.push(ImportWarning {
                file: self.b.files[0].clone(),
                message: format!(
                    "{ent}: the number of section points is ignored (linear elastic shells are integrated exactly through the thickness)"
                ),
            });
        }
        let places =
            |key: &str, locs: &[Loc]| crate::import::text::places(key, locs, &self.b.files);
        if !self.ignored.is_empty() {
            let list: Vec<String> = (self.ignored.iter())
                .map(|(k, locs)| places(k, locs))
                .collect();
            self.b.model.warnings.push(ImportWarning {
                file: self.b.files[0].clone(),
                message: format!(
                    "keywords and element types dropped on request (--ignore), whatever they carry: {}",
                    list.join("; ")
                ),
            });
        }
        for name in &self.ignore {
            let used = (self.ignored.keys())
                .any(|k| super::rules::blankless(k.trim_start_matches('*')) == *name)
                || self.substituted.contains_key(name);
            if !used {
                self.b.model.warnings.push(ImportWarning {
                    file: self.b.files[0].clone(),
                    message: format!(
                        "--ignore {name}: the deck has no such keyword or element type"
                    ),
                });
            }
        }
        if !self.after_frequency.is_empty() {
            let list: Vec<String> = (self.after_frequency.iter())
                .map(|(k, locs)| places(&format!("*{k}"), locs))
                .collect();
            self.b.model.warnings.push(ImportWarning {
                file: self.b.files[0].clone(),
                message: format!(
                    "the keywords after the first *FREQUENCY step are ignored (only that step and what precedes it define the body): {}",
                    list.join("; ")
                ),
            });
        }
        for (name, (why, locs)) in &self.notes {
            let note = format!("{} not read: {why}", places(&format!("*{name}"), locs));
            self.b.model.deck.notes.push(note);
        }
    }

    /// C3D8I: the incompatible-mode hexahedron (`fe::elements::solid_incompatible`), which the
    /// model selects for every linear hexahedron and wedge at once: refused beside C3D8
    /// or C3D6 elements (C3D8R is an element of its own, `fe::elements::hex8r`).
    fn resolve_incompatible_modes(&mut self) -> Result<(), ImportError> {
        let Some(loc) = self.incompatible_hexa else {
            return Ok(());
        };
        if let Some((other, card)) = self.plain_linear_solid {
            return Err(self.err(
                loc,
                "*ELEMENT, TYPE=C3D8I",
                format!(
                    "C3D8I beside {card} elements ({}:{}) is not supported: the incompatible modes apply to every linear hexahedron and wedge of a model",
                    self.b.file_name(other),
                    other.line
                ),
            ));
        }
        self.b.model.params.solid_bubbles = true;
        Ok(())
    }

    /// The steps' loads (loads.rs), their problems as warnings.
    fn resolve_loads(&mut self, sets: &Sets) -> Result<Vec<crate::model::Load>, ImportError> {
        let loads = {
            let err = |loc: Loc, ent: String, msg: String| self.err(loc, ent, msg);
            let at = |loc: Loc| format!("{}:{}", self.b.file_name(loc), loc.line);
            let written_as_shell =
                |e: usize| super::shell_expansion::SHELL_TYPES.contains(&self.b.elem_card[e]);
            super::loads::resolve(
                &self.loads,
                &super::loads::Resolve {
                    model: &self.b.model,
                    nodes: &sets.nodes,
                    elems: &sets.elems,
                    node_sets: &sets.node_sets,
                    element_sets: &sets.element_sets,
                    written_as_shell: &written_as_shell,
                    err: &err,
                    at: &at,
                },
            )?
        };
        let load_warnings = crate::model::load::problem_warnings(&loads, &self.b.files[0]);
        self.b.model.warnings.extend(load_warnings);
        Ok(loads)
    }
}

pub(super) fn single(v: Vec<usize>, loc: Loc, ent: &str, p: &Parser) -> Result<usize, ImportError> {
    match v.as_slice() {
        [n] => Ok(*n),
        _ => Err(p.err(
            loc,
            ent.to_owned(),
            format!("reference node set must hold one node, has {}", v.len()),
        )),
    }
}

fn empty_mass(id: u64, node: usize) -> PointMass {
    PointMass {
        id,
        node,
        mass: 0.0,
        offset: [0.0; 3],
        inertia: [[0.0; 3]; 3],
    }
}
