//! `*NODAL THICKNESS` (node or node set, thickness per data line) and
//! `*SHELL SECTION, NODAL THICKNESS`.
//!
//! As Abaqus and CalculiX 2.20: the nodal thicknesses are those of the shells whose *SHELL
//! SECTION has the NODAL THICKNESS parameter, which then needs one at every node of its
//! elements (an error here when one is missing); the data line's thickness replaces the
//! section's. For a section without the parameter they are not used — a warning says so
//! (measured: ccx 2.20 builds CalculiX's shellf deck, whose section has no parameter, with its
//! section thickness 0.01: 9683 Hz for the first mode, the 0.01 plate; with the parameter
//! 19247 Hz, which is the suite's ccx 2.11 reference). The quadratic shells (S8, S8R, S6) interpolate the nodal values
//! (`Model::shell_thickness`); a linear shell (S4, S3) with different values at its nodes uses
//! their mean — its own copy of the section, with a warning — as the Nastran reader does for
//! CQUAD4/CTRIA3 corner thicknesses.

use std::collections::HashMap;

use super::sets::Sets;
use super::{Parser, Target};
use crate::import::error::ImportError;
use crate::import::text::Loc;
use crate::model::{ElementKind, ImportWarning, Property, Section};

/// One `*NODAL THICKNESS` data line.
#[derive(Debug)]
pub(super) struct RawNodalThickness {
    pub target: Target,
    pub t: f64,
    pub loc: Loc,
}

impl Parser {
    /// A `*NODAL THICKNESS` data line: node or node set, thickness (> 0).
    pub(super) fn nodal_thickness_line(&mut self, line: &str, loc: Loc) -> Result<(), ImportError> {
        let v: Vec<&str> = super::fields(line).collect();
        let ent = format!("*NODAL THICKNESS {}", v[0]);
        let t = match v.get(1) {
            Some(s) if !s.is_empty() => self.real(s, &ent, loc)?,
            _ => return Err(self.err(loc, ent, "needs a node or node set and a thickness")),
        };
        if !(t > 0.0 && t.is_finite()) {
            return Err(self.err(loc, ent, format!("thickness {t} must be > 0")));
        }
        self.nodal_thickness.push(RawNodalThickness {
            target: super::target(v[0]),
            t,
            loc,
        });
        Ok(())
    }

    /// Nodal thicknesses → `Model::shell_thickness` (quadratic shells) or a derived section
    /// of the mean thickness (linear shells), after the sections are assigned (module doc).
    pub(super) fn resolve_nodal_thickness(&mut self, sets: &Sets) -> Result<(), ImportError> {
        let mut at: HashMap<usize, f64> = HashMap::new();
        for r in &self.nodal_thickness {
            for n in sets.target(&r.target, r.loc, "*NODAL THICKNESS", self)? {
                at.insert(n, r.t);
            }
        }
        // (element, its nodal thicknesses, its property, the section's thickness)
        let mut found: Vec<(usize, Vec<f64>, usize, f64)> = Vec::new();
        let mut without_param = None;
        let model = &self.b.model;
        for (e, el) in model.elements.iter().enumerate() {
            let Some(p) = el.property else { continue };
            let Section::Shell(sh) = &model.properties[p].section else {
                continue;
            };
            if !matches!(
                el.kind,
                ElementKind::Quad4 | ElementKind::Tri3 | ElementKind::Quad8 | ElementKind::Tri6
            ) {
                continue;
            }
            let Some(sec) = self.sections.get(p) else {
                continue;
            };
            let required = self.nodal_thickness_sections.contains(&p);
            if !required {
                if el.nodes.iter().any(|n| at.contains_key(n)) {
                    without_param.get_or_insert(sec.elset.clone());
                }
                continue;
            }
            let mut ts = Vec::with_capacity(el.nodes.len());
            for &n in &el.nodes {
                match at.get(&n) {
                    Some(&t) => ts.push(t),
                    None => {
                        return Err(self.b.err(
                            sec.loc,
                            format!("*SHELL SECTION ELSET={}", sec.elset),
                            format!(
                                "NODAL THICKNESS: node {} of element {} has no *NODAL THICKNESS",
                                model.nodes[n].id, el.id
                            ),
                        ))
                    }
                }
            }
            found.push((e, ts, p, sh.thickness));
        }
        let model = &mut self.b.model;
        let mut derived: HashMap<(usize, u64), usize> = HashMap::new();
        let mut averaged = 0usize;
        for (e, ts, p, base) in found {
            if matches!(
                model.elements[e].kind,
                ElementKind::Quad8 | ElementKind::Tri6
            ) {
                model.shell_thickness.insert(e, ts);
                continue;
            }
            let mean = ts.iter().sum::<f64>() / ts.len() as f64;
            if ts.iter().any(|t| (t - mean).abs() > 1e-9 * mean) {
                averaged += 1;
            }
            if (mean - base).abs() <= 1e-12 * mean {
                continue;
            }
            let d = *derived.entry((p, mean.to_bits())).or_insert_with(|| {
                let prop = model.properties[p].clone();
                let mut section = prop.section;
                if let Section::Shell(s) = &mut section {
                    s.thickness = mean;
                }
                model.properties.push(Property {
                    id: prop.id,
                    name: format!("{} (nodal T = {mean})", prop.name),
                    material: prop.material,
                    section,
                });
                model.properties.len() - 1
            });
            model.elements[e].property = Some(d);
        }
        let file = self.b.files[0].clone();
        if let Some(elset) = without_param {
            model.warnings.push(ImportWarning {
                file: file.clone(),
                message: format!(
                    "*NODAL THICKNESS gives thicknesses at nodes of shells whose *SHELL SECTION \
                     (first: ELSET={elset}) has no NODAL THICKNESS parameter: they use the \
                     section's thickness (as Abaqus and CalculiX 2.20 read them)"
                ),
            });
        }
        if averaged > 0 {
            model.warnings.push(ImportWarning {
                file,
                message: format!(
                    "{averaged} linear shell elements (S4/S3) have different nodal thicknesses: \
                     each uses the mean of its nodes"
                ),
            });
        }
        Ok(())
    }
}
