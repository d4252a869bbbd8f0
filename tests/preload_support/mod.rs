//! Test support of the preload tests: a model assembled and constrained as the build does it,
//! its preload system, the lowest eigenvalues of (K_T, M), straight line-element models and
//! loads built in code.
#![allow(dead_code)]

use faer::sparse::SparseColMat;
use faer::Mat;
use flexbody::fe::geometric::{element_stresses, ElementStress, Temperature, Thermal};
use flexbody::fe::preload::{preload, Preload, PreloadCase, PreloadError, PreloadSpec, System};
use flexbody::fe::{assemble, eliminate, Assembled, AssemblySpec, ConstraintSpec, Reduced};
use flexbody::model::{
    DofMask, Element, ElementKind, Load, LoadPart, Material, Model, Node, Property, Section, Spc,
};

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

/// A straight line of `ne` elements of `kind` from `start` to `end`, one property with
/// `section` and `material`, orientation vector `v` (beams).
pub fn straight_line(
    ne: usize,
    start: [f64; 3],
    end: [f64; 3],
    kind: ElementKind,
    section: Section,
    material: Material,
    v: [f64; 3],
) -> Model {
    let mut model = Model {
        source: "line".into(),
        ..Model::default()
    };
    model.materials.push(material);
    model.properties.push(Property {
        id: 1,
        name: "LINE".into(),
        material: 0,
        section,
    });
    for i in 0..=ne {
        let t = i as f64 / ne as f64;
        model.nodes.push(Node {
            id: i as u64 + 1,
            x: std::array::from_fn(|k| start[k] + t * (end[k] - start[k])),
            displacement_frame: None,
        });
    }
    for e in 0..ne {
        model.elements.push(Element {
            id: e as u64 + 1,
            kind,
            nodes: vec![e, e + 1],
            property: Some(0),
            orientation: Some(v),
        });
    }
    model
}

/// f(case)/f(0) of the lowest mode: √(ω²₁(K_T)/`w0`), `w0` the unloaded lowest ω².
pub fn frequency_ratio(b: &Built, case: &PreloadCase, w0: f64) -> Result<f64, PreloadError> {
    let pre = preload(&b.system(), case, &PreloadSpec::default())?;
    Ok((eigenvalues(&pre.k_t, &b.red.m)[0] / w0).sqrt())
}

/// Prints and checks a frequency ratio against its closed form.
pub fn check_ratio(what: &str, got: f64, want: f64, tol: f64) {
    let err = (got - want) / want;
    eprintln!("{what}: f/f0 = {got:.8}, closed form {want:.8}, rel. error {err:+.2e}");
    assert!(err.abs() < tol, "{what}: {got} vs {want}");
}

/// The preload of a uniform temperature change `dt` (α per material) and the element stresses
/// it leaves.
pub fn heated(b: &Built, alpha: Vec<f64>, dt: f64) -> (Preload, Vec<(usize, ElementStress)>) {
    let thermal = Thermal {
        delta_t: Temperature::Uniform(dt),
        alpha,
    };
    let case = PreloadCase {
        thermal: Some(thermal.clone()),
        ..Default::default()
    };
    let pre = preload(&b.system(), &case, &PreloadSpec::default()).expect("preload");
    let stresses =
        element_stresses(&b.model, &b.asm.dofs, &b.spec, &pre.u, Some(&thermal)).expect("stresses");
    (pre, stresses)
}
