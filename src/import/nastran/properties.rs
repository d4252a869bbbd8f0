//! Property and material cards — PSOLID, PSHELL, PCOMP, PROD, PTUBE, PBAR, PBARL, PBEAM, PBEAML,
//! MAT1, MAT2, MAT8, MAT9 — and their resolution (one property id space, WTMASS on non-structural mass).
//!
//! * `MAT1 MID E G NU RHO`: two of E, G, ν give the third, G = E / (2(1+ν)).
//! * `PROD PID MID A J C NSM`; `PTUBE PID MID OD T NSM OD2` (a rod of the tube's A and J, for
//!   CTUBE as a CROD: [`tube`]); `PBAR PID MID A I1 I2 J NSM … K1 K2 I12`;
//!   `PBEAM PID MID A I1 I2 I12 J NSM` (end A; K1, K2 after the stations);
//!   `PBARL/PBEAML PID MID GROUP TYPE / DIM1 … NSM` (MSC QRG "PBARL").
//! * `PSOLID PID MID CORDM IN STRESS ISOP FCTN`: ISOP blank means MSC's CHEXA/CPENTA with
//!   bubble functions, FULL (or 2) full integration.

use super::elements::unique_ids;
use super::fields::C;
use super::reading::Bulk;
use crate::import::error::ImportError;

use crate::import::text::{IdMap, Loc};
use crate::model::beam_library::{dimension_count, library_section};
use crate::model::{BeamSection, BeamTaper, ImportWarning, Material, Property, Section};

/// Note on the library shapes other than ROD: their J and shear factors are textbook values.
const LIBRARY_CONSTANTS: &str = "A, I1, I2, I12 of the shape exactly; J and the shear factors K1, K2 (Nastran does not publish its own for this shape) by the rules of src/model/beam_library.rs: thin-walled J (Bredt for closed walls), K = web area / A";

/// Reader of PSOLID, PSHELL, PROD, PTUBE, PBAR, PBARL, PBEAM, PBEAML.
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
    if matches!(name, "PBARL" | "PBEAML") && !g.text(3).eq_ignore_ascii_case("ROD") {
        d.note(g, LIBRARY_CONSTANTS);
    }
    let p = &mut d.properties;
    p.props.push((pid, mid, section, g.card));
    Ok(())
}

/// Reader of PCOMP (plies, see `shell`).
pub(super) fn pcomp<'a>(d: &mut Bulk<'a>, g: &C<'a>) -> Result<(), ImportError> {
    let pid = g.id(0, "PID")?;
    let (mid, section, offset) = super::shell::pcomp(g)?;
    if offset != 0.0 {
        d.properties
            .mid_plane_offsets
            .insert(pid, (offset, g.card.loc));
    }
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
        elasticity: crate::model::Elasticity::Isotropic,
    };
    d.properties.mats.push((mid, m, g.card));
    Ok(())
}

/// Reader of MAT8 (MSC QRG): `MID E1 E2 NU12 G12 G1Z G2Z RHO / A1 A2 TREF Xt Xc Yt Yc S / GE
/// F12 STRN`, an orthotropic lamina of shells (Q of
/// [`PlaneStress::lamina`](crate::model::PlaneStress::lamina)); G1Z, G2Z blank: shear-rigid
/// (both or neither). A1, A2, TREF are thermal, Xt…S, F12, STRN failure data, GE damping.
pub(super) fn mat8<'a>(d: &mut Bulk<'a>, g: &C<'a>) -> Result<(), ImportError> {
    let mid = g.id(0, "MID")?;
    let need = |k: usize, what: &str| {
        g.real(k)?
            .ok_or_else(|| g.err(k, format!("{what} is required")))
    };
    let (e1, e2, nu12, g12) = (
        need(1, "E1")?,
        need(2, "E2")?,
        need(3, "NU12")?,
        need(4, "G12")?,
    );
    let gz = match (g.real(5)?, g.real(6)?) {
        (None, None) => None,
        (Some(a), Some(b)) => Some([a, b]),
        _ => {
            return Err(g.err(
                5,
                "give both G1Z and G2Z (transverse shear) or neither (shear-rigid)",
            ))
        }
    };
    let p = crate::model::PlaneStress::lamina(e1, e2, nu12, g12, gz).map_err(|m| g.err_card(m))?;
    let rho = g.real_or(7, 0.0)?;
    d.properties
        .mats
        .push((mid, plane_material(mid, "MAT8", p, rho), g.card));
    Ok(())
}

/// Reader of MAT2 (MSC QRG): `MID G11 G12 G13 G22 G23 G33 RHO / A1 A2 A3 TREF GE ST SC SS /
/// MCSID`, an anisotropic plane-stress material of shells (σ = G ε, engineering shear; as a
/// PSHELL MID3 its G11, G12, G22 are the transverse shear stiffness, G13, G23, G33 blank). G
/// must be positive definite (its 2×2 when G13, G23, G33 are blank); MCSID (its own material
/// axes) is an error.
pub(super) fn mat2<'a>(d: &mut Bulk<'a>, g: &C<'a>) -> Result<(), ImportError> {
    let mid = g.id(0, "MID")?;
    let v: Vec<f64> = (1..=6)
        .map(|k| g.real_or(k, 0.0))
        .collect::<Result<_, _>>()?;
    let q = [[v[0], v[1], v[2]], [v[1], v[3], v[4]], [v[2], v[4], v[5]]];
    // A MID3-only MAT2 leaves G13, G23, G33 blank (MSC QRG MAT2): then its 2×2 must be
    // positive definite, else the 3×3.
    let shear_only = [3, 5, 6].iter().all(|&k| g.text(k).is_empty());
    let d2 = q[0][0] * q[1][1] - q[0][1] * q[0][1];
    let d3 = q[0][0] * (q[1][1] * q[2][2] - q[1][2] * q[1][2])
        - q[0][1] * (q[0][1] * q[2][2] - q[1][2] * q[0][2])
        + q[0][2] * (q[0][1] * q[1][2] - q[1][1] * q[0][2]);
    if !(q[0][0] > 0.0 && d2 > 0.0 && (shear_only || d3 > 0.0)) {
        return Err(g.err_card(format!(
            "the material matrix G = {q:?} is not positive definite"
        )));
    }
    if g.int(16)?.is_some_and(|c| c != 0) {
        return Err(g.err(16, "MCSID (MAT2's own material axes) is not supported"));
    }
    let p = crate::model::PlaneStress {
        q,
        transverse: None,
        as_mid3: Some([[v[0], v[1]], [v[1], v[3]]]),
    };
    let rho = g.real_or(7, 0.0)?;
    d.properties
        .mats
        .push((mid, plane_material(mid, "MAT2", p, rho), g.card));
    Ok(())
}

fn plane_material(mid: u64, card: &str, p: crate::model::PlaneStress, rho: f64) -> Material {
    Material::plane_stress_material(mid, &format!("{card} {mid}"), p, rho)
}

/// Reader of MAT9 (MSC QRG): MID, the 21 Gij of the upper triangle row by row in the order
/// xx yy zz xy yz zx (the model's, [`crate::model::elasticity`]; engineering shear strains),
/// RHO (field 22); A1–A6, TREF act only in a thermal preload (`temperature`), GE is damping.
/// An indefinite or singular D is an error naming the card.
#[allow(clippy::needless_range_loop)] // the upper triangle (i, j) in the card's order
pub(super) fn mat9<'a>(d: &mut Bulk<'a>, g: &C<'a>) -> Result<(), ImportError> {
    let mid = g.id(0, "MID")?;
    let mut dm = [[0.0; 6]; 6];
    let mut k = 1;
    for i in 0..6 {
        for j in i..6 {
            let v = g.real_or(k, 0.0)?;
            dm[i][j] = v;
            dm[j][i] = v;
            k += 1;
        }
    }
    match crate::model::elasticity::check(&dm) {
        Ok(crate::model::elasticity::Definiteness::Positive) => {}
        Ok(crate::model::elasticity::Definiteness::Singular { rank }) => {
            return Err(g.err_card(format!(
                "the material matrix G is singular (rank {rank} of 6): strain states without stress"
            )))
        }
        Err(m) => return Err(g.err_card(m)),
    }
    let rho = g.real_or(22, 0.0)?;
    let m = Material::anisotropic(mid, &format!("MAT9 {mid}"), dm, rho);
    d.properties.mats.push((mid, m, g.card));
    Ok(())
}

/// Material axes of a PSOLID (CORDM, field 3) whose material is anisotropic: blank or 0 the
/// basic axes, a rectangular system its axes; −1 (the element coordinate system) and
/// cylindrical or spherical systems are errors naming the card.
fn psolid_axes(
    g: &C,
    model: &crate::model::Model,
) -> Result<Option<crate::model::MaterialAxes>, ImportError> {
    let cid = g.int(2)?.unwrap_or(0);
    match cid {
        0 => Ok(None),
        c if c < 0 => Err(g.err(
            2,
            "CORDM = -1 (the element coordinate system) with an anisotropic material is not \
             supported: give a rectangular CORDM",
        )),
        c => {
            let cs = (model.coord_systems.iter())
                .find(|cs| cs.id == c as u64)
                .ok_or_else(|| g.err(2, format!("CORDM {c}: no such coordinate system")))?;
            if cs.kind != crate::model::CoordKind::Rectangular {
                return Err(g.err(
                    2,
                    format!(
                        "CORDM {c} is not rectangular: curvilinear material axes of an \
                         anisotropic material are not supported"
                    ),
                ));
            }
            Ok(Some(crate::model::MaterialAxes::Rectangular(cs.axes)))
        }
    }
}

/// Materials and properties into the model (WTMASS on densities and non-structural masses);
/// returns the property and material id maps.
pub(super) fn resolve(d: &mut Bulk) -> Result<(IdMap, IdMap), ImportError> {
    let (files, wtmass) = (d.files, d.solution.wtmass);
    let p = &d.properties;
    // Only MAT1, MAT2, MAT8 and MAT9 are read; other MATi cards may legally share their id
    // (e.g. MAT4 holds the thermal data of the same material), so only theirs must be unique.
    let mat_ids: Vec<(u64, &str, Loc)> = (p.mats.iter())
        .map(|m| (m.0, m.2.name.as_str(), m.2.loc))
        .collect();
    unique_ids(
        &mat_ids,
        files,
        "material id",
        "MAT1, MAT2, MAT8 and MAT9 ids must be unique",
    )?;
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
        if card.name == "PSOLID" && model.materials[material].stiffness().is_some() {
            if let Some(axes) = psolid_axes(&g, model)? {
                model.property_axes.insert(model.properties.len(), axes);
            }
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

/// The findings about properties: mixed PSOLID ISOP.
pub(super) fn warnings(d: &mut Bulk) {
    let p = &d.properties;
    let model = &mut d.b.model;
    model.params.solid_bubbles = p.isop.0.is_empty();
    model.params.nastran_deck = true;
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
        taper: None,
    }))
}

/// PTUBE `PID MID OD T NSM OD2` (MSC QRG "PTUBE"): the rod of a tube of outer diameter D = OD
/// and wall T (blank or 0: a solid rod), A = π/4 (D² − d²), J = π/32 (D⁴ − d⁴) with
/// d = D − 2T (the polar moment, as the QRG states J of the tube); a tapered tube (OD2 ≠ OD)
/// is an error.
fn tube(g: &C) -> Result<Section, ImportError> {
    let od = g.real(2)?.filter(|d| *d > 0.0 && d.is_finite());
    let od = od.ok_or_else(|| g.err(2, "OD must be > 0"))?;
    let t = g.real_or(3, 0.0)?;
    if !(t >= 0.0 && t <= 0.5 * od) {
        return Err(g.err(
            3,
            format!("T = {t}: the wall must be 0 ≤ T ≤ OD/2 = {}", 0.5 * od),
        ));
    }
    if differs(g.real(5)?, od) {
        return Err(g.err(
            5,
            format!(
                "OD2 = {} ≠ OD = {od}: a tapered tube is not implemented",
                g.text(5)
            ),
        ));
    }
    let inner = if t == 0.0 { 0.0 } else { od - 2.0 * t };
    let pi = std::f64::consts::PI;
    Ok(Section::Rod {
        area: pi / 4.0 * (od.powi(2) - inner.powi(2)),
        j: pi / 32.0 * (od.powi(4) - inner.powi(4)),
        nsm: g.real_or(4, 0.0)?,
    })
}

/// The section of a PSOLID, PROD, PTUBE, PBAR, PBEAM, PBARL or PBEAML card.
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
        "PBEAM" => pbeam(g)?,
        "PTUBE" => tube(g)?,
        _ => library_card(g)?,
    })
}

/// Relative difference under which a station's value is end A's (the same number written to
/// fewer digits, e.g. `.0052083` and `.005208`).
const SAME_VALUE: f64 = 1e-4;

/// Whether station value `v` (blank: end A's) differs from end A's `a`.
fn differs(v: Option<f64>, a: f64) -> bool {
    v.is_some_and(|v| (v - a).abs() > SAME_VALUE * a.abs().max(v.abs()))
}

/// PBEAM: end A's A, I1, I2, I12, J, NSM, then per station (intermediate, end B: SO, X/XB,
/// the same six, blank = end A's; the stress-point line follows when SO = YES): a station
/// differing from end A makes the beam tapered (`BeamTaper::Values`, each value linear between
/// stations; I12 must stay 0); K1, K2 (default 1.0, shear flexible; 0.0 shear-rigid). Shear
/// relief S1/S2, non-structural mass inertia NSI and the centre-of-gravity/neutral-axis
/// offsets M1…N2 are errors when nonzero. CW (warping) acts only on the warping scalar points
/// CBEAM SA/SB, which are refused.
fn pbeam(g: &C) -> Result<Section, ImportError> {
    let end_a = [2, 3, 4, 5, 6, 7].map(|f| g.real_or(f, 0.0));
    let mut a = [0.0; 6];
    for (x, v) in a.iter_mut().zip(end_a) {
        *x = v?;
    }
    let so = |k: usize| {
        matches!(
            g.text(k).to_ascii_uppercase().as_str(),
            "YES" | "YESA" | "NO"
        )
    };
    // End A's stress-point line (fields 8–15) unless field 8 already starts a station.
    let mut k = 8;
    if !so(k) && g.card.fields.len() > k {
        k += 8;
    }
    // Stations: SO X/XB A I1 I2 I12 J NSM, then the stress points when SO = YES.
    let mut stations = vec![(0.0, [a[0], a[1], a[2], a[4], a[5]])];
    let mut tapered = false;
    while so(k) {
        let xi = station_position(g, k + 1, stations.last().map_or(0.0, |s| s.0))?;
        let mut v = a;
        for (i, x) in v.iter_mut().enumerate() {
            let r = g.real(k + 2 + i)?;
            if differs(r, a[i]) {
                if i == 3 {
                    return Err(g.err(
                        k + 5,
                        format!(
                            "I12 varying along a tapered PBEAM is not implemented ({} at end A)",
                            a[3]
                        ),
                    ));
                }
                tapered = true;
            }
            *x = r.unwrap_or(a[i]);
        }
        stations.push((xi, [v[0], v[1], v[2], v[4], v[5]]));
        k += if g.text(k).eq_ignore_ascii_case("YES") {
            16
        } else {
            8
        };
    }
    let taper = tapered_stations(g, tapered, a[3], stations)?.map(BeamTaper::Values);
    let kf = Some([g.real(k)?.unwrap_or(1.0), g.real(k + 1)?.unwrap_or(1.0)]);
    const REFUSED: [(usize, &str); 12] = [
        (2, "S1 (shear relief)"),
        (3, "S2 (shear relief)"),
        (4, "NSI(A) (non-structural mass inertia)"),
        (5, "NSI(B) (non-structural mass inertia)"),
        (8, "M1(A) (centre of gravity offset)"),
        (9, "M2(A) (centre of gravity offset)"),
        (10, "M1(B) (centre of gravity offset)"),
        (11, "M2(B) (centre of gravity offset)"),
        (12, "N1(A) (neutral axis offset)"),
        (13, "N2(A) (neutral axis offset)"),
        (14, "N1(B) (neutral axis offset)"),
        (15, "N2(B) (neutral axis offset)"),
    ];
    for (off, name) in REFUSED {
        if let Some(v) = g.real(k + off)?.filter(|v| *v != 0.0) {
            return Err(g.err(k + off, format!("{name} = {v} is not implemented")));
        }
    }
    let [area, i1, i2, i12, j, nsm] = a;
    Ok(Section::Beam(BeamSection {
        area,
        i1,
        i2,
        i12,
        j,
        shear_factors: kf,
        nsm,
        shape: None,
        taper,
    }))
}

/// X/XB of a station in field `k`: after the previous station's `last`, at most 1 (end B).
fn station_position(g: &C, k: usize, last: f64) -> Result<f64, ImportError> {
    let xi = g.real(k)?.unwrap_or(1.0);
    if xi <= last || xi > 1.0 {
        return Err(g.err(
            k,
            format!(
                "X/XB = {xi} must lie after the previous station ({last}) and at most 1.0 (end B)"
            ),
        ));
    }
    Ok(xi)
}

/// The stations of a tapered beam (`tapered`: some station differs from end A): they must end
/// at end B (X/XB = 1.0) and the section must have I12 = 0 (`i12`); `None` when prismatic.
fn tapered_stations<T>(
    g: &C,
    tapered: bool,
    i12: f64,
    stations: Vec<(f64, T)>,
) -> Result<Option<Vec<(f64, T)>>, ImportError> {
    if !tapered {
        return Ok(None);
    }
    if i12 != 0.0 {
        return Err(g.err_card(format!(
            "a tapered beam with I12 = {i12} ≠ 0 is not implemented (principal axes along the element)"
        )));
    }
    match stations.last() {
        Some((xi, _)) if *xi == 1.0 => Ok(Some(stations)),
        _ => Err(g.err_card("a tapered beam's last station must be end B (X/XB = 1.0)")),
    }
}

/// PBARL / PBEAML (MSC QRG): `PID MID GROUP TYPE / DIM1 … DIMn NSM`, PBEAML then
/// `SO X/XB DIM1 … DIMn NSM` per further station. The shape's constants from
/// [`library_section`]. Refused, each naming the field: a GROUP other than MSCBML0, a shape
/// not in the library, blank or inconsistent dimensions (also at a station), a PBEAML whose
/// neutral axis is off the shear centre (the
/// offset CBEAM Nastran makes of it is not implemented), anything after a PBARL's NSM.
fn library_card(g: &C) -> Result<Section, ImportError> {
    let pbeaml = g.card.name == "PBEAML";
    let group = g.text(2).to_ascii_uppercase();
    if !(group.is_empty() || group == "MSCBML0") {
        return Err(g.err(
            2,
            format!(
                "GROUP {group}: only Nastran's beam library MSCBML0 is known, not a user library"
            ),
        ));
    }
    let ty = g.text(3).to_ascii_uppercase();
    let n = dimension_count(&ty)
        .ok_or_else(|| g.err(3, library_section(&ty, &[]).err().unwrap_or_default()))?;
    let mut dims = Vec::with_capacity(n);
    for k in 8..8 + n {
        dims.push(g.real(k)?.ok_or_else(|| {
            g.err(
                k,
                format!("TYPE {ty} needs {n} dimensions: DIM{} is blank", k - 7),
            )
        })?);
    }
    let nsm = g.real_or(8 + n, 0.0)?;
    let lib = library_section(&ty, &dims).map_err(|e| g.err(8, e))?;
    let rest = 9 + n..g.card.fields.len();
    let mut taper = None;
    if pbeaml {
        // Stations: SO, X/XB, DIM1…DIMn, NSM (blank: end A's).
        let mut stations = vec![(0.0, (dims.clone(), nsm))];
        let mut tapered = false;
        for k in rest.step_by(n + 3) {
            if (k..(k + n + 3).min(g.card.fields.len())).all(|f| g.text(f).is_empty()) {
                continue;
            }
            let xi = station_position(g, k + 1, stations.last().map_or(0.0, |s| s.0))?;
            let mut d = dims.clone();
            d.push(nsm);
            for (i, x) in d.iter_mut().enumerate() {
                let r = g.real(k + 2 + i)?;
                tapered |= differs(r, *x);
                *x = r.unwrap_or(*x);
            }
            let nsm_k = d.pop().unwrap_or(nsm);
            library_section(&ty, &d)
                .map_err(|e| g.err(k + 2, format!("station X/XB = {xi}: {e}")))?;
            stations.push((xi, (d, nsm_k)));
        }
        taper = tapered_stations(g, tapered, lib.i12, stations)?.map(|st| BeamTaper::Library {
            shape: ty.clone(),
            stations: st.into_iter().map(|(x, (d, m))| (x, d, m)).collect(),
        });
        if !lib.centroid_on_shear_centre {
            return Err(g.err(
                3,
                format!(
                    "PBEAML TYPE {ty} with these dimensions has its neutral axis off the shear \
                     centre; Nastran's CBEAM offsets it there, which is not implemented (PBARL \
                     takes the same shape without the offset, as Nastran's CBAR does)"
                ),
            ));
        }
    } else if let Some(k) = rest.clone().find(|&k| !g.text(k).is_empty()) {
        return Err(g.err(
            k,
            format!(
                "PBARL TYPE {ty} has {n} dimensions and NSM; this field after them is not read"
            ),
        ));
    }
    Ok(Section::Beam(BeamSection {
        area: lib.area,
        i1: lib.i1,
        i2: lib.i2,
        i12: lib.i12,
        j: lib.j,
        shear_factors: Some(lib.shear_factors),
        nsm,
        shape: None,
        taper,
    }))
}
