//! The finite-element model every importer produces and the assembler consumes.
//!
//! Importers parse raw records keyed by *external* ids (the ids printed in the input file), then
//! one resolve pass builds this dense-index [`Model`]: every cross reference (element → node,
//! element → property, property → material, node → coordinate system) is a 0-based index into the
//! owning vector, and every entity keeps its external id for user-facing messages and the output
//! file. Coordinates are resolved to the basic (global rectangular) frame at import.
//!
//! Element connectivity is stored in **Abaqus/Nastran node order** for every element kind (see
//! [`ElementKind`]); importers of other formats permute at the edge.
//!
//! Invariant: this module holds plain data only — no parsing, no linear algebra.

use std::collections::BTreeMap;

pub mod beam_library;
pub mod connector;
pub mod deck;
pub mod elasticity;
pub mod generate;
pub mod geometry;
pub mod load;
pub mod offset_mass;
pub mod section;
pub mod shell_offset;

pub use connector::{Bush, DofMatrix, Mpc, NodeDof, RigidBody, ScalarMass, ScalarSpring};
pub use deck::{ConstraintSource, DeckRequest, EigenRequest};
pub use elasticity::{Elasticity, MaterialAxes, PlaneStress, Stiffness6};
pub use load::{Load, LoadPart};
pub use section::{AnsysShell281, BeamBrickSection, Ply, ShellMaterialAxis, ShellSection};

/// Dense 0-based index of a node in [`Model::nodes`].
pub type NodeIndex = usize;

/// A grid point.
#[derive(Debug, Clone, PartialEq)]
pub struct Node {
    /// External id from the input file.
    pub id: u64,
    /// Position in the basic (global rectangular) frame.
    pub x: [f64; 3],
    /// Displacement coordinate system (Nastran CD): index into [`Model::coord_systems`];
    /// `None` = basic frame.
    pub displacement_frame: Option<usize>,
}

/// Kind of a coordinate system.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CoordKind {
    /// Rectangular (CORD2R, Abaqus *TRANSFORM TYPE=R).
    Rectangular,
    /// Cylindrical (r, θ, z) — CORD2C, *TRANSFORM TYPE=C.
    Cylindrical,
    /// Spherical (r, θ, φ) — CORD2S.
    Spherical,
}

/// A coordinate system, resolved to the basic frame (chained definitions already followed).
#[derive(Debug, Clone, PartialEq)]
pub struct CoordSystem {
    /// External id.
    pub id: u64,
    /// Rectangular, cylindrical or spherical.
    pub kind: CoordKind,
    /// Origin in the basic frame.
    pub origin: [f64; 3],
    /// Rows are the local unit axes e1, e2, e3 expressed in the basic frame
    /// (so `local = axes · (x − origin)` for a rectangular system).
    pub axes: [[f64; 3]; 3],
}

/// Element kinds. Node order is the Abaqus/Nastran order:
///
/// ```text
/// Tet4  : 1-4 corners                Tet10 : 1-4 corners, 5:(1,2) 6:(2,3) 7:(1,3) 8:(1,4) 9:(2,4) 10:(3,4)
/// Hex8  : 1-4 bottom face, 5-8 top   Hex20 : 1-8 corners, 9-12 bottom edges, 13-16 top edges, 17-20 verticals
/// Prism6: 1-3 bottom, 4-6 top        Prism15: 1-6 corners, 7-9 bottom edges, 10-12 top edges, 13-15 verticals
/// Pyram5: 1-4 base, 5 apex           Pyram13: 1-5 corners, 6-9 base edges (1-2 … 4-1), 10-13 edges 1-5 … 4-5
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum ElementKind {
    /// 4-node tetrahedron (C3D4, CTETRA 4).
    Tet4,
    /// 10-node tetrahedron (C3D10, CTETRA 10).
    Tet10,
    /// 8-node hexahedron, full 2×2×2 integration (C3D8, CHEXA 8); incompatible modes when
    /// `ModelParams::solid_bubbles` (Nastran CHEXA, PSOLID ISOP blank).
    Hex8,
    /// 8-node hexahedron with one-point integration and hourglass control, as CalculiX forms
    /// its C3D8R (`fe::elements::hex8r`).
    Hex8R,
    /// 8-node hexahedron with the B-bar (mean dilatation) volumetric strain on 2×2×2 points, as
    /// ANSYS forms SOLID185's default (KEYOPT(2)=0); collapsed into ANSYS's wedge (nodes 3 = 4,
    /// 7 = 8) the fully integrated brick, as ANSYS forms that shape (`fe::elements::hex8_bbar`).
    Hex8Bbar,
    /// 20-node hexahedron, full 3×3×3 integration (C3D20, CHEXA 20).
    Hex20,
    /// 20-node hexahedron, reduced 2×2×2 integration (C3D20R).
    Hex20R,
    /// 6-node wedge (C3D6, CPENTA 6).
    Prism6,
    /// 15-node wedge (C3D15, CPENTA 15).
    Prism15,
    /// 5-node pyramid (CPYRAM 5, C3D5).
    Pyram5,
    /// 13-node pyramid (CPYRAM 13).
    Pyram13,
    /// 13-node pyramid with ANSYS's functions on 2×2×2 points, as ANSYS forms SOLID186 written as
    /// a pyramid (`fe::elements::pyram13_ansys`); nodes as [`ElementKind::Pyram13`].
    Pyram13Ansys,
    /// 2-node 3D beam (B31, CBEAM): 6 dofs per node.
    Beam2,
    /// 2-node 3D bar (Nastran CBAR): the beam formulation of [`ElementKind::Beam2`]; kept apart
    /// because Nastran lumps no rotary inertia on a CBAR but torsional inertia on a CBEAM.
    Bar2,
    /// 2-node 3D beam with linear functions and one-point shear, as ANSYS forms BEAM188 with
    /// KEYOPT(3)=0 (`fe::elements::beam188`): 6 dofs per node.
    Beam2Linear,
    /// 3-node 3D beam (nodes I, J, mid) with quadratic functions, stiffness on two points, as
    /// ANSYS forms BEAM189 (`fe::elements::beam189`): 6 dofs per node.
    Beam3Quadratic,
    /// 4-node 3D beam (nodes I, J, then the inner nodes at 1/3 and 2/3 of IJ) with cubic
    /// functions, stiffness on three points, as ANSYS forms BEAM188 with KEYOPT(3)=3
    /// (`fe::elements::beam189`): 6 dofs per node.
    Beam4Cubic,
    /// 2-node rod: axial + torsion (CROD, T3D2).
    Rod2,
    /// 3-node shell triangle (S3, CTRIA3): DKT/DKMT bending + CST membrane, 6 dofs per node; without
    /// a property (e.g. Gmsh surface elements without `--thickness`) graphics/sets only.
    Tri3,
    /// 4-node shell quadrilateral (S4, CQUAD4): MITC4 bending/shear + QM6 membrane, 6 dofs per
    /// node; without a property graphics/sets only.
    Quad4,
    /// 6-node triangle (surface element, e.g. gmsh tri6) — graphics/sets only.
    Tri6,
    /// 8-node quadrilateral (surface element, S8) — graphics/sets only.
    Quad8,
    /// 3-node quadratic beam (Abaqus/CalculiX B32, B32R): read, then expanded into a 20-node
    /// brick as ccx does (`import::abaqus::beam_expansion`); never assembled.
    Beam3,
}

impl ElementKind {
    /// Number of nodes of this element kind.
    pub fn node_count(self) -> usize {
        match self {
            ElementKind::Tet4 => 4,
            ElementKind::Tet10 => 10,
            ElementKind::Hex8 | ElementKind::Hex8R | ElementKind::Hex8Bbar => 8,
            ElementKind::Hex20 | ElementKind::Hex20R => 20,
            ElementKind::Prism6 => 6,
            ElementKind::Prism15 => 15,
            ElementKind::Pyram5 => 5,
            ElementKind::Pyram13 | ElementKind::Pyram13Ansys => 13,
            ElementKind::Beam2
            | ElementKind::Bar2
            | ElementKind::Beam2Linear
            | ElementKind::Rod2 => 2,
            ElementKind::Tri3 | ElementKind::Beam3 | ElementKind::Beam3Quadratic => 3,
            ElementKind::Quad4 | ElementKind::Beam4Cubic => 4,
            ElementKind::Tri6 => 6,
            ElementKind::Quad8 => 8,
        }
    }

    /// True for 3D continuum elements (3 translational dofs per node).
    pub fn is_solid(self) -> bool {
        matches!(
            self,
            ElementKind::Tet4
                | ElementKind::Tet10
                | ElementKind::Hex8
                | ElementKind::Hex8R
                | ElementKind::Hex8Bbar
                | ElementKind::Hex20
                | ElementKind::Hex20R
                | ElementKind::Prism6
                | ElementKind::Prism15
                | ElementKind::Pyram5
                | ElementKind::Pyram13
                | ElementKind::Pyram13Ansys
        )
    }
}

/// An element.
#[derive(Debug, Clone, PartialEq)]
pub struct Element {
    /// External id.
    pub id: u64,
    /// Kind (fixes the node count and order).
    pub kind: ElementKind,
    /// Node indices in Abaqus/Nastran order.
    pub nodes: Vec<NodeIndex>,
    /// Index into [`Model::properties`]; `None` for surface elements kept only for sets/graphics.
    pub property: Option<usize>,
    /// Beam/bar orientation vector v (basic frame) defining the element's local x–y plane
    /// (Nastran CBAR/CBEAM X1..X3 or G0 resolved; Abaqus B31 n1 direction).
    pub orientation: Option<[f64; 3]>,
}

/// Standard beam cross-section shapes of Abaqus *BEAM SECTION SECTION= (Nastran PBARL/PBEAML:
/// [`beam_library`]).
#[derive(Debug, Clone, PartialEq)]
pub enum SectionShape {
    /// Solid circle, radius r (Nastran ROD: DIM1 = r; Abaqus CIRC: r).
    Circle { radius: f64 },
    /// Hollow circle (Nastran TUBE: outer radius, inner radius; Abaqus PIPE: r, t → converted).
    Tube {
        outer_radius: f64,
        inner_radius: f64,
    },
    /// Solid rectangle, width (local y) × height (local z) (Abaqus RECT).
    Rectangle { width: f64, height: f64 },
    /// Hollow rectangle (Nastran BOX / Abaqus BOX): outer width, outer height, wall thicknesses.
    Box {
        width: f64,
        height: f64,
        t_web: f64,
        t_flange: f64,
    },
    /// I-section: height, flange widths and thicknesses, web thickness.
    I {
        height: f64,
        width_bottom: f64,
        width_top: f64,
        t_web: f64,
        t_bottom: f64,
        t_top: f64,
    },
    /// Any other named shape with its raw dimensions (section values computed by the importer).
    Other { name: String, dims: Vec<f64> },
}

/// Section properties of a beam (local axes: x along the beam, y and z the principal directions).
#[derive(Debug, Clone, PartialEq)]
pub struct BeamSection {
    /// Cross-section area A.
    pub area: f64,
    /// Second moment about local z (bending in the x–y plane), Nastran I1.
    pub i1: f64,
    /// Second moment about local y (bending in the x–z plane), Nastran I2.
    pub i2: f64,
    /// Product of inertia I12.
    pub i12: f64,
    /// Torsion constant J.
    pub j: f64,
    /// Shear area factors (Nastran K1, K2) for a Timoshenko beam; `None` = Euler–Bernoulli.
    pub shear_factors: Option<[f64; 2]>,
    /// Non-structural mass per length.
    pub nsm: f64,
    /// The standard shape the values were computed from, if any.
    pub shape: Option<SectionShape>,
    /// Sections varying along the element (tapered PBEAM/PBEAML); `None`: prismatic, the
    /// values above everywhere.
    pub taper: Option<BeamTaper>,
}

/// A tapered beam's sections along the element, at ξ = x/L from end A (ξ = 0) to end B (1).
#[derive(Debug, Clone, PartialEq)]
pub enum BeamTaper {
    /// PBEAM stations (ξ, [A, I1, I2, J, NSM]) from end A to end B; each value linear between
    /// stations.
    Values(Vec<(f64, [f64; 5])>),
    /// PBEAML stations of library shape `shape`: (ξ, DIM1…DIMn, NSM); the dimensions and NSM
    /// linear between stations, the constants of the shape at the interpolated dimensions.
    Library {
        shape: String,
        stations: Vec<(f64, Vec<f64>, f64)>,
    },
}

/// A beam's section at one point: [A, I1, I2, J, NSM] and the shear factors.
pub type SectionAt = ([f64; 5], Option<[f64; 2]>);

impl BeamSection {
    /// The section at ξ = x/L (the tapered values interpolated, else the prismatic ones).
    pub fn at(&self, xi: f64) -> SectionAt {
        let lerp = |a: f64, b: f64, t: f64| a + (b - a) * t;
        // The interval [ξ_k, ξ_k+1] holding ξ and the fraction t in it.
        fn interval<T>(st: &[(f64, T)], xi: f64) -> (usize, f64) {
            let k = (0..st.len().saturating_sub(1))
                .find(|&k| xi <= st[k + 1].0)
                .unwrap_or(st.len().saturating_sub(2));
            let (a, b) = (st[k].0, st[k + 1].0);
            (
                k,
                if b > a {
                    ((xi - a) / (b - a)).clamp(0.0, 1.0)
                } else {
                    0.0
                },
            )
        }
        match &self.taper {
            None => (
                [self.area, self.i1, self.i2, self.j, self.nsm],
                self.shear_factors,
            ),
            Some(BeamTaper::Values(st)) if st.len() >= 2 => {
                let (k, t) = interval(st, xi);
                let v = std::array::from_fn(|i| lerp(st[k].1[i], st[k + 1].1[i], t));
                (v, self.shear_factors)
            }
            Some(BeamTaper::Library { shape, stations }) if stations.len() >= 2 => {
                let st: Vec<(f64, ())> = stations.iter().map(|s| (s.0, ())).collect();
                let (k, t) = interval(&st, xi);
                let (a, b) = (&stations[k], &stations[k + 1]);
                let dims: Vec<f64> = a.1.iter().zip(&b.1).map(|(p, q)| lerp(*p, *q, t)).collect();
                let nsm = lerp(a.2, b.2, t);
                match beam_library::library_section(shape, &dims) {
                    Ok(l) => ([l.area, l.i1, l.i2, l.j, nsm], Some(l.shear_factors)),
                    // The importer checked every station; a convex mix of valid walls is valid.
                    Err(_) => ([0.0; 5], None),
                }
            }
            Some(_) => (
                [self.area, self.i1, self.i2, self.j, self.nsm],
                self.shear_factors,
            ),
        }
    }

    /// The stations' ξ (0 and 1 for a prismatic beam): where the interpolation has kinks.
    pub fn breakpoints(&self) -> Vec<f64> {
        match &self.taper {
            Some(BeamTaper::Values(st)) => st.iter().map(|s| s.0).collect(),
            Some(BeamTaper::Library { stations, .. }) => stations.iter().map(|s| s.0).collect(),
            None => vec![0.0, 1.0],
        }
    }
}

/// Section kinds.
#[derive(Debug, Clone, PartialEq)]
pub enum Section {
    /// Solid continuum (PSOLID, *SOLID SECTION).
    Solid,
    /// Beam (PBAR, PBARL, PBEAM, PBEAML, *BEAM SECTION).
    Beam(BeamSection),
    /// Rod: axial + torsion (PROD).
    Rod { area: f64, j: f64, nsm: f64 },
    /// Shell (PSHELL, *SHELL SECTION, Gmsh 2D elements with `--thickness`).
    Shell(ShellSection),
}

/// A property: a section plus its material.
#[derive(Debug, Clone, PartialEq)]
pub struct Property {
    /// External id (Nastran PID); for Abaqus a running number, see `name`.
    pub id: u64,
    /// Abaqus element-set name of the section, or "PSOLID 1"-style label.
    pub name: String,
    /// Index into [`Model::materials`].
    pub material: usize,
    /// The section.
    pub section: Section,
}

/// Linear-elastic material: isotropic (E, ν, G), or a general D ([`Elasticity`]).
#[derive(Debug, Clone, PartialEq)]
pub struct Material {
    /// External id (Nastran MID); for Abaqus a running number.
    pub id: u64,
    /// Name (Abaqus *MATERIAL NAME=), or "MAT1 1".
    pub name: String,
    /// Young's modulus E.
    pub e: f64,
    /// Poisson's ratio ν.
    pub nu: f64,
    /// Shear modulus G (given, or E / (2(1+ν))).
    pub g: f64,
    /// Mass density ρ (already multiplied by any mass-unit factor such as Nastran WTMASS).
    pub rho: f64,
    /// Isotropic (E, ν, G above), or a general D in the material axes; then E above is the
    /// largest of D11, D22, D33 and ν = 0 (a stiffness scale for the model checks only).
    pub elasticity: Elasticity,
}

impl Material {
    /// Isotropic material with G = E / (2(1 + ν)).
    pub fn isotropic(id: u64, name: &str, e: f64, nu: f64, rho: f64) -> Material {
        Material {
            id,
            name: name.to_owned(),
            e,
            nu,
            g: e / (2.0 * (1.0 + nu)),
            rho,
            elasticity: Elasticity::Isotropic,
        }
    }

    /// A material with the general stiffness `d` (material axes; [`elasticity`] convention):
    /// E is the largest of D11, D22, D33, ν = 0 and G the largest shear term (stiffness scales
    /// for the model checks).
    pub fn anisotropic(id: u64, name: &str, d: Stiffness6, rho: f64) -> Material {
        Material {
            id,
            name: name.to_owned(),
            e: d[0][0].max(d[1][1]).max(d[2][2]),
            nu: 0.0,
            g: d[3][3].max(d[4][4]).max(d[5][5]),
            rho,
            elasticity: Elasticity::Anisotropic(Box::new(d)),
        }
    }

    /// A plane-stress (shell-only) material `p`: E = max(Q11, Q22), ν = 0, G = Q66 (stiffness
    /// scales for the model checks only).
    pub fn plane_stress_material(id: u64, name: &str, p: PlaneStress, rho: f64) -> Material {
        Material {
            id,
            name: name.to_owned(),
            e: p.q[0][0].max(p.q[1][1]),
            nu: 0.0,
            g: p.q[2][2],
            rho,
            elasticity: Elasticity::PlaneStress(Box::new(p)),
        }
    }

    /// The plane-stress stiffness of a shell-only material (MAT8, MAT2), `None` otherwise.
    pub fn plane_stress(&self) -> Option<&PlaneStress> {
        match &self.elasticity {
            Elasticity::PlaneStress(p) => Some(p),
            _ => None,
        }
    }

    /// The general stiffness of an anisotropic material (material axes), `None` if isotropic.
    pub fn stiffness(&self) -> Option<&Stiffness6> {
        match &self.elasticity {
            Elasticity::Anisotropic(d) => Some(d),
            Elasticity::Isotropic | Elasticity::PlaneStress(_) => None,
        }
    }

    /// Structural steel in SI units (E = 210 GPa, ν = 0.3, ρ = 7850 kg/m³), as in the reference cases.
    pub fn steel() -> Material {
        Material::isotropic(1, "STEEL", 210e9, 0.3, 7850.0)
    }
}

/// A set of the six nodal dofs `[ux uy uz rx ry rz]`; bit k = dof k+1 (Nastran digit k+1).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, PartialOrd, Ord)]
pub struct DofMask(pub u8);

impl DofMask {
    /// All six dofs.
    pub const ALL: DofMask = DofMask(0b11_1111);
    /// The three translations.
    pub const TRANSLATIONS: DofMask = DofMask(0b00_0111);

    /// From Nastran dof digits, e.g. "123456" or "12". Returns `None` on a character other than
    /// 1–6 (0 means "scalar point" in Nastran and is not accepted here; the one dof of a scalar
    /// point is bit 0).
    pub fn from_digits(s: &str) -> Option<DofMask> {
        let mut m = 0u8;
        for c in s.trim().chars() {
            match c {
                '1'..='6' => m |= 1 << (c as u8 - b'1'),
                _ => return None,
            }
        }
        Some(DofMask(m))
    }

    /// From an inclusive 1-based range (Abaqus *BOUNDARY first..last dof).
    pub fn from_range(first: u8, last: u8) -> Option<DofMask> {
        if !(1..=6).contains(&first) || !(first..=6).contains(&last) {
            return None;
        }
        Some(DofMask((first..=last).fold(0, |m, d| m | 1 << (d - 1))))
    }

    /// Does the mask contain dof `k` (0-based, 0 = ux … 5 = rz)?
    pub fn contains(self, k: usize) -> bool {
        k < 6 && self.0 & (1 << k) != 0
    }

    /// The 0-based dofs in the mask, ascending.
    pub fn dofs(self) -> impl Iterator<Item = usize> {
        (0..6).filter(move |&k| self.contains(k))
    }

    /// Union.
    pub fn union(self, other: DofMask) -> DofMask {
        DofMask(self.0 | other.0)
    }

    /// Nastran digit string ("123").
    pub fn digits(self) -> String {
        self.dofs().map(|k| char::from(b'1' + k as u8)).collect()
    }
}

/// A rigid element.
#[derive(Debug, Clone, PartialEq)]
pub enum RigidElement {
    /// RBE2-type rigid spider: the `dofs` of every dependent node follow the rigid motion of the
    /// independent node (Nastran RBE2 GN/CM/GMi; Abaqus *RIGID BODY REF NODE, *KINEMATIC coupling).
    Rbe2 {
        /// External element id (or running number).
        id: u64,
        /// Independent (reference) node, 6 dofs.
        independent: NodeIndex,
        /// Dependent nodes.
        dependent: Vec<NodeIndex>,
        /// Which dependent dofs are constrained (CM).
        dofs: DofMask,
    },
    /// RBE3-type weighted interpolation: the reference node's `ref_dofs` are the weighted
    /// least-squares average of the independent nodes' motion (Nastran RBE3; Abaqus *DISTRIBUTING).
    Rbe3 {
        /// External element id (or running number).
        id: u64,
        /// Reference (dependent) node.
        reference: NodeIndex,
        /// Reference dofs (REFC).
        ref_dofs: DofMask,
        /// Independent nodes with weight and the dofs (Ci) that take part.
        independent: Vec<(NodeIndex, f64, DofMask)>,
    },
}

/// A concentrated mass with inertia (CONM2, *MASS + *ROTARY INERTIA).
#[derive(Debug, Clone, PartialEq)]
pub struct PointMass {
    /// External element id (or running number).
    pub id: u64,
    /// The node it is attached to.
    pub node: NodeIndex,
    /// Mass (already scaled by WTMASS).
    pub mass: f64,
    /// Offset of the centre of gravity from the node, basic frame.
    pub offset: [f64; 3],
    /// 3×3 inertia tensor about the centre of gravity, basic frame (positive-definite tensor
    /// convention: off-diagonals are −∫xy dm).
    pub inertia: [[f64; 3]; 3],
}

/// A single-point constraint (zero displacement) on some dofs of a node.
#[derive(Debug, Clone, PartialEq)]
pub struct Spc {
    /// The node.
    pub node: NodeIndex,
    /// The constrained dofs (in the node's displacement frame).
    pub dofs: DofMask,
    /// Nastran SPC set id (0 for Abaqus *BOUNDARY).
    pub set_id: u64,
}

/// Interface (boundary / a-set) dofs declared in the input (Nastran ASET/ASET1).
#[derive(Debug, Clone, PartialEq)]
pub struct InterfaceDofs {
    /// The node.
    pub node: NodeIndex,
    /// Its interface dofs.
    pub dofs: DofMask,
}

/// A non-fatal import finding (unsupported card, ignored keyword, …), reported to the user.
#[derive(Debug, Clone, PartialEq)]
pub struct ImportWarning {
    /// File the finding is in.
    pub file: String,
    /// Human-readable message, e.g. "unsupported card PLOAD4 ignored (12 cards)".
    pub message: String,
}

/// The mass a deck asks for, and what in the deck asks for it (for the build's note).
#[derive(Debug, Clone, PartialEq)]
pub struct DeckMass {
    /// Consistent (`true`) or lumped mass.
    pub consistent: bool,
    /// What asks for it, as the note names it (`PARAM,COUPMASS,1 at deck.bdf:12`).
    pub asked_by: String,
}

/// Mass-unit hints from the input (Nastran PARAM,WTMASS; PARAM,COUPMASS).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ModelParams {
    /// PARAM,WTMASS factor (1.0 when absent). Already applied to densities and point masses.
    pub wtmass: f64,
    /// The mass the deck's solver would form, when the deck says (PARAM,COUPMASS; an ANSYS
    /// archive's LUMPM).
    pub coupled_mass: Option<DeckMass>,
    /// Linear hexahedra and wedges (CHEXA 8, CPENTA 6) with incompatible (bubble) modes, as MSC
    /// Nastran forms them for PSOLID ISOP blank (`fe::elements::solid_incompatible`); `false`:
    /// fully integrated (CalculiX/Abaqus C3D8, C3D6).
    pub solid_bubbles: bool,
    /// CalculiX's integration rules where they differ from the standard ones (ccx e_c3d, stiffness
    /// and mass in one loop): C3D4 mass with one point (every entry ρV/16), C3D6 stiffness and
    /// mass with two points (`quadrature::wedge_centroid`). Set by the Abaqus/CalculiX importer.
    pub ccx_solid_rules: bool,
    /// ANSYS's integration rules where they differ from the standard ones: SOLID186's (and the
    /// archived SOLID95's) consistent mass with Irons' 14-point rule (`quadrature::cube_irons14`;
    /// SOLID95 KEYOPT(11)=1's on 2×2×2: `Model::hex20_mass_2x2x2`), their full integration's
    /// stiffness on the same 14 points. Set by the ANSYS importer.
    pub ansys_solid_rules: bool,
    /// The 4-node shells are ANSYS's SHELL181 with KEYOPT(3)=2: MITC4 + QM6 with ANSYS's
    /// transverse shear factor and drilling penalty (`fe::elements::shell::Quad4Form`). Set by
    /// the ANSYS importer when it forms a SHELL181.
    pub ansys_shell181: bool,
    /// Nastran `PARAM,K6ROT`: the drilling stiffness of CQUAD4/CTRIA3 shells is the penalty
    /// γ_d = K6ROT·10⁻⁶·G t (`fe::elements::shell`); `None` = MSC's default 100.
    pub k6rot: Option<f64>,
    /// The model is a Nastran deck (its lumped mass is compared with MSC Nastran's: the build
    /// notes where our lumping rule differs from one MSC does not publish).
    pub nastran_deck: bool,
}

/// A whole FE model, resolved to dense indices.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Model {
    /// The file the model was read from (for messages).
    pub source: String,
    /// Grid points, in input order.
    pub nodes: Vec<Node>,
    /// Coordinate systems, resolved to the basic frame.
    pub coord_systems: Vec<CoordSystem>,
    /// Elements, in input order.
    pub elements: Vec<Element>,
    /// Released (pinned) dofs of bar/beam ends, Nastran CBAR/CBEAM PA, PB: element index →
    /// the dofs of the element frame released at end A and at end B.
    pub beam_pins: BTreeMap<usize, [DofMask; 2]>,
    /// Offsets of bar/beam ends, Nastran CBAR/CBEAM WA, WB (basic frame): element index → the
    /// vectors from grid A and grid B to the element's ends, joined to the grids rigidly.
    pub beam_offsets: BTreeMap<usize, [[f64; 3]; 2]>,
    /// Nodal thicknesses of shell elements (Abaqus *NODAL THICKNESS, Nastran CQUAD8/CTRIA6
    /// T1..T4): element index → one thickness per node in the element's node order, replacing
    /// the section's thickness (formed by the quadratic shells, which interpolate it).
    pub shell_thickness: BTreeMap<usize, Vec<f64>>,
    /// Shell elements whose membrane carries drilling rotations (Nastran CQUADR/CTRIAR,
    /// `fe::elements::drill_membrane`) instead of the CQUAD4/CTRIA3 membrane with its drilling
    /// penalty: element indices.
    pub drilling_membranes: std::collections::BTreeSet<usize>,
    /// Material x-axes of shell elements given on the element (Nastran CQUAD4/CTRIA3 THETA or
    /// MCID): element index → axis; others use their section's `material_axis`.
    pub shell_axes: BTreeMap<usize, ShellMaterialAxis>,
    /// 8-node shells formed as ANSYS's SHELL281 (`fe::elements::shell281`): element index →
    /// its section's transverse shear; other `Quad8` elements are flexbody's MITC9.
    pub ansys_shell281: BTreeMap<usize, AnsysShell281>,
    /// Cross-section integration of the 20-node bricks CalculiX makes of B32R beams (element
    /// index → section; `fe::elements::hex20_beam`): the brick spans the section's bounding
    /// rectangle and is integrated at the section's own points.
    pub beam_bricks: BTreeMap<usize, BeamBrickSection>,
    /// 20-node bricks with reduced integration (`Hex20R`) whose consistent mass is on the same
    /// 2×2×2 points as their stiffness where `ModelParams::ansys_solid_rules` would take Irons'
    /// 14 points: ANSYS's archived SOLID95 with KEYOPT(11)=1 (`fe::elements::hex20_beam`);
    /// element indices.
    pub hex20_mass_2x2x2: std::collections::BTreeSet<usize>,
    /// Properties (sections).
    pub properties: Vec<Property>,
    /// Materials.
    pub materials: Vec<Material>,
    /// Material axes of properties (index into `properties` → axes; Abaqus `*ORIENTATION`,
    /// Nastran PSOLID CORDM); a property without an entry has the basic axes.
    pub property_axes: BTreeMap<usize, MaterialAxes>,
    /// Named node sets (names upper-cased as the format allows), sorted unique node indices.
    pub node_sets: BTreeMap<String, Vec<NodeIndex>>,
    /// Named element sets, sorted unique element indices.
    pub element_sets: BTreeMap<String, Vec<usize>>,
    /// Rigid elements.
    pub rigid_elements: Vec<RigidElement>,
    /// Rigid bodies with chosen independent dofs (RBAR, RBAR1, RBE1).
    pub rigid_bodies: Vec<RigidBody>,
    /// Linear multipoint constraints (the selected MPC set).
    pub mpcs: Vec<Mpc>,
    /// Scalar springs (CELAS1–4).
    pub springs: Vec<ScalarSpring>,
    /// Bushes (CBUSH).
    pub bushes: Vec<Bush>,
    /// Scalar masses (CMASS1–4).
    pub scalar_masses: Vec<ScalarMass>,
    /// Stiffness and mass matrices given term by term on dofs (GENEL, DMIG by K2GG/M2GG).
    pub dof_matrices: Vec<DofMatrix>,
    /// The nodes that are scalar points (Nastran SPOINT: one dof, no position; their `x` is
    /// the origin and means nothing), ascending.
    pub scalar_points: Vec<NodeIndex>,
    /// Concentrated masses.
    pub point_masses: Vec<PointMass>,
    /// Single-point constraints.
    pub spcs: Vec<Spc>,
    /// Interface dofs declared in the file (ASET).
    pub interface: Vec<InterfaceDofs>,
    /// Solver parameters that change the physics (WTMASS, COUPMASS).
    pub params: ModelParams,
    /// Non-fatal findings.
    pub warnings: Vec<ImportWarning>,
    /// Where each material was defined, parallel to [`Model::materials`]: (index into
    /// [`Model::files`], 1-based line); shorter (or empty) where unknown.
    pub material_sources: Vec<(u32, u32)>,
    /// Where each element was defined, for messages after import: (external element id,
    /// index into [`Model::files`], 1-based line), sorted by id. Empty for models built in
    /// memory; see [`Model::element_location`].
    pub element_sources: Vec<(u64, u32, u32)>,
    /// The deck's analysis choices (case control, eigenvalue request, a-set, q-set).
    pub deck: DeckRequest,
    /// Where the records of `spcs` came from (card, line, set).
    pub constraint_sources: Vec<ConstraintSource>,
    /// Every file the importer read, as opened: the main file first, then includes in the order
    /// read (empty for models built in memory). The build records their SHA-256 (recipe).
    pub files: Vec<String>,
    /// Scene loads read from the deck (every load set by name; `selected` marks the ones the
    /// case control applies).
    pub loads: Vec<Load>,
}

impl Model {
    /// The largest node id (scalar points included; 0 for no nodes): a node made after import
    /// takes the next one.
    pub fn max_node_id(&self) -> u64 {
        self.nodes.iter().map(|n| n.id).max().unwrap_or(0)
    }

    /// The largest id of every element-like entity — elements, rigid elements, rigid bodies
    /// (RBAR, RBE1), springs, scalar masses, bushes and point masses (0 for none): an element
    /// made after import takes the next one, so it names no card of the deck.
    pub fn max_element_id(&self) -> u64 {
        let rigid = self.rigid_elements.iter().map(|r| match r {
            RigidElement::Rbe2 { id, .. } | RigidElement::Rbe3 { id, .. } => *id,
        });
        (self.elements.iter().map(|e| e.id))
            .chain(rigid)
            .chain(self.rigid_bodies.iter().map(|r| r.id))
            .chain(self.springs.iter().map(|s| s.id))
            .chain(self.scalar_masses.iter().map(|s| s.id))
            .chain(self.bushes.iter().map(|b| b.id))
            .chain(self.point_masses.iter().map(|p| p.id))
            .max()
            .unwrap_or(0)
    }

    /// Whether node `n` is a scalar point.
    pub fn is_scalar_point(&self, n: NodeIndex) -> bool {
        self.scalar_points.binary_search(&n).is_ok()
    }

    /// The node groups that springs, bushes, scalar masses, MPCs and rigid bodies join (one
    /// group per item with more than one node), for connectivity.
    pub fn connector_node_groups(&self) -> Vec<Vec<NodeIndex>> {
        let pair = |a: NodeIndex, b: Option<NodeIndex>| b.filter(|&b| b != a).map(|b| vec![a, b]);
        let mut out: Vec<Vec<NodeIndex>> = Vec::new();
        out.extend((self.springs.iter()).filter_map(|s| pair(s.a.node, s.b.map(|b| b.node))));
        out.extend((self.scalar_masses.iter()).filter_map(|s| pair(s.a.node, s.b.map(|b| b.node))));
        out.extend(self.bushes.iter().filter_map(|s| pair(s.a, s.b)));
        out.extend((self.dof_matrices.iter().map(DofMatrix::nodes)).filter(|n| n.len() > 1));
        for nodes in (self.mpcs.iter())
            .map(|m| m.terms.iter().map(|t| t.0.node).collect::<Vec<_>>())
            .chain(self.rigid_bodies.iter().map(|r| r.nodes().collect()))
        {
            let mut nodes = nodes;
            nodes.sort_unstable();
            nodes.dedup();
            if nodes.len() > 1 {
                out.push(nodes);
            }
        }
        out
    }

    /// `file:line` where element `id` was defined, when the importer recorded it.
    pub fn element_location(&self, id: u64) -> Option<String> {
        let k = self
            .element_sources
            .binary_search_by_key(&id, |&(e, _, _)| e)
            .ok()?;
        let (_, file, line) = self.element_sources[k];
        let file = self.files.get(file as usize).unwrap_or(&self.source);
        Some(format!("{file}:{line}"))
    }

    /// The element's `file:line` if known, else the model's source: the prefix of messages
    /// about element `id` after import.
    pub fn element_origin(&self, id: u64) -> String {
        self.element_location(id)
            .unwrap_or_else(|| self.source.clone())
    }

    /// Map from external node id to dense index (built on demand).
    pub fn node_index_by_id(&self) -> std::collections::HashMap<u64, NodeIndex> {
        self.nodes
            .iter()
            .enumerate()
            .map(|(i, n)| (n.id, i))
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dof_mask_digits_round_trip() {
        let m = DofMask::from_digits("1236").unwrap();
        assert_eq!(m.dofs().collect::<Vec<_>>(), vec![0, 1, 2, 5]);
        assert_eq!(m.digits(), "1236");
        assert_eq!(DofMask::from_digits("7"), None);
        assert_eq!(DofMask::from_range(1, 3), Some(DofMask::TRANSLATIONS));
        assert_eq!(DofMask::from_range(4, 2), None);
    }
}
