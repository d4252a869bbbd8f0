//! Every PBARL/PBEAML shape of Nastran's beam library (MSC QRG "PBARL", Figure 1) as a clamped
//! cantilever held to one bending plane, against the Euler–Bernoulli closed form
//! f = (1.875104²/2π)·√(E I/(ρ A L⁴)) (Blevins, *Formulas for Natural Frequency and Mode Shape*,
//! Table 8-1) with I1 in plane 1 (element x–y) and I2 in plane 2 (x–z). The test's I values come
//! from its own cut of each drawn shape (other rectangles than the library's, with holes of
//! negative area, summed by the parallel-axis theorem), so a shape whose I1 and I2 were swapped
//! fails in both planes. Also: PBARL BAR equals the PBAR with its QRG constants, an L section
//! free to bend in both planes gives the principal frequencies of I1, I2, I12, tapered
//! PBEAML/PBEAM cantilevers equal the same beam cut into 256 prismatic elements, and the refused
//! forms (offset neutral axis, element-frame offsets) name their card and line; pin flags
//! PA/PB releasing the end rotations of a beam clamped at both grids make it simply supported;
//! offsets WA/WB equal rigid links (RBE2) to the offset ends.

use std::f64::consts::PI;
use std::path::Path;

use crate::common::{generalized_eigenvalues, hz};
use crate::nastran_support::write;
use flexbody::fe::{assemble, eliminate, AssemblySpec, BeamTheory, ConstraintSpec, MassKind};
use flexbody::import::{read_model, ImportOptions};
use flexbody::model::Section;

const E: f64 = 2.1e11;
const RHO: f64 = 7850.0;
const LENGTH: f64 = 2.0;
const ELEMENTS: usize = 20;
/// Cantilever first-mode eigenvalue β₁L (Blevins Table 8-1).
const BETA_L: f64 = 1.875_104_068_711_961;

/// (A, I1, I2, I12) of rectangles (width along z, height along y, centre z, centre y, sign):
/// a hole has sign −1 (parallel-axis theorem).
fn rectangles(parts: &[(f64, f64, f64, f64, f64)]) -> (f64, f64, f64, f64) {
    let a: f64 = parts.iter().map(|p| p.4 * p.0 * p.1).sum();
    let zc = parts.iter().map(|p| p.4 * p.0 * p.1 * p.2).sum::<f64>() / a;
    let yc = parts.iter().map(|p| p.4 * p.0 * p.1 * p.3).sum::<f64>() / a;
    let (mut i1, mut i2, mut i12) = (0.0, 0.0, 0.0);
    for &(b, h, z, y, s) in parts {
        let ai = s * b * h;
        i1 += s * b * h.powi(3) / 12.0 + ai * (y - yc).powi(2);
        i2 += s * h * b.powi(3) / 12.0 + ai * (z - zc).powi(2);
        i12 += ai * (y - yc) * (z - zc);
    }
    (a, i1, i2, i12)
}

/// The test's (A, I1, I2, I12) of each shape, from the QRG's drawing (y up, z right).
fn expected(ty: &str, d: &[f64]) -> (f64, f64, f64, f64) {
    let x = |k: usize| d[k - 1];
    let circle = |r: f64, ri: f64| {
        let i = PI * (r.powi(4) - ri.powi(4)) / 4.0;
        (PI * (r * r - ri * ri), i, i, 0.0)
    };
    match ty {
        "ROD" => circle(x(1), 0.0),
        "TUBE" => circle(x(1), x(2)),
        "TUBE2" => circle(x(1), x(1) - x(2)),
        // QRG: I1 = b h³/12, I2 = h b³/12 with b = DIM1, h = DIM2.
        "BAR" => (
            x(1) * x(2),
            x(1) * x(2).powi(3) / 12.0,
            x(2) * x(1).powi(3) / 12.0,
            0.0,
        ),
        "BOX" => {
            let (w, h, tf, ts) = (x(1), x(2), x(3), x(4));
            let (wi, hi) = (w - 2.0 * ts, h - 2.0 * tf);
            (
                w * h - wi * hi,
                (w * h.powi(3) - wi * hi.powi(3)) / 12.0,
                (h * w.powi(3) - hi * wi.powi(3)) / 12.0,
                0.0,
            )
        }
        "BOX1" => {
            let (w, h, tt, tb, tl, tr) = (x(1), x(2), x(3), x(4), x(5), x(6));
            let (wi, hi) = (w - tl - tr, h - tt - tb);
            rectangles(&[
                (w, h, w / 2.0, h / 2.0, 1.0),
                (wi, hi, tl + wi / 2.0, tb + hi / 2.0, -1.0),
            ])
        }
        "I" => {
            let (h, wb, wt, tw, tb, tt) = (x(1), x(2), x(3), x(4), x(5), x(6));
            let hw = h - tb - tt;
            rectangles(&[
                (wb, tb, 0.0, tb / 2.0, 1.0),
                (tw, hw, 0.0, tb + hw / 2.0, 1.0),
                (wt, tt, 0.0, h - tt / 2.0, 1.0),
            ])
        }
        "I1" => {
            let (o, tw, hw, h) = (x(1), x(2), x(3), x(4));
            let zv = tw / 2.0 + o / 4.0;
            rectangles(&[
                (o + tw, h, 0.0, 0.0, 1.0),
                (o / 2.0, hw, zv, 0.0, -1.0),
                (o / 2.0, hw, -zv, 0.0, -1.0),
            ])
        }
        "CHAN" => {
            let (w, h, tw, tf) = (x(1), x(2), x(3), x(4));
            rectangles(&[
                (w, h, w / 2.0, h / 2.0, 1.0),
                (w - tw, h - 2.0 * tf, tw + (w - tw) / 2.0, h / 2.0, -1.0),
            ])
        }
        "CHAN1" => {
            let (o, tw, hw, h) = (x(1), x(2), x(3), x(4));
            rectangles(&[
                (o + tw, h, (o + tw) / 2.0, h / 2.0, 1.0),
                (o, hw, tw + o / 2.0, h / 2.0, -1.0),
            ])
        }
        "CHAN2" => {
            let (tl, tb, h, w) = (x(1), x(2), x(3), x(4));
            rectangles(&[
                (w, h, w / 2.0, h / 2.0, 1.0),
                (w - 2.0 * tl, h - tb, w / 2.0, tb + (h - tb) / 2.0, -1.0),
            ])
        }
        "T" => {
            let (w, h, tf, tw) = (x(1), x(2), x(3), x(4));
            rectangles(&[
                (w, tf, 0.0, h - tf / 2.0, 1.0),
                (tw, h - tf, 0.0, (h - tf) / 2.0, 1.0),
            ])
        }
        "T2" => {
            let (w, h, tf, tw) = (x(1), x(2), x(3), x(4));
            rectangles(&[
                (w, tf, 0.0, tf / 2.0, 1.0),
                (tw, h - tf, 0.0, tf + (h - tf) / 2.0, 1.0),
            ])
        }
        "T1" => {
            let (hf, lw, tf, tw) = (x(1), x(2), x(3), x(4));
            rectangles(&[
                (tf, hf, tf / 2.0, 0.0, 1.0),
                (lw, tw, tf + lw / 2.0, 0.0, 1.0),
            ])
        }
        "L" => {
            let (w, h, t1, t2) = (x(1), x(2), x(3), x(4));
            rectangles(&[
                (w, h, w / 2.0, h / 2.0, 1.0),
                (
                    w - t2,
                    h - t1,
                    t2 + (w - t2) / 2.0,
                    t1 + (h - t1) / 2.0,
                    -1.0,
                ),
            ])
        }
        "Z" => {
            let (o, tw, hw, h) = (x(1), x(2), x(3), x(4));
            let tf = (h - hw) / 2.0;
            rectangles(&[
                (2.0 * o + tw, h, o + tw / 2.0, h / 2.0, 1.0),
                (o, h - tf, o + tw + o / 2.0, tf + (h - tf) / 2.0, -1.0),
                (o, h - tf, o / 2.0, (h - tf) / 2.0, -1.0),
            ])
        }
        "CROSS" => {
            let (la, tv, hv, ta) = (x(1), x(2), x(3), x(4));
            rectangles(&[
                (tv, hv, 0.0, 0.0, 1.0),
                (la + tv, ta, 0.0, 0.0, 1.0),
                (tv, ta, 0.0, 0.0, -1.0),
            ])
        }
        "H" => {
            let (lw, tf2, hf, tw) = (x(1), x(2), x(3), x(4));
            let zf = lw / 2.0 + tf2 / 4.0;
            rectangles(&[
                (tf2 / 2.0, hf, -zf, 0.0, 1.0),
                (lw, tw, 0.0, 0.0, 1.0),
                (tf2 / 2.0, hf, zf, 0.0, 1.0),
            ])
        }
        "HEXA" => {
            // Central rectangle plus two isosceles triangles of base h (along y), height t
            // (along z): ∫y² = t h³/48, ∫(z − z_c)² = h t³/36, centroid t/3 from the base.
            let (t, w, h) = (x(1), x(2), x(3));
            let wr = w - 2.0 * t;
            let at = t * h / 2.0;
            let zt = wr / 2.0 + t / 3.0;
            let a = wr * h + 2.0 * at;
            let i1 = wr * h.powi(3) / 12.0 + 2.0 * t * h.powi(3) / 48.0;
            let i2 = h * wr.powi(3) / 12.0 + 2.0 * (h * t.powi(3) / 36.0 + at * zt * zt);
            (a, i1, i2, 0.0)
        }
        "HAT" => {
            let (h, t, w, b) = (x(1), x(2), x(3), x(4));
            let zw = w / 2.0 - t / 2.0;
            let zb = w / 2.0 + b / 2.0;
            rectangles(&[
                (w, t, 0.0, h - t / 2.0, 1.0),
                (t, h - t, zw, (h - t) / 2.0, 1.0),
                (t, h - t, -zw, (h - t) / 2.0, 1.0),
                (b, t, zb, t / 2.0, 1.0),
                (b, t, -zb, t / 2.0, 1.0),
            ])
        }
        "HAT1" => {
            let (w, h, wt, t, tb) = (x(1), x(2), x(3), x(4), x(5));
            let b = (w - wt) / 2.0;
            let zw = wt / 2.0 - t / 2.0;
            let zb = wt / 2.0 + b / 2.0;
            rectangles(&[
                (w, tb, 0.0, tb / 2.0, 1.0),
                (t, h - tb, zw, tb + (h - tb) / 2.0, 1.0),
                (t, h - tb, -zw, tb + (h - tb) / 2.0, 1.0),
                (wt - 2.0 * t, t, 0.0, h - t / 2.0, 1.0),
                (b, t, zb, tb + t / 2.0, 1.0),
                (b, t, -zb, tb + t / 2.0, 1.0),
            ])
        }
        "DBOX" => {
            let (w, h, c) = (x(1), x(2), x(3));
            let (tl, tm, tr) = (x(4), x(5), x(6));
            let (t1t, t1b, t2t, t2b) = (x(7), x(8), x(9), x(10));
            let (wi1, hi1) = (c - tl - tm / 2.0, h - t1t - t1b);
            let (wi2, hi2) = (w - c - tm / 2.0 - tr, h - t2t - t2b);
            rectangles(&[
                (c, h, c / 2.0, h / 2.0, 1.0),
                (wi1, hi1, tl + wi1 / 2.0, t1b + hi1 / 2.0, -1.0),
                (w - c, h, c + (w - c) / 2.0, h / 2.0, 1.0),
                (wi2, hi2, c + tm / 2.0 + wi2 / 2.0, t2b + hi2 / 2.0, -1.0),
            ])
        }
        _ => unreachable!("{ty}"),
    }
}

/// The shapes with dimensions (m) that make I1 and I2 differ where the shape allows it.
const SHAPES: &[(&str, &[f64])] = &[
    ("ROD", &[0.02]),
    ("TUBE", &[0.03, 0.025]),
    ("TUBE2", &[0.03, 0.005]),
    ("BAR", &[0.06, 0.02]),
    ("BOX", &[0.08, 0.04, 0.004, 0.006]),
    ("BOX1", &[0.08, 0.05, 0.006, 0.004, 0.003, 0.005]),
    ("I", &[0.10, 0.06, 0.04, 0.005, 0.008, 0.006]),
    ("I1", &[0.05, 0.006, 0.08, 0.10]),
    ("CHAN", &[0.05, 0.10, 0.006, 0.008]),
    ("CHAN1", &[0.04, 0.006, 0.08, 0.10]),
    ("CHAN2", &[0.006, 0.008, 0.05, 0.10]),
    ("T", &[0.08, 0.06, 0.008, 0.006]),
    ("T1", &[0.10, 0.05, 0.008, 0.006]),
    ("T2", &[0.08, 0.06, 0.008, 0.006]),
    ("L", &[0.06, 0.09, 0.006, 0.008]),
    ("Z", &[0.04, 0.006, 0.08, 0.10]),
    ("CROSS", &[0.06, 0.01, 0.08, 0.008]),
    ("H", &[0.06, 0.02, 0.08, 0.008]),
    ("HEXA", &[0.01, 0.06, 0.04]),
    ("HAT", &[0.06, 0.004, 0.05, 0.02]),
    ("HAT1", &[0.12, 0.06, 0.05, 0.004, 0.005]),
    (
        "DBOX",
        &[
            0.12, 0.06, 0.05, 0.005, 0.006, 0.004, 0.005, 0.004, 0.006, 0.007,
        ],
    ),
];

/// A cantilever deck along x (v = y, so element y = basic y): GRID 1 clamped, the other grids
/// held in `held` (permanent single-point constraints, GRID PS); `property` the property
/// card(s) of PID 1; `element` CBAR or CBEAM.
fn cantilever(element: &str, property: &str, held: &str) -> String {
    let mut s = String::from("SOL 103\nCEND\nBEGIN BULK\nMAT1,1,2.1+11,,0.3,7850.\n");
    s += property;
    for i in 0..=ELEMENTS {
        let x = LENGTH * i as f64 / ELEMENTS as f64;
        let ps = if i == 0 { "123456" } else { held };
        s += &format!("GRID,{},,{x},0.,0.,,{ps}\n", i + 1);
    }
    for e in 1..=ELEMENTS {
        s += &format!("{element},{e},1,{e},{},0.,1.,0.\n", e + 1);
    }
    s + "ENDDATA\n"
}

/// The library card of a shape: `PBARL` or `PBEAML`, PID 1, MID 1.
fn library_card(card: &str, ty: &str, dims: &[f64]) -> String {
    let d: Vec<String> = dims.iter().map(|v| format!("{v:e}")).collect();
    let mut s = format!("{card},1,1,MSCBML0,{ty}\n");
    for chunk in d.chunks(8) {
        s += &format!(",{}\n", chunk.join(","));
    }
    s
}

/// Euler–Bernoulli lowest frequencies (Hz) of a deck, consistent mass, dense solve.
fn frequencies(deck: &Path) -> Vec<f64> {
    let model = read_model(deck, &ImportOptions::default()).unwrap();
    let spec = AssemblySpec {
        mass: MassKind::Consistent,
        beam: BeamTheory::EulerBernoulli,
        ..Default::default()
    };
    let a = assemble(&model, &spec).unwrap();
    let r = eliminate(&model, &a.dofs, &a.k, &a.m, &ConstraintSpec::default()).unwrap();
    let mut f: Vec<f64> =
        generalized_eigenvalues(&crate::common::dense(&r.k), &crate::common::dense(&r.m))
            .into_iter()
            .map(hz)
            .collect();
    f.sort_by(f64::total_cmp);
    f
}

/// f = (β₁L)²/(2π L²)·√(E I/(ρ A)).
fn cantilever_hz(i: f64, a: f64) -> f64 {
    BETA_L * BETA_L / (2.0 * PI * LENGTH * LENGTH) * (E * i / (RHO * a)).sqrt()
}

/// Plane 1 (x–y: v and θz move) holds 1345; plane 2 (x–z: w and θy) holds 1246.
const PLANE_1: &str = "1345";
const PLANE_2: &str = "1246";

#[test]
fn every_library_shape_bends_with_i1_in_plane_1_and_i2_in_plane_2() {
    let mut report = Vec::new();
    for &(ty, dims) in SHAPES {
        let (a, i1, i2, _) = expected(ty, dims);
        // PBEAML only where Nastran's CBEAM would not offset the neutral axis.
        let cards: &[&str] = match ty {
            "ROD" | "TUBE" | "TUBE2" | "BAR" | "BOX" | "I1" | "H" | "CROSS" | "HEXA" | "Z" => {
                &["PBARL", "PBEAML"]
            }
            _ => &["PBARL"],
        };
        for &card in cards {
            let element = if card == "PBARL" { "CBAR" } else { "CBEAM" };
            let prop = library_card(card, ty, dims);
            let model = read_model(
                &write(
                    "sections",
                    &format!("{ty}_{card}.bdf"),
                    &cantilever(element, &prop, ""),
                ),
                &ImportOptions::default(),
            )
            .unwrap();
            let Section::Beam(s) = &model.properties[0].section else {
                panic!("{ty}: not a beam section");
            };
            assert!(
                (s.area - a).abs() < 1e-12 * a,
                "{ty}: A = {} want {a}",
                s.area
            );
            for (plane, held, i) in [(1, PLANE_1, i1), (2, PLANE_2, i2)] {
                let deck = cantilever(element, &prop, held);
                let path = write("sections", &format!("{ty}_{card}_{plane}.bdf"), &deck);
                let got = frequencies(&path)[0];
                let want = cantilever_hz(i, a);
                let err = (got - want) / want;
                report.push(format!(
                    "{card} {ty} plane {plane}: {got:.4} Hz vs {want:.4} Hz"
                ));
                assert!(
                    err.abs() < 1e-4,
                    "{card} {ty} plane {plane}: {got} Hz, closed form {want} Hz ({err:+.2e})"
                );
            }
        }
        // Where the two planes differ by > 5 %, a swap of I1 and I2 fails above.
        if (i1 / i2 - 1.0).abs() > 0.1 {
            report.push(format!("{ty}: I1/I2 = {:.3}", i1 / i2));
        }
    }
    println!("{}", report.join("\n"));
}

/// The case: PBARL BAR DIM1 = 3·DIM2 gave the plane-2 frequency in plane 1 (×1/3).
/// PBARL BAR equals the PBAR with the QRG's A = b h, I1 = b h³/12, I2 = h b³/12 (b = DIM1,
/// h = DIM2) in both planes, and the planes are 3× apart.
#[test]
fn pbarl_bar_equals_the_pbar_of_its_qrg_constants_in_both_planes() {
    let (b, h) = (0.06, 0.02);
    let pbarl = library_card("PBARL", "BAR", &[b, h]);
    let pbar = format!(
        "PBAR,1,1,{:e},{:e},{:e},1.e-8\n",
        b * h,
        b * h.powi(3) / 12.0,
        h * b.powi(3) / 12.0
    );
    let mut plane_hz = Vec::new();
    for (plane, held) in [(1, PLANE_1), (2, PLANE_2)] {
        let f_l = frequencies(&write(
            "bar",
            &format!("pbarl_{plane}.bdf"),
            &cantilever("CBAR", &pbarl, held),
        ))[0];
        let f_p = frequencies(&write(
            "bar",
            &format!("pbar_{plane}.bdf"),
            &cantilever("CBAR", &pbar, held),
        ))[0];
        assert!(
            (f_l - f_p).abs() < 1e-9 * f_p,
            "plane {plane}: {f_l} vs {f_p}"
        );
        plane_hz.push(f_l);
    }
    let ratio = plane_hz[1] / plane_hz[0];
    assert!((ratio - 3.0).abs() < 1e-6, "plane 2 / plane 1 = {ratio}");
}

/// An L section (I12 ≠ 0) free to bend in both planes (only axial and torsion held) bends about
/// its principal axes: the two lowest frequencies are those of I_min and I_max,
/// I_max,min = (I1 + I2)/2 ± √(((I1 − I2)/2)² + I12²) (Mohr's circle).
#[test]
fn l_section_bends_about_its_principal_axes() {
    let dims = [0.06, 0.09, 0.006, 0.008];
    let (a, i1, i2, i12) = expected("L", &dims);
    assert!(
        i12.abs() > 0.3 * i1.min(i2),
        "the test needs a large I12: {i12}"
    );
    let mid = (i1 + i2) / 2.0;
    let r = (((i1 - i2) / 2.0).powi(2) + i12 * i12).sqrt();
    let deck = cantilever("CBAR", &library_card("PBARL", "L", &dims), "14");
    let f = frequencies(&write("l_free", "l.bdf", &deck));
    for (got, i) in [(f[0], mid - r), (f[1], mid + r)] {
        let want = cantilever_hz(i, a);
        assert!(
            (got - want).abs() < 1e-4 * want,
            "{got} Hz vs principal {want} Hz"
        );
    }
    // Held to plane 1 it bends with I1 (not a principal value): the held direction carries the
    // coupling.
    let deck = cantilever("CBAR", &library_card("PBARL", "L", &dims), PLANE_1);
    let got = frequencies(&write("l_free", "l_plane1.bdf", &deck))[0];
    let want = cantilever_hz(i1, a);
    assert!((got - want).abs() < 1e-4 * want, "{got} vs {want}");
}

/// What is not implemented is an error naming the card, its line and the field.
#[test]
fn unsupported_beam_forms_are_errors_naming_card_and_line() {
    let cases: [(&str, String, &str, &str); 6] = [
        (
            "PBEAML station before the previous",
            "PBEAML,1,1,MSCBML0,BAR\n,0.06,0.02,0.,NO,0.5,0.05,0.02,0.\n,NO,0.4,0.04,0.02\n".into(),
            "CBEAM",
            "X/XB = 0.4",
        ),
        (
            "PBEAML with its neutral axis off the shear centre",
            library_card("PBEAML", "T", &[0.08, 0.06, 0.008, 0.006]),
            "CBEAM",
            "off the shear",
        ),
        (
            "tapered PBEAM with I12",
            "PBEAM,1,1,1.e-3,1.e-7,2.e-7,1.e-8,1.e-8\n,YES,1.,2.e-3,1.e-7,2.e-7,1.e-8,1.e-8\n"
                .into(),
            "CBEAM",
            "I12",
        ),
        (
            "PBEAM neutral-axis offset",
            "PBEAM,1,1,1.e-3,1.e-7,2.e-7,,1.e-8\n,,,,,,,,\n,,,,,,,,\n,,,,,0.01\n".into(),
            "CBEAM",
            "N1(A)",
        ),
        (
            "unknown shape",
            "PBARL,1,1,MSCBML0,FOO\n,0.06,0.02\n".into(),
            "CBAR",
            "FOO",
        ),
        (
            "user library group",
            "PBARL,1,1,MYLIB,BAR\n,0.06,0.02\n".into(),
            "CBAR",
            "MYLIB",
        ),
    ];
    for (what, prop, element, needle) in cases {
        let deck = cantilever(element, &prop, "");
        let path = write("refused", &format!("{}.bdf", what.replace(' ', "_")), &deck);
        let err = read_model(&path, &ImportOptions::default())
            .map(|_| ())
            .expect_err(what)
            .to_string();
        let line = crate::nastran_support::line_of(&deck, prop.lines().next().unwrap());
        assert!(err.contains(needle), "{what}: {err}");
        // The card's line or the line of the field on its continuation.
        assert!(
            (line..line + 4).any(|l| err.contains(&format!(".bdf:{l}:"))),
            "{what} (line {line}): {err}"
        );
    }
    // CBAR bad pin flags and offsets in the element frame: the element card and its line.
    let pbar = "PBAR,1,1,1.e-3,1.e-7,2.e-7,1.e-8\n";
    for (what, cont, needle) in [
        ("bad pin flag", ",7", "pin flags 7"),
        (
            "element-frame offset",
            ",,,0.,0.01",
            "element frame (OFFT GOO)",
        ),
    ] {
        let mut deck = cantilever("CBAR", pbar, "");
        deck = deck.replace(
            "CBAR,3,1,3,4,0.,1.,0.\n",
            &format!("CBAR,3,1,3,4,0.,1.,0.,GOO\n{cont}\n"),
        );
        let path = write("refused", &format!("{}.bdf", what.replace(' ', "_")), &deck);
        let err = read_model(&path, &ImportOptions::default())
            .map(|_| ())
            .expect_err(what)
            .to_string();
        let line = crate::nastran_support::line_of(&deck, "CBAR,3,");
        assert!(
            err.contains(needle) && err.contains("CBAR 3"),
            "{what}: {err}"
        );
        assert!(
            (line..line + 2).any(|l| err.contains(&format!(".bdf:{l}:"))),
            "{what}: {err}"
        );
    }
}

/// A cantilever of `parts` elements along x whose element e has the property card(s)
/// `property(e)` (PID e), held in `held`.
fn cantilever_of(parts: usize, held: &str, property: &dyn Fn(usize) -> String) -> String {
    let mut s = String::from("SOL 103\nCEND\nBEGIN BULK\nMAT1,1,2.1+11,,0.3,7850.\n");
    for i in 0..=parts {
        let x = LENGTH * i as f64 / parts as f64;
        let ps = if i == 0 { "123456" } else { held };
        s += &format!("GRID,{},,{x},0.,0.,,{ps}\n", i + 1);
    }
    for e in 1..=parts {
        s += &property(e);
        s += &format!("CBEAM,{e},{e},{e},{},0.,1.,0.\n", e + 1);
    }
    s + "ENDDATA\n"
}

/// Tapered PBEAML BAR (DIM1 0.04 → 0.02, DIM2 0.03 → 0.015 linearly over the cantilever), 8
/// tapered CBEAMs each with its own end A/B dimensions and a mid station, against the same beam
/// of 256 prismatic PBEAML at each element's mid-length dimensions: both planes, two modes
/// each, within 3e-5 (measured 1e-6 and 1.1e-5; with 64 prismatic elements 1.8e-4: the
/// difference is the prismatic model's stepping, O(1/n²)). End A's section alone (the former
/// behaviour) is > 10 % off.
#[test]
fn tapered_pbeaml_equals_the_finely_cut_prismatic_beam() {
    let dims = |t: f64| [0.04 - 0.02 * t, 0.03 - 0.015 * t];
    let bar =
        |pid: usize, d: [f64; 2]| format!("PBEAML,{pid},1,MSCBML0,BAR\n,{:e},{:e}", d[0], d[1]);
    for (plane, held) in [(1, PLANE_1), (2, PLANE_2)] {
        let tapered = cantilever_of(8, held, &|e| {
            let (a, m, b) = ((e - 1) as f64 / 8.0, (e as f64 - 0.5) / 8.0, e as f64 / 8.0);
            let (dm, db) = (dims(m), dims(b));
            format!(
                "{},0.,NO,0.5,{:e},{:e},0.\n,YES,1.,{:e},{:e}\n",
                bar(e, dims(a)),
                dm[0],
                dm[1],
                db[0],
                db[1]
            )
        });
        let fine = cantilever_of(256, held, &|e| {
            format!("{}\n", bar(e, dims((e as f64 - 0.5) / 256.0)))
        });
        let end_a = cantilever_of(8, held, &|e| format!("{}\n", bar(e, dims(0.0))));
        let f_t = frequencies(&write("taper", &format!("pbeaml_{plane}.bdf"), &tapered));
        let f_f = frequencies(&write("taper", &format!("fine_{plane}.bdf"), &fine));
        let f_a = frequencies(&write("taper", &format!("end_a_{plane}.bdf"), &end_a));
        for k in 0..2 {
            let err = (f_t[k] - f_f[k]) / f_f[k];
            println!("plane {plane} mode {}: tapered {:.5} Hz, 256 prismatic {:.5} Hz ({err:+.1e}), end A only {:.5} Hz", k + 1, f_t[k], f_f[k], f_a[k]);
            assert!(
                err.abs() < 3e-5,
                "plane {plane} mode {}: {} vs {}",
                k + 1,
                f_t[k],
                f_f[k]
            );
        }
        assert!(
            (f_a[0] - f_f[0]).abs() > 0.1 * f_f[0],
            "the taper must matter"
        );
    }
}

/// Tapered PBEAM (A, I1, I2, J linear from end A through a station at X/XB = 0.5 to end B, end
/// B on a SO = NO line without stress points) against 256 prismatic PBEAMs with the values at
/// their mid-lengths: two modes in both planes within 1e-4 (measured 4.5e-6 on the first, 5.4e-5
/// on the second: the 8 tapered elements' own discretization of mode 2).
#[test]
fn tapered_pbeam_with_a_station_equals_the_finely_cut_prismatic_beam() {
    // Values at ξ along the whole cantilever: A, I1, I2, J.
    let v = |t: f64| {
        [
            1.2e-3 * (1.0 - 0.5 * t),
            4.0e-8 * (1.0 - 0.7 * t),
            3.6e-7 * (1.0 - 0.6 * t),
            1.0e-7 * (1.0 - 0.5 * t),
        ]
    };
    let line = |x: [f64; 4]| format!("{:e},{:e},{:e},,{:e}", x[0], x[1], x[2], x[3]);
    for (plane, held) in [(1, PLANE_1), (2, PLANE_2)] {
        let tapered = cantilever_of(8, held, &|e| {
            let (a, m, b) = ((e - 1) as f64 / 8.0, (e as f64 - 0.5) / 8.0, e as f64 / 8.0);
            format!(
                "PBEAM,{e},1,{}\n,NO,0.5,{}\n,NO,1.,{}\n",
                line(v(a)),
                line(v(m)),
                line(v(b))
            )
        });
        let fine = cantilever_of(256, held, &|e| {
            format!("PBEAM,{e},1,{}\n", line(v((e as f64 - 0.5) / 256.0)))
        });
        let f_t = frequencies(&write("taper", &format!("pbeam_{plane}.bdf"), &tapered));
        let f_f = frequencies(&write("taper", &format!("pbeam_fine_{plane}.bdf"), &fine));
        for k in 0..2 {
            let err = (f_t[k] - f_f[k]) / f_f[k];
            println!(
                "PBEAM plane {plane} mode {}: {:.5} Hz vs {:.5} Hz ({err:+.1e})",
                k + 1,
                f_t[k],
                f_f[k]
            );
            assert!(
                err.abs() < 1e-4,
                "plane {plane} mode {}: {} vs {}",
                k + 1,
                f_t[k],
                f_f[k]
            );
        }
    }
}

/// Pin flags: a beam whose end grids are clamped (123456) but whose first element releases the
/// bending rotation at end A (PA) and last element at end B (PB) is simply supported in that
/// plane: f₁ = (π/2L²)·√(E I/(ρ A)) (Blevins Table 8-1), with I1 when the rotation about
/// element z (6) is released and the beam held to plane 1, I2 for 5 in plane 2; PA = PB = 56
/// in both. Without the pins the clamped–clamped beam is 2.27× stiffer (4.730²/π²).
#[test]
fn pin_flags_make_a_clamped_beam_simply_supported() {
    let (b, h): (f64, f64) = (0.06, 0.02);
    let (a, i1, i2) = (b * h, b * h.powi(3) / 12.0, h * b.powi(3) / 12.0);
    let ss = |i: f64| PI / (2.0 * LENGTH * LENGTH) * (E * i / (RHO * a)).sqrt();
    for element in ["CBAR", "CBEAM"] {
        for (plane, held, pin, i) in [
            (1, PLANE_1, "6", i1),
            (2, PLANE_2, "5", i2),
            (1, PLANE_1, "56", i1),
            (2, PLANE_2, "56", i2),
        ] {
            let prop = library_card("PBARL", "BAR", &[b, h])
                .replace("PBARL", if element == "CBAR" { "PBARL" } else { "PBEAML" });
            let mut deck = cantilever(element, &prop, held).replace(
                &format!("GRID,{},,{LENGTH},0.,0.,,{held}\n", ELEMENTS + 1),
                &format!("GRID,{},,{LENGTH},0.,0.,,123456\n", ELEMENTS + 1),
            );
            let first = format!("{element},1,1,1,2,0.,1.,0.\n");
            let last = format!(
                "{element},{ELEMENTS},1,{ELEMENTS},{},0.,1.,0.\n",
                ELEMENTS + 1
            );
            assert!(deck.contains(&first) && deck.contains(&last));
            deck = deck
                .replace(&first, &format!("{first},{pin}\n"))
                .replace(&last, &format!("{last},,{pin}\n"));
            let path = write("pins", &format!("{element}_{plane}_{pin}.bdf"), &deck);
            let got = frequencies(&path)[0];
            let want = ss(i);
            println!("{element} PA/PB = {pin}, plane {plane}: {got:.5} Hz vs {want:.5} Hz");
            assert!(
                (got - want).abs() < 1e-4 * want,
                "{element} {pin} plane {plane}: {got} vs simply supported {want}"
            );
            let clamped = frequencies(&write(
                "pins",
                "clamped.bdf",
                &deck
                    .replace(&format!("\n,{pin}\n"), "\n")
                    .replace(&format!("\n,,{pin}\n"), "\n"),
            ))[0];
            assert!(clamped > 2.0 * want, "{clamped} vs {want}");
        }
    }
}

/// OFFT's first letter says in which frame X1–X3 are (MSC QRG CBAR): G (default) the
/// displacement frame of GA, B basic. GA's displacement frame here is turned 90° about x
/// (CORD2R 5: z' = basic y, x' = basic x, so y' = −basic z).
#[test]
fn offt_b_reads_the_orientation_vector_in_the_basic_frame() {
    let deck = |offt: &str| {
        format!(
            "SOL 103\nCEND\nBEGIN BULK\nMAT1,1,2.1+11,,0.3,7850.\nPBAR,1,1,1.e-3,1.e-7,2.e-7,1.e-8\n\
             CORD2R,5,,0.,0.,0.,0.,1.,0.\n,1.,0.,0.\nGRID,1,,0.,0.,0.,5\nGRID,2,,1.,0.,0.\n\
             CBAR,1,1,1,2,0.,1.,0.,{offt}\nENDDATA\n"
        )
    };
    for (offt, want) in [
        ("", [0.0, 0.0, -1.0]),
        ("GGG", [0.0, 0.0, -1.0]),
        ("BGG", [0.0, 1.0, 0.0]),
    ] {
        let path = write("offt", &format!("offt_{offt}.bdf"), &deck(offt));
        let model = read_model(&path, &ImportOptions::default()).unwrap();
        let v = model.elements[0].orientation.unwrap();
        let err: f64 = v.iter().zip(want).map(|(a, b)| (a - b).abs()).sum();
        assert!(err < 1e-12, "OFFT {offt:?}: {v:?}, want {want:?}");
    }
    let path = write("offt", "offt_bad.bdf", &deck("XYZ"));
    let err = read_model(&path, &ImportOptions::default())
        .map(|_| ())
        .unwrap_err()
        .to_string();
    assert!(err.contains("OFFT XYZ") && err.contains("CBAR 1"), "{err}");
}

/// Offsets WA/WB (OFFT GGG, in the grids' displacement frames, the tip in a turned CD frame)
/// equal the same beam on its own grids at the offset points, each tied to its grid by an
/// RBE2 (123456): the 8 lowest frequencies of the cantilever agree to 1e-9. With lumped mass
/// an offset is an error naming the element.
#[test]
fn offsets_equal_rigid_links_to_the_offset_ends() {
    let w = [0.03, -0.02, 0.1]; // basic
    let n = 10;
    let head = "SOL 103\nCEND\nBEGIN BULK\nMAT1,1,2.1+11,,0.3,7850.\n\
                PBAR,1,1,1.2e-3,4.e-8,3.6e-7,1.e-7\nCORD2R,5,,0.,0.,0.,0.,1.,0.\n,1.,0.,0.\n";
    let x = |i: usize| LENGTH * i as f64 / n as f64;
    // The tip grid displaces in CORD2R 5 (x' = x, y' = −z, z' = y): its offset is (w1, −w3,
    // w2) there. (It is only a GB: GA's frame would also turn the orientation vector.)
    let local = |i: usize| if i == n + 1 { [w[0], -w[2], w[1]] } else { w };
    let mut offset = String::from(head);
    let mut linked = String::from(head);
    for i in 1..=n + 1 {
        let (ps, cd) = (
            if i == 1 { "123456" } else { "" },
            if i == n + 1 { "5" } else { "" },
        );
        offset += &format!("GRID,{i},,{},0.,0.,{cd},{ps}\n", x(i - 1));
        linked += &format!("GRID,{i},,{},0.,0.,,{ps}\n", x(i - 1));
        linked += &format!(
            "GRID,{},,{},{},{}\nRBE2,{},{i},123456,{}\n",
            100 + i,
            x(i - 1) + w[0],
            w[1],
            w[2],
            500 + i,
            100 + i
        );
    }
    for e in 1..=n {
        let (wa, wb) = (local(e), local(e + 1));
        offset += &format!(
            "CBAR,{e},1,{e},{},0.,1.,0.,GGG\n,,,{},{},{},{},{},{}\n",
            e + 1,
            wa[0],
            wa[1],
            wa[2],
            wb[0],
            wb[1],
            wb[2]
        );
        linked += &format!("CBAR,{e},1,{},{},0.,1.,0.\n", 100 + e, 101 + e);
    }
    let f_o = frequencies(&write(
        "offsets",
        "offset.bdf",
        &(offset.clone() + "ENDDATA\n"),
    ));
    let f_l = frequencies(&write("offsets", "linked.bdf", &(linked + "ENDDATA\n")));
    for k in 0..8 {
        println!(
            "mode {}: offset {:.6} Hz, RBE2 links {:.6} Hz",
            k + 1,
            f_o[k],
            f_l[k]
        );
        assert!(
            (f_o[k] - f_l[k]).abs() < 1e-9 * f_l[k],
            "mode {}: {} vs {}",
            k + 1,
            f_o[k],
            f_l[k]
        );
    }
    // Lumped mass: an error naming the element.
    let path = write("offsets", "offset_lumped.bdf", &(offset + "ENDDATA\n"));
    let model = read_model(&path, &ImportOptions::default()).unwrap();
    let spec = AssemblySpec {
        mass: MassKind::Lumped,
        ..Default::default()
    };
    let err = assemble(&model, &spec).map(|_| ()).unwrap_err().to_string();
    assert!(err.contains("offsets WA/WB with lumped mass"), "{err}");
}
