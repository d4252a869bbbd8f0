//! Shells of an archive: shell sections (`SECTYPE,id,SHELL` with its `SECDATA`, `SECOFFSET`,
//! `SECCONTROL` lines) and SHELL181, formed as ANSYS forms it for KEYOPT(3)=2 (full
//! integration with incompatible modes: flexbody's MITC4 + QM6 quadrilateral with ANSYS's
//! transverse shear factor and drilling penalty, `fe::elements::shell::Quad4Form`), or refused
//! by line naming the KEYOPT, the section line or the shape whose form is not shown.
//!
//! What was shown, and how: docs/ansys.md ("Shells").

use std::collections::BTreeMap;

use super::blocks::{Command, ElementRecord};
use crate::import::error::ImportError;
use crate::model::{
    Element, ElementKind, Model, Property, Section, ShellSection as ModelShellSection,
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
}

/// One layer of a shell section (`SECDATA,TK,MAT,THETA,NUMPT`).
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Layer {
    pub line: usize,
    pub thickness: f64,
    /// The layer's material number; 0: the element's `MAT`.
    pub material: i64,
}

/// A SHELL181 as the model receives it: the 4 node ids and its homogeneous section.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Shell {
    pub nodes: Vec<u64>,
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

    /// `SECOFFSET,MID` is the default; TOP, BOT and USER offsets are refused (SHELL181's offset
    /// form is not shown against an ANSYS result here).
    pub fn secoffset(c: &Command) -> Option<String> {
        let location = c.field(0).trim().to_ascii_uppercase();
        (!(location.is_empty() || location == "MID")).then(|| {
            format!(
                "SECOFFSET,{location}: a shell offset from the mid-surface is not formed here \
                 (only MID)"
            )
        })
    }

    /// `SECCONTROL,E11,E22,E12,ADDMAS,MSCALE,BSCALE,DRLSTF` of a shell section: the added mass
    /// per area is read; user transverse shear stiffnesses and a drill stiffness factor other
    /// than 1 are refused; the hourglass factors MSCALE, BSCALE do not enter KEYOPT(3)=2.
    pub fn seccontrol(&mut self, file: &str, c: &Command) -> Result<Option<String>, ImportError> {
        let value = |k: usize| c.real(file, k);
        self.added_mass = value(3)?;
        let shear = [value(0)?, value(1)?, value(2)?];
        if shear.iter().any(|&v| v != 0.0) {
            return Ok(Some(
                "SECCONTROL: user transverse shear stiffnesses E11, E22, E12 are not read".into(),
            ));
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
/// option KEYOPT(1)=1, other KEYOPTs but KEYOPT(8) (what the result file stores), the
/// degenerate triangle.
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
    if (1..4).any(|i| nodes[..i].contains(&nodes[i])) {
        return Err(
            "SHELL181 with repeated nodes (the degenerate triangle): ANSYS's triangular \
                    form is not shown here"
                .into(),
        );
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
        thickness,
        material,
        added_mass,
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

/// Shell properties made so far: (material number, thickness bits, added mass bits) → index.
pub(super) type ShellProperties = BTreeMap<(i64, u64, u64), usize>;

/// The property of `shell` (one per material, thickness and added mass): a homogeneous shell
/// section of the material (membrane, bending, 5/6 transverse shear) with the added mass as
/// non-structural mass; `None` when the material has no MPDATA.
fn shell_property(
    model: &mut Model,
    made: &mut ShellProperties,
    property_of: &BTreeMap<i64, usize>,
    shell: &Shell,
) -> Option<usize> {
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
        name: format!("SHELL181 MAT{} t={}", shell.material, shell.thickness),
        material,
        section: Section::Shell(section),
    });
    made.insert(key, model.properties.len() - 1);
    Some(model.properties.len() - 1)
}

/// Adds `shell` (element `id`, on the model's node indices `nodes`) to the model as a 4-node
/// shell of its property: the element's index, or why not (its material has no MPDATA).
pub(super) fn push_shell(
    model: &mut Model,
    made: &mut ShellProperties,
    property_of: &BTreeMap<i64, usize>,
    (id, line): (u64, usize),
    shell: &Shell,
    nodes: Vec<usize>,
) -> Result<usize, String> {
    let Some(property) = shell_property(model, made, property_of, shell) else {
        return Err(format!(
            "SHELL181 of material {}, which has no MPDATA",
            shell.material
        ));
    };
    model.elements.push(Element {
        id,
        kind: ElementKind::Quad4,
        nodes,
        property: Some(property),
        orientation: None,
    });
    model.params.ansys_shell181 = true;
    model.element_sources.push((id, 0, line as u32));
    Ok(model.elements.len() - 1)
}
