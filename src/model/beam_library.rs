//! Nastran's standard beam cross-sections (PBARL/PBEAML TYPE, GROUP MSCBML0): A, I1, I2, I12,
//! J and the shear factors K1, K2 of each shape from its dimensions DIM1…DIMn.
//!
//! Frame (MSC QRG "PBARL", Figure 1): the shapes are drawn with element y up and element z to
//! the right, so a width is along z and a height along y. I1 = ∫(y−ȳ)² dA bends in plane 1
//! (element x–y, about z), I2 = ∫(z−z̄)² dA in plane 2, I12 = ∫(y−ȳ)(z−z̄) dA. BAR: DIM1 the
//! width (z), DIM2 the height (y), so I1 = DIM1·DIM2³/12 as the QRG states.
//!
//! * A, I1, I2, I12 are exact for the drawn geometry: every shape is cut into rectangles (and
//!   the two triangles of HEXA) whose moments are summed by Green's theorem (polygon area
//!   moments, e.g. Steger 1996 "On the calculation of arbitrary moments of polygons"); ROD and
//!   TUBE are circles. The areas equal the QRG's area formulas (tested).
//! * I12 ≠ 0 (L, Z, BOX1 and DBOX with unequal walls): the sign is that of the legs along +y
//!   and +z as drawn. The element bends about the principal axes (`principal_axes`).
//! * J: ROD/TUBE/TUBE2 exact (polar); BAR Roark's rectangle (Table 10.7 case 4); closed walls
//!   (BOX, BOX1, HAT1's cell, DBOX's two cells) Bredt–Batho on the wall mid-lines (DBOX: the
//!   two-cell shear flows); HEXA Saint-Venant's approximation J ≈ A⁴/(4π² I_p); open
//!   thin-walled shapes Σ b t³/3 over the rectangles. Nastran does not publish its J of these
//!   shapes; these are the textbook values (Roark, 7th ed., Tables 10.1, 10.7).
//! * K1, K2 (shear factors for shear in plane 1 along y, plane 2 along z): ROD 0.9 as Simcenter
//!   Nastran 2019.2 prints it for PBARL ROD (User Information Message 4379 of the external
//!   reference `nastran/beam_modes`); BAR and HEXA 5/6 (compact solid); TUBE/TUBE2 0.5 (thin
//!   circular tube); every other shape the web-area rule NX Nastran's element library states
//!   for L and CHAN (K1 = area of the walls along y / A, K2 = walls along z / A). They are used
//!   only when I12 = 0: Nastran ignores K1, K2 when I12 ≠ 0 (QRG PBAR Remark 4).
//! * The element's axis is the shape's shear centre (QRG PBARL Remark 4); the properties are
//!   centroidal. PBARL does not offset the neutral axis from the shear centre (as in Nastran);
//!   `centroid_on_shear_centre` tells whether the two coincide (PBEAML needs them to).

use std::f64::consts::PI;

/// The section constants a library shape gives its equivalent PBAR/PBEAM.
#[derive(Debug, Clone, PartialEq)]
pub struct LibrarySection {
    /// Area A.
    pub area: f64,
    /// I1 = ∫(y−ȳ)² dA (plane 1, about element z).
    pub i1: f64,
    /// I2 = ∫(z−z̄)² dA (plane 2, about element y).
    pub i2: f64,
    /// I12 = ∫(y−ȳ)(z−z̄) dA.
    pub i12: f64,
    /// Torsion constant J (module doc).
    pub j: f64,
    /// Shear factors K1, K2 (module doc).
    pub shear_factors: [f64; 2],
    /// Whether the centroid (neutral axis) is on the shear centre for these dimensions.
    pub centroid_on_shear_centre: bool,
}

/// The shapes of the library and their dimension counts (QRG PBARL TYPE).
pub const SHAPES: &[(&str, usize)] = &[
    ("ROD", 1),
    ("TUBE", 2),
    ("TUBE2", 2),
    ("I", 6),
    ("CHAN", 4),
    ("T", 4),
    ("BOX", 4),
    ("BAR", 2),
    ("CROSS", 4),
    ("H", 4),
    ("T1", 4),
    ("I1", 4),
    ("CHAN1", 4),
    ("Z", 4),
    ("CHAN2", 4),
    ("T2", 4),
    ("BOX1", 6),
    ("HEXA", 3),
    ("HAT", 4),
    ("HAT1", 5),
    ("DBOX", 10),
    ("L", 4),
];

/// The number of dimensions of library shape `ty`; `None` if it is not one.
pub fn dimension_count(ty: &str) -> Option<usize> {
    SHAPES.iter().find(|s| s.0 == ty).map(|s| s.1)
}

/// An axis-aligned rectangle z0..z1 × y0..y1 (a wall of a shape), with its name for errors.
#[derive(Debug, Clone, Copy)]
struct Rect {
    z: [f64; 2],
    y: [f64; 2],
    name: &'static str,
}

fn rect(name: &'static str, z0: f64, z1: f64, y0: f64, y1: f64) -> Rect {
    Rect {
        z: [z0, z1],
        y: [y0, y1],
        name,
    }
}

impl Rect {
    fn width(&self) -> f64 {
        self.z[1] - self.z[0]
    }
    fn height(&self) -> f64 {
        self.y[1] - self.y[0]
    }
    fn polygon(&self) -> Vec<[f64; 2]> {
        let ([z0, z1], [y0, y1]) = (self.z, self.y);
        vec![[z0, y0], [z1, y0], [z1, y1], [z0, y1]]
    }
}

/// Moments of a counter-clockwise polygon of (z, y) vertices about the origin:
/// [A, ∫z dA, ∫y dA, ∫y² dA, ∫z² dA, ∫yz dA] (Green's theorem, Steger 1996 eqs. 3–5).
fn polygon_moments(p: &[[f64; 2]]) -> [f64; 6] {
    let mut m = [0.0; 6];
    for i in 0..p.len() {
        let ([z0, y0], [z1, y1]) = (p[i], p[(i + 1) % p.len()]);
        let c = z0 * y1 - z1 * y0;
        m[0] += c / 2.0;
        m[1] += c * (z0 + z1) / 6.0;
        m[2] += c * (y0 + y1) / 6.0;
        m[3] += c * (y0 * y0 + y0 * y1 + y1 * y1) / 12.0;
        m[4] += c * (z0 * z0 + z0 * z1 + z1 * z1) / 12.0;
        m[5] += c * (z0 * y1 + 2.0 * z0 * y0 + 2.0 * z1 * y1 + z1 * y0) / 24.0;
    }
    m
}

/// (A, I1, I2, I12) about the centroid of polygons (counter-clockwise, not overlapping).
fn centroidal(polys: &[Vec<[f64; 2]>]) -> (f64, f64, f64, f64) {
    let mut m = [0.0; 6];
    for p in polys {
        for (a, b) in m.iter_mut().zip(polygon_moments(p)) {
            *a += b;
        }
    }
    let [a, sz, sy, yy, zz, yz] = m;
    let (zc, yc) = (sz / a, sy / a);
    (a, yy - a * yc * yc, zz - a * zc * zc, yz - a * yc * zc)
}

/// Σ b t³/3 over the walls (open thin-walled torsion constant).
fn open_torsion(walls: &[Rect]) -> f64 {
    (walls.iter())
        .map(|r| {
            let (b, t) = (r.width().max(r.height()), r.width().min(r.height()));
            b * t.powi(3) / 3.0
        })
        .sum()
}

/// Bredt–Batho single cell: J = 4 A_m² / ∮ ds/t (`sides`: (length, thickness) of the
/// mid-line sides).
fn bredt(area_m: f64, sides: &[(f64, f64)]) -> f64 {
    4.0 * area_m * area_m / sides.iter().map(|(s, t)| s / t).sum::<f64>()
}

/// The walls of shape `ty` with dimensions `d` (QRG PBARL Figure 1; y up, z right).
fn walls(ty: &str, d: &[f64]) -> Vec<Rect> {
    let x = |k: usize| d[k - 1];
    match ty {
        "BAR" => vec![rect("bar", 0.0, x(1), 0.0, x(2))],
        // Width DIM1, height DIM2, top/bottom walls DIM3, side walls DIM4.
        "BOX" => {
            let (w, h, tf, ts) = (x(1), x(2), x(3), x(4));
            vec![
                rect("bottom wall", 0.0, w, 0.0, tf),
                rect("top wall", 0.0, w, h - tf, h),
                rect("left wall", 0.0, ts, tf, h - tf),
                rect("right wall", w - ts, w, tf, h - tf),
            ]
        }
        // Width DIM1, height DIM2, top DIM3, bottom DIM4, left DIM5, right DIM6 walls.
        "BOX1" => {
            let (w, h) = (x(1), x(2));
            let (tt, tb, tl, tr) = (x(3), x(4), x(5), x(6));
            vec![
                rect("bottom wall", 0.0, w, 0.0, tb),
                rect("top wall", 0.0, w, h - tt, h),
                rect("left wall", 0.0, tl, tb, h - tt),
                rect("right wall", w - tr, w, tb, h - tt),
            ]
        }
        // Height DIM1, bottom flange DIM2 × DIM5, top flange DIM3 × DIM6, web DIM4.
        "I" => {
            let (h, wb, wt, tw, tb, tt) = (x(1), x(2), x(3), x(4), x(5), x(6));
            vec![
                rect("bottom flange", -wb / 2.0, wb / 2.0, 0.0, tb),
                rect("web", -tw / 2.0, tw / 2.0, tb, h - tt),
                rect("top flange", -wt / 2.0, wt / 2.0, h - tt, h),
            ]
        }
        // Flange overhang DIM1 (each side DIM1/2), web thickness DIM2, web height DIM3, height DIM4.
        "I1" => {
            let (o, tw, hw, h) = (x(1), x(2), x(3), x(4));
            let (w, tf) = (o + tw, (h - hw) / 2.0);
            vec![
                rect("bottom flange", -w / 2.0, w / 2.0, 0.0, tf),
                rect("web", -tw / 2.0, tw / 2.0, tf, h - tf),
                rect("top flange", -w / 2.0, w / 2.0, h - tf, h),
            ]
        }
        // Flange width DIM1 (with the web), height DIM2, web DIM3, flanges DIM4.
        "CHAN" => {
            let (w, h, tw, tf) = (x(1), x(2), x(3), x(4));
            vec![
                rect("web", 0.0, tw, 0.0, h),
                rect("bottom flange", tw, w, 0.0, tf),
                rect("top flange", tw, w, h - tf, h),
            ]
        }
        // Flange overhang DIM1, web thickness DIM2, web height DIM3, height DIM4.
        "CHAN1" => {
            let (o, tw, hw, h) = (x(1), x(2), x(3), x(4));
            let tf = (h - hw) / 2.0;
            vec![
                rect("web", 0.0, tw, 0.0, h),
                rect("bottom flange", tw, tw + o, 0.0, tf),
                rect("top flange", tw, tw + o, h - tf, h),
            ]
        }
        // Legs DIM1 thick and DIM3 high at both ends of a base DIM4 wide, DIM2 thick.
        "CHAN2" => {
            let (tl, tb, h, w) = (x(1), x(2), x(3), x(4));
            vec![
                rect("left leg", 0.0, tl, 0.0, h),
                rect("base", tl, w - tl, 0.0, tb),
                rect("right leg", w - tl, w, 0.0, h),
            ]
        }
        // Flange DIM1 × DIM3 on top of a web DIM4 thick, height DIM2.
        "T" => {
            let (w, h, tf, tw) = (x(1), x(2), x(3), x(4));
            vec![
                rect("web", -tw / 2.0, tw / 2.0, 0.0, h - tf),
                rect("flange", -w / 2.0, w / 2.0, h - tf, h),
            ]
        }
        // T2: flange DIM1 × DIM3 at the bottom, web DIM4 thick, height DIM2.
        "T2" => {
            let (w, h, tf, tw) = (x(1), x(2), x(3), x(4));
            vec![
                rect("flange", -w / 2.0, w / 2.0, 0.0, tf),
                rect("web", -tw / 2.0, tw / 2.0, tf, h),
            ]
        }
        // T1: a vertical flange DIM1 high, DIM3 thick, and a web DIM2 long, DIM4 thick.
        "T1" => {
            let (hf, lw, tf, tw) = (x(1), x(2), x(3), x(4));
            vec![
                rect("flange", 0.0, tf, -hf / 2.0, hf / 2.0),
                rect("web", tf, tf + lw, -tw / 2.0, tw / 2.0),
            ]
        }
        // Legs: DIM1 along z (DIM3 thick), DIM2 along y (DIM4 thick), corner at the origin.
        "L" => {
            let (w, h, t1, t2) = (x(1), x(2), x(3), x(4));
            vec![
                rect("horizontal leg", 0.0, w, 0.0, t1),
                rect("vertical leg", 0.0, t2, t1, h),
            ]
        }
        // Flange overhang DIM1, web thickness DIM2, web height DIM3, height DIM4; top flange
        // to the left of the web, bottom flange to the right.
        "Z" => {
            let (o, tw, hw, h) = (x(1), x(2), x(3), x(4));
            let tf = (h - hw) / 2.0;
            vec![
                rect("bottom flange", o, 2.0 * o + tw, 0.0, tf),
                rect("web", o, o + tw, tf, h - tf),
                rect("top flange", 0.0, o + tw, h - tf, h),
            ]
        }
        // Arms DIM1 long in all (DIM1/2 each side), DIM4 thick; vertical bar DIM2 × DIM3.
        "CROSS" => {
            let (la, tv, hv, ta) = (x(1), x(2), x(3), x(4));
            vec![
                rect(
                    "left arm",
                    -tv / 2.0 - la / 2.0,
                    -tv / 2.0,
                    -ta / 2.0,
                    ta / 2.0,
                ),
                rect("vertical bar", -tv / 2.0, tv / 2.0, -hv / 2.0, hv / 2.0),
                rect(
                    "right arm",
                    tv / 2.0,
                    tv / 2.0 + la / 2.0,
                    -ta / 2.0,
                    ta / 2.0,
                ),
            ]
        }
        // Two flanges DIM2/2 thick, DIM3 high, joined by a web DIM1 long, DIM4 thick.
        "H" => {
            let (lw, tf2, hf, tw) = (x(1), x(2), x(3), x(4));
            let tf = tf2 / 2.0;
            let half = lw / 2.0;
            vec![
                rect("left flange", -half - tf, -half, -hf / 2.0, hf / 2.0),
                rect("web", -half, half, -tw / 2.0, tw / 2.0),
                rect("right flange", half, half + tf, -hf / 2.0, hf / 2.0),
            ]
        }
        // Height DIM1, wall DIM2, top width DIM3 (outside), brims DIM4 beyond the walls.
        "HAT" => {
            let (h, t, w, b) = (x(1), x(2), x(3), x(4));
            let s = w / 2.0;
            vec![
                rect("left brim", -s - b, -s + t, 0.0, t),
                rect("right brim", s - t, s + b, 0.0, t),
                rect("left wall", -s, -s + t, t, h - t),
                rect("right wall", s - t, s, t, h - t),
                rect("top", -s, s, h - t, h),
            ]
        }
        // Base DIM1 wide, DIM5 thick; hat DIM2 high overall, top DIM3 wide, walls DIM4.
        "HAT1" => {
            let (w, h, wt, t, tb) = (x(1), x(2), x(3), x(4), x(5));
            let (s, e) = (wt / 2.0, w / 2.0);
            vec![
                rect("base", -e, e, 0.0, tb),
                rect("left brim", -e, -s + t, tb, tb + t),
                rect("right brim", s - t, e, tb, tb + t),
                rect("left wall", -s, -s + t, tb + t, h - t),
                rect("right wall", s - t, s, tb + t, h - t),
                rect("top", -s, s, h - t, h),
            ]
        }
        // Width DIM1, height DIM2, left cell to DIM3 (the middle wall's centre); walls: left
        // DIM4, middle DIM5, right DIM6; left cell top DIM7, bottom DIM8; right cell top DIM9,
        // bottom DIM10.
        "DBOX" => {
            let (w, h, c) = (x(1), x(2), x(3));
            let (tl, tm, tr) = (x(4), x(5), x(6));
            let (t1t, t1b, t2t, t2b) = (x(7), x(8), x(9), x(10));
            let (m0, m1) = (c - tm / 2.0, c + tm / 2.0);
            vec![
                rect("left wall", 0.0, tl, t1b, h - t1t),
                rect("left cell bottom", 0.0, c, 0.0, t1b),
                rect("left cell top", 0.0, c, h - t1t, h),
                rect("middle wall (left half)", m0, c, t1b, h - t1t),
                rect("middle wall (right half)", c, m1, t2b, h - t2t),
                rect("right cell bottom", c, w, 0.0, t2b),
                rect("right cell top", c, w, h - t2t, h),
                rect("right wall", w - tr, w, t2b, h - t2t),
            ]
        }
        // HEXA's central rectangle; its two triangles are added by `polygons`.
        "HEXA" => {
            let (tri, w, h) = (x(1), x(2), x(3));
            let s = w / 2.0 - tri;
            vec![rect("central rectangle", -s, s, -h / 2.0, h / 2.0)]
        }
        _ => Vec::new(),
    }
}

/// The section of library shape `ty` (upper case) with dimensions `d` (exactly its count);
/// an error text naming the inconsistent dimension or wall otherwise.
pub fn library_section(ty: &str, d: &[f64]) -> Result<LibrarySection, String> {
    let n = dimension_count(ty).ok_or_else(|| {
        let names: Vec<&str> = SHAPES.iter().map(|s| s.0).collect();
        format!(
            "cross-section TYPE {ty} is not a shape of Nastran's beam library ({})",
            names.join(", ")
        )
    })?;
    if d.len() != n {
        return Err(format!(
            "TYPE {ty} has {n} dimensions, the card gives {}",
            d.len()
        ));
    }
    if let Some(k) = d.iter().position(|&v| v.is_nan() || v <= 0.0) {
        return Err(format!("TYPE {ty}: DIM{} = {} must be > 0", k + 1, d[k]));
    }
    let x = |k: usize| d[k - 1];
    let round = |r: f64, ri: f64, k: [f64; 2]| {
        let ip = PI * (r.powi(4) - ri.powi(4)) / 4.0;
        LibrarySection {
            area: PI * (r * r - ri * ri),
            i1: ip,
            i2: ip,
            i12: 0.0,
            j: 2.0 * ip,
            shear_factors: k,
            centroid_on_shear_centre: true,
        }
    };
    match ty {
        "ROD" => return Ok(round(x(1), 0.0, [0.9, 0.9])),
        "TUBE" | "TUBE2" => {
            let ri = if ty == "TUBE" { x(2) } else { x(1) - x(2) };
            if ri <= 0.0 || ri >= x(1) {
                return Err(format!(
                    "TYPE {ty}: the inner radius {ri} must be between 0 and the outer radius DIM1 = {}",
                    x(1)
                ));
            }
            return Ok(round(x(1), ri, [0.5, 0.5]));
        }
        _ => {}
    }
    let walls = walls(ty, d);
    if let Some(r) = walls.iter().find(|r| r.width() <= 0.0 || r.height() <= 0.0) {
        return Err(format!(
            "TYPE {ty}: the dimensions {d:?} leave the {} with size {} × {} (no material)",
            r.name,
            r.width(),
            r.height()
        ));
    }
    for (k, a) in walls.iter().enumerate() {
        for b in &walls[k + 1..] {
            let dz = a.z[1].min(b.z[1]) - a.z[0].max(b.z[0]);
            let dy = a.y[1].min(b.y[1]) - a.y[0].max(b.y[0]);
            if dz > 0.0 && dy > 0.0 {
                return Err(format!(
                    "TYPE {ty}: the dimensions {d:?} make the {} and the {} overlap",
                    a.name, b.name
                ));
            }
        }
    }
    let mut polys: Vec<Vec<[f64; 2]>> = walls.iter().map(Rect::polygon).collect();
    if ty == "HEXA" {
        let (tri, w, h) = (x(1), x(2), x(3));
        let s = w / 2.0 - tri;
        polys.push(vec![[s, -h / 2.0], [w / 2.0, 0.0], [s, h / 2.0]]);
        polys.push(vec![[-s, -h / 2.0], [-s, h / 2.0], [-w / 2.0, 0.0]]);
    }
    let (area, i1, i2, i12) = centroidal(&polys);
    let web = |vertical: bool| {
        let a: f64 = (walls.iter())
            .filter(|r| (r.height() > r.width()) == vertical && r.height() != r.width())
            .map(|r| r.width() * r.height())
            .sum();
        a / area
    };
    let shear_factors = match ty {
        "BAR" | "HEXA" => [5.0 / 6.0; 2],
        _ => [web(true), web(false)],
    };
    Ok(LibrarySection {
        area,
        i1,
        i2,
        i12: if i12.abs() <= 1e-12 * (i1 * i2).sqrt() {
            0.0
        } else {
            i12
        },
        j: torsion(ty, d, &walls, area, i1 + i2),
        shear_factors,
        centroid_on_shear_centre: symmetric_about_centre(ty, d),
    })
}

/// Whether the shape is symmetric about both axes or about its centre (then its centroid is
/// its shear centre).
fn symmetric_about_centre(ty: &str, d: &[f64]) -> bool {
    match ty {
        "BAR" | "BOX" | "I1" | "H" | "CROSS" | "HEXA" | "Z" => true,
        "I" => d[1] == d[2] && d[4] == d[5],
        "BOX1" => d[2] == d[3] && d[4] == d[5],
        "DBOX" => {
            d[2] * 2.0 == d[0] && d[3] == d[5] && d[6] == d[7] && d[7] == d[8] && d[8] == d[9]
        }
        _ => false,
    }
}

/// Torsion constant J of a non-circular shape (module doc).
fn torsion(ty: &str, d: &[f64], walls: &[Rect], area: f64, ip: f64) -> f64 {
    let x = |k: usize| d[k - 1];
    match ty {
        "BAR" => crate::model::section::rect_torsion(x(1), x(2)),
        "HEXA" => area.powi(4) / (4.0 * PI * PI * ip),
        "BOX" => {
            let (w, h, tf, ts) = (x(1), x(2), x(3), x(4));
            let (wm, hm) = (w - ts, h - tf);
            bredt(wm * hm, &[(wm, tf), (wm, tf), (hm, ts), (hm, ts)])
        }
        "BOX1" => {
            let (w, h) = (x(1), x(2));
            let (tt, tb, tl, tr) = (x(3), x(4), x(5), x(6));
            let (wm, hm) = (w - (tl + tr) / 2.0, h - (tt + tb) / 2.0);
            bredt(wm * hm, &[(wm, tt), (wm, tb), (hm, tl), (hm, tr)])
        }
        "HAT1" => {
            // The cell (top, walls, base between the walls) plus the open brims on the base.
            let (w, h, wt, t, tb) = (x(1), x(2), x(3), x(4), x(5));
            let (wm, hm) = (wt - t, h - t / 2.0 - tb / 2.0);
            let b = (w - wt) / 2.0;
            bredt(wm * hm, &[(wm, t), (wm, tb), (hm, t), (hm, t)])
                + 2.0 * b * (t + tb).powi(3) / 3.0
        }
        "DBOX" => {
            let (w, h, c) = (x(1), x(2), x(3));
            let (tl, tm, tr) = (x(4), x(5), x(6));
            let (t1t, t1b, t2t, t2b) = (x(7), x(8), x(9), x(10));
            let (w1, w2) = (c - tl / 2.0, w - c - tr / 2.0);
            let (h1, h2) = (h - (t1t + t1b) / 2.0, h - (t2t + t2b) / 2.0);
            let hs = (h1 + h2) / 2.0;
            // Two-cell shear flows at unit Gθ: [δ11 −δ12; −δ12 δ22] q = 2 A (Megson, Aircraft
            // Structures, §18.3); J = 2 Σ A_i q_i.
            let (a1, a2) = (w1 * h1, w2 * h2);
            let d12 = hs / tm;
            let d11 = h1 / tl + w1 / t1t + w1 / t1b + d12;
            let d22 = h2 / tr + w2 / t2t + w2 / t2b + d12;
            let det = d11 * d22 - d12 * d12;
            let q1 = (2.0 * a1 * d22 + 2.0 * a2 * d12) / det;
            let q2 = (2.0 * a2 * d11 + 2.0 * a1 * d12) / det;
            2.0 * (a1 * q1 + a2 * q2)
        }
        _ => open_torsion(walls),
    }
}

/// The principal second moments (I_y', I_z') and the angle θ (radians, about element x from
/// y towards z) of the principal frame y' = y cos θ + z sin θ of a section with I1, I2, I12:
/// tan 2θ = 2 I12 / (I1 − I2) makes I12' = ½(I2 − I1) sin 2θ + I12 cos 2θ vanish (Mohr's
/// circle). Returns (I1', I2', θ) with I1' = ∫y'² dA.
pub fn principal_axes(i1: f64, i2: f64, i12: f64) -> (f64, f64, f64) {
    let theta = 0.5 * (2.0 * i12).atan2(i1 - i2);
    let (s, c) = theta.sin_cos();
    let i1p = i1 * c * c + i2 * s * s + 2.0 * i12 * s * c;
    let i2p = i1 * s * s + i2 * c * c - 2.0 * i12 * s * c;
    (i1p, i2p, theta)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: f64, b: f64, tol: f64) -> bool {
        (a - b).abs() <= tol * b.abs().max(1e-300)
    }

    /// The areas equal the QRG's area formulas (QRG PBARL Figure 1) for every shape.
    #[test]
    fn areas_equal_the_qrg_area_formulas() {
        for &(ty, n) in SHAPES {
            let dims: Vec<f64> = match ty {
                "TUBE" | "TUBE2" => vec![3.0, 1.0],
                "HEXA" => vec![1.0, 8.0, 4.0],
                "HAT1" => vec![10.0, 8.0, 6.0, 1.0, 1.2],
                "DBOX" => vec![10.0, 8.0, 4.0, 1.0, 1.2, 0.9, 0.8, 0.7, 0.6, 0.5],
                "BOX" | "BOX1" => vec![10.0, 8.0, 1.0, 1.2, 0.9, 0.8][..n].to_vec(),
                "I" => vec![10.0, 8.0, 6.0, 1.0, 1.2, 0.9],
                "HAT" => vec![10.0, 1.0, 6.0, 3.0],
                "CHAN2" => vec![1.0, 1.5, 6.0, 9.0],
                "T1" => vec![10.0, 8.0, 1.0, 1.5],
                "CROSS" | "H" => vec![10.0, 2.0, 6.0, 1.0],
                _ => vec![10.0, 8.0, 1.0, 1.5][..n].to_vec(),
            };
            let s = library_section(ty, &dims).unwrap_or_else(|e| panic!("{ty}: {e}"));
            let mut d = [0.0; 10];
            d[..dims.len()].copy_from_slice(&dims);
            let want = area_formula(ty, d);
            assert!(
                close(s.area, want, 1e-12),
                "{ty}: A = {} want {want}",
                s.area
            );
        }
    }

    fn area_formula(ty: &str, d: [f64; 10]) -> f64 {
        let [d1, d2, d3, d4, d5, d6, d7, d8, d9, d10] = d;
        match ty {
            "ROD" => PI * d1 * d1,
            "TUBE" => PI * (d1 * d1 - d2 * d2),
            "TUBE2" => PI * (d1 * d1 - (d1 - d2).powi(2)),
            "I" => d3 * d6 + d2 * d5 + (d1 - (d5 + d6)) * d4,
            "I1" | "CHAN1" | "Z" => d2 * d3 + (d4 - d3) * (d1 + d2),
            "CHAN" => 2.0 * d1 * d4 + (d2 - 2.0 * d4) * d3,
            "CHAN2" => 2.0 * d1 * d3 + (d4 - 2.0 * d1) * d2,
            "T" | "T2" => d1 * d3 + (d2 - d3) * d4,
            "T1" => d1 * d3 + d2 * d4,
            "BOX" => 2.0 * d1 * d3 + 2.0 * (d2 - 2.0 * d3) * d4,
            "BOX1" => d2 * d6 + d2 * d5 + (d1 - d5 - d6) * d3 + (d1 - d5 - d6) * d4,
            "BAR" => d1 * d2,
            "CROSS" => d2 * d3 + 2.0 * (0.5 * d1) * d4,
            "H" => 2.0 * (0.5 * d2) * d3 + d1 * d4,
            "HEXA" => (d2 - 2.0 * d1) * d3 + d3 * d1,
            "HAT" => d2 * d3 + 2.0 * (d1 - d2) * d2 + 2.0 * d2 * d4,
            "HAT1" => d1 * d5 + d3 * d4 + (d1 - d3) * d4 + 2.0 * (d2 - d5 - d4) * d4,
            "DBOX" => {
                (d2 * d3 - (d2 - d7 - d8) * (d3 - (0.5 * d5 + d4)))
                    + ((d1 - d3) * d2 - (d2 - (d9 + d10)) * (d1 - d3 - 0.5 * d5 - d6))
            }
            "L" => d1 * d3 + (d2 - d3) * d4,
            _ => unreachable!(),
        }
    }
}
