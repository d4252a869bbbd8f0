//! Test support of the preload tests: a model assembled and constrained as the build does it,
//! its preload system, dense eigenvalues of (K_T, M) and loads built in code.
#![allow(dead_code)]

use faer::sparse::SparseColMat;
use faer::Mat;
use flexbody::fe::preload::System;
use flexbody::fe::{assemble, eliminate, Assembled, AssemblySpec, ConstraintSpec, Reduced};
use flexbody::model::{DofMask, Load, LoadPart, Model, Spc};

/// A model with its assembly and elimination.
pub struct Built {
    pub model: Model,
    pub spec: AssemblySpec,
    pub asm: Assembled,
    pub red: Reduced,
}

impl Built {
    pub fn new(model: Model, spec: AssemblySpec) -> Built {
        let asm = assemble(&model, &spec).expect("assembles");
        let red = eliminate(
            &model,
            &asm.dofs,
            &asm.k,
            &asm.m,
            &ConstraintSpec::default(),
        )
        .expect("eliminates");
        Built {
            model,
            spec,
            asm,
            red,
        }
    }

    pub fn system(&self) -> System<'_> {
        System {
            model: &self.model,
            assembled: &self.asm,
            reduced: &self.red,
            assembly: &self.spec,
        }
    }
}

pub fn dense(a: &SparseColMat<usize, f64>) -> Mat<f64> {
    let a = a.as_ref();
    let mut d = Mat::zeros(a.nrows(), a.ncols());
    for j in 0..a.ncols() {
        for (i, v) in a.row_idx_of_col(j).zip(a.val_of_col(j)) {
            d[(i, j)] += v;
        }
    }
    d
}

/// The `count` lowest eigenpairs of K x = λ M x with the project's eigensolver (shift-invert:
/// accurate for the lowest modes whatever the stiffest dofs; a dense Cholesky of M is not),
/// M-orthonormal vectors.
pub fn lowest(
    k: &SparseColMat<usize, f64>,
    m: &SparseColMat<usize, f64>,
    count: usize,
) -> (Vec<f64>, Mat<f64>) {
    let s = flexbody::solve::lowest_modes(
        k,
        m,
        &flexbody::solve::EigenSpec {
            count,
            ..Default::default()
        },
    )
    .expect("eigensolver");
    (s.eigenvalues, s.vectors)
}

/// The lowest eigenvalues of K x = λ M x (a few).
pub fn eigenvalues(k: &SparseColMat<usize, f64>, m: &SparseColMat<usize, f64>) -> Vec<f64> {
    lowest(k, m, 4.min(k.nrows())).0
}

/// A load of one nodal force/moment.
pub fn nodal_load(node: usize, values: [f64; 6]) -> Load {
    Load {
        name: "PRELOAD".into(),
        source: "test".into(),
        selected: true,
        parts: vec![LoadPart::Nodal { node, values }],
        problem: None,
    }
}

/// Hold the digits of `node`.
pub fn hold(model: &mut Model, node: usize, digits: &str) {
    model.spcs.push(Spc {
        node,
        dofs: DofMask::from_digits(digits).expect("digits 1-6"),
        set_id: 0,
    });
}
