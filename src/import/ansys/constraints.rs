//! `D`, `CE`, `CP` (constraints) and `F`, `ACEL` (scene loads) → the model's SPCs, MPCs and
//! loads. `D` holds a dof at zero (as the other formats' SPCs: a reference condition of the
//! body); `CE` is the MPC Σ cᵢ uᵢ = 0 it states; `CP` makes the listed nodes' dof equal to the
//! first node's (one two-term MPC per further node: the MPC the coupled set stands for). On a
//! rotated node (NBLOCK angles) ANSYS reads all four in the nodal coordinate system: `D`, `CE`
//! and `CP` name the node's dofs, which are in its displacement frame ([`super::nodal`]), and
//! `F` is turned to global components for the scene load.

use std::collections::BTreeMap;

use super::blocks::Command;
use super::list;
use crate::import::error::{parse_err, ImportError};
use crate::import::text::IdMap;
use crate::model::deck::ConstraintSource;
use crate::model::load::{Load, LoadPart};
use crate::model::{DofMask, Model, Mpc, NodeDof, Spc};

/// A dof label's 0-based component (UX…ROTZ), `None` for a label not structural.
pub(super) fn dof_of(label: &str) -> Option<u8> {
    Some(match label.trim().to_ascii_uppercase().as_str() {
        "UX" => 0,
        "UY" => 1,
        "UZ" => 2,
        "ROTX" => 3,
        "ROTY" => 4,
        "ROTZ" => 5,
        _ => return None,
    })
}

/// A force label's component (FX…MZ).
fn force_of(label: &str) -> Option<usize> {
    Some(match label.trim().to_ascii_uppercase().as_str() {
        "FX" => 0,
        "FY" => 1,
        "FZ" => 2,
        "MX" => 3,
        "MY" => 4,
        "MZ" => 5,
        _ => return None,
    })
}

/// A constraint equation's terms: (node id, 0-based dof, coefficient).
pub(super) type Terms = Vec<(u64, u8, f64)>;

/// The constraints and loads read, by external node id.
#[derive(Debug, Default)]
pub(super) struct Raw {
    /// (line, node, dof mask bits).
    pub held: Vec<(usize, u64, u8)>,
    /// Constraint equations: (line, terms (node, dof, coefficient)).
    pub equations: Vec<(usize, Terms)>,
    /// Coupled sets: set number → (first line, dof, nodes).
    pub coupled: BTreeMap<i64, (usize, u8, Vec<u64>)>,
    /// Nodal forces: (line, node, component, value).
    pub forces: Vec<(usize, u64, usize, f64)>,
    /// ACEL: (line, acceleration).
    pub acel: Option<(usize, [f64; 3])>,
}

/// A refusal: line and reason.
pub(super) type Refused = (usize, String);

/// A node field: a positive node number (a component name or ALL is refused).
fn node_field(file: &str, c: &Command, i: usize) -> Result<Option<u64>, ImportError> {
    let s = c.field(i);
    if s.chars()
        .all(|ch| ch.is_ascii_digit() || ch == '.' || ch == '+')
        && !s.is_empty()
    {
        let n = c.int(file, i)?;
        return Ok((n > 0).then_some(n as u64));
    }
    Ok(None)
}

impl Raw {
    /// `D,NODE,Lab,VALUE,VALUE2`.
    pub fn d(
        &mut self,
        file: &str,
        c: &Command,
        refused: &mut Vec<Refused>,
    ) -> Result<(), ImportError> {
        let Some(node) = node_field(file, c, 0)? else {
            refused.push((
                c.line,
                format!("D on '{}': only node numbers are read", c.field(0)),
            ));
            return Ok(());
        };
        let lab = c.field(1).to_ascii_uppercase();
        let mask = match (lab.as_str(), dof_of(&lab)) {
            ("ALL", _) => 0b11_1111,
            (_, Some(k)) => 1u8 << k,
            (_, None) => {
                refused.push((
                    c.line,
                    format!("D on dof {lab}: only UX…ROTZ and ALL are read"),
                ));
                return Ok(());
            }
        };
        if c.real(file, 2)? != 0.0 || c.real(file, 3)? != 0.0 {
            refused.push((
                c.line,
                "D with a nonzero value: an enforced displacement is not a constraint of the \
                 body"
                    .into(),
            ));
            return Ok(());
        }
        self.held.push((c.line, node, mask));
        Ok(())
    }

    /// A constraint equation's terms (from the `CE,R5.0,DEFI` block) and its constant.
    pub fn ce(
        &mut self,
        line: usize,
        terms: Vec<(u64, String, f64, usize)>,
        constant: f64,
        refused: &mut Vec<Refused>,
    ) {
        if constant != 0.0 {
            refused.push((
                line,
                format!("CE with the constant {constant}: an enforced motion is not read"),
            ));
            return;
        }
        let mut out = Vec::with_capacity(terms.len());
        for (node, lab, coef, at) in terms {
            match dof_of(&lab) {
                Some(k) => out.push((node, k, coef)),
                None => {
                    refused.push((at, format!("CE term on dof {lab}: only UX…ROTZ are read")));
                    return;
                }
            }
        }
        self.equations.push((line, out));
    }

    /// `CP,NSET,Lab,NODE1,…,NODE17` (the same NSET again adds nodes).
    pub fn cp(
        &mut self,
        file: &str,
        c: &Command,
        refused: &mut Vec<Refused>,
    ) -> Result<(), ImportError> {
        let set = c.int(file, 0)?;
        let lab = c.field(1).to_ascii_uppercase();
        let Some(k) = dof_of(&lab) else {
            refused.push((c.line, format!("CP on dof {lab}: only UX…ROTZ are read (ALL couples every dof: write one set per dof)")));
            return Ok(());
        };
        let mut nodes = Vec::new();
        for i in 2..c.fields.len() {
            if c.field(i).is_empty() {
                continue;
            }
            match node_field(file, c, i)? {
                Some(n) => nodes.push(n),
                None => {
                    refused.push((
                        c.line,
                        format!("CP node '{}': only node numbers are read", c.field(i)),
                    ));
                    return Ok(());
                }
            }
        }
        let entry = self.coupled.entry(set).or_insert((c.line, k, Vec::new()));
        if entry.1 != k {
            refused.push((c.line, format!("CP set {set} on {lab} after another dof")));
            return Ok(());
        }
        entry.2.extend(nodes);
        Ok(())
    }

    /// `F,NODE,Lab,VALUE` (the imaginary part VALUE2 must be zero).
    pub fn f(
        &mut self,
        file: &str,
        c: &Command,
        refused: &mut Vec<Refused>,
    ) -> Result<(), ImportError> {
        let Some(node) = node_field(file, c, 0)? else {
            refused.push((
                c.line,
                format!("F on '{}': only node numbers are read", c.field(0)),
            ));
            return Ok(());
        };
        let lab = c.field(1);
        let Some(k) = force_of(lab) else {
            refused.push((c.line, format!("F of {lab}: only FX…MZ are read")));
            return Ok(());
        };
        if c.real(file, 3)? != 0.0 {
            refused.push((c.line, "F with an imaginary part: not read".into()));
            return Ok(());
        }
        self.forces.push((c.line, node, k, c.real(file, 2)?));
        Ok(())
    }

    /// `ACEL,ACELX,ACELY,ACELZ` (all zero: nothing).
    pub fn acel(&mut self, file: &str, c: &Command) -> Result<(), ImportError> {
        let a = [c.real(file, 0)?, c.real(file, 1)?, c.real(file, 2)?];
        self.acel = (a != [0.0; 3]).then_some((c.line, a));
        Ok(())
    }
}

impl super::Archive {
    /// D → SPCs (one constraint source), CE/CP → MPCs, F/ACEL → loads.
    pub(super) fn constraints(
        &mut self,
        file: &str,
        node_map: &IdMap,
        model: &mut Model,
    ) -> Result<(), ImportError> {
        let node = |id: u64, line: usize, what: &str| {
            node_map
                .get(id)
                .ok_or_else(|| parse_err(file, line, what, format!("unknown node {id}")))
        };
        let first = model.spcs.len();
        for &(line, id, mask) in &self.raw.held {
            model.spcs.push(Spc {
                node: node(id, line, "D")?,
                dofs: DofMask(mask),
                set_id: 0,
            });
        }
        if let Some(&(line, ..)) = self.raw.held.first() {
            model.constraint_sources.push(ConstraintSource {
                card: "D".into(),
                id: format!("{} D line(s)", self.raw.held.len()),
                file: file.to_owned(),
                line,
                set: None,
                spcs: first..model.spcs.len(),
                permanent: false,
            });
        }
        let mut id = 0u64;
        let mut zero_first = Vec::new();
        for (line, terms) in &self.raw.equations {
            id += 1;
            let mut t = Vec::with_capacity(terms.len());
            for &(n, k, c) in terms {
                t.push((
                    NodeDof {
                        node: node(n, *line, "CE")?,
                        component: k,
                    },
                    c,
                ));
            }
            if t.first().is_none_or(|x| x.1 == 0.0) {
                zero_first.push(*line);
                continue;
            }
            model.mpcs.push(Mpc { id, terms: t });
        }
        for line in zero_first {
            self.refuse(
                line,
                "CE",
                "a constraint equation whose first coefficient is zero",
            );
        }
        for (line, k, nodes) in self.raw.coupled.values() {
            let Some((&lead, rest)) = nodes.split_first() else {
                continue;
            };
            let lead = node(lead, *line, "CP")?;
            for &n in rest {
                id += 1;
                let dependent = node(n, *line, "CP")?;
                model.mpcs.push(Mpc {
                    id,
                    terms: vec![
                        (
                            NodeDof {
                                node: dependent,
                                component: *k,
                            },
                            1.0,
                        ),
                        (
                            NodeDof {
                                node: lead,
                                component: *k,
                            },
                            -1.0,
                        ),
                    ],
                });
            }
        }
        if !self.raw.forces.is_empty() {
            let mut parts = Vec::new();
            for &(line, n, k, v) in &self.raw.forces {
                // ANSYS's F is in the node's nodal system; a scene load's parts are global
                let at = node(n, line, "F")?;
                let mut nodal = [0.0; 3];
                nodal[k % 3] = v;
                let global = super::nodal::to_global(model, at, nodal);
                let mut values = [0.0; 6];
                values[3 * (k / 3)..3 * (k / 3) + 3].copy_from_slice(&global);
                parts.push(LoadPart::Nodal { node: at, values });
            }
            let lines: Vec<usize> = self.raw.forces.iter().map(|f| f.0).collect();
            model.loads.push(Load {
                name: "F".into(),
                source: format!("F ({file}:{})", list(&lines)),
                selected: true,
                parts,
                problem: None,
            });
        }
        if let Some((line, a)) = self.raw.acel {
            // ANSYS's ACEL is the acceleration of the frame: the inertia load acts against it
            model.loads.push(Load {
                name: "ACEL".into(),
                source: format!("ACEL ({file}:{line})"),
                selected: true,
                parts: vec![LoadPart::Gravity {
                    accel: a.map(|v| -v),
                }],
                problem: None,
            });
        }
        Ok(())
    }
}
