//! # flexbody-reader
//!
//! Reads and validates *reduced flexible-body files* (`.flexbody`, format v1) written by
//! flexbody, for multibody solvers. The crate owns the file's types; it has no linear algebra
//! and no solver code. The authority on the bytes is `format-spec/SPEC.md`.
//!
//! * [`read`] / [`from_bytes`] → [`ReducedBody`], every checksum and consistency rule checked;
//!   [`from_bytes_with_limits`] takes explicit [`ReadLimits`].
//! * [`ReadError`] names the entry and the rule broken; a hostile file never panics the reader
//!   and never makes it allocate beyond the limits. [`ReadError::variant`] is its SPEC §8 name
//!   and [`ReadError::named`] prints it in front of the message (`Checksum: entry …`).
//! * The container is read by the one procedure of SPEC §7.1 (`archive`, no zip library) and
//!   `manifest.json`/`recipe.json` by the strict JSON rules of §4.1 (`json`), so that every
//!   conforming reader sees the same file.
//! * [`validate`] runs the consistency rules on an in-memory body (the writer uses it), and
//!   [`codec`] holds the entry names, the manifest type and the v1 payload encoding.
//!
//! ```no_run
//! let body = flexbody_reader::read("rod.flexbody")?;
//! println!("{} nodes, {} modes", body.node_count(), body.mode_count());
//! # Ok::<(), flexbody_reader::ReadError>(())
//! ```
#![deny(missing_docs)]

mod archive;
pub mod codec;
mod container;
mod error;
mod interfaces;
mod json;
mod limits;
mod recipe;
mod types;
mod validate;

use std::path::Path;

pub use error::{NamedError, ReadError};
pub use interfaces::{CentreFit, FitMethod, InterfaceInfo, InterfaceKind, FIT_TOL};
pub use limits::ReadLimits;
pub use recipe::*;
pub use types::*;
pub use validate::{validate, FRAME_TOL, REL_TOL};

/// The newest format version this crate writes and fully understands. A writer stamps the
/// oldest version that has everything the file holds ([`version_for`]).
pub const FORMAT_VERSION: Version = Version { major: 1, minor: 9 };

/// The oldest format version that has everything `body` holds (SPEC §7.3): 1.1 added
/// `lines.bin`, 1.2 `recipe.json` and `label_shares.bin`, 1.3 `interfaces.bin`, 1.4
/// `modal_loads.bin`, 1.5 the shells' bottom-fibre field shapes, 1.6 normal modes that count
/// residual vectors removed as dependent (`method.counts.removed_dependent` > 0), 1.7
/// `geometric_stiffness.bin`, 1.8 its beam-column form with the axial and torsional terms and
/// exact zeros for the acceleration fields under inertia relief (every file with the entry,
/// except a body whose `version` says 1.7: a 1.7 file read and written again keeps its stamp,
/// its terms being 1.7's), 1.9 `eigen_residuals.bin`.
pub fn version_for(body: &ReducedBody) -> Version {
    let normal_removed =
        body.method.method == Method::NormalModes && body.method.counts.removed_dependent > 0;
    // a normal mode mixed with residual vectors below half (share < 1, no mode flagged): 1.6
    let normal_mixed = body.method.method == Method::NormalModes
        && body.modal_loads.as_ref().is_some_and(|ml| {
            !ml.residual.is_empty()
                && ml.residual.iter().all(|&r| r == 0)
                && body.label_shares.as_ref().is_some_and(|s| {
                    (s.iter().zip(&body.modes.labels))
                        .any(|(&v, &l)| v != 1.0 && l != ModeLabel::Rigid)
                })
        });
    let normal_removed = normal_removed || normal_mixed;
    let entry_minor = encoded_names(body)
        .filter_map(|name| codec::ENTRIES.iter().find(|e| e.0 == name))
        .map(|e| e.2)
        .max()
        .unwrap_or(0);
    let minor = if body.geometric_stiffness.is_some() {
        // 1.8's terms, unless the body is a 1.7 file read back (its terms stay 1.7's)
        let read_as_1_7 = body.version.major == 1 && body.version.minor == 7;
        entry_minor.max(if read_as_1_7 { 7 } else { 8 })
    } else if normal_removed {
        entry_minor.max(6)
    } else {
        entry_minor
    };
    Version { major: 1, minor }
}

/// The names of the entries `body` writes, in container order (manifest excluded).
fn encoded_names(body: &ReducedBody) -> impl Iterator<Item = &'static str> {
    use codec::*;
    let optional = [
        (STRESS_SHAPES, body.stress_shapes.is_some()),
        (STRAIN_SHAPES, body.strain_shapes.is_some()),
        (DAMPING, body.damping.is_some()),
        (LINES, body.lines.is_some()),
        (RECIPE, body.recipe.is_some()),
        (LABEL_SHARES, body.label_shares.is_some()),
        (INTERFACES, body.interfaces.is_some()),
        (MODAL_LOADS, body.modal_loads.is_some()),
        (STRESS_SHAPES_BOTTOM, body.stress_shapes_bottom.is_some()),
        (STRAIN_SHAPES_BOTTOM, body.strain_shapes_bottom.is_some()),
        (GEOMETRIC_STIFFNESS, body.geometric_stiffness.is_some()),
        (EIGEN_RESIDUALS, body.eigen_residuals.is_some()),
    ];
    ENTRIES[..7]
        .iter()
        .map(|e| e.0)
        .chain(optional.into_iter().filter(|x| x.1).map(|x| x.0))
}

/// Reads and validates a file with the default [`ReadLimits`].
pub fn read(path: impl AsRef<Path>) -> Result<ReducedBody, ReadError> {
    let path = path.as_ref();
    let bytes = std::fs::read(path).map_err(|source| ReadError::Io {
        path: path.to_path_buf(),
        source,
    })?;
    from_bytes(&bytes)
}

/// Reads and validates a file held in memory with the default [`ReadLimits`].
pub fn from_bytes(bytes: &[u8]) -> Result<ReducedBody, ReadError> {
    from_bytes_with_limits(bytes, &ReadLimits::default())
}

fn entry<'a>(c: &'a container::Container, name: &str) -> Result<&'a [u8], ReadError> {
    c.entries
        .get(name)
        .map(Vec::as_slice)
        .ok_or_else(|| ReadError::MissingEntry {
            entry: name.to_string(),
            rule: "required in v1".to_string(),
        })
}

fn optional<T: serde::de::DeserializeOwned>(
    c: &container::Container,
    name: &str,
) -> Result<Option<T>, ReadError> {
    c.entries
        .get(name)
        .map(|b| codec::decode(name, b, codec::STRING_RECORDS.contains(&name)))
        .transpose()
}

/// Reads and validates a file held in memory with explicit limits.
pub fn from_bytes_with_limits(bytes: &[u8], limits: &ReadLimits) -> Result<ReducedBody, ReadError> {
    from_bytes_with_manifest(bytes, limits).map(|(body, _)| body)
}

/// Like [`from_bytes_with_limits`], also returning the manifest (entry sizes and checksums,
/// unknown optional entries included) for tools that report on the container.
pub fn from_bytes_with_manifest(
    bytes: &[u8],
    limits: &ReadLimits,
) -> Result<(ReducedBody, codec::Manifest), ReadError> {
    use codec::*;
    let c = container::open(bytes, limits)?;
    // SPEC §7.1 step 7: decoded in container order (§2), so the first record that does not
    // decode is the one every reader names.
    let header = decode(HEADER, entry(&c, HEADER)?, true)?;
    let nodes = decode(NODES, entry(&c, NODES)?, false)?;
    let faces = decode(FACES, entry(&c, FACES)?, false)?;
    let nodal_mass = decode(NODAL_MASS, entry(&c, NODAL_MASS)?, false)?;
    let modes = decode(MODES, entry(&c, MODES)?, false)?;
    let invariants = decode(INVARIANTS, entry(&c, INVARIANTS)?, false)?;
    let method = decode(METHOD, entry(&c, METHOD)?, false)?;
    let stress_shapes = optional(&c, STRESS_SHAPES)?;
    let strain_shapes = optional(&c, STRAIN_SHAPES)?;
    let damping = optional(&c, DAMPING)?;
    let lines = optional(&c, LINES)?;
    let recipe = c
        .entries
        .get(RECIPE)
        .map(|b| decode_recipe(b))
        .transpose()?;
    let label_shares = optional(&c, LABEL_SHARES)?;
    let interfaces = optional(&c, INTERFACES)?;
    let modal_loads = optional(&c, MODAL_LOADS)?;
    let stress_shapes_bottom = optional(&c, STRESS_SHAPES_BOTTOM)?;
    let strain_shapes_bottom = optional(&c, STRAIN_SHAPES_BOTTOM)?;
    let geometric_stiffness = optional(&c, GEOMETRIC_STIFFNESS)?;
    let eigen_residuals = optional(&c, EIGEN_RESIDUALS)?;
    let body = ReducedBody {
        version: c.manifest.version,
        generator: c.manifest.generator.clone(),
        units: c.manifest.units.clone(),
        header,
        nodes,
        faces,
        nodal_mass,
        modes,
        invariants,
        method,
        stress_shapes,
        strain_shapes,
        damping,
        lines,
        recipe,
        label_shares,
        interfaces,
        stress_shapes_bottom,
        strain_shapes_bottom,
        modal_loads,
        geometric_stiffness,
        eigen_residuals,
    };
    validate(&body, limits)?;
    Ok((body, c.manifest))
}

/// The payload entries of `body` in container order: (name, required, bytes). The writer
/// zips these after `manifest.json`.
pub fn encode_entries(body: &ReducedBody) -> Vec<(&'static str, bool, Vec<u8>)> {
    use codec::*;
    let mut out = vec![
        (HEADER, true, encode(&body.header)),
        (NODES, true, encode(&body.nodes)),
        (FACES, true, encode(&body.faces)),
        (NODAL_MASS, true, encode(&body.nodal_mass)),
        (MODES, true, encode(&body.modes)),
        (INVARIANTS, true, encode(&body.invariants)),
        (METHOD, true, encode(&body.method)),
    ];
    if let Some(s) = &body.stress_shapes {
        out.push((STRESS_SHAPES, false, encode(s)));
    }
    if let Some(s) = &body.strain_shapes {
        out.push((STRAIN_SHAPES, false, encode(s)));
    }
    if let Some(d) = &body.damping {
        out.push((DAMPING, false, encode(d)));
    }
    if let Some(l) = &body.lines {
        out.push((LINES, false, encode(l)));
    }
    if let Some(r) = &body.recipe {
        out.push((RECIPE, false, encode_recipe(r)));
    }
    if let Some(s) = &body.label_shares {
        out.push((LABEL_SHARES, false, encode(s)));
    }
    if let Some(i) = &body.interfaces {
        out.push((INTERFACES, false, encode(i)));
    }
    if let Some(s) = &body.modal_loads {
        out.push((MODAL_LOADS, false, encode(s)));
    }
    if let Some(s) = &body.stress_shapes_bottom {
        out.push((STRESS_SHAPES_BOTTOM, false, encode(s)));
    }
    if let Some(s) = &body.strain_shapes_bottom {
        out.push((STRAIN_SHAPES_BOTTOM, false, encode(s)));
    }
    if let Some(g) = &body.geometric_stiffness {
        out.push((GEOMETRIC_STIFFNESS, false, encode(g)));
    }
    if let Some(e) = &body.eigen_residuals {
        out.push((EIGEN_RESIDUALS, false, encode(e)));
    }
    out
}

/// The manifest for `body` whose payload entries are `entries` (from [`encode_entries`]).
pub fn manifest_for(body: &ReducedBody, entries: &[(&str, bool, Vec<u8>)]) -> codec::Manifest {
    codec::Manifest {
        format: codec::FORMAT_NAME.to_string(),
        version: version_for(body),
        generator: body.generator.clone(),
        units: body.units.clone(),
        entries: entries
            .iter()
            .map(|(name, required, bytes)| codec::ManifestEntry {
                name: name.to_string(),
                size: bytes.len() as u64,
                sha256: codec::sha256_hex(bytes),
                required: *required,
            })
            .collect(),
    }
}
