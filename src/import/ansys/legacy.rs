//! ANSYS's archived ("legacy") solids, which archives of older pipelines and old models carried
//! into new MAPDL versions hold: SOLID45 and SOLID95 formed as the MAPDL Archived Elements
//! Theory Reference (§1.6, §1.17; release 2024 R2) forms them, with the elements formed today
//! where the text gives the same functions and points; SOLID92 is refused by the catalogue (its
//! Theory page was not at hand: docs/ansys.md).
//!
//! - SOLID45 (8 nodes): stiffness with the "modified extra shape functions" (Wilson, Taylor et
//!   al.) when KEYOPT(1)=0 and the element has 8 unique nodes, else the trilinear functions;
//!   2×2×2 points (KEYOPT(2)=0); mass and stress stiffness with the trilinear functions on the
//!   same points. Wilson's incompatible modes with Taylor's correction on 2×2×2 points and the
//!   compatible mass are flexbody's SOLID185 KEYOPT(2)=3 (`Hex8` with incompatible modes); the
//!   trilinear brick on 2×2×2 is `Hex8` without them; collapsed into ANSYS's wedge it is the
//!   brick as written on 2×2×2 points, which `Hex8Bbar` forms for SOLID185's wedge.
//! - SOLID95 (20 nodes): stiffness, mass and stress stiffness "14 if KEYOPT(11) = 0, 2 x 2 x 2
//!   if KEYOPT(11) = 1" for the brick; wedge 3 × 3, pyramid 2 × 2 × 2, tetrahedron 4 points
//!   (SOLID186's table): KEYOPT(11)=0 is SOLID186 KEYOPT(2)=1, KEYOPT(11)=1 has SOLID186
//!   KEYOPT(2)=0's stiffness with its mass on the same 2×2×2 points
//!   (`elements::Brick20Rule::Gauss2`).
//!
//! Their records are formed by `elements::form` (`solid45`, `solid95`) as the kinds above; what
//! a kind does not say — SOLID45 KEYOPT(1)=1's brick without incompatible modes, SOLID95
//! KEYOPT(11)=1's 2×2×2 mass — is this file's ([`solid_rule`], run over the formed elements).

use std::collections::{BTreeMap, BTreeSet};

use super::elements::ElementType;
use super::Archive;
use crate::model::{ElementKind, Model};

/// What an element of type `t` formed as `kind` carries beyond its kind.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum SolidRule {
    /// Nothing: the kind's formulation.
    AsKind,
    /// SOLID45 KEYOPT(1)=1: `Hex8` without incompatible modes.
    PlainBrick,
    /// SOLID95 KEYOPT(11)=1: `Hex20R` with its mass on 2×2×2 points (`Model::hex20_mass_2x2x2`).
    MassOnGauss2,
}

/// The rule of an element of type `t` that [`super::elements::form`] formed as `kind`.
pub(super) fn solid_rule(t: &ElementType, kind: ElementKind) -> SolidRule {
    let number = t.row.map(|r| r.0);
    let keyopt = |k: u32| t.keyopts.get(&k).copied().unwrap_or(0);
    if number == Some(45) && kind == ElementKind::Hex8 && keyopt(1) == 1 {
        SolidRule::PlainBrick
    } else if number == Some(95) && kind == ElementKind::Hex20R {
        SolidRule::MassOnGauss2
    } else {
        SolidRule::AsKind
    }
}

impl Archive {
    /// After the elements are formed (`elements`: record id → model element index): the
    /// per-element rules of the archived solids ([`solid_rule`]) — SOLID95 KEYOPT(11)=1's 2×2×2
    /// mass into `Model::hex20_mass_2x2x2` — and flexbody's incompatible modes, which are
    /// model-wide (`ModelParams::solid_bubbles`): on when the archive forms a brick with them
    /// (SOLID185 KEYOPT(2)=3, SOLID45 KEYOPT(1)=0); then SOLID45 KEYOPT(1)=1 bricks, which have
    /// none, are refused by their first record's line.
    pub(super) fn archived_solid_rules(
        &mut self,
        elements: &BTreeMap<u64, Option<usize>>,
        model: &mut Model,
    ) {
        let mut plain: Vec<(usize, usize)> = Vec::new();
        for r in &self.elements {
            let (Some(t), Some(&Some(e))) = (self.types.get(&r.etype), elements.get(&r.id)) else {
                continue;
            };
            let Some(kind) = model.elements.get(e).map(|x| x.kind) else {
                continue;
            };
            match solid_rule(t, kind) {
                SolidRule::AsKind => {}
                SolidRule::PlainBrick => plain.push((r.line, e)),
                SolidRule::MassOnGauss2 => {
                    model.hex20_mass_2x2x2.insert(e);
                }
            }
        }
        let plain_set: BTreeSet<usize> = plain.iter().map(|p| p.1).collect();
        model.params.solid_bubbles = (model.elements.iter().enumerate())
            .any(|(i, e)| e.kind == ElementKind::Hex8 && !plain_set.contains(&i));
        if let (true, Some(&(line, _))) = (model.params.solid_bubbles, plain.first()) {
            self.refuse(
                line,
                "SOLID45",
                format!(
                    "SOLID45 KEYOPT(1)=1 (no extra shapes: {} brick(s), the first here) beside \
                     bricks with incompatible modes (SOLID45 KEYOPT(1)=0, SOLID185 KEYOPT(2)=3) \
                     in one archive: flexbody forms incompatible modes for the whole body",
                    plain.len()
                ),
            );
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::elements::tests::record;
    use super::super::elements::{Formed, Refusal};
    use super::*;

    fn formed(t: &ElementType, nodes: Vec<u64>) -> Result<Formed, Refusal> {
        super::super::elements::form(t, &record(nodes), None, None, None)
    }

    #[test]
    fn solid95_keyopt11_picks_the_brick_rule_and_its_mass() {
        let nodes: Vec<u64> = (1..=20).collect();
        let mut t = ElementType::new(3, "SOLID95");
        assert_eq!(
            formed(&t, nodes.clone()),
            Ok(Formed::Element(ElementKind::Hex20, nodes.clone()))
        );
        assert_eq!(solid_rule(&t, ElementKind::Hex20), SolidRule::AsKind);
        t.keyopts.insert(11, 1);
        assert_eq!(
            formed(&t, nodes.clone()),
            Ok(Formed::Element(ElementKind::Hex20R, nodes.clone()))
        );
        assert_eq!(solid_rule(&t, ElementKind::Hex20R), SolidRule::MassOnGauss2);
        // SOLID186 KEYOPT(2)=0 is Hex20R too, with the 14-point mass
        let t186 = ElementType::new(3, "186");
        assert_eq!(solid_rule(&t186, ElementKind::Hex20R), SolidRule::AsKind);
        t.keyopts.insert(3, 1);
        let why = formed(&t, nodes).unwrap_err();
        assert!(why.contains("SOLID95 KEYOPT(3)=1"), "{why}");
    }

    #[test]
    fn solid45_keyopt1_and_shapes() {
        let brick: Vec<u64> = (1..=8).collect();
        let mut t = ElementType::new(3, "45");
        assert_eq!(
            formed(&t, brick.clone()),
            Ok(Formed::Element(ElementKind::Hex8, brick.clone()))
        );
        assert_eq!(solid_rule(&t, ElementKind::Hex8), SolidRule::AsKind);
        let wedge = vec![1, 2, 3, 3, 5, 6, 7, 7];
        assert_eq!(
            formed(&t, wedge.clone()),
            Ok(Formed::Element(ElementKind::Hex8Bbar, wedge.clone()))
        );
        t.keyopts.insert(1, 1);
        assert_eq!(solid_rule(&t, ElementKind::Hex8), SolidRule::PlainBrick);
        assert_eq!(solid_rule(&t, ElementKind::Hex8Bbar), SolidRule::AsKind);
        let why = formed(&t, vec![1, 2, 3, 4, 5, 5, 5, 5]).unwrap_err();
        assert!(why.contains("other than ANSYS's wedge"), "{why}");
        t.keyopts.insert(2, 1);
        let why = formed(&t, brick).unwrap_err();
        assert!(why.contains("SOLID45 KEYOPT(2)=1"), "{why}");
    }
}
