//! Property and material cards — PSOLID, PSHELL, PCOMP, PROD, PBAR, PBARL, PBEAM, PBEAML,
//! MAT1 — and their resolution (one property id space, WTMASS on non-structural mass).
//!
//! * `MAT1 MID E G NU RHO`: two of E, G, ν give the third, G = E / (2(1+ν)).
//! * `PROD PID MID A J C NSM`; `PBAR PID MID A I1 I2 J NSM … K1 K2 I12`;
//!   `PBEAM PID MID A I1 I2 I12 J NSM` (end A; K1, K2 after the stations);
//!   `PBARL/PBEAML PID MID GROUP TYPE / DIM1 … NSM` (MSC QRG "PBARL").
//! * `PSOLID PID MID CORDM IN STRESS ISOP FCTN`: ISOP blank means MSC's CHEXA/CPENTA with
//!   bubble functions, FULL (or 2) full integration.

use super::bulk::Bulk;
use super::elements::unique_ids;
use super::fields::C;
use super::lex::Card;
use crate::import::error::ImportError;
use crate::import::text::{IdMap, Loc};
use crate::model::{BeamSection, ImportWarning, Material, Property, Section, SectionShape};

/// The raw records of the property and material cards.
#[derive(Default)]
pub(super) struct PropertyCards<'a> {
    /// (PID, MID, section with external material ids, card).
    pub props: Vec<(u64, u64, Section, &'a Card)>,
    /// Property cards of the other element families (dampers, springs, masses, bushes): they
    /// share the property id space; a structural element may not name them.
    pub others: Vec<(u64, &'a Card)>,
    /// (MID, material, card).
    pub mats: Vec<(u64, Material, &'a Card)>,
    /// PBARL/PBEAML whose shape has no Nastran shear factors here, for one warning.
    pub shear_rigid: Vec<String>,
    /// PSOLID ISOP: (FULL, other) property ids with their `file:line` — MSC's CHEXA/CPENTA
    /// default has bubble modes.
    pub isop: (Vec<String>, Vec<String>),
}

/// Reader of PSOLID, PSHELL, PROD, PBAR, PBARL, PBEAM, PBEAML.
pub(super) fn property<'a>(d: &mut Bulk<'a>, g: &C<'a>) -> Result<(), ImportError> {
    let name = g.card.name.as_str();
    let p = &mut d.properties;
    let pid = g.id(0, "PID")?;
    if name == "PSOLID" {
        let at = format!("{pid} ({}:{})", g.file, g.card.loc.line);
        match g.text(5).to_ascii_uppercase().as_str() {
            "FULL" | "2" => p.isop.0.push(at),
            _ => p.isop.1.push(at),
        }
    }
    let (mid, section) = match name {
        "PSHELL" => super::shell::pshell(g)?,
        _ => (g.id(1, "MID")?, section(g)?),
    };
    if let (true, Section::Beam(bs)) = (matches!(name, "PBARL" | "PBEAML"), &section) {
        if bs.shear_factors.is_none() {
            p.shear_rigid.push(format!(
                "{name} {pid} TYPE {} ({}:{})",
                g.text(3),
                g.file,
                g.card.loc.line
            ));
        }
    }
    p.props.push((pid, mid, section, g.card));
    Ok(())
}

/// Reader of PCOMP (one isotropic material, see `shell`).
pub(super) fn pcomp<'a>(d: &mut Bulk<'a>, g: &C<'a>) -> Result<(), ImportError> {
    let pid = g.id(0, "PID")?;
    let (mid, section) = super::shell::pcomp(g)?;
    d.properties.props.push((pid, mid, section, g.card));
    Ok(())
}

/// Reader of the damper properties PDAMP, PDAMP5, PDAMPT, PVISC: their id is kept (one
/// property id space); damping is a note.
pub(super) fn damper<'a>(d: &mut Bulk<'a>, g: &C<'a>) -> Result<(), ImportError> {
    let pid = g.id(0, "PID")?;
    d.properties.others.push((pid, g.card));
    d.note(g, super::cards::DAMPING);
    Ok(())
}

/// Reader of MAT1.
pub(super) fn mat1<'a>(d: &mut Bulk<'a>, g: &C<'a>) -> Result<(), ImportError> {
    let mid = g.id(0, "MID")?;
    let (e, gg, nu) = (g.real(1)?, g.real(2)?, g.real(3)?);
    // Two of E, G, ν given → the third from G = E / (2(1+ν)).
    let (e, gg, nu) = match (e, gg, nu) {
        (Some(e), Some(gg), Some(nu)) => (e, gg, nu),
        (Some(e), None, Some(nu)) => (e, e / (2.0 * (1.0 + nu)), nu),
        (Some(e), Some(gg), None) => (e, gg, e / (2.0 * gg) - 1.0),
        (None, Some(gg), Some(nu)) => (2.0 * (1.0 + nu) * gg, gg, nu),
        _ => return Err(g.err_card("MAT1 needs two of E, G, NU")),
    };
    let m = Material {
        id: mid,
        name: format!("MAT1 {mid}"),
        e,
        nu,
        g: gg,
        rho: g.real_or(4, 0.0)?,
    };
    d.properties.mats.push((mid, m, g.card));
    Ok(())
}

/// Materials and properties into the model (WTMASS on densities and non-structural masses);
/// returns the property and material id maps.
pub(super) fn resolve(d: &mut Bulk) -> Result<(IdMap, IdMap), ImportError> {
    let (files, wtmass) = (d.files, d.solution.wtmass);
    let p = &d.properties;
    // Only MAT1 is read; other MATi cards may legally share a MAT1 id (e.g. MAT4 holds the
    // thermal data of the same material), so only MAT1 ids must be unique.
    let mat_ids: Vec<(u64, &str, Loc)> = p.mats.iter().map(|m| (m.0, "MAT1", m.2.loc)).collect();
    unique_ids(&mat_ids, files, "material id", "MAT1 ids must be unique")?;
    let mids = IdMap::build(p.mats.iter().map(|m| m.0))
        .map_err(|(_, k)| C::new(p.mats[k].2, files).err_card("duplicate material id"))?;
    let model = &mut d.b.model;
    model.materials = p.mats.iter().map(|m| m.1.clone()).collect();
    model.material_sources = (p.mats.iter())
        .map(|m| (m.2.loc.file, m.2.loc.line))
        .collect();
    for m in &mut model.materials {
        m.rho *= wtmass;
    }
    // Supported and unsupported property types share one id space.
    let prop_ids: Vec<(u64, &str, Loc)> = (p.props.iter().map(|p| (p.0, p.3)))
        .chain(p.others.iter().copied())
        .map(|(id, c)| (id, c.name.as_str(), c.loc))
        .collect();
    unique_ids(
        &prop_ids,
        files,
        "property id",
        "all property cards share one id space",
    )?;
    let pids = IdMap::build(p.props.iter().map(|p| p.0))
        .map_err(|(_, k)| C::new(p.props[k].3, files).err_card("duplicate property id"))?;
    for (pid, mid, section, card) in &p.props {
        let g = C::new(card, files);
        let material = mids
            .get(*mid)
            .ok_or_else(|| g.err(1, format!("references unknown material {mid}")))?;
        let mut section = section.clone();
        match &mut section {
            Section::Beam(s) => s.nsm *= wtmass,
            Section::Rod { nsm, .. } => *nsm *= wtmass,
            Section::Shell(s) => {
                s.nsm *= wtmass;
                super::shell::resolve_mids(s, &mids, &g)?;
            }
            _ => {}
        }
        model.properties.push(Property {
            id: *pid,
            name: format!("{} {pid}", card.name),
            material,
            section,
        });
    }
    Ok((pids, mids))
}

/// The findings about properties: shapes without Nastran's shear factors, mixed PSOLID ISOP.
pub(super) fn warnings(d: &mut Bulk) {
    let p = &d.properties;
    let model = &mut d.b.model;
    if !p.shear_rigid.is_empty() {
        model.warnings.push(ImportWarning {
            file: d.files[0].clone(),
            message: format!(
                "{}: the shear factors Nastran derives for these cross-section shapes are not implemented here (only ROD's 0.9): shear-rigid bending, stiffer than Nastran's shear-flexible element",
                p.shear_rigid.join(", ")
            ),
        });
    }
    model.params.solid_bubbles = p.isop.0.is_empty();
    if !p.isop.0.is_empty() && !p.isop.1.is_empty() {
        model.warnings.push(ImportWarning {
            file: d.files[0].clone(),
            message: format!(
                "PSOLID {} ask for full integration (ISOP = FULL), PSOLID {} for MSC's default \
                 bubble functions: one formulation per model is implemented, every CHEXA/CPENTA \
                 is fully integrated (stiffer than MSC Nastran on the others)",
                p.isop.0.join(", "),
                p.isop.1.join(", ")
            ),
        });
    }
}

/// Beam section from the fields holding [A, I1, I2, I12, J, NSM] (blank = 0).
fn beam(g: &C, at: [usize; 6], k: Option<[f64; 2]>) -> Result<Section, ImportError> {
    let mut v = [0.0; 6];
    for (x, &f) in v.iter_mut().zip(&at) {
        *x = g.real_or(f, 0.0)?;
    }
    let [area, i1, i2, i12, j, nsm] = v;
    Ok(Section::Beam(BeamSection {
        area,
        i1,
        i2,
        i12,
        j,
        shear_factors: k,
        nsm,
        shape: None,
    }))
}

/// Standard shape from PBARL/PBEAML TYPE and dimensions (MSC QRG "PBARL"), with dimension count.
fn nastran_shape(ty: &str, d: &[f64]) -> Option<(SectionShape, usize)> {
    Some(match (ty, d) {
        ("ROD", [r, ..]) => (SectionShape::Circle { radius: *r }, 1),
        ("TUBE", [ro, ri, ..]) => (
            SectionShape::Tube {
                outer_radius: *ro,
                inner_radius: *ri,
            },
            2,
        ),
        ("BAR", [w, h, ..]) => (
            SectionShape::Rectangle {
                width: *w,
                height: *h,
            },
            2,
        ),
        // BOX: DIM1 width, DIM2 height, DIM3 top/bottom wall, DIM4 side walls.
        ("BOX", [w, h, t1, t2, ..]) => (
            SectionShape::Box {
                width: *w,
                height: *h,
                t_web: *t2,
                t_flange: *t1,
            },
            4,
        ),
        ("I", [h, wb, wt, tw, tb, tt, ..]) => (
            SectionShape::I {
                height: *h,
                width_bottom: *wb,
                width_top: *wt,
                t_web: *tw,
                t_bottom: *tb,
                t_top: *tt,
            },
            6,
        ),
        _ => return None,
    })
}

/// The section of a PSOLID, PROD, PBAR, PBEAM, PBARL or PBEAML card.
fn section(g: &C) -> Result<Section, ImportError> {
    Ok(match g.card.name.as_str() {
        "PSOLID" => Section::Solid,
        "PROD" => Section::Rod {
            area: g.real_or(2, 0.0)?,
            j: g.real_or(3, 0.0)?,
            nsm: g.real_or(5, 0.0)?,
        },
        "PBAR" => {
            let k = match (g.real(16)?, g.real(17)?) {
                (None, None) => None,
                (k1, k2) => Some([k1.unwrap_or(0.0), k2.unwrap_or(0.0)]),
            };
            beam(g, [2, 3, 4, 18, 5, 6], k)?
        }
        "PBEAM" => {
            // End A values; skip the stress-point line and any intermediate/end-B stations.
            let mut k = 8;
            let so = |k: usize| {
                matches!(
                    g.text(k).to_ascii_uppercase().as_str(),
                    "YES" | "YESA" | "NO"
                )
            };
            if !so(k) && g.card.fields.len() > k {
                k += 8;
            }
            while so(k) {
                k += 16;
            }
            // Nastran PBEAM: K1, K2 default 1.0 (shear flexible); 0.0 means shear-rigid.
            let kf = Some([g.real(k)?.unwrap_or(1.0), g.real(k + 1)?.unwrap_or(1.0)]);
            beam(g, [2, 3, 4, 5, 6, 7], kf)?
        }
        _ => {
            // PBARL / PBEAML: TYPE in field 5, dimensions from the first continuation.
            let ty = g.text(3).to_ascii_uppercase();
            let mut d = Vec::new();
            for k in 8..g.card.fields.len().min(8 + 7) {
                match g.real(k)? {
                    Some(v) => d.push(v),
                    None => break,
                }
            }
            let (shape, n) = nastran_shape(&ty, &d).ok_or_else(|| {
                g.err(3, format!("cross-section TYPE {ty} with {} dimensions not supported (ROD, TUBE, BAR, BOX, I)", d.len()))
            })?;
            let nsm = d.get(n).copied().unwrap_or(0.0);
            let mut s = shape
                .to_section()
                .ok_or_else(|| g.err(3, "unsupported shape"))?;
            s.nsm = nsm;
            // The shear factors Nastran derives for the shape (its equivalent PBAR/PBEAM).
            s.shear_factors = shape.nastran_shear_factors();
            Section::Beam(s)
        }
    })
}
