//! Orthotropic and anisotropic `*ELASTIC` and `*ORIENTATION` (the CalculiX/Abaqus manuals'
//! field orders).
//!
//! * `*ELASTIC, TYPE=ORTHO` (ORTHOTROPIC): D1111, D1122, D2222, D1133, D2233, D3333, D1212,
//!   D1313, D2323[, T] over two lines; `TYPE=ENGINEERING CONSTANTS`: E1, E2, E3, ν12, ν13, ν23,
//!   G12, G13, G23[, T]; `TYPE=ANISO` (ANISOTROPIC): the 21 D of the lower triangle row by row
//!   in the order 11 22 33 12 13 23 (D1111; D1122 D2222; D1133 D2233 D3333; D1112 … D1212;
//!   D1113 … D1313; D1123 … D2323)[, T] over three lines. D1212 multiplies the engineering
//!   shear γ12 (σ12 = D1212 γ12 for an orthotropic material). A row is 8 values a line; a table
//!   of rows is read at the part's temperature like the isotropic one (temperature.rs).
//!   `TYPE=LAMINA`: E1, E2, ν12, G12, G13, G23[, T], a plane-stress lamina of shells
//!   ([`PlaneStress::lamina`]; G13 = G23 = 0: shear-rigid, src/fe/shell_section.rs).
//! * `*ORIENTATION, NAME=…, SYSTEM=RECTANGULAR | CYLINDRICAL`: line 1 the points a, b
//!   (rectangular: a on axis 1, b in the 1–2 plane; cylindrical: a and b on the axis, as
//!   CalculiX's `transformatrix`); an optional line 2 "axis, angle" adds a rotation in degrees
//!   about that local axis (rectangular only, as CalculiX). `DEFINITION=` other than
//!   COORDINATES and a third point c away from the origin are refused. `*SOLID SECTION,
//!   ORIENTATION=name` gives its elements those material axes; on `*SHELL SECTION` the
//!   material x-axis is axis 1 of a rectangular orientation projected onto each element
//!   (Abaqus Analysis User's Guide §2.2.5 "Orientations": shells project the local 1-direction
//!   onto the surface); without one, Abaqus's default local directions: global x projected, or
//!   global z when x is within 0.1° of the normal (ibid. "Conventions", §1.2.2).

use super::keywords::Keyword;
use super::temperature::Row;
use super::{Block, Parser};
use crate::import::error::ImportError;
use crate::import::text::Loc;
use crate::model::elasticity::{self, Definiteness, Stiffness6};
use crate::model::{MaterialAxes, PlaneStress};

/// The kinds of a general `*ELASTIC`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum ElasticKind {
    Ortho,
    EngineeringConstants,
    Aniso,
    Lamina,
}

impl ElasticKind {
    /// Constants a row holds (the temperature not counted).
    pub fn count(self) -> usize {
        match self {
            ElasticKind::Ortho | ElasticKind::EngineeringConstants => 9,
            ElasticKind::Aniso => 21,
            ElasticKind::Lamina => 6,
        }
    }
}

/// A general `*ELASTIC` of a material: its kind, its rows (constants padded to 21), and the
/// values of a row being read over several lines.
#[derive(Debug)]
pub(super) struct GeneralElastic {
    pub kind: ElasticKind,
    pub rows: Vec<Row<21>>,
    pub pending: Vec<f64>,
    pending_loc: Option<Loc>,
    pub loc: Loc,
}

/// An `*ORIENTATION` as read.
#[derive(Debug)]
pub(super) struct RawOrientation {
    name: String,
    cylindrical: bool,
    points: Vec<f64>,
    rotation: Option<(usize, f64)>,
    loc: Loc,
}

/// A ply of `*SHELL SECTION, COMPOSITE` as read: thickness, material name, angle (degrees).
#[derive(Debug, Clone)]
pub(super) struct RawPly {
    pub thickness: f64,
    pub material: String,
    pub angle_deg: f64,
    pub loc: Loc,
}

/// Abaqus's Voigt position (11 22 33 12 13 23) → the model's (xx yy zz xy yz zx).
const FROM_ABAQUS: [usize; 6] = [0, 1, 2, 3, 5, 4];

impl Parser {
    /// `*ELASTIC, TYPE=…` other than isotropic: the block of its data lines.
    pub(super) fn general_elastic_keyword(
        &mut self,
        kw: &Keyword,
        t: &str,
    ) -> Result<Block, ImportError> {
        let upper = t.trim().to_ascii_uppercase();
        let kind = match upper.as_str() {
            "ORTHO" | "ORTHOTROPIC" => ElasticKind::Ortho,
            "ENGINEERING CONSTANTS" | "ENGINEERINGCONSTANTS" => ElasticKind::EngineeringConstants,
            "ANISO" | "ANISOTROPIC" => ElasticKind::Aniso,
            "LAMINA" => ElasticKind::Lamina,
            _ => {
                return Err(self.err(
                    kw.loc,
                    "*ELASTIC",
                    format!(
                        "TYPE={t} not supported (ISO, ORTHO, ENGINEERING CONSTANTS, ANISO and \
                         LAMINA are)"
                    ),
                ))
            }
        };
        let k = self.materials.len() - 1;
        if self.materials[k].general.is_some() || !self.materials[k].elastic.is_empty() {
            return Err(self.err(
                kw.loc,
                format!("*MATERIAL {}", self.materials[k].name),
                "a second *ELASTIC in one material",
            ));
        }
        self.materials[k].general = Some(GeneralElastic {
            kind,
            rows: Vec::new(),
            pending: Vec::new(),
            pending_loc: None,
            loc: kw.loc,
        });
        Ok(Block::ElasticGeneral)
    }

    /// A data line of a general `*ELASTIC` (module doc: a row continues while it lacks
    /// constants).
    pub(super) fn general_elastic_line(&mut self, line: &str, loc: Loc) -> Result<(), ImportError> {
        let k = self.materials.len() - 1;
        let ent = format!("*MATERIAL {}", self.materials[k].name);
        let v = self.reals(line, &ent, loc)?;
        let Some(g) = self.materials[k].general.as_mut() else {
            return Ok(());
        };
        g.pending_loc.get_or_insert(loc);
        g.pending.extend(v);
        let n = g.kind.count();
        if g.pending.len() < n {
            return Ok(());
        }
        if g.pending.len() > n + 1 {
            let got = g.pending.len();
            return Err(self.err(
                loc,
                ent,
                format!("*ELASTIC row has {got} values, expected {n} constants and a temperature"),
            ));
        }
        let mut vals = [0.0; 21];
        vals[..n].copy_from_slice(&g.pending[..n]);
        let t = g.pending.get(n).copied();
        let at = g.pending_loc.take().unwrap_or(loc);
        g.rows.push((vals, t, at));
        g.pending.clear();
        Ok(())
    }

    /// The material's D (model convention) from the constants of a general `*ELASTIC`; a
    /// singular D is a note, an indefinite one an error naming the material and line.
    #[allow(clippy::needless_range_loop)] // the lower triangle (i, j) in the manual's order
    pub(super) fn general_stiffness(
        &self,
        kind: ElasticKind,
        v: &[f64; 21],
        (ent, loc): (&str, Loc),
        notes: &mut Vec<String>,
    ) -> Result<Stiffness6, ImportError> {
        let mut d = [[0.0; 6]; 6];
        match kind {
            ElasticKind::Ortho => {
                let pos = [
                    (0, 0),
                    (0, 1),
                    (1, 1),
                    (0, 2),
                    (1, 2),
                    (2, 2),
                    (3, 3),
                    (4, 4),
                    (5, 5),
                ];
                for (&(i, j), &x) in pos.iter().zip(v) {
                    let (i, j) = (FROM_ABAQUS[i], FROM_ABAQUS[j]);
                    d[i][j] = x;
                    d[j][i] = x;
                }
            }
            ElasticKind::EngineeringConstants => {
                d = elasticity::from_engineering_constants(
                    [v[0], v[1], v[2]],
                    [v[3], v[4], v[5]],
                    [v[6], v[7], v[8]],
                )
                .map_err(|m| self.err(loc, ent.to_owned(), format!("*ELASTIC: {m}")))?;
            }
            ElasticKind::Lamina => {
                return Err(self.err(loc, ent.to_owned(), "*ELASTIC, TYPE=LAMINA has no 3-D D"))
            }
            ElasticKind::Aniso => {
                let mut it = v.iter();
                for i in 0..6 {
                    for j in 0..=i {
                        let x = *it.next().unwrap_or(&0.0);
                        let (i, j) = (FROM_ABAQUS[i], FROM_ABAQUS[j]);
                        d[i][j] = x;
                        d[j][i] = x;
                    }
                }
            }
        }
        match elasticity::check(&d) {
            Ok(Definiteness::Positive) => {}
            Ok(Definiteness::Singular { rank }) => notes.push(format!(
                "{}:{}: {ent}: *ELASTIC's D is positive semi-definite of rank {rank} (strain \
                 states without stress, as an acoustic medium's): accepted as CalculiX accepts it",
                self.b.file_name(loc),
                loc.line
            )),
            Err(m) => return Err(self.err(loc, ent.to_owned(), format!("*ELASTIC: {m}"))),
        }
        Ok(d)
    }

    /// The plane-stress lamina of `*ELASTIC, TYPE=LAMINA` constants E1, E2, ν12, G12, G13, G23
    /// (G13 = G23 = 0: shear-rigid).
    pub(super) fn lamina(
        &self,
        v: &[f64; 21],
        (ent, loc): (&str, Loc),
    ) -> Result<PlaneStress, ImportError> {
        let gz = (v[4] != 0.0 || v[5] != 0.0).then_some([v[4], v[5]]);
        PlaneStress::lamina(v[0], v[1], v[2], v[3], gz)
            .map_err(|m| self.err(loc, ent.to_owned(), format!("*ELASTIC, TYPE=LAMINA: {m}")))
    }

    /// A data line of `*SHELL SECTION, COMPOSITE` k: thickness, section points (not used),
    /// material, orientation — an angle in degrees about the normal from the section's
    /// material x-axis (blank: 0); an `*ORIENTATION` name per ply is an error — ply name.
    pub(super) fn composite_line(
        &mut self,
        k: usize,
        line: &str,
        loc: Loc,
    ) -> Result<(), ImportError> {
        let ent = format!("*SHELL SECTION ELSET={}", self.sections[k].elset);
        let f: Vec<&str> = super::fields(line).collect();
        let thickness = self.real(f[0], &ent, loc)?;
        if !(thickness > 0.0 && thickness.is_finite()) {
            return Err(self.err(loc, ent, format!("ply thickness {thickness} must be > 0")));
        }
        let material = f.get(2).copied().unwrap_or("").to_ascii_uppercase();
        if material.is_empty() {
            return Err(self.err(loc, ent, "a ply needs its material (third field)"));
        }
        let orientation = f.get(3).copied().unwrap_or("");
        let angle_deg = match orientation {
            "" => 0.0,
            o => crate::import::text::parse_f64(o).ok_or_else(|| {
                self.err(
                    loc,
                    ent.clone(),
                    format!(
                        "ply orientation {o}: an *ORIENTATION per ply is not supported; give \
                         the ply angle in degrees (about the normal, from the section's axes)"
                    ),
                )
            })?,
        };
        let sec = &mut self.sections[k];
        if sec.material.is_empty() {
            sec.material.clone_from(&material);
        }
        if let Some(p) = sec.plies.as_mut() {
            p.push(RawPly {
                thickness,
                material,
                angle_deg,
                loc,
            });
        }
        Ok(())
    }

    /// The shell material axis of a `*SHELL SECTION` (module doc): axis 1 of a rectangular
    /// `*ORIENTATION` projected, else Abaqus's default.
    pub(super) fn shell_axis(
        &self,
        orientation: Option<&str>,
        loc: Loc,
    ) -> Result<crate::model::ShellMaterialAxis, ImportError> {
        use crate::model::ShellMaterialAxis;
        let Some(name) = orientation else {
            return Ok(ShellMaterialAxis::AbaqusDefault);
        };
        match self.material_axes(name, loc)? {
            MaterialAxes::Rectangular(r) => Ok(ShellMaterialAxis::Projected(r[0])),
            MaterialAxes::Cylindrical { .. } => Err(self.err(
                loc,
                "*SHELL SECTION",
                format!(
                    "ORIENTATION={name} is cylindrical: curvilinear material axes of a shell are \
                     not supported"
                ),
            )),
        }
    }

    /// `*ORIENTATION`: the block of its data lines.
    /// Whether the deck defines `*ORIENTATION, NAME=name` (upper case).
    pub(super) fn orientation_exists(&self, name: &str) -> bool {
        self.orientations.iter().any(|o| o.name == name)
    }

    pub(super) fn orientation_keyword(&mut self, kw: &Keyword) -> Result<Block, ImportError> {
        let name = kw.need("NAME", self)?.to_ascii_uppercase();
        let ent = format!("*ORIENTATION {name}");
        let cylindrical = match kw.param("SYSTEM").map(|s| s.trim().to_ascii_uppercase()) {
            None => false,
            Some(s) if s.starts_with('R') => false,
            Some(s) if s.starts_with('C') => true,
            Some(s) => {
                return Err(self.err(
                    kw.loc,
                    ent,
                    format!("SYSTEM={s} not supported (RECTANGULAR or CYLINDRICAL)"),
                ))
            }
        };
        if let Some(d) = kw.param("DEFINITION") {
            if !d.trim().eq_ignore_ascii_case("COORDINATES") {
                return Err(self.err(
                    kw.loc,
                    ent,
                    format!("DEFINITION={d} not supported (COORDINATES only)"),
                ));
            }
        }
        self.orientations.push(RawOrientation {
            name,
            cylindrical,
            points: Vec::new(),
            rotation: None,
            loc: kw.loc,
        });
        Ok(Block::Orientation(self.orientations.len() - 1, 0))
    }

    /// Data line `n` of `*ORIENTATION` k: the points, then the additional rotation.
    pub(super) fn orientation_line(
        &mut self,
        k: usize,
        n: usize,
        line: &str,
        loc: Loc,
    ) -> Result<(), ImportError> {
        let ent = format!("*ORIENTATION {}", self.orientations[k].name);
        let v = self.reals(line, &ent, loc)?;
        self.block = Block::Orientation(k, n + 1);
        match n {
            0 => {
                if v.len() < 6 {
                    return Err(self.err(loc, ent, "needs the points a and b (6 coordinates)"));
                }
                if v.len() > 6 && v[6..].iter().any(|&c| c != 0.0) {
                    return Err(self.err(
                        loc,
                        ent,
                        "a third point c (origin) away from the global origin is not supported \
                         (CalculiX reads a and b only)",
                    ));
                }
                self.orientations[k].points = v[..6].to_vec();
            }
            1 => {
                let axis = v.first().copied().unwrap_or(0.0);
                let angle = v.get(1).copied().unwrap_or(0.0);
                if ![1.0, 2.0, 3.0].contains(&axis) {
                    return Err(self.err(
                        loc,
                        ent,
                        format!("additional rotation about axis {axis}: the axis is 1, 2 or 3"),
                    ));
                }
                if self.orientations[k].cylindrical && angle != 0.0 {
                    return Err(self.err(
                        loc,
                        ent,
                        "an additional rotation is allowed for rectangular systems only (as \
                         CalculiX)",
                    ));
                }
                self.orientations[k].rotation = Some((axis as usize, angle));
            }
            _ => return Err(self.err(loc, ent, "more than two data lines")),
        }
        Ok(())
    }

    /// The material axes of `*ORIENTATION` `name` (for the section at `loc`).
    pub(super) fn material_axes(&self, name: &str, loc: Loc) -> Result<MaterialAxes, ImportError> {
        let upper = name.trim().to_ascii_uppercase();
        let o = (self.orientations.iter().rev())
            .find(|o| o.name == upper)
            .ok_or_else(|| {
                self.err(
                    loc,
                    "*SECTION",
                    format!("ORIENTATION={name}: no *ORIENTATION of that name"),
                )
            })?;
        let ent = format!("*ORIENTATION {}", o.name);
        if o.points.len() < 6 {
            return Err(self.err(o.loc, ent, "missing data line (the points a and b)"));
        }
        let a = [o.points[0], o.points[1], o.points[2]];
        let b = [o.points[3], o.points[4], o.points[5]];
        if o.cylindrical {
            if a == b {
                return Err(self.err(o.loc, ent, "the axis points a and b coincide"));
            }
            return Ok(MaterialAxes::Cylindrical { a, b });
        }
        let (axis, angle) = o.rotation.unwrap_or((0, 0.0));
        MaterialAxes::rectangular(a, b, axis, angle)
            .ok_or_else(|| self.err(o.loc, ent, "a is zero or b is parallel to a"))
    }
}
