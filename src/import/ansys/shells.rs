//! Shells of an archive: shell sections (`SECTYPE,id,SHELL` with its `SECDATA`, `SECOFFSET`,
//! `SECCONTROL` lines), SHELL181, formed as ANSYS forms it for KEYOPT(3)=2 (full integration
//! with incompatible modes: flexbody's MITC4 + QM6 quadrilateral with ANSYS's transverse shear
//! factor and drilling penalty, `fe::elements::shell::Quad4Form`; its degenerate triangle K = L
//! the same element with nodes 3 and 4 at one point), and SHELL281 (the 8-node
//! serendipity shell on 2 × 2 points with the section's offset and user transverse shear,
//! `fe::elements::shell281`), or refused by line naming the KEYOPT, the section line or the
//! shape whose form is not shown.
//!
//! What was shown, and how: docs/ansys.md ("Shells").

use std::collections::BTreeMap;

use super::blocks::{Command, ElementRecord};
use crate::import::error::ImportError;
use crate::model::geometry::{cross, norm, sub};
use crate::model::shell_offset::{offset_shells_and_flat_quad8, ShellOffset};
use crate::model::{
    AnsysShell281, Element, ElementKind, Model, Property, Section,
    ShellSection as ModelShellSection,
};

/// A `SECTYPE,id,SHELL` section: its layers (`SECDATA` lines), offset and added mass.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct ShellSection {
    /// The `SECTYPE` line.
    pub line: usize,
    /// One per `SECDATA` line, bottom to top.
    pub layers: Vec<Layer>,
    /// Added mass per unit area (`SECCONTROL`'s ADDMAS).
    pub added_mass: f64,
    /// `SECOFFSET` TOP or BOT (`None`: MID, the default): its line and whether the nodes are
    /// on the top surface.
    pub offset: Option<(usize, Offset)>,
    /// `SECCONTROL`'s user transverse shear stiffnesses E11, E22, E12 and its line.
    pub shear: Option<(usize, [f64; 3])>,
}

/// Where a shell section's nodes are (`SECOFFSET`'s location).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Offset {
    /// The nodes on the top surface: the mid-surface t/2 below them (along −N).
    Top,
    /// The nodes on the bottom surface: the mid-surface t/2 above them (along N).
    Bot,
}

/// One layer of a shell section (`SECDATA,TK,MAT,THETA,NUMPT`).
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Layer {
    pub line: usize,
    pub thickness: f64,
    /// The layer's material number; 0: the element's `MAT`.
    pub material: i64,
}

/// A SHELL181 or SHELL281 as the model receives it: the node ids and its homogeneous section.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Shell {
    /// SHELL181's 4 node ids or SHELL281's 8.
    pub nodes: Vec<u64>,
    /// SHELL281's user transverse shear (`None`: a SHELL181).
    pub shell281: Option<AnsysShell281>,
    /// Distance from the nodes to the mid-surface along the element normal (SHELL281's TOP:
    /// −t/2, BOT: +t/2; else 0).
    pub offset: f64,
    pub thickness: f64,
    /// The material number (the section's, else the element's `MAT`).
    pub material: i64,
    /// Added mass per unit area.
    pub added_mass: f64,
}

impl ShellSection {
    /// A new section opened by `SECTYPE,id,SHELL[,subtype]`; a subtype (a FiberSIM or
    /// preintegrated section) is refused (the reason).
    pub fn open(c: &Command) -> (ShellSection, Option<String>) {
        let refusal = (!c.field(2).is_empty()).then(|| {
            format!(
                "SECTYPE {},SHELL,{}: a shell section subtype is not read (a plain SHELL section \
                 of SECDATA layers is)",
                c.field(0),
                c.field(2)
            )
        });
        let s = ShellSection {
            line: c.line,
            layers: Vec::new(),
            added_mass: 0.0,
            offset: None,
            shear: None,
        };
        (s, refusal)
    }

    /// `SECDATA,TK,MAT,THETA,NUMPT`: one layer. One integration point through a layer is
    /// refused (ANSYS then has no bending stiffness in the layer: not shown here).
    pub fn secdata(&mut self, file: &str, c: &Command) -> Result<Option<String>, ImportError> {
        let thickness = c.real(file, 0)?;
        let material = c.int(file, 1)?;
        let points = c.int(file, 3)?;
        self.layers.push(Layer {
            line: c.line,
            thickness,
            material,
        });
        Ok(match points {
            0 | 3 | 5 | 7 | 9 => (!(thickness > 0.0 && thickness.is_finite()))
                .then(|| format!("SECDATA: layer thickness {thickness} (not positive)")),
            n => Some(format!(
                "SECDATA: {n} integration point(s) through the layer: only 3, 5, 7 or 9 (Simpson's \
                 rule, exact for a linear material) are read"
            )),
        })
    }

    /// `SECOFFSET,MID` (the default), TOP and BOT are read (SHELL281 forms TOP and BOT, SHELL181
    /// refuses them at its record); USER offsets are refused.
    pub fn secoffset(&mut self, c: &Command) -> Option<String> {
        let location = c.field(0).trim().to_ascii_uppercase();
        match location.as_str() {
            "" | "MID" => self.offset = None,
            "TOP" => self.offset = Some((c.line, Offset::Top)),
            "BOT" => self.offset = Some((c.line, Offset::Bot)),
            _ => {
                return Some(format!(
                    "SECOFFSET,{location}: a user offset of a shell section is not formed here \
                     (MID, TOP and BOT are)"
                ))
            }
        }
        None
    }

    /// `SECCONTROL,E11,E22,E12,ADDMAS,MSCALE,BSCALE,DRLSTF` of a shell section: the added mass
    /// per area and the user transverse shear stiffnesses (SHELL281 forms them, SHELL181 refuses
    /// them at its record) are read; a drill stiffness factor other than 1 is refused; the
    /// hourglass factors MSCALE, BSCALE do not enter SHELL181 KEYOPT(3)=2 nor SHELL281.
    pub fn seccontrol(&mut self, file: &str, c: &Command) -> Result<Option<String>, ImportError> {
        let value = |k: usize| c.real(file, k);
        self.added_mass = value(3)?;
        let shear = [value(0)?, value(1)?, value(2)?];
        self.shear = shear.iter().any(|&v| v != 0.0).then_some((c.line, shear));
        if shear[0] < 0.0 || shear[1] < 0.0 || shear[2] * shear[2] > shear[0] * shear[1] {
            return Ok(Some(format!(
                "SECCONTROL: transverse shear stiffnesses E11 = {}, E22 = {}, E12 = {} are not \
                 positive semi-definite",
                shear[0], shear[1], shear[2]
            )));
        }
        let drill = value(6)?;
        if drill != 0.0 && drill != 1.0 {
            return Ok(Some(format!(
                "SECCONTROL: drill stiffness factor {drill}: only ANSYS's default (1) is formed"
            )));
        }
        Ok((self.added_mass < 0.0).then(|| {
            format!(
                "SECCONTROL: added mass per area {} is negative",
                self.added_mass
            )
        }))
    }

    /// The section as one homogeneous layer: several layers of one material are that material
    /// over their summed thickness (each layer integrated exactly: the same stiffness and mass);
    /// layers of different materials (a laminate) are refused.
    fn homogeneous(&self, element_mat: i64) -> Result<(f64, i64), String> {
        let material = |l: &Layer| {
            if l.material > 0 {
                l.material
            } else {
                element_mat
            }
        };
        let Some(first) = self.layers.first() else {
            return Err(format!(
                "shell section of SECTYPE line {} has no SECDATA layer",
                self.line
            ));
        };
        if let Some(other) = self.layers.iter().find(|l| material(l) != material(first)) {
            return Err(format!(
                "shell section of SECTYPE line {}: layers of different materials (SECDATA lines \
                 {} and {}): a laminate's form in SHELL181 is not shown here",
                self.line, first.line, other.line
            ));
        }
        Ok((
            self.layers.iter().map(|l| l.thickness).sum(),
            material(first),
        ))
    }
}

/// SHELL181 (MAPDL Theory Reference §13.181; docs/ansys.md): KEYOPT(3)=2 formed, on a shell
/// section or on the legacy real constants TK(I)…TK(L) of one thickness; refused by line:
/// KEYOPT(3)=0 (the default, uniform reduced integration with hourglass control), the membrane
/// option KEYOPT(1)=1, other KEYOPTs but KEYOPT(8) (what the result file stores), repeated
/// nodes other than the degenerate triangle K = L (formed: the quadrilateral with nodes 3 and 4
/// at one point, as ANSYS's strain and kinetic energies show it).
pub(super) fn shell181(
    keyopts: &BTreeMap<u32, i64>,
    rec: &ElementRecord,
    reals: Option<&[f64]>,
    section: Option<&ShellSection>,
) -> Result<Shell, String> {
    let keyopt = |k: u32| keyopts.get(&k).copied().unwrap_or(0);
    match keyopt(3) {
        2 => {}
        0 => {
            return Err(
                "SHELL181 KEYOPT(3)=0 (the default: uniform reduced integration with \
                        ANSYS's hourglass control): its hourglass stiffness is not shown against \
                        an ANSYS result here; KEYOPT(3)=2 (full integration) is formed"
                    .into(),
            )
        }
        k => {
            return Err(format!(
                "SHELL181 KEYOPT(3)={k}: not a SHELL181 option formed here"
            ))
        }
    }
    if keyopt(1) != 0 {
        return Err(format!(
            "SHELL181 KEYOPT(1)={}: the membrane-only shell is not formed here",
            keyopt(1)
        ));
    }
    if let Some((k, v)) = keyopts.iter().find(|(k, _)| ![3, 8].contains(*k)) {
        return Err(format!(
            "SHELL181 KEYOPT({k})={v}: this option's formulation is not formed here"
        ));
    }
    let nodes: Vec<u64> = rec.nodes.iter().take(4).copied().collect();
    if nodes.len() != 4 || nodes.contains(&0) {
        return Err(format!(
            "SHELL181 with {} nodes (I, J, K, L expected)",
            nodes.len()
        ));
    }
    // ANSYS's degenerate triangle (K = L) is the quadrilateral with its nodes 3 and 4 at one
    // point, as ANSYS forms it (its strain and kinetic energies, docs/ansys.md); other
    // repeated nodes are not ANSYS's triangle.
    let distinct = |k: usize| !nodes[..k].contains(&nodes[k]);
    if !(distinct(1) && distinct(2) && (distinct(3) || nodes[2] == nodes[3])) {
        return Err(format!(
            "SHELL181 with repeated nodes {nodes:?} other than ANSYS's degenerate triangle \
             (K = L with I, J, K distinct): that shape is not formed here"
        ));
    }
    if let Some(s) = section {
        if let Some((line, o)) = s.offset {
            return Err(format!(
                "SHELL181 on a section offset to its {} surface (SECOFFSET line {line}): \
                 SHELL181's offset form is not shown against an ANSYS result here (SHELL281's is)",
                if o == Offset::Top { "top" } else { "bottom" }
            ));
        }
        if let Some((line, _)) = s.shear {
            return Err(format!(
                "SHELL181 on a section with user transverse shear stiffnesses (SECCONTROL line \
                 {line}): not formed for SHELL181 (SHELL281 forms them)"
            ));
        }
    }
    let (thickness, material, added_mass) = match (section, reals) {
        (Some(s), _) => {
            let (t, m) = s.homogeneous(rec.mat)?;
            (t, m, s.added_mass)
        }
        (None, Some(r)) => (legacy_thickness(r)?, rec.mat, 0.0),
        (None, None) => {
            return Err(format!(
                "SHELL181 without a shell section (SECNUM {}) or real constant set (REAL {}): no \
                 thickness",
                rec.section, rec.real
            ))
        }
    };
    Ok(Shell {
        nodes,
        shell281: None,
        offset: 0.0,
        thickness,
        material,
        added_mass,
    })
}

/// SHELL281 (MAPDL Theory Reference §13.281; docs/ansys.md): the 8-node shell on a homogeneous
/// shell section, its offset (MID, TOP, BOT) and user transverse shear; refused by line: the
/// membrane option KEYOPT(1)=1, other KEYOPTs but KEYOPT(8) (what the result file stores), the
/// triangle (K = L = O) and other repeated nodes, a record without a shell section.
pub(super) fn shell281(
    keyopts: &BTreeMap<u32, i64>,
    rec: &ElementRecord,
    section: Option<&ShellSection>,
) -> Result<Shell, String> {
    if let Some((k, v)) = keyopts.iter().find(|(k, v)| **k != 8 && **v != 0) {
        return Err(format!(
            "SHELL281 KEYOPT({k})={v}: {}",
            if *k == 1 {
                "the membrane-only shell is not formed here"
            } else {
                "this option's formulation is not formed here"
            }
        ));
    }
    let nodes: Vec<u64> = rec.nodes.iter().take(8).copied().collect();
    if nodes.len() != 8 || nodes.contains(&0) {
        return Err(format!(
            "SHELL281 with {} nodes (I, J, K, L, M, N, O, P expected: mid-side nodes may not be \
             dropped)",
            nodes.iter().filter(|&&n| n != 0).count()
        ));
    }
    if (1..8).any(|i| nodes[..i].contains(&nodes[i])) {
        return Err(
            "SHELL281 with repeated nodes (the triangle K = L = O): ANSYS's 6-node triangle is \
             not formed here"
                .into(),
        );
    }
    let Some(s) = section else {
        return Err(format!(
            "SHELL281 without a shell section (SECNUM {}): no thickness",
            rec.section
        ));
    };
    let (thickness, material) = s.homogeneous(rec.mat)?;
    let offset = match s.offset {
        None => 0.0,
        Some((_, Offset::Bot)) => 0.5 * thickness,
        Some((_, Offset::Top)) => -0.5 * thickness,
    };
    Ok(Shell {
        nodes,
        shell281: Some(AnsysShell281 {
            shear: s.shear.map(|(_, e)| e),
        }),
        offset,
        thickness,
        material,
        added_mass: s.added_mass,
    })
}

/// The legacy real constants TK(I), TK(J), TK(K), TK(L) (0: as TK(I)) of one thickness; nodal
/// thicknesses that differ and any further real constant are refused.
fn legacy_thickness(reals: &[f64]) -> Result<f64, String> {
    let tk = reals.first().copied().unwrap_or(0.0);
    if !(tk > 0.0 && tk.is_finite()) {
        return Err(format!(
            "SHELL181 real constant TK(I) = {tk} (not a positive thickness)"
        ));
    }
    if reals.iter().take(4).any(|&v| v != 0.0 && v != tk) {
        return Err(
            "SHELL181 real constants TK(I)…TK(L) differ: a tapered shell is not formed here".into(),
        );
    }
    if let Some(v) = reals.iter().skip(4).find(|v| **v != 0.0) {
        return Err(format!("SHELL181 real constant {v} past TK(L): not read"));
    }
    Ok(tk)
}

/// Shell properties made so far ((material number, thickness bits, added mass bits) → index)
/// and the offset SHELL281s waiting for their rigid offsets.
pub(super) struct ShellProperties {
    made: BTreeMap<(i64, u64, u64), usize>,
    /// (element index, offset, EBLOCK line, element type)
    offsets: Vec<(usize, f64, usize, i64)>,
    /// EBLOCK lines of SHELL181s smaller than [`DRILL_SHOWN_AREA`] t² (their drilling
    /// stiffness is not ANSYS's: docs/ansys.md)
    drill_unshown: Vec<usize>,
}

/// Area, in thicknesses squared, above which flexbody's SHELL181 drilling penalty was shown to
/// be ANSYS's (ANSYS's artificial energy AENE: 1.0010 of it at A ≈ 100 t², the box's element
/// forces at A ≈ 1800–2100 t²); at A ≈ 0.3–1.5 t² ANSYS's is 4–14 times larger on
/// quadrilaterals, up to 27 on triangles (docs/ansys.md).
const DRILL_SHOWN_AREA: f64 = 100.0;

impl ShellProperties {
    pub fn new() -> ShellProperties {
        ShellProperties {
            made: BTreeMap::new(),
            offsets: Vec::new(),
            drill_unshown: Vec::new(),
        }
    }

    /// The warning for SHELL181s smaller than [`DRILL_SHOWN_AREA`] t², if any.
    pub fn drill_warning(&self, file: &str) -> Option<crate::model::ImportWarning> {
        let lines = &self.drill_unshown;
        let first = lines.iter().min()?;
        Some(crate::model::ImportWarning {
            file: file.to_string(),
            message: format!(
                "{} SHELL181 element(s) smaller in area than {DRILL_SHOWN_AREA} times their \
                 thickness squared (the first at line {first}): their drilling stiffness is \
                 flexbody's rule (s k G t/200), shown to be ANSYS's only for larger elements — \
                 ANSYS's is 4–27 times stiffer at areas of 0.3–1.5 t² (docs/ansys.md); bending \
                 modes agree with ANSYS's, a mode that turns shell nodes about their normal \
                 (in-plane rotation at a point support, a beam or rigid link on the drilling \
                 rotation) does not",
                lines.len()
            ),
        })
    }

    /// Moves the offset SHELL281s onto nodes at their mid-surfaces joined rigidly to theirs
    /// (`model::shell_offset`, as Nastran's ZOFFS): ANSYS's element forces of an offset section
    /// are those of the mid-surface element under that rigid link (docs/ansys.md). A curved
    /// (non-flat) offset element is refused: its offset along one normal is not ANSYS's. The
    /// refusals: (line, (element type, why)).
    pub fn apply_offsets(self, model: &mut Model) -> Vec<(usize, (i64, String))> {
        let mut refused = Vec::new();
        let mut offsets = Vec::new();
        let mut lines = Vec::new();
        for &(elem, zoffs, line, etype) in &self.offsets {
            let x: Vec<[f64; 3]> = (model.elements[elem].nodes.iter())
                .map(|&n| model.nodes[n].x)
                .collect();
            match out_of_plane(&x) {
                Some(d) => refused.push((
                    line,
                    (
                        etype,
                        format!(
                            "SHELL281 on an offset section (TOP or BOT) is formed flat only: this \
                             element's nodes lie up to {d:.3e} of its size off one plane"
                        ),
                    ),
                )),
                None => {
                    offsets.push(ShellOffset { elem, zoffs });
                    lines.push((line, etype));
                }
            }
        }
        if let Err((at, why)) = offset_shells_and_flat_quad8(model, &offsets) {
            refused.push((lines[at].0, (lines[at].1, why)));
        }
        refused
    }
}

/// How far the nodes `x` of an 8-node shell lie off the plane of its corners' diagonals, over
/// its size, when more than 1e-9 (`None`: flat).
fn out_of_plane(x: &[[f64; 3]]) -> Option<f64> {
    use crate::model::geometry::{cross, dot, norm, sub};
    let n = cross(sub(x[2], x[0]), sub(x[3], x[1]));
    let size = (x.iter())
        .flat_map(|a| x.iter().map(move |b| norm(sub(*a, *b))))
        .fold(0.0, f64::max);
    let d = (x.iter())
        .map(|p| dot(sub(*p, x[0]), n).abs() / norm(n))
        .fold(0.0, f64::max)
        / size;
    (d > 1e-9 || d.is_nan()).then_some(d)
}

/// The property of `shell` (one per material, thickness and added mass): a homogeneous shell
/// section of the material (membrane, bending, 5/6 transverse shear) with the added mass as
/// non-structural mass; `None` when the material has no MPDATA.
fn shell_property(
    model: &mut Model,
    made: &mut ShellProperties,
    property_of: &BTreeMap<i64, usize>,
    shell: &Shell,
) -> Option<usize> {
    let made = &mut made.made;
    let key = (
        shell.material,
        shell.thickness.to_bits(),
        shell.added_mass.to_bits(),
    );
    if let Some(&p) = made.get(&key) {
        return Some(p);
    }
    let material = model.properties[*property_of.get(&shell.material)?].material;
    let mut section = ModelShellSection::homogeneous(shell.thickness, material);
    section.nsm = shell.added_mass;
    model.properties.push(Property {
        id: (model.properties.len() + 1) as u64,
        name: format!("SHELL MAT{} t={}", shell.material, shell.thickness),
        material,
        section: Section::Shell(section),
    });
    made.insert(key, model.properties.len() - 1);
    Some(model.properties.len() - 1)
}

/// Adds `shell` (element `id`, on the model's node indices `nodes`) to the model as a 4-node
/// shell (SHELL181) or an 8-node one (SHELL281, with its entry in `Model::ansys_shell281`) of
/// its property: the element's index, or why not (its material has no MPDATA).
pub(super) fn push_shell(
    model: &mut Model,
    made: &mut ShellProperties,
    property_of: &BTreeMap<i64, usize>,
    (id, line, etype): (u64, usize, i64),
    shell: &Shell,
    nodes: Vec<usize>,
) -> Result<usize, String> {
    let Some(property) = shell_property(model, made, property_of, shell) else {
        return Err(format!(
            "{} of material {}, which has no MPDATA",
            if shell.shell281.is_some() {
                "SHELL281"
            } else {
                "SHELL181"
            },
            shell.material
        ));
    };
    let kind = match shell.shell281 {
        Some(sec) => {
            model.ansys_shell281.insert(model.elements.len(), sec);
            if shell.offset != 0.0 {
                (made.offsets).push((model.elements.len(), shell.offset, line, etype));
            }
            ElementKind::Quad8
        }
        None => {
            model.params.ansys_shell181 = true;
            let x = |a: usize| model.nodes[nodes[a]].x;
            let (d1, d2) = (sub(x(2), x(0)), sub(x(3), x(1)));
            let twice_area = norm(cross(d1, d2));
            if 0.5 * twice_area < DRILL_SHOWN_AREA * shell.thickness * shell.thickness {
                made.drill_unshown.push(line);
            }
            ElementKind::Quad4
        }
    };
    model.elements.push(Element {
        id,
        kind,
        nodes,
        property: Some(property),
        orientation: None,
    });
    model.element_sources.push((id, 0, line as u32));
    Ok(model.elements.len() - 1)
}

/// Why `LUMPM,ON` is refused: a SHELL281 in the model, whose lumped mass ANSYS's documents do not
/// establish.
pub(super) fn lumped_refusal(model: &Model) -> Option<&'static str> {
    (!model.ansys_shell281.is_empty()).then_some(
        "LUMPM,ON with SHELL281: ANSYS's lumped mass of the 8-node shell is not established here \
         (its consistent mass on the 2 × 2 points is formed)",
    )
}
