//! ANSYS nodal coordinate systems (NBLOCK angles, `D`/`F`/`CE`/`CP` in them), archives written
//! here, through the CLI, each against an independent reference:
//! - a LINK180 bar whose end node is rotated by three angles and held in its nodal Y and Z:
//!   frequency and static response to a nodal-X force against closed form (the documented
//!   rotation order);
//! - SOLID185 with rotated nodes, `D`, `F`, `CP` and `CE` on them against Nastran CHEXA with
//!   CORD2R, GRID CD, SPC1, FORCE (CID) and MPC; SOLID186 with rotated nodes against C3D20R
//!   with `*TRANSFORM`;
//! - ESYS elements, a rigid link on a rotated node and a full file over rotated nodes refused.

use std::collections::BTreeMap;

use crate::ansys_support::writers::{
    block, block_archive, build_body as build, ccx_deck, eblock, frequency_difference,
    lumped_load_differences, material, nblock, root, static_response, RESIDUALS, STEEL,
};
use crate::common::{exe, scratch};

/// The nodal X axis of the angles [THXY, THYZ, THZX] (degrees) as the N command states them:
/// first about nodal Z, then about the new X, then about the new Y — A = R_z R_x R_y, its
/// first column written out.
fn nodal_x([a, b, c]: [f64; 3]) -> [f64; 3] {
    let [a, b, c] = [a, b, c].map(f64::to_radians);
    [
        a.cos() * c.cos() - a.sin() * b.sin() * c.sin(),
        a.sin() * c.cos() + a.cos() * b.sin() * c.sin(),
        -b.cos() * c.sin(),
    ]
}

/// A LINK180 bar from node 1 (held) to node 2 along x with a MASS21 on node 2; node 2 rotated
/// by (THXY, THYZ, THZX) = (35°, 25°, 40°) and held in its nodal UY and UZ moves only along
/// its nodal X: ω² = (EA/L)(X·eₓ)² / (m + ρAL/2) (lumped), and the force F in nodal X moves it
/// by F / ((EA/L)(X·eₓ)²) along X (global components checked).
#[test]
fn a_bar_on_a_rotated_roller_equals_the_closed_form() {
    let (l, area, m) = (0.5, 1.0e-4, 3.0);
    let [e, _, rho] = STEEL;
    let angles = [35.0, 25.0, 40.0];
    let force = 1.0e3;
    let text = format!(
        "/PREP7\nET,1,180\nET,2,21\nKEYOPT,2,3,2\nR,1,{area:e}\nR,2,{m:e}\n{}{}{}\
         D,1,ALL,0\nD,2,UY,0\nD,2,UZ,0\nLUMPM,ON\nF,2,FX,{force:e}\nFINISH\n",
        nblock(&[(1, [0.0; 3], [0.0; 3]), (2, [l, 0.0, 0.0], angles)]),
        eblock(&[(1, 1, vec![1, 2]), (2, 2, vec![2])]),
        material(STEEL)
    );
    let work = scratch("ansys-rotated-roller");
    let cdb = work.join("roller.cdb");
    std::fs::write(&cdb, text).unwrap();
    let body = build(&cdb, 1, &RESIDUALS);
    let x = nodal_x(angles);
    let k = e * area / l * x[0] * x[0];
    let w2 = k / (m + rho * area * l / 2.0);
    let f = body.modes.omega2[0];
    let u = static_response(&body, 0)[&2];
    let expected = x.map(|c| c * force / k);
    let off_w = (f - w2).abs() / w2;
    let off_u = (0..3)
        .map(|c| (u[c] - expected[c]).abs() / (force / k))
        .fold(0.0, f64::max);
    println!("rotated roller: ω² {f:.9e} against {w2:.9e} ({off_w:.2e}); u {u:?} against {expected:?} ({off_u:.2e})");
    // measured 0 and 2.5e-16
    assert!(off_w < 3e-15 && off_u < 3e-15, "{off_w} {off_u}");
    // with the angles ignored the bar would be held in y and z only: its ω² is (EA/L)/(m+…)
    assert!((w2 - e * area / l / (m + rho * area * l / 2.0)).abs() > 0.1 * w2);
}

/// SOLID185 (KEYOPT(2)=3) with rotated end nodes, `D` (nodal UY), `F` (nodal FX), `CP` (nodal
/// UZ) and `CE` (nodal UX of one against nodal UY of another) on them, against Nastran CHEXA
/// (its incompatible modes, the same element) with a CORD2R per rotation, GRID CD, SPC1 in the
/// CD frame, FORCE along the CORD2R's x and MPC: frequencies and static responses equal.
#[test]
fn rotated_nodes_equal_nastran_cd_frames() {
    let m = block([4, 1, 1], [0.8, 0.2, 0.2], false);
    let end: Vec<u64> = (m.nodes.iter())
        .filter(|(_, x)| x[0] == 0.8)
        .map(|(&id, _)| id)
        .collect();
    assert_eq!(end.len(), 4);
    let rotations = [[30.0, 20.0, 10.0], [-15.0, 40.0, 5.0]];
    let angles: BTreeMap<u64, [f64; 3]> = (end.iter().enumerate())
        .map(|(k, &n)| (n, rotations[k % 2]))
        .collect();
    let clamp: String = root(&m).iter().map(|n| format!("D,{n},ALL,0\n")).collect();
    let extra = format!(
        "{clamp}D,{a},UY,0\nF,{b},FX,2.0e5\nF,{c},FY,-1.0e5\nCP,1,UZ,{b},{c}\n\
         CE,R5.0,DEFI,       2,       1,  0.00000000    \n\
         CE,R5.0,NODE,{d:>9},UX  ,  1.00000000    ,{a:>9},UY  , -2.00000000    \n",
        a = end[0],
        b = end[1],
        c = end[2],
        d = end[3]
    );
    let work = scratch("ansys-rotated-nastran");
    let cdb = work.join("rotated.cdb");
    let et = "ET,1,185\nKEYOPT,1,2,3\n";
    std::fs::write(&cdb, block_archive(&m, et, &angles, &extra)).unwrap();
    // Nastran: CORD2R 1, 2 from the nodal axes computed here from the documented order
    let axes = |r: [f64; 3]| {
        let x = nodal_x(r);
        // nodal Z: A e_z = R_z R_x (sin c, 0, cos c)
        let [a, b, c] = r.map(f64::to_radians);
        let z = [
            a.cos() * c.sin() + a.sin() * b.sin() * c.cos(),
            a.sin() * c.sin() - a.cos() * b.sin() * c.cos(),
            b.cos() * c.cos(),
        ];
        (x, z)
    };
    let [e, nu, rho] = STEEL;
    let mut d = String::from("SOL 103\nCEND\nSPC = 1\nMPC = 1\nLOAD = 1\nBEGIN BULK\n");
    for (k, r) in rotations.iter().enumerate() {
        let (x, z) = axes(*r);
        d += &format!(
            "CORD2R,{},0,0.,0.,0.,{:.16e},{:.16e},{:.16e},+\n+,{:.16e},{:.16e},{:.16e}\n",
            k + 1,
            z[0],
            z[1],
            z[2],
            x[0],
            x[1],
            x[2]
        );
    }
    for (id, x) in &m.nodes {
        let cd = end.iter().position(|n| n == id).map_or(0, |k| k % 2 + 1);
        d += &format!("GRID,{id},,{:?},{:?},{:?},{cd}\n", x[0], x[1], x[2]);
    }
    for (k, el) in m.elements.iter().enumerate() {
        let ids: Vec<String> = el.iter().map(u64::to_string).collect();
        d += &format!(
            "CHEXA,{},1,{},+\n+,{}\n",
            k + 1,
            ids[..6].join(","),
            ids[6..].join(",")
        );
    }
    d += &format!("PSOLID,1,1\nMAT1,1,{e:?},,{nu:?},{rho:?}\n");
    for n in root(&m) {
        d += &format!("SPC1,1,123,{n}\n");
    }
    let (a, b, c, dd) = (end[0], end[1], end[2], end[3]);
    d += &format!("SPC1,1,2,{a}\n");
    d += &format!("FORCE,1,{b},2,2.0e5,1.,0.,0.\nFORCE,1,{c},1,1.0e5,0.,-1.,0.\n");
    d += &format!("MPC,1,{c},3,1.,{b},3,-1.\nMPC,1,{dd},1,1.,{a},2,-2.\nENDDATA\n");
    let bdf = work.join("rotated.bdf");
    std::fs::write(&bdf, d).unwrap();
    let (modes, worst) = lumped_load_differences(&cdb, &bdf, 8);
    // the same archive without the angles is another body
    let plain = work.join("plain.cdb");
    std::fs::write(&plain, block_archive(&m, et, &BTreeMap::new(), &extra)).unwrap();
    let (unrotated, _) = lumped_load_differences(&plain, &bdf, 8);
    println!("rotated nodes against Nastran CD: frequencies {modes:.2e}, static {worst:.2e} (without the angles {unrotated:.2e})");
    // measured 2.1e-15 and 7.7e-15
    assert!(modes < 3e-14 && worst < 8e-14, "{modes} {worst}");
    assert!(unrotated > 1e-4, "{unrotated}");
}

/// An isotropic element with an element coordinate system (ESYS naming a LOCAL) is the same
/// body (the system orients only an orthotropic material, tests/ansys_orthotropic.rs); an ESYS
/// naming no system of the archive is refused naming it; an MPC184 rigid link on a rotated node
/// is refused (its equation is formed on global components).
#[test]
fn esys_elements_are_refused_naming_their_local() {
    let m = block([2, 1, 1], [0.4, 0.2, 0.2], false);
    let work = scratch("ansys-esys");
    let et = "ET,1,185\nKEYOPT,1,2,3\nLOCAL,11,0,0.,0.,0.,30.,0.,0.\n";
    let clamp: String = root(&m).iter().map(|n| format!("D,{n},ALL,0\n")).collect();
    let plain = block_archive(&m, et, &BTreeMap::new(), &clamp);
    // element 2's ESYS field (the fifth) names system `esys`
    let with_esys = |esys: u64| {
        plain.replacen(
            "        1        1        1        1        0        0        0        0        8        0        2",
            &format!("        1        1        1        1{esys:>9}        0        0        0        8        0        2"),
            1,
        )
    };
    let (a, b) = (work.join("plain.cdb"), work.join("esys.cdb"));
    std::fs::write(&a, &plain).unwrap();
    std::fs::write(&b, with_esys(11)).unwrap();
    let diff = frequency_difference(&build(&a, 4, &[]), &build(&b, 4, &[]), 4);
    assert!(diff == 0.0, "{diff}");
    let cdb = work.join("undefined.cdb");
    std::fs::write(&cdb, with_esys(12)).unwrap();
    let o = exe()
        .arg("build")
        .arg(&cdb)
        .args(["--units", "si", "--method", "normal", "--modes", "4", "-o"])
        .arg(work.join("esys.flexbody"))
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.contains("element coordinate system 12 (no LOCAL of the archive defines it)"),
        "{err}"
    );
    let link = work.join("link.cdb");
    let text = format!(
        "/PREP7\nET,1,184\nET,2,21\nKEYOPT,2,3,2\nR,2,1.0\n{}{}D,1,ALL,0\nFINISH\n",
        nblock(&[
            (1, [0.0; 3], [30.0, 0.0, 0.0]),
            (2, [1.0, 0.0, 0.0], [0.0; 3])
        ]),
        eblock(&[(1, 1, vec![1, 2]), (2, 2, vec![2])])
    );
    std::fs::write(&link, text).unwrap();
    let o = exe()
        .arg("build")
        .arg(&link)
        .args(["--units", "si", "--method", "normal", "--modes", "1", "-o"])
        .arg(work.join("link.flexbody"))
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.contains("MPC184 rigid link on a node with a nodal coordinate system"),
        "{err}"
    );
}

/// The nodal Y axis of the angles (A e_y = R_z R_x e_y, written out).
fn nodal_y([a, b, _]: [f64; 3]) -> [f64; 3] {
    let [a, b] = [a, b].map(f64::to_radians);
    [-a.sin() * b.cos(), a.cos() * b.cos(), b.sin()]
}

/// SOLID186 with its end face's nodes rotated (two angle triples), `D` (nodal UY), `CP` (nodal
/// UZ) and `CE` on them, against the same mesh as C3D20R with a `*TRANSFORM` (TYPE=R, the
/// nodal X and Y axes) per rotated node, `*BOUNDARY` and `*EQUATION` in the transformed
/// system (lumped mass: the same element matrices through both importers): frequencies equal.
#[test]
fn rotated_nodes_equal_abaqus_transform() {
    // two elements across (one C3D20R layer has zero-energy modes of its own)
    let m = block([4, 2, 2], [0.8, 0.2, 0.2], true);
    let end: Vec<u64> = (m.nodes.iter())
        .filter(|(_, x)| x[0] == 0.8)
        .map(|(&id, _)| id)
        .collect();
    assert_eq!(end.len(), 21);
    let rotations = [[30.0, 20.0, 10.0], [-15.0, 40.0, 5.0]];
    let angles: BTreeMap<u64, [f64; 3]> = (end.iter().enumerate())
        .map(|(k, &n)| (n, rotations[k % 2]))
        .collect();
    let clamp: String = root(&m).iter().map(|n| format!("D,{n},ALL,0\n")).collect();
    let (a, b, c, d) = (end[0], end[1], end[2], end[3]);
    let extra = format!(
        "{clamp}D,{a},UY,0\nCP,1,UZ,{b},{c}\n\
         CE,R5.0,DEFI,       2,       1,  0.00000000    \n\
         CE,R5.0,NODE,{d:>9},UX  ,  1.00000000    ,{a:>9},UY  , -2.00000000    \nLUMPM,ON\n"
    );
    let work = scratch("ansys-rotated-abaqus");
    let cdb = work.join("rotated.cdb");
    std::fs::write(&cdb, block_archive(&m, "ET,1,186\n", &angles, &extra)).unwrap();
    let mut keywords = String::new();
    for (n, r) in &angles {
        let (x, y) = (nodal_x(*r), nodal_y(*r));
        keywords.push_str(&format!(
            "*NSET, NSET=R{n}\n{n}\n*TRANSFORM, NSET=R{n}, TYPE=R\n{:.17e}, {:.17e}, {:.17e}, \
             {:.17e}, {:.17e}, {:.17e}\n",
            x[0], x[1], x[2], y[0], y[1], y[2]
        ));
    }
    keywords.push_str(&format!(
        "*BOUNDARY\n{a}, 2, 2\n*EQUATION\n2\n{c}, 3, 1.0, {b}, 3, -1.0\n2\n{d}, 1, 1.0, {a}, 2, -2.0\n"
    ));
    let inp = work.join("rotated.inp");
    let deck = ccx_deck(&m, "").replace("*STEP\n*STATIC\n*END STEP\n", "");
    let deck = deck.replace("*STEP\n*FREQUENCY", &format!("{keywords}*STEP\n*FREQUENCY"));
    std::fs::write(&inp, deck).unwrap();
    let ours = build(&cdb, 8, &[]);
    let abaqus = build(&inp, 8, &["--mass", "lumped"]);
    let modes = frequency_difference(&ours, &abaqus, 8);
    println!("rotated nodes against Abaqus *TRANSFORM: frequencies {modes:.2e}");
    // measured 3.8e-14
    assert!(modes < 3e-13, "{modes}");
}

/// A full file whose archive rotates a node stays refused, naming the node's NBLOCK line and
/// why (ANSYS's K and M of a rotated node are in its nodal system; no full file of rotated
/// nodes was at hand to show that the displacement frame holds them).
#[test]
fn a_full_file_over_rotated_nodes_is_refused_by_line() {
    let Some(dir) = crate::ansys_support::examples("a full file over rotated nodes") else {
        return;
    };
    let work = scratch("ansys-full-rotated");
    std::fs::copy(dir.join("file.full"), work.join("beam.full")).unwrap();
    let text = std::fs::read_to_string(dir.join("HexBeam.cdb")).unwrap();
    let node1 = "        1        0        0 0.0000000000000E+000\n";
    assert!(text.contains(node1));
    let rotated = format!(
        "        1        0        0{}\n",
        [0.0, 0.0, 0.0, 30.0, 0.0, 0.0]
            .map(|v: f64| format!("{v:>21.13E}"))
            .concat()
    );
    let line = text[..text.find(node1).unwrap()].lines().count() + 1;
    std::fs::write(work.join("beam.cdb"), text.replacen(node1, &rotated, 1)).unwrap();
    let o = exe()
        .arg("build")
        .arg(work.join("beam.full"))
        .args(["--units", "si", "--method", "normal", "--modes", "4", "-o"])
        .arg(work.join("beam.flexbody"))
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.contains(&format!("beam.cdb:{line}: NBLOCK node 1"))
            && err.contains("a nodal coordinate system (NBLOCK rotation angles) under a full file"),
        "{err}"
    );
}
