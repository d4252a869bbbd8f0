//! Beams of an archive: beam sections (`SECTYPE,id,BEAM,subtype` with its `SECDATA`,
//! `SECOFFSET`, `SECCONTROL` lines), BEAM188 with linear shape functions (KEYOPT(3)=0,
//! `fe::elements::beam188`), quadratic (KEYOPT(3)=2) or cubic (KEYOPT(3)=3) ones on ANSYS's
//! internal nodes (`fe::elements::beam189`) and BEAM189, formed as the MAPDL Theory Reference
//! §13.188 and §13.189 state them, or refused by line naming the KEYOPT, the section line or
//! what is not formed.
//!
//! Section constants: ASEC the user's own (A, Iyy, Izz, J; shear factor 1, as ANSYS's VM50
//! frequency shows); RECT, CSOLID and CTUBE in closed form — A and I exact, J exact for the
//! circles and Saint-Venant's series for the rectangle, the shear factors Cowper's (1966), where
//! ANSYS computes J and the shear factors on its own section mesh (docs/ansys.md says how close
//! they are expected to be).

use std::collections::BTreeMap;
use std::f64::consts::PI;

use super::blocks::{Command, ElementRecord};
use crate::fe::elements::beam189::Order;
use crate::import::error::ImportError;
use crate::model::geometry::{cross, dot, norm, scale, sub};
use crate::model::{
    BeamSection as ModelBeamSection, Element, ElementKind, Model, Node, Property, Section,
};

/// The subtypes of `SECTYPE,id,BEAM` whose constants are computed here.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Subtype {
    /// The user's constants: A, Iyy, Iyz, Izz, Iw, J, CGy, CGz, SHy, SHz, TKz, TKy.
    Asec,
    /// Solid rectangle B (along the section's y) × H (along z).
    Rect,
    /// Solid circle of radius R.
    Csolid,
    /// Circular tube of radii Ri, Ro.
    Ctube,
}

/// A `SECTYPE,id,BEAM,subtype` section: its data (one `SECDATA` line), offset and added mass.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct BeamSection {
    /// The `SECTYPE` line.
    pub line: usize,
    pub subtype: Subtype,
    /// The `SECDATA` values (blank fields 0) and its line.
    pub data: Option<(usize, Vec<f64>)>,
    /// The `SECOFFSET` location (upper case; CENT when none) and its line.
    pub offset: (usize, String),
    /// Added mass per unit length (`SECCONTROL`'s ADDMAS).
    pub added_mass: f64,
}

/// A beam section's constants in the element frame (ANSYS's section y, z are the element's).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Constants {
    pub area: f64,
    /// ∫z² dA: bending in the element's x–z plane.
    pub iyy: f64,
    /// ∫y² dA: bending in the element's x–y plane.
    pub izz: f64,
    pub j: f64,
    /// Shear factors (k_y, k_z): shear stiffness k G A along y and z.
    pub shear: [f64; 2],
}

impl BeamSection {
    /// A new section opened by `SECTYPE,id,BEAM,subtype`; a subtype not computed here is
    /// refused (the reason).
    pub fn open(c: &Command) -> Result<BeamSection, String> {
        let sub = c.field(2).trim().to_ascii_uppercase();
        // CDWRITE writes the subtype's first four letters (SECTYPE,1,BEAM,CSOL)
        let subtype = match sub.as_str() {
            "ASEC" => Subtype::Asec,
            "RECT" => Subtype::Rect,
            "CSOLID" | "CSOL" => Subtype::Csolid,
            "CTUBE" | "CTUB" => Subtype::Ctube,
            "MESH" => {
                return Err(format!(
                    "SECTYPE {},BEAM,MESH: a user section mesh is not read (ANSYS integrates \
                     over it: not formed here)",
                    c.field(0)
                ))
            }
            _ => {
                return Err(format!(
                    "SECTYPE {},BEAM,{sub}: beam section subtype {} not computed here (ASEC, \
                     RECT, CSOLID and CTUBE are; ANSYS computes the others' constants on its own \
                     section mesh)",
                    c.field(0),
                    if sub.is_empty() { "(blank)" } else { &sub }
                ))
            }
        };
        Ok(BeamSection {
            line: c.line,
            subtype,
            data: None,
            offset: (c.line, "CENT".into()),
            added_mass: 0.0,
        })
    }

    /// A `SECDATA` or `SECCONTROL` line of this section: the refusal's reason, if any.
    pub fn read(&mut self, file: &str, c: &Command) -> Result<Option<String>, ImportError> {
        if c.name == "SECDATA" {
            self.secdata(file, c)
        } else {
            self.seccontrol(file, c)
        }
    }

    /// `SECDATA,…`: the section's dimensions or constants (one line).
    pub fn secdata(&mut self, file: &str, c: &Command) -> Result<Option<String>, ImportError> {
        let values = (0..c.fields.len().max(1))
            .map(|k| c.real(file, k))
            .collect::<Result<Vec<_>, _>>()?;
        if let Some((first, _)) = &self.data {
            return Ok(Some(format!(
                "SECDATA: a second data line for the beam section of SECTYPE line {} (the first \
                 at line {first})",
                self.line
            )));
        }
        self.data = Some((c.line, values));
        Ok(None)
    }

    /// `SECOFFSET,Location,…`: kept, checked against the subtype when the constants are read.
    pub fn secoffset(&mut self, c: &Command) -> Option<String> {
        let location = c.field(0).trim().to_ascii_uppercase();
        self.offset = (
            c.line,
            if location.is_empty() {
                "CENT".into()
            } else {
                location
            },
        );
        None
    }

    /// `SECCONTROL,TXZ,TXY,ADDMAS`: the added mass per length is read; user transverse shear
    /// stiffnesses are refused.
    pub fn seccontrol(&mut self, file: &str, c: &Command) -> Result<Option<String>, ImportError> {
        let (txz, txy, addmas) = (c.real(file, 0)?, c.real(file, 1)?, c.real(file, 2)?);
        self.added_mass = addmas;
        if txz != 0.0 || txy != 0.0 {
            return Ok(Some(
                "SECCONTROL: user transverse shear stiffnesses TXZ, TXY of a beam section are not \
                 read"
                    .into(),
            ));
        }
        Ok((!(addmas >= 0.0 && addmas.is_finite()))
            .then(|| format!("SECCONTROL: added mass per length {addmas} (not ≥ 0)")))
    }

    /// The constants for a material of Poisson's ratio `nu`, or why not.
    pub fn constants(&self, nu: f64) -> Result<Constants, String> {
        let Some((data_line, d)) = &self.data else {
            return Err(format!(
                "beam section of SECTYPE line {} has no SECDATA line",
                self.line
            ));
        };
        let v = |k: usize| d.get(k).copied().unwrap_or(0.0);
        let (offset_line, location) = &self.offset;
        let centred = matches!(self.subtype, Subtype::Csolid | Subtype::Ctube);
        match location.as_str() {
            "CENT" => {}
            "SHRC" | "ORIGIN" if centred => {}
            other => {
                return Err(format!(
                    "SECOFFSET,{other} (line {offset_line}): a beam node off the section's \
                     centroid is not formed here (CENT is; SHRC and ORIGIN for CSOLID and CTUBE)"
                ))
            }
        }
        let bad = |what: &str| {
            Err(format!(
                "SECDATA line {data_line}: {what} (beam section of SECTYPE line {})",
                self.line
            ))
        };
        let c = match self.subtype {
            Subtype::Asec => {
                if v(2) != 0.0 {
                    return bad("ASEC with a product of inertia Iyz ≠ 0: not formed here");
                }
                if (6..10).any(|k| v(k) != 0.0) {
                    return bad(
                        "ASEC with its centroid or shear centre off the node (CGy, CGz, SHy, \
                         SHz): not formed here",
                    );
                }
                Constants {
                    area: v(0),
                    iyy: v(1),
                    izz: v(3),
                    j: v(5),
                    shear: [1.0, 1.0],
                }
            }
            Subtype::Rect => {
                let (b, h) = (v(0), v(1));
                let k = 10.0 * (1.0 + nu) / (12.0 + 11.0 * nu);
                Constants {
                    area: b * h,
                    iyy: b * h.powi(3) / 12.0,
                    izz: h * b.powi(3) / 12.0,
                    j: rectangle_torsion(b, h),
                    shear: [k, k],
                }
            }
            Subtype::Csolid => {
                let r = v(0);
                let i = PI * r.powi(4) / 4.0;
                let k = 6.0 * (1.0 + nu) / (7.0 + 6.0 * nu);
                Constants {
                    area: PI * r * r,
                    iyy: i,
                    izz: i,
                    j: 2.0 * i,
                    shear: [k, k],
                }
            }
            Subtype::Ctube => {
                let (ri, ro) = (v(0), v(1));
                if !(ri >= 0.0 && ro > ri) {
                    return bad(&format!("CTUBE radii Ri = {ri}, Ro = {ro} (0 ≤ Ri < Ro)"));
                }
                let i = PI * (ro.powi(4) - ri.powi(4)) / 4.0;
                let m2 = (ri / ro).powi(2);
                let k = 6.0 * (1.0 + nu) * (1.0 + m2).powi(2)
                    / ((7.0 + 6.0 * nu) * (1.0 + m2).powi(2) + (20.0 + 12.0 * nu) * m2);
                Constants {
                    area: PI * (ro * ro - ri * ri),
                    iyy: i,
                    izz: i,
                    j: 2.0 * i,
                    shear: [k, k],
                }
            }
        };
        let ok = [c.area, c.iyy, c.izz, c.j]
            .iter()
            .all(|x| *x > 0.0 && x.is_finite());
        if !ok {
            return bad(&format!(
                "A = {}, Iyy = {}, Izz = {}, J = {} (each must be > 0)",
                c.area, c.iyy, c.izz, c.j
            ));
        }
        Ok(c)
    }
}

/// Saint-Venant's torsion constant of a b × h rectangle (Timoshenko & Goodier, *Theory of
/// Elasticity* §109): J = a c³ [1/3 − (64/π⁵)(c/a) Σ_{n odd} tanh(nπa/(2c))/n⁵], a ≥ c the
/// long and short sides.
pub(super) fn rectangle_torsion(b: f64, h: f64) -> f64 {
    let (a, c) = if b >= h { (b, h) } else { (h, b) };
    let mut sum = 0.0;
    for k in 0..50 {
        let n = (2 * k + 1) as f64;
        sum += (n * PI * a / (2.0 * c)).tanh() / n.powi(5);
    }
    a * c.powi(3) * (1.0 / 3.0 - 64.0 / PI.powi(5) * (c / a) * sum)
}

/// A BEAM188 or BEAM189 as the model receives it: nodes I, J, the mid node and the orientation
/// node.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Beam {
    pub ends: [u64; 2],
    pub mid: Mid,
    pub orientation: Option<u64>,
}

/// A beam's middle node.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Mid {
    /// BEAM188 KEYOPT(3)=0: none (linear).
    None,
    /// BEAM189: the archive's node K.
    Node(u64),
    /// BEAM188 KEYOPT(3)=2 (quadratic) or 3 (cubic): ANSYS's internal nodes, which the
    /// archive does not hold: made where the order puts them along IJ (the middle; 1/3 and
    /// 2/3).
    Internal(Order),
}

/// BEAM188 (MAPDL Element Reference "BEAM188"; Theory Reference §13.188): KEYOPT(3)=0 (linear,
/// the default), 2 (quadratic) and 3 (cubic) with six dofs per node (KEYOPT(1)=0) formed; the
/// warping dof and options that change the element are refused naming the KEYOPT. KEYOPT(2)
/// (cross-section scaling in large deflection), KEYOPT(11) (pre-integrated section) and the
/// output controls (4, 6, 7, 9, 15) have no effect on a linear body.
pub(super) fn beam188(keyopts: &BTreeMap<u32, i64>, rec: &ElementRecord) -> Result<Beam, String> {
    let keyopt = |k: u32| keyopts.get(&k).copied().unwrap_or(0);
    if keyopt(1) != 0 {
        return Err(format!(
            "BEAM188 KEYOPT(1)={}: the warping dof (restrained warping) is not formed here",
            keyopt(1)
        ));
    }
    let mid = match keyopt(3) {
        0 => Mid::None,
        2 => Mid::Internal(Order::Quadratic),
        3 => Mid::Internal(Order::Cubic),
        k => return Err(format!("BEAM188 KEYOPT(3)={k}: not an option of BEAM188")),
    };
    let no_effect = [1, 2, 3, 4, 6, 7, 9, 11, 15];
    if let Some((k, v)) = keyopts.iter().find(|(k, _)| !no_effect.contains(*k)) {
        return Err(format!(
            "BEAM188 KEYOPT({k})={v}: this option's formulation is not formed here"
        ));
    }
    if keyopt(2) > 1 || keyopt(11) > 1 {
        return Err(format!(
            "BEAM188 KEYOPT(2)={}, KEYOPT(11)={}: not options of BEAM188",
            keyopt(2),
            keyopt(11)
        ));
    }
    let n = &rec.nodes;
    let (i, j) = (
        n.first().copied().unwrap_or(0),
        n.get(1).copied().unwrap_or(0),
    );
    if i == 0 || j == 0 || i == j {
        return Err("BEAM188 without two distinct nodes I and J".into());
    }
    if n.iter().skip(3).any(|&m| m != 0) {
        return Err(
            "BEAM188 with a fourth node (an internal node of the quadratic or cubic form): not \
             formed here"
                .into(),
        );
    }
    let k = n.get(2).copied().filter(|&k| k != 0);
    Ok(Beam {
        ends: [i, j],
        mid,
        orientation: k,
    })
}

/// BEAM189 (MAPDL Element Reference "BEAM189"; Theory Reference §13.189): nodes I, J, the mid
/// node K and the orientation node L, six dofs per node (KEYOPT(1)=0) formed; the warping dof
/// and options that change the element are refused naming the KEYOPT; KEYOPT(2), KEYOPT(11)
/// and the output controls (4, 6, 7, 9, 15) have no effect on a linear body.
pub(super) fn beam189(keyopts: &BTreeMap<u32, i64>, rec: &ElementRecord) -> Result<Beam, String> {
    let keyopt = |k: u32| keyopts.get(&k).copied().unwrap_or(0);
    if keyopt(1) != 0 {
        return Err(format!(
            "BEAM189 KEYOPT(1)={}: the warping dof (restrained warping) is not formed here",
            keyopt(1)
        ));
    }
    let no_effect = [1, 2, 4, 6, 7, 9, 11, 15];
    if let Some((k, v)) = keyopts.iter().find(|(k, _)| !no_effect.contains(*k)) {
        return Err(format!(
            "BEAM189 KEYOPT({k})={v}: this option's formulation is not formed here"
        ));
    }
    if keyopt(2) > 1 || keyopt(11) > 1 {
        return Err(format!(
            "BEAM189 KEYOPT(2)={}, KEYOPT(11)={}: not options of BEAM189",
            keyopt(2),
            keyopt(11)
        ));
    }
    let n = |k: usize| rec.nodes.get(k).copied().unwrap_or(0);
    let (i, j, mid) = (n(0), n(1), n(2));
    if i == 0 || j == 0 || mid == 0 || i == j || mid == i || mid == j {
        return Err("BEAM189 without three distinct nodes I, J and the mid node K".into());
    }
    if rec.nodes.iter().skip(4).any(|&m| m != 0) {
        return Err("BEAM189 with more than four nodes (I, J, K, L)".into());
    }
    Ok(Beam {
        ends: [i, j],
        mid: Mid::Node(mid),
        orientation: Some(n(3)).filter(|&l| l != 0),
    })
}

/// Beam properties made so far: (section id, material number) → property index.
pub(super) type BeamProperties = BTreeMap<(i64, i64), usize>;

/// Where the archive's beam sections, materials and properties are.
pub(super) struct BeamContext<'a> {
    pub sections: &'a BTreeMap<i64, BeamSection>,
    pub property_of: &'a BTreeMap<i64, usize>,
    pub made: BeamProperties,
    /// The id of the next internal node (BEAM188 KEYOPT(3)=2, 3): after the archive's largest.
    next_internal: Option<u64>,
}

/// The refusals of the archive's elements: (element type, reason) → (first line, count).
pub(super) type Refusals = BTreeMap<(i64, String), (usize, usize)>;

impl<'a> BeamContext<'a> {
    /// No beam property made yet.
    pub fn new(
        sections: &'a BTreeMap<i64, BeamSection>,
        property_of: &'a BTreeMap<i64, usize>,
    ) -> BeamContext<'a> {
        BeamContext {
            sections,
            property_of,
            made: BeamProperties::new(),
            next_internal: None,
        }
    }

    /// `beam` (record `rec`) into the model ([`push_beam`]), its node ids mapped by `node_of`:
    /// the element's index, or `None` with its refusal counted in `refusals`.
    pub fn push(
        &mut self,
        model: &mut Model,
        rec: &ElementRecord,
        beam: &Beam,
        node_of: impl Fn(u64) -> Result<usize, ImportError>,
        refusals: &mut Refusals,
    ) -> Result<Option<usize>, ImportError> {
        let mut nodes = vec![node_of(beam.ends[0])?, node_of(beam.ends[1])?];
        let name = match beam.mid {
            Mid::None => "BEAM188",
            Mid::Node(mid) => {
                nodes.push(node_of(mid)?);
                "BEAM189"
            }
            Mid::Internal(order) => {
                for &at in order.inner() {
                    nodes.push(self.internal_node(model, [nodes[0], nodes[1]], at));
                }
                match order {
                    Order::Quadratic => "BEAM188 KEYOPT(3)=2",
                    Order::Cubic => "BEAM188 KEYOPT(3)=3",
                }
            }
        };
        let k = beam.orientation.map(&node_of).transpose()?;
        Ok(match push_beam(model, self, rec, &nodes, k, name) {
            Ok(e) => Some(e),
            Err(why) => {
                if let Mid::Internal(order) = beam.mid {
                    // the internal nodes were the last ones made: no element holds them now
                    let made = order.inner().len();
                    model.nodes.truncate(model.nodes.len() - made);
                    self.next_internal = self.next_internal.map(|id| id - made as u64);
                }
                refusals.entry((rec.etype, why)).or_insert((rec.line, 0)).1 += 1;
                None
            }
        })
    }

    /// An internal node of BEAM188 KEYOPT(3)=2 or 3 at the fraction `at` of `ends` from I,
    /// numbered as ANSYS numbers KEYOPT(3)=2's (the result file of ansys/example-data's
    /// `post_beam_result_01.rst`: after the largest node id, in element order; KEYOPT(3)=3's
    /// two per element likewise, the one at 1/3 first — no ANSYS file here shows their
    /// numbers): its model index.
    fn internal_node(&mut self, model: &mut Model, ends: [usize; 2], at: f64) -> usize {
        let id = *self
            .next_internal
            .get_or_insert_with(|| model.nodes.iter().map(|n| n.id).max().unwrap_or(0) + 1);
        self.next_internal = Some(id + 1);
        let [a, b] = ends.map(|k| model.nodes[k].x);
        model.nodes.push(Node {
            id,
            x: std::array::from_fn(|c| a[c] + at * (b[c] - a[c])),
            displacement_frame: None,
        });
        model.nodes.len() - 1
    }
}

/// Adds a beam (record `rec`, named `name` in refusals; its nodes as model indices: I, J and
/// the inner nodes; `k` the orientation node) to the model as a [`ElementKind::Beam2Linear`]
/// (BEAM188), [`ElementKind::Beam3Quadratic`] (BEAM189; BEAM188 KEYOPT(3)=2, whose
/// functions and points the Theory Reference gives as BEAM189's) or [`ElementKind::Beam4Cubic`]
/// (BEAM188 KEYOPT(3)=3) of its section and material: the element's index, or why not.
pub(super) fn push_beam(
    model: &mut Model,
    ctx: &mut BeamContext,
    rec: &ElementRecord,
    nodes: &[usize],
    k: Option<usize>,
    name: &str,
) -> Result<usize, String> {
    let ends = [nodes[0], nodes[1]];
    let (kind, inner) = match nodes.len() {
        2 => (ElementKind::Beam2Linear, &[][..]),
        3 => (ElementKind::Beam3Quadratic, Order::Quadratic.inner()),
        _ => (ElementKind::Beam4Cubic, Order::Cubic.inner()),
    };
    let Some(section) = ctx.sections.get(&rec.section) else {
        return Err(format!(
            "{name} of section {}, which is no beam section (SECTYPE,{},BEAM)",
            rec.section, rec.section
        ));
    };
    let Some(&solid) = ctx.property_of.get(&rec.mat) else {
        return Err(format!(
            "{name} of material {}, which has no MPDATA",
            rec.mat
        ));
    };
    let material = model.properties[solid].material;
    let nu = model.materials[material].nu;
    let c = section.constants(nu)?;
    let x = [model.nodes[ends[0]].x, model.nodes[ends[1]].x];
    let along = sub(x[1], x[0]);
    let length = norm(along);
    if length.is_nan() || length <= 0.0 {
        return Err(format!("{name} of zero length (I and J coincide)"));
    }
    for (&m, at) in nodes[2..].iter().zip(inner) {
        let place: [f64; 3] = std::array::from_fn(|c| x[0][c] + at * (x[1][c] - x[0][c]));
        if norm(sub(model.nodes[m].x, place)) > 1e-6 * length {
            return Err(format!(
                "{name} with its mid node off the middle of IJ (a curved or uneven element): not \
                 formed here"
            ));
        }
    }
    let ex = scale(along, 1.0 / length);
    let orientation = match k {
        Some(k) => {
            // the element's z axis lies in the plane of I, J and K, toward K; y = z × x
            let toward = sub(model.nodes[k].x, x[0]);
            let z = sub(toward, scale(ex, dot(toward, ex)));
            if norm(z) <= 1e-9 * norm(toward).max(length) {
                return Err(format!("{name} orientation node on the line IJ"));
            }
            cross(scale(z, 1.0 / norm(z)), ex)
        }
        None => {
            let symmetric = c.iyy == c.izz && c.shear[0] == c.shear[1];
            if !symmetric {
                return Err(format!(
                    "{name} without an orientation node K on a section whose orientation \
                     matters (Iyy ≠ Izz): ANSYS's default orientation is not established here"
                ));
            }
            // any direction across the axis: the section is the same in every one
            let least = (0..3)
                .min_by(|&a, &b| ex[a].abs().total_cmp(&ex[b].abs()))
                .unwrap_or(0);
            let mut e = [0.0; 3];
            e[least] = 1.0;
            e
        }
    };
    let key = (rec.section, rec.mat);
    let property = match ctx.made.get(&key) {
        Some(&p) => p,
        None => {
            model.properties.push(Property {
                id: (model.properties.len() + 1) as u64,
                name: format!("{name} SECNUM {} MAT{}", rec.section, rec.mat),
                material,
                section: Section::Beam(ModelBeamSection {
                    area: c.area,
                    i1: c.izz,
                    i2: c.iyy,
                    i12: 0.0,
                    j: c.j,
                    shear_factors: Some(c.shear),
                    nsm: section.added_mass,
                    shape: None,
                    taper: None,
                }),
            });
            ctx.made.insert(key, model.properties.len() - 1);
            model.properties.len() - 1
        }
    };
    model.elements.push(Element {
        id: rec.id,
        kind,
        nodes: nodes.to_vec(),
        property: Some(property),
        orientation: Some(orientation),
    });
    model.element_sources.push((rec.id, 0, rec.line as u32));
    Ok(model.elements.len() - 1)
}

/// The build's note when the model has ANSYS beams: how they are formed and where their
/// section constants come from.
pub(super) fn note(model: &Model) -> Option<String> {
    let beams = [
        ElementKind::Beam2Linear,
        ElementKind::Beam3Quadratic,
        ElementKind::Beam4Cubic,
    ];
    (model.elements.iter())
        .any(|e| beams.contains(&e.kind))
        .then(|| {
            "ANSYS archive: BEAM188 (KEYOPT(3)=0, 2 and 3) and BEAM189 formed as the Theory \
         Reference states them (linear functions and one-point stiffness, quadratic \
         functions and two-point stiffness, or cubic functions and three-point stiffness — \
         BEAM188 KEYOPT(3)=2 on its internal node, made at the middle of IJ and numbered \
         after the archive's largest node id, as ANSYS numbers it; KEYOPT(3)=3 on two, made \
         at 1/3 and 2/3 of IJ and numbered likewise, the one at 1/3 first; consistent mass \
         with rotary inertia; BEAM188's lumped mass on the translations only); RECT, CSOLID \
         and CTUBE constants in \
         closed form (A and I exact, J exact for circles and by Saint-Venant's series \
         for rectangles, Cowper's shear factors) where ANSYS computes J and the shear \
         factors on its own section mesh: they may differ from ANSYS's by a few per \
         cent (docs/ansys.md)"
                .into()
        })
}

/// Why `LUMPM,ON` is refused: a BEAM189 or BEAM188 KEYOPT(3)=2 or 3 in the model, whose lumped
/// mass ANSYS's documents do not establish (the Theory Reference names the points, not how the
/// quadratic and cubic functions' mass is made diagonal).
pub(super) fn lumped_refusal(model: &Model) -> Option<&'static str> {
    let higher = [ElementKind::Beam3Quadratic, ElementKind::Beam4Cubic];
    (model.elements.iter())
        .any(|e| higher.contains(&e.kind))
        .then_some(
            "LUMPM,ON with BEAM189 or BEAM188 KEYOPT(3)=2 or 3: ANSYS's lumped mass of the \
             quadratic and cubic beams is not established here (their consistent mass is \
             formed)",
        )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Saint-Venant's table (Timoshenko & Goodier §109): J = β a c³ with β = 0.141 (square),
    /// 0.229 (a = 2c), 0.263 (a = 3c), 1/3 (a/c → ∞).
    #[test]
    fn rectangle_torsion_matches_the_published_table() {
        for (ratio, beta, tol) in [(1.0, 0.1406, 1e-4), (2.0, 0.229, 1e-3), (3.0, 0.263, 1e-3)] {
            let j = rectangle_torsion(ratio, 1.0);
            assert!((j / ratio - beta).abs() < tol, "{ratio}: {}", j / ratio);
        }
        let thin = rectangle_torsion(1000.0, 1.0) / 1000.0;
        assert!((thin - (1.0 / 3.0 - 0.21 / 1000.0)).abs() < 1e-5, "{thin}");
    }
}
