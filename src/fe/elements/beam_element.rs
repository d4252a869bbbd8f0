//! The 2-node beam (Nastran CBEAM/CBAR, Abaqus B31) as an [`Element`]: the section at its
//! orientation, Timoshenko or Euler–Bernoulli, pinned ends ([`beam::matrices_pinned`]), a
//! tapered section ([`tapered_beam`]) and offsets WA/WB (rigid links, [`beam::offset`]).

use super::beam::{self, BeamProps};
use super::element::{
    BeamTheory, Element, ElementInput, ElementMatrices, MatricesError, ModePoint, NodalGradients,
    SolidRules,
};
use super::{tapered_beam, ElementError, Xyz};
use crate::model::Section;

/// The 2-node beam and bar.
pub struct BeamElement;

impl Element for BeamElement {
    fn matrices(&self, input: &ElementInput) -> Result<ElementMatrices, MatricesError> {
        let unsupported = |m: String| Err(MatricesError::Unsupported(m));
        let Section::Beam(s) = &input.property.section else {
            return unsupported(format!(
                "beam element with non-beam property {}",
                input.property.id
            ));
        };
        let (model, e, lumped) = (input.model, input.index, input.lumped());
        let grid_x = input.coords::<2>();
        let offsets = model.beam_offsets.get(&e).copied();
        if offsets.is_some() && lumped {
            return unsupported(
                "offsets WA/WB with lumped mass are not implemented (the lumped masses at the \
                 offset ends would couple the grids' translations and rotations); use \
                 consistent mass (PARAM,COUPMASS,1 or --mass consistent)"
                    .into(),
            );
        }
        // The element runs between its offset ends (grid + W); rigid links join them below.
        let x = match offsets {
            Some(w) => [0, 1].map(|i| [0, 1, 2].map(|c| grid_x[i][c] + w[i][c])),
            None => grid_x,
        };
        let (v, iz, iy) = match model.elements[e].orientation {
            Some(v) => {
                let (v, iz, iy) = beam::principal_orientation(&x, v, s.i1, s.i2, s.i12)?;
                (Some(v), iz, iy)
            }
            None => (None, s.i1, s.i2),
        };
        let timoshenko = input.spec.beam == BeamTheory::Timoshenko;
        let p = BeamProps {
            area: s.area,
            iz,
            iy,
            j: s.j,
            // Nastran ignores K1, K2 when I12 ≠ 0 (QRG PBAR Remark 4).
            shear: if timoshenko && s.i12 == 0.0 {
                s.shear_factors
            } else {
                None
            },
            nsm: s.nsm,
        };
        let lumping = lumped.then_some(input.spec.beam_lumping.for_element(input.kind));
        let pins = model.beam_pins.get(&e).copied();
        let iso = &input.iso;
        let (k, m) = match (&s.taper, pins) {
            (None, None) => beam::matrices(&x, v, iso, &p, lumping),
            (None, Some(pins)) => beam::matrices_pinned(&x, v, iso, &p, lumping, pins),
            (Some(_), Some(_)) => {
                return unsupported("pin flags on a tapered beam are not implemented".into())
            }
            (Some(_), None) => {
                let at = |xi: f64| {
                    let ([area, iz, iy, j, nsm], k) = s.at(xi);
                    let shear = k.filter(|_| timoshenko);
                    BeamProps {
                        area,
                        iz,
                        iy,
                        j,
                        shear,
                        nsm,
                    }
                };
                let breaks = s.breakpoints();
                tapered_beam::matrices(&x, v, iso, &at, &breaks, lumping)
            }
        }?;
        let (k, m) = match offsets {
            Some(w) => (beam::offset(&k, &w), beam::offset(&m, &w)),
            None => (k, m),
        };
        Ok(ElementMatrices::nodal(6, k, m))
    }

    fn stiffness_points(
        &self,
        _: &[Xyz],
        _: SolidRules,
    ) -> Result<Option<Vec<ModePoint>>, ElementError> {
        Ok(None)
    }

    fn nodal_gradients(&self, _: &[Xyz]) -> Result<Option<NodalGradients>, ElementError> {
        Ok(None)
    }
}
