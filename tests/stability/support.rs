//! Models, matrices, dense references and command-line runs for the stability rows.
#![allow(dead_code)]

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::atomic::{AtomicUsize, Ordering};

use faer::sparse::SparseColMat;
use faer::Mat;
use flexbody::build::{BuildMethod, BuildSpec};
use flexbody::fe::{assemble, AssemblySpec, DofMap, MassKind};
use flexbody::model::generate::{block as gen_block, BlockElement, BlockSpec};
use flexbody::model::{
    BeamSection, Element, ElementKind, Material, Model, Node, Property, Section,
};
use flexbody::solve::EigenSpec;
use flexbody_reader as file;

pub type Sparse = SparseColMat<usize, f64>;

/// Steel hex8 block [0, size] with `n` bricks (node sets X0, XL, NALL; element set SOLID).
pub fn block(n: [usize; 3], size: [f64; 3]) -> Model {
    gen_block(&BlockSpec {
        n,
        size,
        element: BlockElement::Hex8,
        material: Material::steel(),
    })
}

/// Lumped K and M over all physical dofs (the models here have no rigid elements).
pub fn system(model: &Model) -> (Model, Sparse, Sparse) {
    let a = assemble(
        model,
        &AssemblySpec {
            mass: MassKind::Lumped,
            ..Default::default()
        },
    )
    .expect("test model assembles");
    (model.clone(), a.k, a.m)
}

pub fn eig() -> EigenSpec {
    EigenSpec {
        dofs_per_node: Some(3),
        ..Default::default()
    }
}

/// The first `count` dofs of each node.
pub fn node_dofs(model: &Model, nodes: &[usize], count: usize) -> Vec<usize> {
    let d = DofMap::from_model(model).expect("dof map");
    nodes
        .iter()
        .flat_map(|&n| (0..count.min(usize::from(d.count[n]))).map(move |c| (n, c)))
        .map(|(n, c)| d.first[n] + c)
        .collect()
}

/// Every dof of the nodes of a node set.
pub fn set_dofs(model: &Model, set: &str) -> Vec<usize> {
    node_dofs(model, &model.node_sets[set], 6)
}

/// How the second block of [`two_blocks`] meets the first.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Joint {
    /// 10 mm apart.
    Gap,
    /// Sharing one corner node.
    Corner,
    /// Sharing one edge (a line of nodes).
    Edge,
}

/// Block A [0,0.2]×[0,0.05]² and a copy B beside it (elements in element sets PART_A / PART_B,
/// one property each; node sets A_X0, B_ALL). Coincident nodes are merged.
pub fn two_blocks(joint: Joint) -> Model {
    let a = block([4, 1, 1], [0.2, 0.05, 0.05]);
    let b = block([4, 1, 1], [0.2, 0.05, 0.05]);
    let shift = match joint {
        Joint::Gap => [0.21, 0.0, 0.0],
        Joint::Corner => [0.2, 0.05, 0.05],
        Joint::Edge => [0.2, 0.05, 0.0],
    };
    let mut m = a.clone();
    m.source = format!("two blocks {joint:?}");
    m.element_sets.clear();
    m.node_sets.clear();
    m.node_sets.insert("A_X0".into(), a.node_sets["X0"].clone());
    m.properties[0].name = "PART_A".into();
    m.properties.push(Property {
        id: 2,
        name: "PART_B".into(),
        material: 0,
        section: Section::Solid,
    });
    let next_id = a.nodes.iter().map(|n| n.id).max().unwrap_or(0) + 1;
    let mut map = vec![0usize; b.nodes.len()];
    for (i, n) in b.nodes.iter().enumerate() {
        let x = [n.x[0] + shift[0], n.x[1] + shift[1], n.x[2] + shift[2]];
        let same = m
            .nodes
            .iter()
            .position(|p| (0..3).all(|k| (p.x[k] - x[k]).abs() < 1e-12));
        map[i] = same.unwrap_or_else(|| {
            m.nodes.push(Node {
                id: next_id + i as u64,
                x,
                displacement_frame: None,
            });
            m.nodes.len() - 1
        });
    }
    let ne = a.elements.len();
    for e in &b.elements {
        m.elements.push(Element {
            id: e.id + ne as u64,
            kind: e.kind,
            nodes: e.nodes.iter().map(|&n| map[n]).collect(),
            property: Some(1),
            orientation: None,
        });
    }
    m.element_sets.insert("PART_A".into(), (0..ne).collect());
    m.element_sets
        .insert("PART_B".into(), (ne..m.elements.len()).collect());
    let mut b_all: Vec<usize> = map.clone();
    b_all.sort_unstable();
    b_all.dedup();
    m.node_sets.insert("B_ALL".into(), b_all);
    m
}

/// 8×2×2 block 0.4 × 0.05 × 0.05 whose middle quarter (0.15 < x < 0.25) is `contrast` times
/// stiffer (same density).
pub fn insert_block(contrast: f64) -> Model {
    insert_block_of([8, 2, 2], contrast)
}

/// [`insert_block`] meshed with `bricks` hexahedra.
pub fn insert_block_of(bricks: [usize; 3], contrast: f64) -> Model {
    let mut m = block(bricks, [0.4, 0.05, 0.05]);
    let mut stiff = Material::steel();
    stiff.id = 2;
    stiff.name = "INSERT".into();
    stiff.e *= contrast;
    stiff.g *= contrast;
    m.materials.push(stiff);
    m.properties.push(Property {
        id: 2,
        name: "INSERT".into(),
        material: 1,
        section: Section::Solid,
    });
    for e in 0..m.elements.len() {
        let xc = m.elements[e]
            .nodes
            .iter()
            .map(|&n| m.nodes[n].x[0])
            .sum::<f64>()
            / 8.0;
        if xc > 0.15 && xc < 0.25 {
            m.elements[e].property = Some(1);
        }
    }
    m
}

/// A free straight beam of `ne` Beam2 elements, length 1, square 10 mm section, steel.
pub fn beam_model(ne: usize) -> Model {
    let mut m = Model {
        source: "beam".into(),
        ..Default::default()
    };
    m.materials.push(Material::steel());
    let (b, h) = (0.01f64, 0.01f64);
    m.properties.push(Property {
        id: 1,
        name: "BEAM".into(),
        material: 0,
        section: Section::Beam(BeamSection {
            area: b * h,
            i1: b * h.powi(3) / 12.0,
            i2: h * b.powi(3) / 12.0,
            i12: 0.0,
            j: 0.141 * b.powi(4),
            shear_factors: None,
            nsm: 0.0,
            shape: None,
            taper: None,
        }),
    });
    for i in 0..=ne {
        m.nodes.push(Node {
            id: i as u64 + 1,
            x: [i as f64 / ne as f64, 0.0, 0.0],
            displacement_frame: None,
        });
    }
    for i in 0..ne {
        m.elements.push(Element {
            id: i as u64 + 1,
            kind: ElementKind::Beam2,
            nodes: vec![i, i + 1],
            property: Some(0),
            orientation: Some([0.0, 1.0, 0.0]),
        });
    }
    m
}

/// Ids of the block corners (0,0,0), (Lx,0,0), (0,Ly,0).
pub fn corner_ids(model: &Model) -> [u64; 3] {
    let lx = model.nodes.iter().map(|n| n.x[0]).fold(0.0, f64::max);
    let ly = model.nodes.iter().map(|n| n.x[1]).fold(0.0, f64::max);
    let at = |p: [f64; 3]| {
        model
            .nodes
            .iter()
            .find(|n| (0..3).all(|k| (n.x[k] - p[k]).abs() < 1e-12))
            .map(|n| n.id)
            .expect("corner node")
    };
    [at([0.0; 3]), at([lx, 0.0, 0.0]), at([0.0, ly, 0.0])]
}

/// ‖ΦᵀMΦ − I‖_max and ‖ΦᵀKΦ − diag ω²‖_max / max ω², computed here from the full matrices.
pub fn orthonormality(k: &Sparse, m: &Sparse, phi: &Mat<f64>, omega2: &[f64]) -> (f64, f64) {
    let kd = dense(k);
    let md = dense(m);
    let kk = phi.transpose() * &kd * phi;
    let mm = phi.transpose() * &md * phi;
    let lmax = omega2.iter().fold(0.0f64, |a, &b| a.max(b.abs()));
    let (mut o, mut s) = (0.0f64, 0.0f64);
    for i in 0..omega2.len() {
        for j in 0..omega2.len() {
            let id = if i == j { 1.0 } else { 0.0 };
            o = o.max((mm[(i, j)] - id).abs());
            s = s.max((kk[(i, j)] - id * omega2[j]).abs() / lmax);
        }
    }
    (o, s)
}

pub fn dense(a: &Sparse) -> Mat<f64> {
    let a = a.as_ref();
    let mut d = Mat::zeros(a.nrows(), a.ncols());
    for j in 0..a.ncols() {
        for (i, v) in a.row_idx_of_col(j).zip(a.val_of_col(j)) {
            d[(i, j)] += v;
        }
    }
    d
}

/// All eigenpairs of K x = λ M x (M positive definite) by dense Cholesky of M and faer's dense
/// symmetric eigensolver on L⁻¹KL⁻ᵀ — independent of the sparse shift-invert path. Vectors are
/// M-orthonormal.
pub fn dense_reference(k: &Sparse, m: &Sparse) -> (Vec<f64>, Mat<f64>) {
    let (kd, md) = (dense(k), dense(m));
    let n = kd.nrows();
    let l = md.llt(faer::Side::Lower).expect("M positive definite");
    let l = l.L().to_owned();
    let mut a = kd.clone();
    faer::linalg::triangular_solve::solve_lower_triangular_in_place(
        l.as_ref(),
        a.as_mut(),
        faer::Par::Seq,
    );
    let mut at = a.transpose().to_owned();
    faer::linalg::triangular_solve::solve_lower_triangular_in_place(
        l.as_ref(),
        at.as_mut(),
        faer::Par::Seq,
    );
    let sym = Mat::from_fn(n, n, |i, j| 0.5 * (at[(i, j)] + at[(j, i)]));
    let (vals, u) = flexbody::solve::dense::eigh(sym.as_ref()).expect("dense eigen");
    let mut x = u;
    faer::linalg::triangular_solve::solve_upper_triangular_in_place(
        l.transpose(),
        x.as_mut(),
        faer::Par::Seq,
    );
    (vals, x)
}

/// Index groups of values within `rel` of their neighbour (relative to the larger one).
pub fn clusters(vals: &[f64], rel: f64) -> Vec<Vec<usize>> {
    let scale = vals.iter().fold(0.0f64, |a, &b| a.max(b.abs()));
    let mut out: Vec<Vec<usize>> = vec![];
    for (i, &v) in vals.iter().enumerate() {
        let join = i > 0 && (v - vals[i - 1]).abs() <= rel * v.abs().max(1e-9 * scale);
        if join {
            out.last_mut().unwrap().push(i); // i > 0, so a group exists
        } else {
            out.push(vec![i]);
        }
    }
    out
}

/// Largest principal angle (rad) between the spans of M-orthonormal A and B: sin θ_max =
/// ‖B − A AᵀMB‖ in the M-norm (accurate for small angles, unlike acos of the cosines).
pub fn max_principal_angle(m: &Sparse, a: &Mat<f64>, b: &Mat<f64>) -> f64 {
    let md = dense(m);
    let c = a.transpose() * &md * b;
    let r = b - a * &c;
    let g = r.transpose() * &md * &r;
    let (vals, _) = flexbody::solve::dense::eigh(g.as_ref()).expect("eigen");
    vals.iter()
        .fold(0.0f64, |x, &y| x.max(y))
        .max(0.0)
        .sqrt()
        .min(1.0)
        .asin()
}

/// A measured figure for docs/stability.md (shown with `--nocapture`).
pub fn record(row: &str, what: &str, value: f64) {
    println!("STABILITY row {row}: {what} = {value:.3e}");
}

pub fn assert_contains(text: &str, parts: &[&str]) {
    for p in parts {
        assert!(text.contains(p), "expected {p:?} in:\n{text}");
    }
}

pub fn build_spec(model: &str, method: BuildMethod, interface: &[String]) -> BuildSpec {
    let names: Vec<&str> = interface.iter().map(String::as_str).collect();
    BuildSpec {
        method,
        ..BuildSpec::new(PathBuf::from(model), file::Units::si(), &names)
    }
}

/// A fresh directory under the system temp dir, removed on drop.
pub struct TempDir(PathBuf);

impl TempDir {
    pub fn new(name: &str) -> TempDir {
        let p =
            std::env::temp_dir().join(format!("flexbody-stability-{}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&p);
        std::fs::create_dir_all(&p).expect("temp dir");
        TempDir(p)
    }

    pub fn path(&self, name: &str) -> String {
        self.0.join(name).to_string_lossy().into_owned()
    }

    /// Writes `model` as an Abaqus .inp (nodes, elements per property with its section, node and
    /// element sets, materials) and returns the path.
    pub fn write_inp(&self, name: &str, model: &Model) -> String {
        let path = self.path(name);
        std::fs::write(&path, inp_text(model)).expect("write inp");
        path
    }

    pub fn files(&self) -> Vec<String> {
        std::fs::read_dir(&self.0)
            .map(|d| {
                d.filter_map(|e| e.ok())
                    .map(|e| e.file_name().to_string_lossy().into_owned())
                    .collect()
            })
            .unwrap_or_default()
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

fn id_lines(out: &mut String, ids: impl Iterator<Item = u64>) {
    let ids: Vec<u64> = ids.collect();
    for chunk in ids.chunks(12) {
        let line: Vec<String> = chunk.iter().map(|i| i.to_string()).collect();
        let _ = writeln!(out, "{}", line.join(", "));
    }
}

pub fn inp_text(model: &Model) -> String {
    let mut s = String::from("** written by tests/stability\n*NODE\n");
    for n in &model.nodes {
        let _ = writeln!(
            s,
            "{}, {:.17e}, {:.17e}, {:.17e}",
            n.id, n.x[0], n.x[1], n.x[2]
        );
    }
    for (p, prop) in model.properties.iter().enumerate() {
        let _ = writeln!(s, "*ELEMENT, TYPE=C3D8, ELSET={}", prop.name);
        for e in model.elements.iter().filter(|e| e.property == Some(p)) {
            let ids: Vec<String> = e
                .nodes
                .iter()
                .map(|&n| model.nodes[n].id.to_string())
                .collect();
            let _ = writeln!(s, "{}, {}", e.id, ids.join(", "));
        }
    }
    for (name, nodes) in &model.node_sets {
        let _ = writeln!(s, "*NSET, NSET={name}");
        id_lines(&mut s, nodes.iter().map(|&n| model.nodes[n].id));
    }
    for (name, els) in &model.element_sets {
        if model.properties.iter().any(|p| &p.name == name) {
            continue;
        }
        let _ = writeln!(s, "*ELSET, ELSET={name}");
        id_lines(&mut s, els.iter().map(|&e| model.elements[e].id));
    }
    for m in &model.materials {
        let _ = writeln!(
            s,
            "*MATERIAL, NAME={}\n*ELASTIC\n{:e}, {}\n*DENSITY\n{:e}",
            m.name, m.e, m.nu, m.rho
        );
    }
    for p in &model.properties {
        let _ = writeln!(
            s,
            "*SOLID SECTION, ELSET={}, MATERIAL={}",
            p.name, model.materials[p.material].name
        );
    }
    s
}

static RUNS: AtomicUsize = AtomicUsize::new(0);

/// Runs the binary: (exit code, stdout, stderr).
pub fn run_cli(args: &[&str], env: &[(&str, &str)]) -> (Option<i32>, String, String) {
    let mut c = Command::new(env!("CARGO_BIN_EXE_flexbody"));
    c.args(args);
    c.env_remove("FLEXBODY_MAX_MEMORY");
    for (k, v) in env {
        c.env(k, v);
    }
    let o = c.output().expect("run flexbody");
    (
        o.status.code(),
        String::from_utf8_lossy(&o.stdout).into_owned(),
        String::from_utf8_lossy(&o.stderr).into_owned(),
    )
}

/// `flexbody build ARGS -q -o DIR/out-N.flexbody` must fail with exit code 2, leave no output
/// (nor a temporary file) in DIR, and never panic; returns stderr.
pub fn fail_run(dir: &TempDir, args: &[&str], env: &[(&str, &str)]) -> String {
    let out = dir.path(&format!(
        "out-{}.flexbody",
        RUNS.fetch_add(1, Ordering::SeqCst)
    ));
    let mut all = vec!["build"];
    all.extend_from_slice(args);
    all.extend_from_slice(&["-q", "-o", &out]);
    let (code, _, err) = run_cli(&all, env);
    assert_eq!(code, Some(2), "{args:?}: expected exit 2, stderr:\n{err}");
    assert!(!Path::new(&out).exists(), "{args:?} left {out}");
    let stray: Vec<String> = dir
        .files()
        .into_iter()
        .filter(|f| f.contains("out-"))
        .collect();
    assert!(stray.is_empty(), "{args:?} left {stray:?}");
    assert!(!err.contains("panicked") && !err.contains("NaN"), "{err}");
    println!("STDERR {args:?}\n{err}");
    err
}
