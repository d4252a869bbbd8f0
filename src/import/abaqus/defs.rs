//! Abaqus tables and small geometric definitions: element type names, *BEAM SECTION shapes,
//! *TRANSFORM frames.

use crate::model::{CoordKind, CoordSystem, ElementKind, SectionShape};

/// Abaqus element type → (model kind, `None` for the point and connector elements MASS,
/// ROTARYI, SPRINGA, SPRING1, SPRING2, DASHPOTA; canonical type name).
pub(super) fn element_kind(t: &str) -> Option<(Option<ElementKind>, &'static str)> {
    use ElementKind::*;
    Some(match t {
        "C3D4" => (Some(Tet4), "C3D4"),
        "C3D10" => (Some(Tet10), "C3D10"),
        "C3D8" => (Some(Hex8), "C3D8"),
        // one-point integration with ccx's hourglass control (`fe::elements::hex8r`)
        "C3D8R" => (Some(Hex8R), "C3D8R"),
        // incompatible modes: `ModelParams::solid_bubbles` (the reader checks it is model-wide)
        "C3D8I" => (Some(Hex8), "C3D8I"),
        "C3D20" => (Some(Hex20), "C3D20"),
        "C3D20R" => (Some(Hex20R), "C3D20R"),
        "C3D6" => (Some(Prism6), "C3D6"),
        "C3D15" => (Some(Prism15), "C3D15"),
        "B31" => (Some(Beam2), "B31"),
        // expanded into 20-node bricks as ccx does (`beam_expansion`)
        "B32" => (Some(Beam3), "B32"),
        "B32R" => (Some(Beam3), "B32R"),
        "T3D2" => (Some(Rod2), "T3D2"),
        "S3" => (Some(Tri3), "S3"),
        "S4" => (Some(Quad4), "S4"),
        // read only when the shells are expanded as ccx does (`shell_expansion`: C3D8R);
        // flexbody's own shells refuse it (`VARIANTS`)
        "S4R" => (Some(Quad4), "S4R"),
        "S6" => (Some(Tri6), "S6"),
        // as flexbody's shells S8R is the same 8-node shell; expanded as ccx does, S8 becomes
        // C3D20 and S8R C3D20R (`shell_expansion`)
        "S8" => (Some(Quad8), "S8"),
        "S8R" => (Some(Quad8), "S8R"),
        // 2D continuum faces, as gmsh writes the faces of physical surfaces: kept as surface
        // elements (sets, graphics); a section on them is not assembled.
        "CPS3" | "CPE3" => (Some(Tri3), "CPS3"),
        "CPS4" | "CPE4" => (Some(Quad4), "CPS4"),
        "CPS6" | "CPE6" | "STRI65" => (Some(Tri6), "CPS6"),
        "CPS8" | "CPE8" => (Some(Quad8), "CPS8"),
        "MASS" => (None, "MASS"),
        "ROTARYI" => (None, "ROTARYI"),
        "SPRINGA" => (None, "SPRINGA"),
        "SPRING1" => (None, "SPRING1"),
        "SPRING2" => (None, "SPRING2"),
        "DASHPOTA" => (None, "DASHPOTA"),
        _ => return None,
    })
}

/// Element types that are a variant of a type flexbody forms, which it does not reproduce:
/// (variant, base, why), measured with ccx 2.20 on cantilevers (the decks of
/// `fixtures/ccx_elements/`). Refused; `--ignore VARIANT=BASE` reads them as the base type on
/// purpose (C3D8R is formed as CalculiX does, `fe::elements::hex8r`).
pub(super) const VARIANTS: &[(&str, &str, &str)] = &[
    (
        "C3D10M",
        "C3D10",
        "CalculiX 2.20 refuses C3D10M too; Abaqus's modified tetrahedron is not C3D10",
    ),
    (
        "B31R",
        "B31",
        "CalculiX expands B31R into one layer of C3D8R bricks that hourglass in bending \
         (a 20-element cantilever 1 × 0.1 × 0.05 m: first mode 6.89 Hz in ccx 2.20, 41.86 Hz as \
         B31, Euler–Bernoulli 41.9 Hz); flexbody's B31 is a beam element",
    ),
    (
        "S3R",
        "S3",
        "CalculiX 2.20 refuses S3R too; Abaqus's S3R is its reduced-integration triangle",
    ),
    (
        "S4R",
        "S4",
        "CalculiX expands S4R into one layer of C3D8R bricks (a 10 × 10 cantilever plate \
         1 × 0.5 × 0.01 m: 9.26, 60.1, 143.7 Hz in ccx 2.20; 8.54, 36.9, 53.7 Hz as S4) and \
         Abaqus's S4R is a reduced-integration shell with hourglass control; flexbody's S4 is \
         MITC4",
    ),
];

/// *TRANSFORM frame. TYPE=R: a on local x, b in the local x–y plane, origin 0:
/// e1 = a/|a|, e3 = a×b/|a×b|, e2 = e3×e1. TYPE=C: a and b on the local z axis, origin a,
/// e3 = (b−a)/|b−a| (e1 any unit vector ⟂ e3; nodal r, θ directions follow from the position).
pub(super) fn transform_frame(id: u64, cyl: bool, a: [f64; 3], b: [f64; 3]) -> Option<CoordSystem> {
    let cross = |p: [f64; 3], q: [f64; 3]| {
        [
            p[1] * q[2] - p[2] * q[1],
            p[2] * q[0] - p[0] * q[2],
            p[0] * q[1] - p[1] * q[0],
        ]
    };
    let unit = |p: [f64; 3]| {
        let n = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
        (n > 0.0 && n.is_finite()).then(|| p.map(|c| c / n))
    };
    if cyl {
        let e3 = unit([b[0] - a[0], b[1] - a[1], b[2] - a[2]])?;
        let k = (0..3)
            .min_by(|&i, &j| e3[i].abs().total_cmp(&e3[j].abs()))
            .unwrap_or(0);
        let mut t = [0.0; 3];
        t[k] = 1.0;
        let e2 = unit(cross(e3, t))?;
        let e1 = cross(e2, e3);
        Some(CoordSystem {
            id,
            kind: CoordKind::Cylindrical,
            origin: a,
            axes: [e1, e2, e3],
        })
    } else {
        let e1 = unit(a)?;
        let e3 = unit(cross(a, b))?;
        let e2 = cross(e3, e1);
        Some(CoordSystem {
            id,
            kind: CoordKind::Rectangular,
            origin: [0.0; 3],
            axes: [e1, e2, e3],
        })
    }
}

/// Abaqus *BEAM SECTION shapes (Abaqus Analysis User's Guide, "Beam cross-section library");
/// `Err` says why a shape is not formed.
pub(super) fn abaqus_shape(name: &str, v: &[f64]) -> Result<SectionShape, String> {
    Ok(match (name, v) {
        ("CIRC", [r, ..]) => SectionShape::Circle { radius: *r },
        ("PIPE", [r, t, ..]) => SectionShape::Tube {
            outer_radius: *r,
            inner_radius: r - t,
        },
        ("RECT", [a, b, ..]) => SectionShape::Rectangle {
            width: *a,
            height: *b,
        },
        // BOX: a (width, 1-dir), b (height, 2-dir), t1..t4 around the box: opposite walls equal
        // (a wall thicker than its opposite moves the centroid off the node: not formed).
        ("BOX", [_, _, t1, t2, t3, t4, ..]) if t1 != t3 || t2 != t4 => {
            return Err(format!(
                "SECTION=BOX with unequal opposite walls (t1 = {t1}, t3 = {t3}; t2 = {t2}, \
                 t4 = {t4}) is not supported: its centroid is off the beam node"
            ))
        }
        ("BOX", [a, b, t1, t2, ..]) => SectionShape::Box {
            width: *a,
            height: *b,
            t_web: *t2,
            t_flange: *t1,
        },
        // I: l (the beam node's height above the bottom), h, b1 (bottom), b2 (top), t1, t2, t3
        // (web); formed about the centroid, so l must be the centroid's height.
        ("I", [l, h, b1, b2, t1, t2, t3, ..]) => {
            let hw = h - t1 - t2;
            let parts = [
                (b1 * t1, 0.5 * t1),
                (t3 * hw, t1 + 0.5 * hw),
                (b2 * t2, h - 0.5 * t2),
            ];
            let area: f64 = parts.iter().map(|p| p.0).sum();
            let centroid = parts.iter().map(|p| p.0 * p.1).sum::<f64>() / area;
            if (l - centroid).abs() > 1e-6 * h {
                return Err(format!(
                    "SECTION=I with l = {l}: the beam node is {:.6e} off the section's centroid \
                     (at {centroid:.6e} above the bottom); an I section off its centroid is not \
                     supported (give l = {centroid:.6e})",
                    l - centroid
                ));
            }
            SectionShape::I {
                height: *h,
                width_bottom: *b1,
                width_top: *b2,
                t_web: *t3,
                t_bottom: *t1,
                t_top: *t2,
            }
        }
        _ => {
            return Err(format!(
                "SECTION={name} with {} dimensions not supported",
                v.len()
            ))
        }
    })
}
