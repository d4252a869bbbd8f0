//! Local coordinate systems (`LOCAL`, `CLOCAL`, `CSYS`) and element coordinate systems (the
//! `EBLOCK` ESYS field): the material axes of orthotropic solids.
//!
//! What was read: the Command Reference's `LOCAL` (release 18.2 and 2024 R2): "LOCAL, KCN, KCS,
//! XC, YC, ZC, THXY, THYZ, THZX, PAR1, PAR2 … THXY — First rotation about local Z (positive X
//! toward Y). THYZ — Second rotation about local X (positive Y toward Z). THZX — Third rotation
//! about local Y (positive Z toward X)" — the order of the `NBLOCK`'s nodal angles, so the axes
//! are [`super::nodal::nodal_axes`]'s; "This local system becomes the active coordinate system
//! (CSYS)". `CLOCAL` has the same fields "relative to the active coordinate system". `CDWRITE`
//! writes a system as three lines, `LOCAL,R5.0,LOC,KCN,KCS,XC,YC,ZC`,
//! `LOCAL,R5.0,ANG,KCN,KCS,THXY,THYZ,THZX` and `LOCAL,R5.0,PRM,KCN,KCS,PAR1,PAR2` (`UNBL` in an
//! unblocked archive). The Element Reference (§3.3.1): "Solid elements: The default orientation
//! is generally parallel to the global Cartesian coordinate system"; `ESYS`: "For non-layered
//! volume elements, the local coordinate system N is assigned as the element coordinate
//! system", and the element coordinate system "is used for: Orthotropic material input". So a
//! solid's material axes are its ESYS system's axes (global without one). For a cylindrical or
//! spherical ESYS no statement of where the curvilinear axes are taken (the element's centroid,
//! each integration point) was found: an orthotropic solid in one is refused. An isotropic
//! element is the same in any system and is accepted.

use std::collections::BTreeMap;

use super::blocks::{archive_form, Command};
use super::nodal::nodal_axes;
use crate::import::error::ImportError;
use crate::model::{MaterialAxes, Model, Property};

/// One local system as the archive leaves it.
#[derive(Debug, Clone)]
pub(super) struct LocalSystem {
    /// Its (first) defining line.
    pub line: usize,
    /// `LOCAL` or `CLOCAL`.
    pub command: &'static str,
    /// KCS: 0 Cartesian, 1 cylindrical, 2 spherical, 3 toroidal.
    pub kind: i64,
    /// Origin, global.
    pub origin: [f64; 3],
    /// Rows: the system's X, Y, Z unit axes in global components; `Err`: why they are not
    /// known (a `CLOCAL` relative to a curvilinear active system).
    pub axes: Result<[[f64; 3]; 3], String>,
}

/// The archive's local systems and the active one.
#[derive(Debug, Default)]
pub(super) struct LocalSystems {
    /// KCN → the system (a redefinition replaces it, as ANSYS does).
    pub systems: BTreeMap<i64, LocalSystem>,
    /// The active system: 0 global Cartesian, 1 global cylindrical, 2 global spherical, or a KCN.
    active: i64,
}

const IDENTITY: [[f64; 3]; 3] = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];

impl LocalSystems {
    /// `CSYS,KCN`: the active system.
    pub fn csys(&mut self, file: &str, c: &Command) -> Result<(), ImportError> {
        self.active = if c.field(0).is_empty() {
            0
        } else {
            c.int(file, 0)?
        };
        Ok(())
    }

    /// `LOCAL`/`CLOCAL,KCN,KCS,XC,YC,ZC,THXY,THYZ,THZX,…`, or the archive's three lines
    /// `LOCAL,R5.0,LOC|ANG|PRM,KCN,KCS,…` (module doc). Returns the system number.
    pub fn define(&mut self, file: &str, c: &Command) -> Result<i64, ImportError> {
        let command = if c.name == "CLOCAL" {
            "CLOCAL"
        } else {
            "LOCAL"
        };
        let real = |k: usize| -> Result<f64, ImportError> {
            if c.field(k).is_empty() {
                Ok(0.0)
            } else {
                c.real(file, k)
            }
        };
        if archive_form(c.field(0)) {
            let kcn = c.int(file, 2)?;
            let kind = if c.field(3).is_empty() {
                0
            } else {
                c.int(file, 3)?
            };
            let part = c.field(1).to_ascii_uppercase();
            let entry = self.systems.entry(kcn).or_insert_with(|| LocalSystem {
                line: c.line,
                command,
                kind,
                origin: [0.0; 3],
                axes: Ok(IDENTITY),
            });
            entry.kind = kind;
            match part.as_str() {
                "LOC" => {
                    // a new definition starts with its LOC line
                    entry.line = c.line;
                    entry.origin = [real(4)?, real(5)?, real(6)?];
                    entry.axes = Ok(IDENTITY);
                }
                "ANG" => entry.axes = Ok(nodal_axes([real(4)?, real(5)?, real(6)?])),
                // PAR1, PAR2: the ellipse ratios of a curvilinear system (refused for an
                // orthotropic element anyway)
                _ => {}
            }
            self.active = kcn;
            return Ok(kcn);
        }
        let kcn = c.int(file, 0)?;
        let kind = if c.field(1).is_empty() {
            0
        } else {
            c.int(file, 1)?
        };
        let given = [real(2)?, real(3)?, real(4)?];
        let angles = [real(5)?, real(6)?, real(7)?];
        let own = nodal_axes(angles);
        let (origin, axes) = if command == "LOCAL" {
            (given, Ok(own))
        } else {
            self.relative_to_active(given, own)
        };
        self.systems.insert(
            kcn,
            LocalSystem {
                line: c.line,
                command,
                kind,
                origin,
                axes,
            },
        );
        self.active = kcn;
        Ok(kcn)
    }

    /// A `CLOCAL`'s origin and axes given in the active system: global when the active system
    /// is Cartesian (origin o + Σ xᵢ aᵢ, axes rows A·R_active), else why not.
    fn relative_to_active(
        &self,
        at: [f64; 3],
        own: [[f64; 3]; 3],
    ) -> ([f64; 3], Result<[[f64; 3]; 3], String>) {
        let (origin, frame) = match self.active {
            0 => ([0.0; 3], Ok(IDENTITY)),
            1 | 2 => ([0.0; 3], Err(format!("global system {}", self.active))),
            n => match self.systems.get(&n) {
                Some(s) if s.kind == 0 => (s.origin, s.axes.clone()),
                Some(s) => (s.origin, Err(format!("system {n} of KCS {}", s.kind))),
                None => ([0.0; 3], Err(format!("system {n}, which no LOCAL defines"))),
            },
        };
        match frame {
            Ok(r) => {
                let o = std::array::from_fn(|j| origin[j] + (0..3).map(|i| at[i] * r[i][j]).sum::<f64>());
                let axes = std::array::from_fn(|a| {
                    std::array::from_fn(|j| (0..3).map(|i| own[a][i] * r[i][j]).sum())
                });
                (o, Ok(axes))
            }
            Err(what) => (
                origin,
                Err(format!(
                    "a CLOCAL relative to the active curvilinear {what}: its axes are not resolved here"
                )),
            ),
        }
    }
}

/// The solid properties of orthotropic materials in element systems: (material property,
/// ESYS) → property with those material axes.
#[derive(Debug, Default)]
pub(super) struct SolidAxes {
    made: BTreeMap<(usize, i64), usize>,
}

impl SolidAxes {
    /// The property of a solid element whose material has the property `base` and whose
    /// EBLOCK ESYS is `esys`: `base` itself for an isotropic material, no ESYS, or a system no
    /// `LOCAL` defines (refused by [`super::Archive::element_systems`]); for an orthotropic
    /// material in a Cartesian system, one property per (material, system) with the system's
    /// axes as material axes; otherwise why not.
    pub fn property(
        &mut self,
        model: &mut Model,
        systems: &LocalSystems,
        base: usize,
        esys: i64,
    ) -> Result<usize, String> {
        let material = &model.materials[model.properties[base].material];
        let Some(system) = systems.systems.get(&esys) else {
            return Ok(base);
        };
        if material.stiffness().is_none() {
            return Ok(base);
        }
        if system.kind != 0 {
            return Err(format!(
                "an orthotropic material ({}) in element coordinate system {esys} of KCS {} \
                 ({} at line {}): where ANSYS takes a curvilinear element system's axes was not \
                 found in the documentation at hand; not formed here",
                material.name, system.kind, system.command, system.line
            ));
        }
        let axes = system.axes.clone().map_err(|why| {
            format!(
                "element coordinate system {esys} ({} at line {}) is {why}",
                system.command, system.line
            )
        })?;
        if let Some(&p) = self.made.get(&(base, esys)) {
            return Ok(p);
        }
        let mut property: Property = model.properties[base].clone();
        property.name = format!("{} ESYS {esys}", property.name);
        model.properties.push(property);
        let p = model.properties.len() - 1;
        model
            .property_axes
            .insert(p, MaterialAxes::Rectangular(axes));
        self.made.insert((base, esys), p);
        Ok(p)
    }
}

impl super::Archive {
    /// Elements whose `EBLOCK` ESYS names a system no `LOCAL`/`CLOCAL` of the archive defines:
    /// refused, one line per system at its first element (ANSYS needs the system; its axes
    /// are unknown here).
    pub(super) fn element_systems(&mut self) {
        let mut first: BTreeMap<i64, (usize, u64, usize)> = BTreeMap::new();
        let undefined = self
            .elements
            .iter()
            .filter(|r| r.esys > 0 && !self.locals.systems.contains_key(&r.esys));
        for r in undefined {
            first.entry(r.esys).or_insert((r.line, r.id, 0)).2 += 1;
        }
        for (esys, (line, id, count)) in first {
            self.refused.push((
                line,
                format!("EBLOCK element {id}"),
                "ESYS".into(),
                format!(
                    "element coordinate system {esys} (no LOCAL of the archive defines it) on \
                     {count} element(s), the first here"
                ),
            ));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn command(text: &str) -> Command<'_> {
        super::super::blocks::command(text, 1).unwrap()
    }

    /// The archive's three lines give the command's system; a CLOCAL in a rotated, moved
    /// LOCAL composes with it (axis rows A·R, origin o + Σ xᵢ aᵢ).
    #[test]
    fn archive_lines_and_clocal_compose() {
        let mut a = LocalSystems::default();
        a.define("f", &command("LOCAL,12,0,1.0,2.0,3.0,30.0,20.0,40.0"))
            .unwrap();
        let mut b = LocalSystems::default();
        for line in [
            "LOCAL,R5.0,LOC,      12,  0, 1.0, 2.0, 3.0",
            "LOCAL,R5.0,ANG,      12,  0, 30.0, 20.0, 40.0",
            "LOCAL,R5.0,PRM,      12,  0, 1.0, 1.0",
        ] {
            b.define("f", &command(line)).unwrap();
        }
        let (sa, sb) = (a.systems[&12].clone(), &b.systems[&12]);
        assert_eq!(sa.origin, sb.origin);
        assert_eq!(sa.axes, sb.axes);
        // CLOCAL,13 in 12 (active after its LOCAL): 90° about the local Z, moved along local X
        a.define("f", &command("CLOCAL,13,0,1.0,0.0,0.0,90.0,0.0,0.0"))
            .unwrap();
        let r = sa.axes.clone().unwrap();
        let s = a.systems[&13].clone();
        let t = s.axes.unwrap();
        for j in 0..3 {
            assert!((s.origin[j] - (sa.origin[j] + r[0][j])).abs() < 1e-15);
            assert!((t[0][j] - r[1][j]).abs() < 1e-15, "{t:?}");
            assert!((t[1][j] + r[0][j]).abs() < 1e-15, "{t:?}");
        }
        // relative to a cylindrical system: not resolved
        a.define("f", &command("LOCAL,14,1,0,0,0")).unwrap();
        a.define("f", &command("CLOCAL,15,0,1,0,0")).unwrap();
        assert!(a.systems[&15].axes.is_err());
        a.csys("f", &command("CSYS,0")).unwrap();
        a.define("f", &command("CLOCAL,16,0,1,0,0")).unwrap();
        assert_eq!(a.systems[&16].origin, [1.0, 0.0, 0.0]);
    }
}
