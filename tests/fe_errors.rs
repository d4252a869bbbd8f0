//! Bad input gives an `FeError` naming the file and the element, never a panic.

use crate::common::steel;
use flexbody::fe::elements::ElementError;
use flexbody::fe::{assemble, AssemblySpec, FeError};
use flexbody::model::{BeamSection, Element, ElementKind, Model, Node, Property, Section};

fn base() -> Model {
    let mut m = Model {
        source: "bad.inp".into(),
        ..Model::default()
    };
    m.materials.push(steel());
    m.properties.push(Property {
        id: 1,
        name: "S".into(),
        material: 0,
        section: Section::Solid,
    });
    for (i, x) in [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
    ]
    .iter()
    .enumerate()
    {
        m.nodes.push(Node {
            id: 10 + i as u64,
            x: *x,
            displacement_frame: None,
        });
    }
    m
}

fn tet(nodes: Vec<usize>) -> Element {
    Element {
        id: 77,
        kind: ElementKind::Tet4,
        nodes,
        property: Some(0),
        orientation: None,
    }
}

#[test]
fn inverted_tet_is_a_jacobian_error_naming_the_element() {
    let mut m = base();
    m.elements.push(tet(vec![0, 2, 1, 3]));
    let e = assemble(&m, &AssemblySpec::default()).unwrap_err();
    assert!(
        matches!(
            &e,
            FeError::Element {
                id: 77,
                err: ElementError::NonPositiveJacobian { .. },
                ..
            }
        ),
        "{e}"
    );
    assert!(e.to_string().starts_with("bad.inp: element 77"), "{e}");
}

#[test]
fn wrong_node_count_dangling_node_and_missing_property_are_errors() {
    let mut m = base();
    m.elements.push(tet(vec![0, 1, 2]));
    assert!(matches!(
        assemble(&m, &AssemblySpec::default()),
        Err(FeError::Unsupported { id: 77, .. })
    ));
    let mut m = base();
    m.elements.push(tet(vec![0, 1, 2, 9]));
    assert!(assemble(&m, &AssemblySpec::default()).is_err());
    let mut m = base();
    let mut t = tet(vec![0, 1, 2, 3]);
    t.property = Some(5);
    m.elements.push(t);
    let e = assemble(&m, &AssemblySpec::default()).unwrap_err();
    assert!(e.to_string().contains("property"), "{e}");
}

#[test]
fn shells_beams_without_orientation_and_bad_materials_are_errors() {
    let mut m = base();
    m.properties.push(Property {
        id: 2,
        name: "SH".into(),
        material: 0,
        section: Section::Shell(flexbody::model::ShellSection::homogeneous(0.01, 0)),
    });
    m.elements.push(Element {
        id: 5,
        kind: ElementKind::Quad4,
        nodes: vec![0, 1, 2, 3],
        // a shell on a solid section (e.g. an Abaqus CPS4 with *SOLID SECTION)
        property: Some(0),
        orientation: None,
    });
    let e = assemble(&m, &AssemblySpec::default()).unwrap_err();
    assert!(e.to_string().contains("non-shell property"), "{e}");
    assert!(
        matches!(
            &e,
            FeError::Unsupported {
                id: 5,
                kind: ElementKind::Quad4,
                ..
            }
        ),
        "{e}"
    );

    let mut m = base();
    let sec = BeamSection {
        area: 1e-4,
        i1: 1e-9,
        i2: 1e-9,
        i12: 0.0,
        j: 2e-9,
        shear_factors: None,
        nsm: 0.0,
        shape: None,
        taper: None,
    };
    m.properties.push(Property {
        id: 3,
        name: "B".into(),
        material: 0,
        section: Section::Beam(sec),
    });
    m.elements.push(Element {
        id: 6,
        kind: ElementKind::Beam2,
        nodes: vec![0, 1],
        property: Some(1),
        orientation: None,
    });
    let e = assemble(&m, &AssemblySpec::default()).unwrap_err();
    assert!(
        matches!(
            &e,
            FeError::Element {
                id: 6,
                err: ElementError::BadOrientation { .. },
                ..
            }
        ),
        "{e}"
    );
    // Orientation parallel to the axis.
    m.elements[0].orientation = Some([2.0, 0.0, 0.0]);
    assert!(matches!(
        assemble(&m, &AssemblySpec::default()),
        Err(FeError::Element { id: 6, .. })
    ));

    let mut m = base();
    m.materials[0].nu = 0.5;
    m.elements.push(tet(vec![0, 1, 2, 3]));
    let e = assemble(&m, &AssemblySpec::default()).unwrap_err();
    assert!(
        matches!(
            &e,
            FeError::Element {
                err: ElementError::BadConstants(_),
                ..
            }
        ),
        "{e}"
    );
}
