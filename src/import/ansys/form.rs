//! Elements of an archive formed by type and KEYOPT ([`super::elements`]), with one solid
//! property per material number; refusals grouped by type and reason.

use std::collections::{BTreeMap, BTreeSet};

use super::connections::{place_spring, rigid_link, rod_property, rotary_without_rotations};
use super::elements::Formed;
use super::{beams, elements, esys, segments, shells, solid_properties, Archive};
use crate::import::error::{parse_err, ImportError};
use crate::import::text::IdMap;
use crate::model::{DofMask, Element, ElementKind, Model, RigidElement};

impl Archive {
    /// Refused element records, one refusal per (type, reason): its first line and count.
    fn refuse_elements(&mut self, refusals: BTreeMap<(i64, String), (usize, usize)>) {
        for ((etype, why), (line, count)) in refusals {
            let t = &self.types[&etype];
            let name = t.name();
            self.refused.push((
                line,
                format!(
                    "EBLOCK element of type {etype} ({name}, ET line {})",
                    t.line
                ),
                name,
                format!("{why} ({count} element(s), the first here)"),
            ));
        }
    }

    /// The elements formed by type and KEYOPT, their properties (one solid property per
    /// material number); refusals grouped by type and reason, named by the first element's line.
    /// Returns the element ids → index (elements without stiffness: `None`).
    pub(super) fn form_elements(
        &mut self,
        file: &str,
        ignored: &BTreeSet<String>,
        node_map: &IdMap,
        materials: &BTreeMap<i64, crate::model::Material>,
        model: &mut Model,
    ) -> Result<BTreeMap<u64, Option<usize>>, ImportError> {
        let property_of = solid_properties(materials, model);
        let mut refusals: BTreeMap<(i64, String), (usize, usize)> = BTreeMap::new();
        let mut index: BTreeMap<u64, Option<usize>> = BTreeMap::new();
        let mut skipped: BTreeMap<String, Vec<usize>> = BTreeMap::new();
        let mut damped = Vec::new();
        let mut rods = BTreeMap::new();
        let mut shell_props = shells::ShellProperties::new();
        let mut solid_axes = esys::SolidAxes::default();
        let mut beam_ctx = beams::BeamContext::new(&self.beam_sections, &property_of);
        // MASS21 with rotary inertia: (line, type, point mass)
        let mut rotary = Vec::new();
        let (segs, others) = segments::split(&self.elements, &self.types, ignored);
        for r in others {
            let Some(t) = self.types.get(&r.etype) else {
                return Err(parse_err(
                    file,
                    r.line,
                    format!("EBLOCK element {}", r.id),
                    format!("element type {} has no ET", r.etype),
                ));
            };
            if ignored.contains(&t.name()) {
                skipped
                    .entry(format!("{} (--ignore)", t.name()))
                    .or_default()
                    .push(r.line);
                index.insert(r.id, None);
                continue;
            }
            let node_of = |id: u64| {
                node_map.get(id).ok_or_else(|| {
                    parse_err(
                        file,
                        r.line,
                        format!("EBLOCK element {}", r.id),
                        format!("references unknown node {id}"),
                    )
                })
            };
            let reals = self.reals.get(&r.real).map(Vec::as_slice);
            let shell = self.shell_sections.get(&r.section);
            // an orthotropic material where only isotropic ones are formed: refused as a form
            let formed = elements::form(t, r, reals, self.sections.get(&r.section), shell)
                .and_then(|f| isotropic_only(&f, r.mat, model, &property_of).map_or(Ok(f), Err));
            let slot = match formed {
                Ok(Formed::NoStiffness) => {
                    skipped.entry(t.name()).or_default().push(r.line);
                    None
                }
                Ok(Formed::PointMass(id, mass, inertia)) => {
                    if inertia.iter().any(|&i| i != 0.0) {
                        rotary.push((r.line, r.etype, model.point_masses.len()));
                    }
                    model.point_masses.push(crate::model::PointMass {
                        id: r.id,
                        node: node_of(id)?,
                        mass,
                        offset: [0.0; 3],
                        inertia: [
                            [inertia[0], 0.0, 0.0],
                            [0.0, inertia[1], 0.0],
                            [0.0, 0.0, inertia[2]],
                        ],
                    });
                    None
                }
                Ok(Formed::Spring(s)) => {
                    if s.damped {
                        damped.push(r.line);
                    }
                    if let Err(why) = place_spring(r.id, &s, node_of(s.a)?, node_of(s.b)?, model) {
                        refusals.entry((r.etype, why)).or_insert((r.line, 0)).1 += 1;
                        continue;
                    }
                    None
                }
                Ok(Formed::Rod(ends, area, added_mass)) => {
                    let key = (r.mat, area.to_bits(), added_mass.to_bits());
                    let Some(property) = rod_property(model, &mut rods, &property_of, key) else {
                        let why = format!("LINK180 of material {}, which has no MPDATA", r.mat);
                        refusals.entry((r.etype, why)).or_insert((r.line, 0)).1 += 1;
                        continue;
                    };
                    model.elements.push(Element {
                        id: r.id,
                        kind: crate::model::ElementKind::Rod2,
                        nodes: vec![node_of(ends[0])?, node_of(ends[1])?],
                        property: Some(property),
                        orientation: None,
                    });
                    model.element_sources.push((r.id, 0, r.line as u32));
                    Some(model.elements.len() - 1)
                }
                Ok(Formed::RigidLink(a, b)) => {
                    let mpc = match rigid_link(r.id, node_of(a)?, node_of(b)?, model) {
                        Ok(mpc) => mpc,
                        Err(why) => {
                            refusals.entry((r.etype, why)).or_insert((r.line, 0)).1 += 1;
                            continue;
                        }
                    };
                    self.links.push(model.mpcs.len());
                    model.mpcs.push(mpc);
                    None
                }
                Ok(Formed::RigidBeam(a, b)) => {
                    model.rigid_elements.push(RigidElement::Rbe2 {
                        id: r.id,
                        independent: node_of(a)?,
                        dependent: vec![node_of(b)?],
                        dofs: DofMask::ALL,
                    });
                    None
                }
                Ok(Formed::Shell(shell)) => {
                    let nodes = (shell.nodes.iter().map(|&id| node_of(id)))
                        .collect::<Result<Vec<_>, _>>()?;
                    let at = (r.id, r.line, r.etype);
                    match shells::push_shell(
                        model,
                        &mut shell_props,
                        &property_of,
                        at,
                        &shell,
                        nodes,
                    ) {
                        Ok(e) => Some(e),
                        Err(why) => {
                            refusals.entry((r.etype, why)).or_insert((r.line, 0)).1 += 1;
                            continue;
                        }
                    }
                }
                Ok(Formed::Beam(beam)) => beam_ctx.push(model, r, &beam, node_of, &mut refusals)?,
                Ok(Formed::Element(kind, ids)) => {
                    let nodes = ids
                        .into_iter()
                        .map(node_of)
                        .collect::<Result<Vec<_>, _>>()?;
                    let base = property_of.get(&r.mat).copied();
                    match push_solid(model, &mut solid_axes, &self.locals, base, r, kind, nodes) {
                        Ok(e) => Some(e),
                        Err(why) => {
                            refusals.entry((r.etype, why)).or_insert((r.line, 0)).1 += 1;
                            index.insert(r.id, None);
                            continue;
                        }
                    }
                }
                Err(why) => {
                    let e = refusals.entry((r.etype, why)).or_insert((r.line, 0));
                    e.1 += 1;
                    // known but refused: a component naming it is not an error of its own
                    index.insert(r.id, None);
                    continue;
                }
            };
            if index.insert(r.id, slot).is_some() {
                return Err(parse_err(
                    file,
                    r.line,
                    format!("element {}", r.id),
                    "duplicate element id",
                ));
            }
        }
        model.warnings.extend(shell_props.drill_warning(file));
        let offsets = shell_props.apply_offsets(model);
        self.contact_pairs(file, &segs, node_map, model, &mut refusals, &mut index)?;
        for why in offsets
            .into_iter()
            .chain(rotary_without_rotations(model, &rotary))
        {
            refusals.entry(why.1).or_insert((why.0, 0)).1 += 1;
        }
        model.element_sources.sort_unstable_by_key(|s| s.0);
        self.refuse_elements(refusals);
        if !damped.is_empty() {
            self.noted.insert(
                "COMBIN14 damping CV1/CV2 (not read: the body is undamped; --damping gives modal damping)".into(),
                damped,
            );
        }
        for (name, lines) in skipped {
            self.noted
                .insert(format!("{name} elements (no stiffness or mass)"), lines);
        }
        Ok(index)
    }
}

/// Why an element that takes isotropic materials only is refused for its orthotropic material
/// (`mat`, or its shell section's): shells (ANSYS's shell element axes and its plane-stress
/// reduction of an orthotropic material are not formed here), beams and links (they read E
/// and G of one direction), SOLID185's B-bar (its mean dilatation is formed for an isotropic
/// D only); `None` for any other.
fn isotropic_only(
    formed: &Formed,
    mat: i64,
    model: &Model,
    property_of: &BTreeMap<i64, usize>,
) -> Option<String> {
    let (what, mat) = match formed {
        Formed::Shell(shell) => (
            "a shell: ANSYS's shell element axes (S1 along the first parametric direction at \
             the element's centre) and its plane-stress reduction of the nine constants are \
             not formed here",
            shell.material,
        ),
        Formed::Beam(_) => ("a beam: beams read one E and G", mat),
        Formed::Rod(..) => ("a LINK180: links read one E", mat),
        Formed::Element(ElementKind::Hex8Bbar, _) => (
            "SOLID185 KEYOPT(2)=0 or a brick collapsed into ANSYS's wedge (SOLID185, SOLID45): \
             the B-bar brick's mean dilatation and that wedge are formed for isotropic \
             materials only (SOLID185 KEYOPT(2)=3 and SOLID45's bricks are formed with an \
             orthotropic one)",
            mat,
        ),
        Formed::Element(..)
        | Formed::NoStiffness
        | Formed::PointMass(..)
        | Formed::Spring(_)
        | Formed::RigidLink(..)
        | Formed::RigidBeam(..) => return None,
    };
    let property = property_of.get(&mat)?;
    let material = &model.materials[model.properties[*property].material];
    material.stiffness()?;
    Some(format!("orthotropic material {mat} on {what}"))
}

/// A solid element of `kind` on `nodes` into the model, its property the material's (`base`)
/// in the element's ESYS ([`esys::SolidAxes`]): its index, or why not.
fn push_solid(
    model: &mut Model,
    solid_axes: &mut esys::SolidAxes,
    locals: &esys::LocalSystems,
    base: Option<usize>,
    r: &super::blocks::ElementRecord,
    kind: ElementKind,
    nodes: Vec<usize>,
) -> Result<usize, String> {
    let property = match base {
        Some(base) => Some(solid_axes.property(model, locals, base, r.esys)?),
        None => None,
    };
    model.elements.push(Element {
        id: r.id,
        kind,
        nodes,
        property,
        orientation: None,
    });
    model.element_sources.push((r.id, 0, r.line as u32));
    Ok(model.elements.len() - 1)
}
