//! Temperatures of an Abaqus/CalculiX deck and the material data that depend on them.
//!
//! * `*INITIAL CONDITIONS, TYPE=TEMPERATURE` (node or node set, T) gives the initial
//!   temperatures; a `*TEMPERATURE` of the static step that a `*FREQUENCY, PERTURBATION` step
//!   perturbs gives the temperatures of the state the modes are taken in (CalculiX: the
//!   perturbation step's material data are those of that state).
//! * Temperature tables of `*ELASTIC` (E, ν, T rows) and `*DENSITY` (ρ, T) are evaluated at
//!   that state's temperature as CalculiX interpolates them: linearly between rows, the first
//!   or last row outside the table (ccx's `interpol`). The part must have one temperature
//!   (a uniform field): a table over a non-uniform field is refused, as is a table without
//!   any temperature.
//! * `*EXPANSION` (α, T rows): a thermal strain arises only where the state's temperature
//!   differs from the initial one and α ≠ 0; that thermal preload is refused by line. With
//!   zero expansion (CalculiX beamft) the temperatures change the material data only.

use super::sets::Sets;
use super::{Parser, Target};
use crate::import::error::ImportError;
use crate::import::text::Loc;

/// One row of a material table: values and the temperature (None: no temperature column).
pub(super) type Row<const N: usize> = ([f64; N], Option<f64>, Loc);

/// A `*TEMPERATURE` or `*INITIAL CONDITIONS, TYPE=TEMPERATURE` data line: target and T; the
/// step it belongs to (None: initial conditions).
#[derive(Debug, Clone)]
pub(super) struct RawTemperature {
    pub step: Option<usize>,
    pub target: Target,
    pub t: f64,
    pub loc: Loc,
}

/// The values of a table at temperature `t` (CalculiX `interpol`: linear between rows sorted by
/// temperature, the end rows outside). `None` when rows need a temperature and `t` is `None`.
pub(super) fn at_temperature<const N: usize>(rows: &[Row<N>], t: Option<f64>) -> Option<[f64; N]> {
    match rows {
        [] => None,
        [only] => Some(only.0),
        _ => {
            let t = t?;
            let mut sorted: Vec<&Row<N>> = rows.iter().collect();
            sorted.sort_by(|a, b| a.1.unwrap_or(0.0).total_cmp(&b.1.unwrap_or(0.0)));
            let temp = |r: &Row<N>| r.1.unwrap_or(0.0);
            let (first, last) = (sorted[0], sorted[sorted.len() - 1]);
            if t <= temp(first) {
                return Some(first.0);
            }
            if t >= temp(last) {
                return Some(last.0);
            }
            let k = sorted.iter().position(|r| temp(r) > t)?;
            let (a, b) = (sorted[k - 1], sorted[k]);
            let w = (t - temp(a)) / (temp(b) - temp(a));
            Some(std::array::from_fn(|i| a.0[i] + w * (b.0[i] - a.0[i])))
        }
    }
}

/// A table that depends on temperature: more than one row.
pub(super) fn depends_on_temperature<const N: usize>(rows: &[Row<N>]) -> bool {
    rows.len() > 1
}

/// The temperatures per node (like the model's nodes) of the initial state and of the state the
/// modes are taken in (the perturbed static step's `*TEMPERATURE` over the initial ones).
#[derive(Debug, Clone, Default)]
pub(super) struct TemperatureState {
    pub initial: Vec<Option<f64>>,
    pub state: Vec<Option<f64>>,
    /// A `*TEMPERATURE` of a step before the `*FREQUENCY` step that is not the state's (its
    /// line): which temperatures CalculiX takes then is not modelled.
    pub other_step: Option<Loc>,
    /// The first temperature line of the state.
    pub first: Option<Loc>,
    /// Per node: used by an element (a node of no element, acou3's node 262, needs no
    /// temperature); empty = all.
    pub used: Vec<bool>,
}

impl TemperatureState {
    /// The one temperature of the state over the nodes of elements: `Ok(None)` without
    /// temperatures, `Err((lo, hi))` for a field that is not uniform (a node without a
    /// temperature counts as different).
    pub(super) fn uniform(&self) -> Result<Option<f64>, (f64, f64)> {
        let used = |n: usize| self.used.get(n).copied().unwrap_or(true);
        let state: Vec<Option<f64>> = (self.state.iter().enumerate())
            .filter(|(n, _)| used(*n))
            .map(|(_, t)| *t)
            .collect();
        let given: Vec<f64> = state.iter().flatten().copied().collect();
        let Some(&t0) = given.first() else {
            return Ok(None);
        };
        let (lo, hi) = given
            .iter()
            .fold((t0, t0), |(a, b), &t| (a.min(t), b.max(t)));
        if lo != hi || given.len() != state.len() {
            return Err((lo, hi));
        }
        Ok(Some(t0))
    }
}

impl Parser {
    /// The deck's temperatures (module doc); `base` is the static step a `*FREQUENCY,
    /// PERTURBATION` step perturbs, if any.
    pub(super) fn temperature_state(
        &self,
        sets: &Sets,
        n_nodes: usize,
        base: Option<usize>,
    ) -> Result<TemperatureState, ImportError> {
        let freq = self.steps.frequency_step().unwrap_or(usize::MAX);
        let mut st = TemperatureState {
            initial: vec![None; n_nodes],
            ..Default::default()
        };
        for t in self.temperatures.iter().filter(|t| t.step.is_none()) {
            for n in sets.target(&t.target, t.loc, "*INITIAL CONDITIONS", self)? {
                st.initial[n] = Some(t.t);
            }
            st.first.get_or_insert(t.loc);
        }
        st.state = st.initial.clone();
        let mut step_first = None;
        for t in &self.temperatures {
            match t.step {
                Some(k) if Some(k) == base => {
                    for n in sets.target(&t.target, t.loc, "*TEMPERATURE", self)? {
                        st.state[n] = Some(t.t);
                    }
                    step_first.get_or_insert(t.loc);
                }
                Some(k) if k < freq => {
                    st.other_step.get_or_insert(t.loc);
                }
                _ => {}
            }
        }
        st.first = step_first.or(st.first);
        st.used = vec![false; n_nodes];
        for el in &self.b.model.elements {
            for &n in &el.nodes {
                if let Some(u) = st.used.get_mut(n) {
                    *u = true;
                }
            }
        }
        Ok(st)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(v: f64, t: f64) -> Row<1> {
        ([v], Some(t), Loc { file: 0, line: 1 })
    }

    /// ccx interpolates linearly and holds the end rows outside the table (beamft: E from
    /// 210000 at 0° to 30000 at 500°, at 499.999°).
    #[test]
    fn tables_interpolate_and_clamp_as_calculix() {
        let rows = [row(30000.0, 500.0), row(210000.0, 0.0)];
        let e = at_temperature(&rows, Some(499.999)).unwrap()[0];
        assert!((e - 30000.36).abs() < 1e-9, "{e}");
        assert_eq!(at_temperature(&rows, Some(-5.0)).unwrap()[0], 210000.0);
        assert_eq!(at_temperature(&rows, Some(900.0)).unwrap()[0], 30000.0);
        assert_eq!(at_temperature(&rows, None), None);
        assert_eq!(at_temperature(&rows[..1], None).unwrap()[0], 30000.0);
    }
}
