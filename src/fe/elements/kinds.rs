//! The one lookup from an element kind to its formulation ([`super::element::Element`]): a
//! new kind is one arm here, and the compiler names every other place that must know it.

use super::element::Element;
use crate::model::ElementKind;

/// The formulation of `kind`.
pub fn element(kind: ElementKind) -> &'static dyn Element {
    match kind {
        ElementKind::Tet4 => &super::tet4::Tet4Element,
        ElementKind::Tet10 => &super::tet10::Tet10Element,
        ElementKind::Hex8 => &super::solid_incompatible::Hex8Element,
        ElementKind::Hex8R => &super::hex8r::Hex8rElement,
        ElementKind::Hex8Bbar => &super::hex8_bbar::Hex8BbarElement,
        ElementKind::Hex20 => &super::hex20_beam::Hex20Element { reduced: false },
        ElementKind::Hex20R => &super::hex20_beam::Hex20Element { reduced: true },
        ElementKind::Prism6 => &super::solid_incompatible::Prism6Element,
        ElementKind::Prism15 => &super::prism15::Prism15Element,
        ElementKind::Pyram5 => &super::pyram5::Pyram5Element,
        ElementKind::Pyram13 => &super::pyram13::Pyram13Element,
        ElementKind::Pyram13Ansys => &super::pyram13_ansys::Pyram13AnsysElement,
        ElementKind::Beam2 | ElementKind::Bar2 => &super::beam_element::BeamElement,
        ElementKind::Beam2Linear => &super::beam188::Beam188Element,
        ElementKind::Beam3Quadratic => &super::beam189::HigherOrderBeam {
            order: super::beam189::Order::Quadratic,
        },
        ElementKind::Beam4Cubic => &super::beam189::HigherOrderBeam {
            order: super::beam189::Order::Cubic,
        },
        ElementKind::Rod2 => &super::rod::RodElement,
        ElementKind::Tri3 => &super::tri3_shell::Tri3Element,
        ElementKind::Quad4 => &super::quad4_shell::Quad4Element,
        ElementKind::Tri6 => &super::tri6_shell::Tri6Element,
        ElementKind::Quad8 => &super::quad8_shell::Quad8Element,
        ElementKind::Beam3 => &super::element::Unassembled,
    }
}
