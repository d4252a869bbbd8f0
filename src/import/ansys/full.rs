//! ANSYS full files (`Jobname.full`): the assembled K and M, the dof reference table and the
//! constrained dofs, as a matrix import ([`MatrixModel`], like the Matrix Market and CalculiX
//! dumps), node coordinates and components from the matching archive.
//!
//! Layout (MAPDL Programmer's Reference, "Description of the Full File"; checked against
//! ansys-mapdl-reader's `file.full`): a sequence of Fortran records `[n][flags][n words][1
//! word]`, word pointers counting 4-byte words from the file start. The standard header (at
//! word 0) is followed by the full header (100 integers: `neqn` at 2, `numdof` at 8, the term
//! counts and pointers as low/high word pairs), the dof labels (1 = UX … 6 = ROTZ), the nodal
//! equivalence table (node numbers in equation order); at `ptrDOF` the dofs per node, then the
//! constraint table (a negative entry: the equation is constrained). K (at `ptrSTF`) and M (at
//! `ptrMAS`) are written row by row: a record of 1-based column numbers, then a record of their
//! values; each pair of the symmetric matrix is written once. Compressed records, unsymmetric
//! or lumped matrices and constraint equations in the file are refused.
//!
//! `flexbody build Jobname.full` ([`read_model`]) takes the nodes and node components from the
//! archive of the same job, `Jobname.cdb` beside it.

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

use crate::import::ccx_matrices::{EquationDof, SymmetricTriplets};
use crate::import::error::{parse_err, ImportError};
use crate::import::matrix_market::MatrixModel;
use crate::model::deck::ConstraintSource;
use crate::model::{DeckMass, DofMask, DofMatrix, Model, NodeDof, NodeIndex, Spc};

/// The content of a full file.
#[derive(Debug, Clone, PartialEq)]
pub struct FullFile {
    /// Equation k ↔ (node, direction), every equation of the file (constrained ones too).
    pub dofs: Vec<EquationDof>,
    /// Whether equation k is constrained (the file's constraint table).
    pub constrained: Vec<bool>,
    /// Stiffness, upper triangle over all equations.
    pub k: SymmetricTriplets,
    /// Mass, upper triangle over all equations (`None`: the file holds no mass matrix).
    pub m: Option<SymmetricTriplets>,
}

/// A reader over the file's words; every failure names the file and the word pointer.
struct Words<'a> {
    bytes: &'a [u8],
    file: &'a str,
}

impl Words<'_> {
    fn err(&self, at: u64, what: impl Into<String>) -> ImportError {
        parse_err(self.file, 1, format!("word {at}"), what)
    }

    fn word(&self, at: u64) -> Result<i32, ImportError> {
        let i = usize::try_from(at * 4).map_err(|_| self.err(at, "pointer past the file"))?;
        let b = self
            .bytes
            .get(i..i + 4)
            .ok_or_else(|| self.err(at, "the file ends inside a record (truncated?)"))?;
        Ok(i32::from_le_bytes([b[0], b[1], b[2], b[3]]))
    }

    /// The record at `at`: its word count, its data's first word, the pointer after it.
    fn record(&self, at: u64) -> Result<(usize, u64, u64), ImportError> {
        let n = self.word(at)?;
        let flags = self.word(at + 1)? as u32;
        let byte = (flags >> 24) as u8;
        if byte & 0b0011_1000 != 0 {
            return Err(self.err(
                at,
                "a compressed record (sparse or zlib): write the full file uncompressed \
                 (/FCOMP,FULL,0) to read it",
            ));
        }
        if n < 0 {
            return Err(self.err(at, format!("record length {n}")));
        }
        let end = at + 2 + n as u64 + 1;
        if end * 4 > self.bytes.len() as u64 {
            return Err(self.err(at, "the file ends inside a record (truncated?)"));
        }
        Ok((n as usize, at + 2, end))
    }

    fn ints(&self, at: u64) -> Result<(Vec<i32>, u64), ImportError> {
        let (n, data, end) = self.record(at)?;
        let v = (0..n as u64)
            .map(|k| self.word(data + k))
            .collect::<Result<_, _>>()?;
        Ok((v, end))
    }

    /// A record of `count` doubles.
    fn doubles(&self, at: u64, count: usize) -> Result<(Vec<f64>, u64), ImportError> {
        let (n, data, end) = self.record(at)?;
        if n < 2 * count {
            return Err(self.err(at, format!("{n} words for {count} values")));
        }
        let start = (data * 4) as usize;
        let v = (0..count)
            .map(|k| {
                let b = &self.bytes[start + 8 * k..start + 8 * k + 8];
                f64::from_le_bytes([b[0], b[1], b[2], b[3], b[4], b[5], b[6], b[7]])
            })
            .collect();
        Ok((v, end))
    }
}

/// Two header words (low, high) as one pointer or count.
fn long(header: &[i32], low: usize) -> u64 {
    (header.get(low).copied().unwrap_or(0) as u32 as u64)
        | ((header.get(low + 1).copied().unwrap_or(0) as u32 as u64) << 32)
}

/// Read a full file.
pub fn read_full(path: &Path) -> Result<FullFile, ImportError> {
    let file = path.display().to_string();
    let bytes = std::fs::read(path).map_err(|source| ImportError::Io {
        file: file.clone(),
        source,
    })?;
    let w = Words {
        bytes: &bytes,
        file: &file,
    };
    if w.word(0)? != 100 {
        return Err(ImportError::NotAModel {
            file,
            what: "not a little-endian ANSYS binary file (its first record is not the \
                   100-word standard header)"
                .into(),
        });
    }
    let (_, after_standard) = w.ints(0)?;
    let (header, after_header) = w.ints(after_standard)?;
    let get = |k: usize| header.get(k).copied().unwrap_or(0);
    if get(0) != -4 && get(0) != 4 {
        return Err(w.err(
            after_standard,
            format!("full header's fun04 is {}, not −4", get(0)),
        ));
    }
    let neqn = usize::try_from(get(1)).map_err(|_| w.err(after_standard, "negative neqn"))?;
    for (k, what) in [
        (10, "a lumped mass matrix"),
        (13, "an unsymmetric matrix"),
        (20, "constraint equations"),
    ] {
        if get(k) != 0 {
            return Err(w.err(after_standard, format!("the file holds {what}: not read")));
        }
    }
    let (labels, after_labels) = w.ints(after_header)?;
    let (neqv, _) = w.ints(after_labels)?;
    let (ndof, after_ndof) = w.ints(long(&header, 35))?;
    let (table, _) = w.ints(after_ndof)?;
    if ndof.len() != neqv.len() || table.len() != neqn {
        return Err(w.err(
            long(&header, 35),
            "the dof tables do not match the equation count",
        ));
    }
    let mut dofs = Vec::with_capacity(neqn);
    for (&node, &count) in neqv.iter().zip(&ndof) {
        for j in 0..count.max(0) as usize {
            let label = labels.get(j).copied().unwrap_or(0);
            if !(1..=6).contains(&label) || node <= 0 {
                return Err(w.err(
                    after_header,
                    format!("node {node}: dof label {label} is not UX…ROTZ"),
                ));
            }
            dofs.push(EquationDof {
                node: node as u64,
                dir: (label - 1) as u8,
            });
        }
    }
    if dofs.len() != neqn {
        return Err(w.err(
            long(&header, 35),
            format!("{} dofs for {neqn} equations", dofs.len()),
        ));
    }
    let k = matrix(&w, long(&header, 18), neqn, long(&header, 8))?;
    let m_terms = (get(33) as u32 as u64) | ((get(21) as u32 as u64) << 32);
    let m = match long(&header, 26) {
        0 => None,
        at => Some(matrix(&w, at, neqn, m_terms)?),
    };
    Ok(FullFile {
        dofs,
        constrained: table.iter().map(|&c| c < 0).collect(),
        k,
        m,
    })
}

/// A matrix written row by row from `at` (see the module doc); `terms` is the header's count.
fn matrix(
    w: &Words,
    mut at: u64,
    neqn: usize,
    terms: u64,
) -> Result<SymmetricTriplets, ImportError> {
    let start = at;
    let mut upper = Vec::with_capacity(terms.min(1 << 26) as usize);
    for row in 0..neqn {
        let (cols, next) = w.ints(at)?;
        let (values, next) = w.doubles(next, cols.len())?;
        for (&c, &v) in cols.iter().zip(&values) {
            let c = c as i64 - 1;
            if c < 0 || c as usize >= neqn {
                return Err(w.err(at, format!("row {} names column {}", row + 1, c + 1)));
            }
            let c = c as usize;
            upper.push((row.min(c), row.max(c), v));
        }
        at = next;
    }
    if upper.len() as u64 != terms {
        return Err(w.err(
            start,
            format!("{} terms read, the header says {terms}", upper.len()),
        ));
    }
    Ok(SymmetricTriplets { n: neqn, upper })
}

/// A [`MatrixModel`] of the full file's free equations (constrained rows and columns removed,
/// as the constrained dofs of a CalculiX dump are absent), node coordinates from `mesh` (the
/// archive the file was solved from). The file must hold M.
pub fn matrix_model(path: &Path, mesh: &Model) -> Result<MatrixModel, ImportError> {
    let file = path.display().to_string();
    let full = read_full(path)?;
    let m = full
        .m
        .ok_or_else(|| parse_err(&file, 1, "file", "the full file holds no mass matrix"))?;
    let mut free = vec![usize::MAX; full.dofs.len()];
    let mut dofs = Vec::new();
    for (k, d) in full.dofs.iter().enumerate() {
        if !full.constrained[k] {
            free[k] = dofs.len();
            dofs.push(*d);
        }
    }
    let keep = |t: SymmetricTriplets| SymmetricTriplets {
        n: dofs.len(),
        upper: t
            .upper
            .into_iter()
            .filter(|&(r, c, _)| free[r] != usize::MAX && free[c] != usize::MAX)
            .map(|(r, c, v)| (free[r], free[c], v))
            .collect(),
    };
    let (k, m) = (keep(full.k), keep(m));
    let index = mesh.node_index_by_id();
    let mut nodes = Vec::new();
    let mut seen = std::collections::HashSet::new();
    for d in &dofs {
        if seen.insert(d.node) {
            let i = index.get(&d.node).ok_or_else(|| {
                parse_err(
                    &file,
                    1,
                    format!("node {}", d.node),
                    format!("node not in the archive {}", mesh.source),
                )
            })?;
            nodes.push(mesh.nodes[*i].clone());
        }
    }
    Ok(MatrixModel {
        source: file,
        nodes,
        dofs,
        k,
        m,
    })
}

/// A full file as a model (`flexbody build Jobname.full`): the nodes and node components of the
/// archive `Jobname.cdb` beside it ([`read_mesh`]: coordinates for spiders, graphics and
/// inertia; components as `--interface` names), the file's K and M over its free equations as
/// one term-by-term matrix on the nodes' own dofs, and its constrained dofs held (SPCs: the
/// file's rows of those dofs are not the structure's, so they are never released). The mass is
/// the file's (consistent when ANSYS formed it so).
pub fn read_model(path: &Path) -> Result<Model, ImportError> {
    let file = path.display().to_string();
    let cdb = path.with_extension("cdb");
    if !cdb.is_file() {
        let job = path
            .file_stem()
            .map_or_else(String::new, |s| s.to_string_lossy().into());
        return Err(parse_err(
            &file,
            1,
            "full file",
            format!(
                "no archive {} beside it: a full file's nodes and components are read from the \
                 archive of the same job (CDWRITE,DB,{job},cdb in ANSYS, or copy the archive \
                 there under that name)",
                cdb.display()
            ),
        ));
    }
    let full = read_full(path)?;
    let m = full.m.as_ref().ok_or_else(|| {
        parse_err(
            &file,
            1,
            "full file",
            "the file holds no mass matrix (a static analysis's full file): write it from a \
             modal analysis",
        )
    })?;
    let (mut model, element_components) = read_mesh(&cdb)?;
    let index = model.node_index_by_id();
    let mut at = Vec::with_capacity(full.dofs.len());
    for d in &full.dofs {
        let node = index.get(&d.node).ok_or_else(|| {
            parse_err(
                &file,
                1,
                format!("node {}", d.node),
                format!("the node is not in the archive {}", cdb.display()),
            )
        })?;
        at.push(NodeDof {
            node: *node,
            component: d.dir,
        });
    }
    // both triangles, as a DofMatrix lists them; terms on constrained equations left out
    let terms = |t: &SymmetricTriplets| {
        let mut out = Vec::with_capacity(2 * t.upper.len());
        for &(r, c, v) in &t.upper {
            if full.constrained[r] || full.constrained[c] {
                continue;
            }
            out.push((at[r], at[c], v));
            if r != c {
                out.push((at[c], at[r], v));
            }
        }
        out
    };
    // a zero term on each constrained equation: its node keeps the dof, which the SPC below
    // holds (a reference condition the build knows of, not a node absent from the system)
    let mut stiffness = terms(&full.k);
    stiffness.extend(
        (at.iter().zip(&full.constrained))
            .filter(|(_, c)| **c)
            .map(|(d, _)| (*d, *d, 0.0)),
    );
    model.dof_matrices.push(DofMatrix {
        what: format!("full file {file}"),
        stiffness,
        mass: terms(m),
        basic: false,
    });
    let mut held: BTreeMap<NodeIndex, u8> = BTreeMap::new();
    for (d, _) in at.iter().zip(&full.constrained).filter(|(_, c)| **c) {
        *held.entry(d.node).or_default() |= 1 << d.component;
    }
    let held_dofs: u32 = held.values().map(|m| m.count_ones()).sum();
    for (&node, &mask) in &held {
        model.spcs.push(Spc {
            node,
            dofs: DofMask(mask),
            set_id: 0,
        });
    }
    if !held.is_empty() {
        model.constraint_sources.push(ConstraintSource {
            card: "full file constraint table".into(),
            id: format!("{held_dofs} dofs at {} nodes", held.len()),
            file: file.clone(),
            line: 1,
            set: None,
            spcs: 0..model.spcs.len(),
            permanent: false,
        });
    }
    // a component's nodes without an equation in the file are no part of the body
    let carried: std::collections::HashSet<NodeIndex> = at.iter().map(|d| d.node).collect();
    for set in model.node_sets.values_mut() {
        set.retain(|n| carried.contains(n));
    }
    model.params.coupled_mass = Some(DeckMass {
        consistent: true,
        asked_by: format!("the full file {file}'s mass matrix"),
    });
    let notes = &mut model.deck.notes;
    notes.push(format!(
        "ANSYS full file: K and M of {} equations ({} held by the file's constraint table), nodes \
         and node components from {} (its elements, materials, constraints and loads not read)",
        full.dofs.len(),
        held_dofs,
        cdb.display()
    ));
    if !element_components.is_empty() {
        notes.push(format!(
            "ANSYS full file: element components not read (the body has no elements): {}",
            element_components.join(", ")
        ));
    }
    model.source = file.clone();
    model.files = vec![file, cdb.display().to_string()];
    Ok(model)
}

/// Why a full file over rotated nodes is refused (its archive's NBLOCK angles).
const ROTATED_NODE: &str = "a nodal coordinate system (NBLOCK rotation angles) under a full \
    file: ANSYS writes a rotated node's rows of K and M in its nodal system, which the node's \
    displacement frame would hold, but no full file of rotated nodes was at hand to show it \
    (docs/ansys.md): refused";

/// The nodes and node components of an archive, nothing else: the mesh a full file's matrices
/// were assembled on ([`read_model`]). The archive's elements, materials, constraints and
/// loads are not read (the full file's K, M and constraint table are the body), so a command or
/// element type this reader would refuse does not stop it; a nodal rotation (NBLOCK angles) is
/// refused, as the full file's dofs would be in the rotated frame. Also returns the names of
/// the element components left out.
fn read_mesh(path: &Path) -> Result<(Model, Vec<String>), ImportError> {
    let file = path.display().to_string();
    let text = crate::import::text::read_text(path)?;
    let mut archive = super::Archive::default();
    archive.read(&file, &text, &BTreeSet::new())?;
    archive.refused.clear();
    let mut model = Model {
        source: file.clone(),
        ..Default::default()
    };
    let node_map = archive.place_nodes(&file, &mut model, Some(ROTATED_NODE))?;
    archive.refusals(&file)?;
    let element_components = (archive.components.iter())
        .filter(|c| !c.2)
        .map(|c| c.1.clone())
        .collect();
    archive.components.retain(|c| c.2);
    archive.components(&file, &node_map, &BTreeMap::new(), &mut model)?;
    Ok((model, element_components))
}
