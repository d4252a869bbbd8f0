//! Archives and decks the load and nodal-system tests write (`tests/ansys_loads*.rs`): a
//! structured brick mesh, NBLOCK/EBLOCK/material lines, the same mesh as a CalculiX deck, a CLI
//! build and the static response of the file's scene loads.

use std::collections::BTreeMap;
use std::path::Path;

use crate::common::exe;
use flexbody_reader as file;

/// A structured mesh of 20-node bricks (or 8-node with `quadratic` false) over
/// [0, l] × [0, b] × [0, h]: node ids on the lattice of half-cells, elements in the node order
/// SOLID186/C3D20R share (corners I…P, mid-sides Q…X of the bottom and top, Y…B vertical).
pub struct Block {
    pub nodes: BTreeMap<u64, [f64; 3]>,
    pub elements: Vec<Vec<u64>>,
}

pub fn block(cells: [usize; 3], size: [f64; 3], quadratic: bool) -> Block {
    let step = if quadratic { 2 } else { 1 };
    let n = cells.map(|c| step * c + 1);
    let id = |i: usize, j: usize, k: usize| ((k * n[1] + j) * n[0] + i + 1) as u64;
    let mut nodes = BTreeMap::new();
    for k in 0..n[2] {
        for j in 0..n[1] {
            for i in 0..n[0] {
                if quadratic && (i % 2) + (j % 2) + (k % 2) > 1 {
                    continue;
                }
                let at = [i, j, k];
                let p = std::array::from_fn(|c| size[c] * at[c] as f64 / (n[c] - 1) as f64);
                nodes.insert(id(i, j, k), p);
            }
        }
    }
    let corners = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)];
    let mut elements = Vec::new();
    for ck in 0..cells[2] {
        for cj in 0..cells[1] {
            for ci in 0..cells[0] {
                let (i0, j0, k0) = (step * ci, step * cj, step * ck);
                let at = |di: usize, dj: usize, dk: usize| id(i0 + di, j0 + dj, k0 + dk);
                let mut e: Vec<u64> = Vec::new();
                for dk in [0, step] {
                    e.extend(corners.map(|(a, b, _)| at(a * step, b * step, dk)));
                }
                if quadratic {
                    let mids = [(1, 0), (2, 1), (1, 2), (0, 1)];
                    for dk in [0, 2] {
                        e.extend(mids.map(|(a, b)| at(a, b, dk)));
                    }
                    e.extend(corners.map(|(a, b, _)| at(2 * a, 2 * b, 1)));
                }
                elements.push(e);
            }
        }
    }
    Block { nodes, elements }
}

/// E, ν, ρ of the tests' steel.
pub const STEEL: [f64; 3] = [2.1e11, 0.3, 7850.0];

/// An NBLOCK of (id, position, rotation angles).
pub fn nblock(nodes: &[(u64, [f64; 3], [f64; 3])]) -> String {
    let mut s = format!("NBLOCK,6,SOLID,{0},{0}\n(3i9,6e21.13e3)\n", nodes.len());
    for (id, x, a) in nodes {
        s.push_str(&format!("{id:>9}{:>9}{:>9}", 0, 0));
        for v in x
            .iter()
            .chain(if *a == [0.0; 3] { &[][..] } else { &a[..] })
        {
            s.push_str(&format!("{v:>21.13E}"));
        }
        s.push('\n');
    }
    s.push_str("N,R5.3,LOC,       -1,\n");
    s
}

/// An EBLOCK (SOLID layout) of (type, real/section, nodes) records, ids 1, 2, ….
pub fn eblock(records: &[(usize, usize, Vec<u64>)]) -> String {
    let mut s = format!("EBLOCK,19,SOLID,{0},{0}\n(19i9)\n", records.len());
    for (k, (etype, real, nodes)) in records.iter().enumerate() {
        let head = [1, *etype, *real, *real, 0, 0, 0, 0, nodes.len(), 0, k + 1];
        let mut fields: Vec<String> = head.iter().map(|v| format!("{v:>9}")).collect();
        fields.extend(nodes.iter().map(|v| format!("{v:>9}")));
        for (i, f) in fields.iter().enumerate() {
            if i == 19 {
                s.push('\n');
            }
            s.push_str(f);
        }
        s.push('\n');
    }
    s.push_str("       -1\n");
    s
}

pub fn material([e, nu, rho]: [f64; 3]) -> String {
    format!(
        "MPTEMP,R5.0, 1, 1,  0.00000000    ,\nMPDATA,R5.0, 1,EX  ,       1, 1, {e:e},\n\
         MPDATA,R5.0, 1,NUXY,       1, 1, {nu:e},\nMPDATA,R5.0, 1,DENS,       1, 1, {rho:e},\n"
    )
}

/// The block as an archive of element type `et` (its ET/KEYOPT lines), `extra` appended.
pub fn block_archive(m: &Block, et: &str, angles: &BTreeMap<u64, [f64; 3]>, extra: &str) -> String {
    let nodes: Vec<(u64, [f64; 3], [f64; 3])> = (m.nodes.iter())
        .map(|(&id, &x)| (id, x, angles.get(&id).copied().unwrap_or([0.0; 3])))
        .collect();
    let records: Vec<(usize, usize, Vec<u64>)> =
        m.elements.iter().map(|e| (1, 1, e.clone())).collect();
    format!(
        "/PREP7\n{et}{}{}{}{extra}FINISH\n",
        nblock(&nodes),
        eblock(&records),
        material(STEEL)
    )
}

/// The nodes with x = 0.
pub fn root(m: &Block) -> Vec<u64> {
    (m.nodes.iter())
        .filter(|(_, x)| x[0] == 0.0)
        .map(|(&id, _)| id)
        .collect()
}

/// `--residual-vectors loads`: the scene loads' static responses are in the file.
pub const RESIDUALS: [&str; 2] = ["--residual-vectors", "loads"];

/// `flexbody build PATH --units si --method normal --modes N EXTRA…`: the file read back.
pub fn build_body(path: &Path, modes: usize, extra: &[&str]) -> file::ReducedBody {
    let out = path.with_extension("flexbody");
    let o = exe()
        .arg("build")
        .arg(path)
        .args(["--units", "si", "--method", "normal", "--modes"])
        .arg(modes.to_string())
        .args(extra)
        .arg("-o")
        .arg(&out)
        .output()
        .unwrap();
    assert!(
        o.status.success(),
        "{}: {}",
        path.display(),
        String::from_utf8_lossy(&o.stderr)
    );
    file::read(&out).unwrap()
}

/// The static response to load `index` of the file at every stored node (translations, body
/// frame), by node id, from the file alone: u = Σ φ_j g_j / ω_j² over the flexible modes.
pub fn static_response(body: &file::ReducedBody, index: usize) -> BTreeMap<u64, [f64; 3]> {
    let ml = body.modal_loads.as_ref().expect("modal_loads.bin");
    let g = &ml.loads[index].values;
    let n = body.nodes.len();
    let mut u = BTreeMap::new();
    for (p, node) in body.nodes.iter().enumerate() {
        let mut v = [0.0; 3];
        for (j, &w2) in body.modes.omega2.iter().enumerate() {
            if body.modes.labels[j] == file::ModeLabel::Rigid {
                continue;
            }
            for (c, vc) in v.iter_mut().enumerate() {
                *vc += body.modes.shapes[(j * n + p) * 6 + c] * g[j] / w2;
            }
        }
        u.insert(node.id, v);
    }
    u
}

/// The largest difference of two responses at their common nodes over the largest
/// displacement of `b`.
pub fn response_difference(a: &BTreeMap<u64, [f64; 3]>, b: &BTreeMap<u64, [f64; 3]>) -> f64 {
    let scale = (b.values().flatten()).fold(0.0f64, |m, v| m.max(v.abs()));
    assert!(scale > 0.0);
    let mut worst = 0.0f64;
    let mut common = 0;
    for (id, ub) in b {
        if let Some(ua) = a.get(id) {
            common += 1;
            for c in 0..3 {
                worst = worst.max((ua[c] - ub[c]).abs() / scale);
            }
        }
    }
    assert!(common > 0);
    worst
}

pub fn frequency_difference(a: &file::ReducedBody, b: &file::ReducedBody, count: usize) -> f64 {
    let (fa, fb) = (&a.modes.frequency_hz, &b.modes.frequency_hz);
    (0..count)
        .map(|j| ((fa[j] - fb[j]) / fb[j]).abs())
        .fold(0.0, f64::max)
}

/// `ours` against the same model and loads written for another importer (`reference`), both
/// built with `--mass lumped` and the scene loads' residual vectors: (the largest relative
/// difference of the lowest `modes` frequencies, that of the first load's static response).
pub fn lumped_load_differences(ours: &Path, reference: &Path, modes: usize) -> (f64, f64) {
    let args = ["--mass", "lumped", RESIDUALS[0], RESIDUALS[1]];
    let (a, b) = (
        build_body(ours, modes, &args),
        build_body(reference, modes, &args),
    );
    let response = response_difference(&static_response(&a, 0), &static_response(&b, 0));
    (frequency_difference(&a, &b, modes), response)
}

/// The block as a CalculiX deck (C3D20R, the same ids), clamped at x = 0, `step` in a
/// `*STATIC` step before a `*FREQUENCY` one.
pub fn ccx_deck(m: &Block, step: &str) -> String {
    let [e, nu, rho] = STEEL;
    let mut s = String::from("*NODE\n");
    for (id, x) in &m.nodes {
        s.push_str(&format!("{id}, {:?}, {:?}, {:?}\n", x[0], x[1], x[2]));
    }
    s.push_str("*ELEMENT, TYPE=C3D20R, ELSET=EALL\n");
    for (k, el) in m.elements.iter().enumerate() {
        let ids: Vec<String> = el.iter().map(u64::to_string).collect();
        s.push_str(&format!(
            "{}, {},\n{}\n",
            k + 1,
            ids[..15].join(", "),
            ids[15..].join(", ")
        ));
    }
    s.push_str(&format!(
        "*MATERIAL, NAME=STEEL\n*ELASTIC\n{e:?}, {nu:?}\n*DENSITY\n{rho:?}\n\
         *SOLID SECTION, ELSET=EALL, MATERIAL=STEEL\n*BOUNDARY\n"
    ));
    for id in root(m) {
        s.push_str(&format!("{id}, 1, 3\n"));
    }
    s.push_str(&format!(
        "*STEP\n*STATIC\n{step}*END STEP\n*STEP\n*FREQUENCY\n6\n*END STEP\n"
    ));
    s
}
