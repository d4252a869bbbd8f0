//! Fixture generator shared by the `format_*` tests: two physically consistent synthetic bodies
//! (spring–mass chains whose modes solve K φ = ω² M φ and are mass-orthonormal, whose
//! invariants are computed from nodes, masses and modes) and the broken files derived from
//! them. Only `+ − × ÷ √` are used so the bytes are identical on every IEEE-754 platform.
#![allow(dead_code)]

pub mod broken;
mod eigen;
mod geometric;
mod residual;

pub use eigen::body_3node_eigen_residuals;
pub use geometric::{body_3node_geometric_stiffness, body_3node_geometric_stiffness_1_7};
pub use residual::body_3node_residual_vectors;

use std::path::{Path, PathBuf};

use flexbody_reader::*;

/// `fixtures/` of this repository.
pub fn fixtures_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures")
}

/// Symmetric eigen-decomposition by cyclic Jacobi rotations (Golub & Van Loan §8.5.2):
/// returns (λ ascending, V column-major per eigenvector: `v[j][i]`).
pub fn jacobi_eigen(mut a: Vec<Vec<f64>>) -> (Vec<f64>, Vec<Vec<f64>>) {
    let n = a.len();
    let mut v: Vec<Vec<f64>> = (0..n)
        .map(|i| (0..n).map(|j| if i == j { 1.0 } else { 0.0 }).collect())
        .collect();
    for _sweep in 0..100 {
        let off: f64 = (0..n)
            .flat_map(|i| (0..n).filter(move |&j| j != i).map(move |j| (i, j)))
            .map(|(i, j)| a[i][j] * a[i][j])
            .sum();
        let scale: f64 = (0..n).map(|i| a[i][i] * a[i][i]).sum();
        if off <= 1e-30 * scale {
            break;
        }
        for p in 0..n {
            for q in (p + 1)..n {
                if a[p][q] == 0.0 {
                    continue;
                }
                let theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
                let t = theta.signum() / (theta.abs() + (theta * theta + 1.0).sqrt());
                let t = if theta == 0.0 { 1.0 } else { t };
                let c = 1.0 / (t * t + 1.0).sqrt();
                let s = t * c;
                for row in a.iter_mut() {
                    let (akp, akq) = (row[p], row[q]);
                    row[p] = c * akp - s * akq;
                    row[q] = s * akp + c * akq;
                }
                let (lo, hi) = a.split_at_mut(q);
                for (apk, aqk) in lo[p].iter_mut().zip(hi[0].iter_mut()) {
                    let (x, y) = (*apk, *aqk);
                    *apk = c * x - s * y;
                    *aqk = s * x + c * y;
                }
                for row in v.iter_mut() {
                    let (vp, vq) = (row[p], row[q]);
                    row[p] = c * vp - s * vq;
                    row[q] = s * vp + c * vq;
                }
            }
        }
    }
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&x, &y| a[x][x].total_cmp(&a[y][y]));
    let vals = order.iter().map(|&j| a[j][j]).collect();
    let vecs = order
        .iter()
        .map(|&j| (0..n).map(|i| v[i][j]).collect())
        .collect();
    (vals, vecs)
}

/// Skew matrix ã with ã b = a × b.
pub fn skew(a: [f64; 3]) -> [[f64; 3]; 3] {
    [[0.0, -a[2], a[1]], [a[2], 0.0, -a[0]], [-a[1], a[0], 0.0]]
}

fn mat_mul(a: &[[f64; 3]; 3], b: &[[f64; 3]; 3]) -> [[f64; 3]; 3] {
    let mut c = [[0.0; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            c[i][j] = (0..3).map(|k| a[i][k] * b[k][j]).sum();
        }
    }
    c
}

/// The nine invariants (DESIGN.md §3, SPEC.md §5.6) from every mass node: positions `s`,
/// masses, nodal inertias and mode-major shapes (6 per node). Unselected ones are empty.
pub fn invariants(
    nodes: &[Node],
    nm: &[NodalMass],
    shapes: &[f64],
    m: usize,
    set: InvariantSet,
) -> Invariants {
    let n = nodes.len();
    let t = |j: usize, p: usize| {
        [
            shapes[(j * n + p) * 6],
            shapes[(j * n + p) * 6 + 1],
            shapes[(j * n + p) * 6 + 2],
        ]
    };
    let r = |j: usize, p: usize| {
        [
            shapes[(j * n + p) * 6 + 3],
            shapes[(j * n + p) * 6 + 4],
            shapes[(j * n + p) * 6 + 5],
        ]
    };
    let (mut i1, mut i2) = (vec![0.0], vec![0.0; 3]);
    let (mut i3, mut i4) = (vec![0.0; 3 * m], vec![0.0; 3 * m]);
    let (mut i5, mut i6) = (vec![0.0; m * 3 * m], vec![0.0; m * m]);
    let (mut i7, mut i8, mut i9) = (vec![0.0; 9], vec![0.0; m * 9], vec![0.0; m * m * 9]);
    for p in 0..n {
        let (mp, ip, s) = (nm[p].mass, nm[p].inertia, nodes[p].xyz);
        let st = skew(s);
        i1[0] += mp;
        for a in 0..3 {
            i2[a] += mp * s[a];
        }
        let sts = mat_mul(
            &[
                [st[0][0], st[1][0], st[2][0]],
                [st[0][1], st[1][1], st[2][1]],
                [st[0][2], st[1][2], st[2][2]],
            ],
            &st,
        );
        for a in 0..3 {
            for b in 0..3 {
                i7[a * 3 + b] += mp * sts[a][b] + ip[a][b];
            }
        }
        for j in 0..m {
            let (phi, psi) = (t(j, p), r(j, p));
            for a in 0..3 {
                i3[a * m + j] += mp * phi[a];
                let s_phi: f64 = (0..3).map(|b| st[a][b] * phi[b]).sum();
                let i_psi: f64 = (0..3).map(|b| ip[a][b] * psi[b]).sum();
                i4[a * m + j] += mp * s_phi + i_psi;
            }
            let pt = skew(phi);
            let s_pt = mat_mul(&st, &pt);
            for a in 0..3 {
                for b in 0..3 {
                    i8[j * 9 + a * 3 + b] += mp * s_pt[a][b];
                }
            }
            for k in 0..m {
                let (phk, psk) = (t(k, p), r(k, p));
                let tt: f64 = (0..3).map(|a| phi[a] * phk[a]).sum();
                let rr: f64 = (0..3)
                    .map(|a| (0..3).map(|b| psi[a] * ip[a][b] * psk[b]).sum::<f64>())
                    .sum();
                i6[j * m + k] += mp * tt + rr;
                for a in 0..3 {
                    i5[(j * 3 + a) * m + k] += mp * (0..3).map(|b| pt[a][b] * phk[b]).sum::<f64>();
                }
                let pp = mat_mul(&pt, &skew(phk));
                for a in 0..3 {
                    for b in 0..3 {
                        i9[((j * m + k) * 3 + a) * 3 + b] += mp * pp[a][b];
                    }
                }
            }
        }
    }
    let mask = set.mask();
    let mut all = [i1, i2, i3, i4, i5, i6, i7, i8, i9];
    for k in 0..9 {
        if !mask[k] {
            all[k].clear();
        }
    }
    let [i1, i2, i3, i4, i5, i6, i7, i8, i9] = all;
    Invariants {
        mask,
        i1,
        i2,
        i3,
        i4,
        i5,
        i6,
        i7,
        i8,
        i9,
    }
}

/// Modal quantities from lumped masses (one per dof) and a dense stiffness over `ndof` dofs:
/// M^{-1/2} K M^{-1/2} y = ω² y, φ = M^{-1/2} y (so φᵀ M φ = I).
pub fn lumped_modes(mass_dof: &[f64], k: &[Vec<f64>], keep: usize) -> (Vec<f64>, Vec<Vec<f64>>) {
    let nd = mass_dof.len();
    let inv_sqrt: Vec<f64> = mass_dof.iter().map(|m| 1.0 / m.sqrt()).collect();
    let a: Vec<Vec<f64>> = (0..nd)
        .map(|i| {
            (0..nd)
                .map(|j| inv_sqrt[i] * k[i][j] * inv_sqrt[j])
                .collect()
        })
        .collect();
    let (vals, vecs) = jacobi_eigen(a);
    let phis = vecs
        .iter()
        .take(keep)
        .map(|y| y.iter().zip(&inv_sqrt).map(|(y, s)| y * s).collect())
        .collect();
    (vals.into_iter().take(keep).collect(), phis)
}

pub(crate) fn hz(w2: f64) -> f64 {
    w2.max(0.0).sqrt() / (2.0 * std::f64::consts::PI)
}

fn diag(v: &[f64]) -> Vec<f64> {
    let m = v.len();
    let mut d = vec![0.0; m * m];
    for j in 0..m {
        d[j * m + j] = v[j];
    }
    d
}

fn identity_frame() -> [[f64; 3]; 3] {
    [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]
}

/// Spring constant and node mass of the 3-node chain.
pub const K3: f64 = 800.0;
/// Node mass of the 3-node chain.
pub const M3: f64 = 2.0;

/// Three 2 kg masses, axial (x) springs k = 800 N/m, free-free. Closed form (mass-normalized):
/// ω² = 0, k/m, 3k/m with φ ∝ (1,1,1), (1,0,−1), (1,−2,1).
pub fn body_3node() -> ReducedBody {
    let nodes = vec![
        Node {
            id: 101,
            xyz: [0.0, 0.0, 0.0],
            interface: true,
        },
        Node {
            id: 102,
            xyz: [1.0, 0.5, 0.0],
            interface: false,
        },
        Node {
            id: 103,
            xyz: [2.0, 0.0, 0.0],
            interface: true,
        },
    ];
    let nm: Vec<NodalMass> = (0..3)
        .map(|_| NodalMass {
            mass: M3,
            inertia: [[0.01, 0.0, 0.0], [0.0, 0.01, 0.0], [0.0, 0.0, 0.01]],
        })
        .collect();
    let omega2 = vec![0.0, K3 / M3, 3.0 * K3 / M3];
    let ux: [[f64; 3]; 3] = [
        [1.0 / (3.0 * M3).sqrt(); 3],
        [1.0 / (2.0 * M3).sqrt(), 0.0, -1.0 / (2.0 * M3).sqrt()],
        [
            1.0 / (6.0 * M3).sqrt(),
            -2.0 / (6.0 * M3).sqrt(),
            1.0 / (6.0 * M3).sqrt(),
        ],
    ];
    let mut shapes = vec![0.0; 3 * 3 * 6];
    for j in 0..3 {
        for p in 0..3 {
            shapes[(j * 3 + p) * 6] = ux[j][p];
        }
    }
    let invariants = invariants(&nodes, &nm, &shapes, 3, InvariantSet::Full);
    let request = Request {
        method: Method::NormalModes,
        fmax_hz: None,
        mode_count: Some(3),
        keep_nodes: KeepNodes::All,
        invariant_set: InvariantSet::Full,
        mass_kind: MassKind::Lumped,
    };
    ReducedBody {
        version: V1_0,
        generator: Generator {
            name: "flexbody-fixtures".into(),
            version: "1".into(),
        },
        units: Units::si(),
        header: Header {
            title: "3-node axial spring-mass chain (closed form)".into(),
            created_utc: None,
            request,
        },
        nodes,
        faces: vec![Face::Tri([0, 1, 2])],
        nodal_mass: nm,
        modes: Modes {
            frequency_hz: omega2.iter().map(|&w| hz(w)).collect(),
            labels: vec![ModeLabel::Rigid, ModeLabel::Normal, ModeLabel::Normal],
            generalized_mass: diag(&[1.0; 3]),
            generalized_stiffness: diag(&omega2),
            omega2,
            shapes,
        },
        invariants,
        method: MethodRecord {
            method: Method::NormalModes,
            mass_kind: MassKind::Lumped,
            interface: vec![
                InterfaceNode {
                    node: 0,
                    dofs: [true; 6],
                    frame: identity_frame(),
                },
                InterfaceNode {
                    node: 2,
                    dofs: [true, true, true, false, false, false],
                    frame: identity_frame(),
                },
            ],
            reference_conditions: vec![],
            counts: ModeCounts {
                rigid: 1,
                normal: 2,
                ..Default::default()
            },
            cutoffs: Cutoffs::default(),
        },
        stress_shapes: None,
        strain_shapes: None,
        damping: Some(Damping {
            ratio: vec![0.0, 0.02, 0.02],
        }),
        lines: None,
        recipe: None,
        label_shares: None,
        stress_shapes_bottom: None,
        strain_shapes_bottom: None,
        interfaces: None,
        modal_loads: None,
        geometric_stiffness: None,
        eigen_residuals: None,
    }
}

/// Mass (t) of node p of the 20-node chain.
pub fn mass20(p: usize) -> f64 {
    0.0005 + 0.00005 * (p % 4) as f64
}
/// Axial spring (N/mm) of element e (nodes e, e+1).
pub fn kx20(e: usize) -> f64 {
    10.0 * (1.0 + 0.1 * (e % 3) as f64)
}
/// Transverse (shear) spring (N/mm) of element e.
pub fn ky20(e: usize) -> f64 {
    2.5 * (1.0 + 0.05 * (e % 5) as f64)
}
/// Node spacing (mm) of the 20-node chain.
pub const L20: f64 = 50.0;

/// Stiffness of the 20-node chain over dofs (ux_p at 2p, uy_p at 2p+1).
pub fn stiffness20() -> Vec<Vec<f64>> {
    let nd = 40;
    let mut k = vec![vec![0.0; nd]; nd];
    for e in 0..19 {
        for (c, ke) in [(0, kx20(e)), (1, ky20(e))] {
            let (a, b) = (2 * e + c, 2 * (e + 1) + c);
            k[a][a] += ke;
            k[b][b] += ke;
            k[a][b] -= ke;
            k[b][a] -= ke;
        }
    }
    k
}

/// 20 masses along x (mm, t, s, N), axial and transverse springs, free-free; lowest 8 modes
/// by Jacobi (2 rigid translations + 6 elastic), invariants `Partial`, strain shapes.
pub fn body_20node() -> ReducedBody {
    let n = 20;
    let nodes: Vec<Node> = (0..n)
        .map(|p| Node {
            id: 1000 + 10 * p as u64,
            xyz: [L20 * p as f64, 0.5 * (p % 3) as f64, 0.0],
            interface: p == 0 || p == n - 1,
        })
        .collect();
    let nm: Vec<NodalMass> = (0..n)
        .map(|p| {
            let j = mass20(p) * 10.0;
            NodalMass {
                mass: mass20(p),
                inertia: [[j, -0.1 * j, 0.0], [-0.1 * j, j, 0.0], [0.0, 0.0, 2.0 * j]],
            }
        })
        .collect();
    let mass_dof: Vec<f64> = (0..2 * n).map(|d| mass20(d / 2)).collect();
    let m = 8;
    let (mut omega2, phis) = lumped_modes(&mass_dof, &stiffness20(), m);
    let scale = omega2.iter().fold(0.0f64, |a, w| a.max(w.abs()));
    let labels: Vec<ModeLabel> = omega2
        .iter()
        .map(|w| {
            if w.abs() < 1e-9 * scale {
                ModeLabel::Rigid
            } else {
                ModeLabel::Normal
            }
        })
        .collect();
    for (w, l) in omega2.iter_mut().zip(&labels) {
        if *l == ModeLabel::Rigid {
            *w = 0.0; // exact zero for rigid modes: the spring matrix annihilates them exactly
        }
    }
    let mut shapes = vec![0.0; m * n * 6];
    for j in 0..m {
        for p in 0..n {
            shapes[(j * n + p) * 6] = phis[j][2 * p];
            shapes[(j * n + p) * 6 + 1] = phis[j][2 * p + 1];
        }
    }
    // Strain at node p: mean over adjacent elements of εxx = Δux/L and γxy = Δuy/L.
    let mut strain = vec![0.0; m * n * 6];
    for j in 0..m {
        for p in 0..n {
            let elems: Vec<usize> = [p.checked_sub(1), (p + 1 < n).then_some(p)]
                .into_iter()
                .flatten()
                .collect();
            for c in 0..2 {
                let mean: f64 = elems
                    .iter()
                    .map(|&e| (phis[j][2 * (e + 1) + c] - phis[j][2 * e + c]) / L20)
                    .sum::<f64>()
                    / elems.len() as f64;
                strain[(j * n + p) * 6 + if c == 0 { 0 } else { 3 }] = mean;
            }
        }
    }
    let invariants = invariants(&nodes, &nm, &shapes, m, InvariantSet::Partial);
    let faces = (0..n - 2)
        .step_by(2)
        .map(|p| Face::Tri([p as u32, p as u32 + 1, p as u32 + 2]))
        .chain([Face::Quad([0, 1, 3, 2])])
        .collect();
    let request = Request {
        method: Method::NormalModes,
        fmax_hz: Some(200.0),
        mode_count: Some(m as u64),
        keep_nodes: KeepNodes::List(vec![1000, 1190]),
        invariant_set: InvariantSet::Partial,
        mass_kind: MassKind::Lumped,
    };
    let units = Units {
        mass: Unit {
            name: "t".into(),
            si: 1000.0,
        },
        length: Unit {
            name: "mm".into(),
            si: 0.001,
        },
        time: Unit {
            name: "s".into(),
            si: 1.0,
        },
        force: Unit {
            name: "N".into(),
            si: 1.0,
        },
    };
    ReducedBody {
        version: V1_0,
        generator: Generator {
            name: "flexbody-fixtures".into(),
            version: "1".into(),
        },
        units,
        header: Header {
            title: "20-node chain, axial + shear springs, mm-t-s".into(),
            created_utc: Some("2026-01-01T00:00:00Z".into()),
            request,
        },
        nodes,
        faces,
        nodal_mass: nm,
        modes: Modes {
            frequency_hz: omega2.iter().map(|&w| hz(w)).collect(),
            labels,
            generalized_mass: diag(&vec![1.0; m]),
            generalized_stiffness: diag(&omega2),
            omega2,
            shapes,
        },
        invariants,
        method: MethodRecord {
            method: Method::NormalModes,
            mass_kind: MassKind::Lumped,
            interface: vec![
                InterfaceNode {
                    node: 0,
                    dofs: [true, true, false, false, false, true],
                    frame: identity_frame(),
                },
                InterfaceNode {
                    node: 19,
                    dofs: [true; 6],
                    frame: [[0.6, 0.8, 0.0], [-0.8, 0.6, 0.0], [0.0, 0.0, 1.0]],
                },
            ],
            reference_conditions: vec![],
            counts: ModeCounts {
                rigid: 2,
                normal: 6,
                ..Default::default()
            },
            cutoffs: Cutoffs {
                fmax_hz: Some(200.0),
                ..Default::default()
            },
        },
        stress_shapes: None,
        strain_shapes: Some(FieldShapes {
            nodes: (0..n as u32).collect(),
            values: strain,
        }),
        damping: None,
        lines: None,
        recipe: None,
        label_shares: None,
        stress_shapes_bottom: None,
        strain_shapes_bottom: None,
        interfaces: None,
        modal_loads: None,
        geometric_stiffness: None,
        eigen_residuals: None,
    }
}

/// Format version 1.0 (the golden files of v1.0 keep it: a body without v1.1 entries is written as
/// 1.0).
pub const V1_0: Version = Version { major: 1, minor: 0 };

/// The 3-node chain drawn as two graphics lines (format 1.1 `lines.bin`).
pub fn body_3node_lines() -> ReducedBody {
    let mut b = body_3node();
    b.lines = Some(vec![[0, 1], [1, 2]]);
    b.version = flexbody_reader::version_for(&b);
    b
}

/// A recipe for the 3-node chain (format 1.2 `recipe.json`): a normal-mode build of a made-up
/// deck with one include, node 101 named directly and node 103 the centre of an RBE2 spider.
pub fn recipe_3node() -> Recipe {
    let hex = |c: char| std::iter::repeat_n(c, 64).collect::<String>();
    Recipe {
        tool: Generator {
            name: "flexbody".into(),
            version: "0.1.0".into(),
        },
        model_files: vec![
            ModelFile {
                path: "chain.inp".into(),
                role: "main".into(),
                size: 240,
                sha256: hex('a'),
            },
            ModelFile {
                path: "mesh/chain_mesh.inp".into(),
                role: "include".into(),
                size: 1024,
                sha256: hex('0'),
            },
        ],
        options: RecipeOptions {
            format: None,
            material: Some("E=210000000000,nu=0.3,rho=7850".into()),
            method: "normal".into(),
            modes: Some(3),
            fmax_hz: None,
            mass: "lumped".into(),
            beam_mass: "section".into(),
            units: Units::si(),
            interface: vec!["101".into(), "RIGHT_END".into()],
            spider: "rbe2".into(),
            reference_conditions: vec![],
            reference_method: 1,
            keep_nodes: "all".into(),
            invariants: "full".into(),
            stress_fields: "none".into(),
            damping: Some("0-1:0%,1-:2%".into()),
            thickness: None,
            subcase: None,
            gravity: None,
            loads: vec![],
            residual_vectors: None,
            select: None,
            preload: Vec::new(),
            ignore: Vec::new(),
            inp_shells: None,
            eigensolver: None,
            geometric_stiffness: None,
        },
        interfaces: vec![
            RecipeInterface {
                entry: "101".into(),
                nodes: vec![101],
                spider: None,
            },
            RecipeInterface {
                entry: "RIGHT_END".into(),
                nodes: vec![103],
                spider: Some(RecipeSpider {
                    kind: "rbe2".into(),
                    centre_node: 103,
                    centre: [2.0, 0.0, 0.0],
                    fit: "NodeAverage".into(),
                    offset_from_node_average: 0.0,
                    set_nodes: vec![7, 8, 9],
                }),
            },
        ],
        accuracy_band: AccuracyBand {
            fmax_hz: hz(3.0 * K3 / M3),
            rule: "normal-modes".into(),
            basis_cutoff_hz: None,
        },
        preload: None,
    }
}

/// The 3-node chain with its build recipe (format 1.2 `recipe.json`).
pub fn body_3node_recipe() -> ReducedBody {
    let mut b = body_3node();
    b.recipe = Some(recipe_3node());
    b.label_shares = Some(vec![1.0, 1.0, 1.0]);
    b.version = flexbody_reader::version_for(&b);
    b
}

/// The 3-node chain with interface metadata (format 1.3 `interfaces.bin`): node 101 named by
/// its id, node 103 the centre of an RBE2 spider over mesh nodes 7, 8, 9 (not stored) placed by a
/// cylinder fit about the x axis.
pub fn body_3node_interfaces() -> ReducedBody {
    let mut b = body_3node_recipe();
    if let Some(s) = b
        .recipe
        .as_mut()
        .and_then(|r| r.interfaces[1].spider.as_mut())
    {
        s.fit = "CylinderFit".into();
        s.offset_from_node_average = 1e-3;
    }
    b.interfaces = Some(vec![
        InterfaceInfo {
            node: 0,
            name: "NODE101".into(),
            kind: InterfaceKind::Node,
            dependent: vec![],
            fit: None,
        },
        InterfaceInfo {
            node: 2,
            name: "RIGHT_END".into(),
            kind: InterfaceKind::Rbe2,
            dependent: vec![7, 8, 9],
            fit: Some(CentreFit {
                method: FitMethod::CylinderFit,
                centre: [2.0, 0.0, 0.0],
                axis: Some([1.0, 0.0, 0.0]),
                radius: Some(0.05),
                offset_from_node_average: 1e-3,
            }),
        },
    ]);
    b.version = flexbody_reader::version_for(&b);
    b
}

/// The 3-node chain (x axis, nodes 101–103) with the modal loads of its scene (format 1.4
/// `modal_loads.bin`): gravity −9.81 m/s² along x (Φᵀ M g: only the rigid mode,
/// 3·m·(−9.81)/√(3m)) and a 10 N axial tip force at node 103 (10·φ_103,j), closed form; no
/// residual vectors. The recipe records the options as given.
pub fn body_3node_modal_loads() -> ReducedBody {
    let mut b = body_3node_recipe();
    let n = b.nodes.len();
    let phi = |j: usize, p: usize| b.modes.shapes[(j * n + p) * 6];
    let gravity: Vec<f64> = (0..3)
        .map(|j| (0..n).map(|p| M3 * -9.81 * phi(j, p)).sum())
        .collect();
    let tip: Vec<f64> = (0..3).map(|j| 10.0 * phi(j, 2)).collect();
    b.modal_loads = Some(ModalLoads {
        loads: vec![
            ModalLoad {
                name: "GRAVITY".into(),
                source: "--gravity -9.81,0,0".into(),
                values: gravity,
            },
            ModalLoad {
                name: "TIP".into(),
                source: "--load TIP:103:10,0,0".into(),
                values: tip,
            },
        ],
        residual: vec![],
    });
    if let Some(r) = &mut b.recipe {
        r.options.gravity = Some("-9.81,0,0".into());
        r.options.loads = vec!["TIP:103:10,0,0".into()];
    }
    b.version = flexbody_reader::version_for(&b);
    b
}

/// The 3-node chain read as a shell strip (format 1.5): stress and strain shapes at all three
/// nodes, the top fibre, and the bottom fibre of nodes 1 and 2 (SPEC §5.15).
pub fn body_3node_shell_fibres() -> ReducedBody {
    let mut b = body_3node();
    let m = b.modes.omega2.len();
    let field = |nodes: Vec<u32>, scale: f64| {
        let k = nodes.len();
        FieldShapes {
            nodes,
            values: (0..m * k * 6)
                .map(|i| scale * (i as f64 * 0.25 - 1.5))
                .collect(),
        }
    };
    b.stress_shapes = Some(field(vec![0, 1, 2], 1.0e6));
    b.strain_shapes = Some(field(vec![0, 1, 2], 1.0e-5));
    b.stress_shapes_bottom = Some(field(vec![1, 2], -1.0e6));
    b.strain_shapes_bottom = Some(field(vec![1, 2], -1.0e-5));
    b.version = flexbody_reader::version_for(&b);
    b
}

/// Golden files: (file stem, body); each goes under `golden/v<its version>/`.
pub fn golden() -> Vec<(&'static str, ReducedBody)> {
    vec![
        ("three_node_chain", body_3node()),
        ("twenty_node_chain", body_20node()),
        ("three_node_chain_lines", body_3node_lines()),
        ("three_node_chain_recipe", body_3node_recipe()),
        ("three_node_chain_interfaces", body_3node_interfaces()),
        ("three_node_chain_modal_loads", body_3node_modal_loads()),
        ("three_node_chain_shell_fibres", body_3node_shell_fibres()),
        (
            "three_node_chain_residual_vectors",
            body_3node_residual_vectors(),
        ),
        (
            "three_node_chain_geometric_stiffness",
            body_3node_geometric_stiffness_1_7(),
        ),
        (
            "three_node_chain_geometric_stiffness",
            body_3node_geometric_stiffness(),
        ),
        (
            "three_node_chain_eigen_residuals",
            body_3node_eigen_residuals(),
        ),
    ]
}

/// Every fixture file (path relative to `fixtures/`, bytes), generated deterministically:
/// golden files with their JSON summaries, compat files (must be accepted) with summaries,
/// broken files with their `.expect`.
pub fn generate_all() -> Vec<(String, Vec<u8>)> {
    let summary = |bytes: &[u8]| {
        let (body, manifest) = from_bytes_with_manifest(bytes, &ReadLimits::default())
            .expect("generated fixture must read back");
        let mut s = serde_json::to_vec_pretty(&flexbody::inspect::summarize(&body, &manifest))
            .expect("summary json");
        s.push(b'\n');
        s
    };
    let mut out = Vec::new();
    for (stem, body) in golden() {
        let bytes =
            flexbody::write::to_bytes(&body, &Default::default()).expect("golden body is valid");
        let dir = format!("golden/v{}.{}", body.version.major, body.version.minor);
        out.push((format!("{dir}/{stem}.json"), summary(&bytes)));
        out.push((format!("{dir}/{stem}.flexbody"), bytes));
    }
    for case in broken::cases(&body_3node()) {
        match case.expect {
            None => {
                out.push((format!("compat/{}.json", case.name), summary(&case.bytes)));
                out.push((format!("compat/{}.flexbody", case.name), case.bytes));
            }
            Some((variant, message)) => {
                let mut e = serde_json::to_vec_pretty(
                    &serde_json::json!({ "variant": variant, "message": message }),
                )
                .expect("json");
                e.push(b'\n');
                out.push((format!("broken/{}.expect", case.name), e));
                out.push((format!("broken/{}.flexbody", case.name), case.bytes));
            }
        }
    }
    out
}
