//! The raw records of each card family: what the card readers (`elements`, `properties`,
//! `mass`, `scalar`, `bush`, `sets`, `solution`, `loads`, `dmig`, `shear`, `shell`) gather
//! while the bulk data is read, with external ids, and their resolve passes turn into the
//! model (`bulk` drives both). Below every reader, so that `reading::Bulk`, which holds them,
//! is below the readers too.

use std::collections::{BTreeMap, HashMap};

use super::lex::Card;
use crate::import::text::Loc;
use crate::model::{DofMask, Material, NodeDof, PointMass, Section};

/// The raw records of CBUSH and PBUSH.
#[derive(Default)]
pub(super) struct BushCards<'a> {
    /// PBUSH K1–K6 by PID.
    pub pbush: HashMap<u64, [f64; 6]>,
    /// CBUSH cards with their resolved end nodes.
    pub cbush: Vec<(&'a Card, usize, Option<usize>)>,
    /// PBUSH1D K and M by PID, with the card (a CBUSH1D on a PBUSH1D with mass is refused).
    pub pbush1d: HashMap<u64, (f64, f64, &'a Card)>,
    /// CBUSH1D cards with their resolved end nodes.
    pub cbush1d: Vec<(&'a Card, usize, Option<usize>)>,
}

/// The raw DMIG cards, by matrix name.
#[derive(Default)]
pub(super) struct DmigCards<'a> {
    /// Header cards (field 3 is 0).
    pub headers: BTreeMap<String, &'a Card>,
    /// Column cards, in deck order.
    pub columns: BTreeMap<String, Vec<&'a Card>>,
}

/// The raw records of the element cards.
#[derive(Default)]
pub(super) struct ElementCards<'a> {
    /// Property of each element of the builder, in element order, with its card's location.
    pub pid: Vec<(ElementProperty, Loc)>,
    /// Corner thicknesses of shell elements.
    pub shell_t: Vec<ElementThickness>,
    /// CQUAD4/CTRIA3 ZOFFS (non-zero) with the card's place.
    pub shell_offsets: Vec<(crate::model::shell_offset::ShellOffset, Loc)>,
    /// THETA/MCID of shell elements.
    pub shell_axes: Vec<ElementAxis>,
    /// Orientation of bars and beams: (element index, as given, card location).
    pub orient: Vec<(usize, Orientation, Loc)>,
    /// Offsets WA, WB of bars and beams in the displacement frames of GA, GB (OFFT …GG).
    pub offsets: Vec<(usize, [[f64; 3]; 2], Loc)>,
    /// Ids of the other cards in the element id space (concentrated masses, springs).
    pub other_ids: Vec<(u64, &'a Card)>,
    /// Ids of the rigid elements: unique among themselves.
    pub rigid_ids: Vec<(u64, &'a Card)>,
    /// CQUAD8/CTRIA6 with blank mid-side grids: (element index, the blank slots, card place).
    pub blank_midsides: Vec<(usize, Vec<usize>, Loc)>,
    /// BAROR and BEAMOR: the defaults of blank CBAR resp. CBEAM fields.
    pub bar_defaults: [Option<&'a Card>; 2],
}

/// The property of an element as its card gives it.
pub(super) enum ElementProperty {
    /// By property id.
    Id(u64),
    /// On the card (CONROD): material id and the rod section.
    Rod { mid: u64, section: Section },
}

/// A bar/beam orientation as the card gives it.
pub(super) enum Orientation {
    /// X1–X3, in the displacement frame of GA (OFFT G…, the default).
    Vector([f64; 3]),
    /// X1–X3 in the basic frame (OFFT B…).
    Basic([f64; 3]),
    /// Towards grid G0.
    Node(u64),
}

/// The raw records of the mass cards.
#[derive(Default)]
pub(super) struct MassCards<'a> {
    /// CONM2: (point mass with CID-frame offset and inertia, CID, card).
    pub conm2: Vec<(PointMass, i64, &'a Card)>,
    /// CONM1 cards.
    pub conm1: Vec<Conm1<'a>>,
}

/// A CONM1 read: (EID, node, CID, the 6×6 matrix in CID, card).
pub(super) type Conm1<'a> = (u64, usize, i64, [[f64; 6]; 6], &'a Card);

/// The raw records of the property and material cards.
#[derive(Default)]
pub(super) struct PropertyCards<'a> {
    /// (PID, MID, section with external material ids, card).
    pub props: Vec<(u64, u64, Section, &'a Card)>,
    /// Property cards of the other element families (dampers, springs, masses, bushes): they
    /// share the property id space; a structural element may not name them.
    pub others: Vec<(u64, &'a Card)>,
    /// (MID, material, card).
    pub mats: Vec<(u64, Material, &'a Card)>,
    /// PSOLID ISOP: (FULL, other) property ids with their `file:line` — MSC's CHEXA/CPENTA
    /// default has bubble modes.
    pub isop: (Vec<String>, Vec<String>),
    /// PCOMP Z0 other than −T/2: PID → (mid-plane offset Z0 + T/2 from the reference plane,
    /// card place), applied with the elements' ZOFFS (`model::shell_offset`).
    pub mid_plane_offsets: BTreeMap<u64, (f64, Loc)>,
    /// MATT1/MATT2/MATT8/MATT9, decided once every property is read (`material_temperature`).
    pub temperature_tables: Vec<&'a Card>,
}

/// The raw records of the scalar element cards.
#[derive(Default)]
pub(super) struct ScalarCards<'a> {
    /// PELAS by PID: (K, card).
    pub pelas: HashMap<u64, (f64, &'a Card)>,
    /// PMASS by PID: (M, card).
    pub pmass: HashMap<u64, (f64, &'a Card)>,
    /// The elements, in deck order.
    pub elements: Vec<ScalarElement<'a>>,
}

/// A CELASi or CMASSi card read.
pub(super) struct ScalarElement<'a> {
    /// A spring (CELAS), else a mass (CMASS).
    pub spring: bool,
    pub id: u64,
    /// The value given on the card (CELAS2/4, CMASS2/4), or the property id (CELAS1/3,
    /// CMASS1/3).
    pub value: Result<f64, u64>,
    pub a: NodeDof,
    pub b: Option<NodeDof>,
    pub card: &'a Card,
}

/// An SPCADD or MPCADD: (SID, [(set id, field index)], card).
pub(super) type SetAdd<'a> = (u64, Vec<(u64, usize)>, &'a Card);

/// One MPC equation read: its terms (dof, coefficient) and its card.
pub(super) type MpcCard<'a> = (Vec<(NodeDof, f64)>, &'a Card);

/// The raw records of the set cards.
#[derive(Default)]
pub(super) struct SetCards<'a> {
    /// SPC/SPC1 set id → (node, components, card).
    pub spc: BTreeMap<u64, Vec<(usize, DofMask, &'a Card)>>,
    /// SPCADD cards.
    pub spcadd: Vec<SetAdd<'a>>,
    /// How many ASET/ASET1/BSET/BSET1 cards were read, by card.
    pub aset_cards: BTreeMap<&'static str, usize>,
    /// QSET/QSET1 dofs.
    pub qset: Vec<(usize, DofMask)>,
    /// How many QSET/QSET1 cards were read, by card.
    pub qset_cards: BTreeMap<&'static str, usize>,
    /// MPC set id → its equations (terms, card).
    pub mpc: BTreeMap<u64, Vec<MpcCard<'a>>>,
    /// MPCADD cards.
    pub mpcadd: Vec<SetAdd<'a>>,
}

/// The raw records of CSHEAR and PSHEAR.
#[derive(Default)]
pub(super) struct ShearCards<'a> {
    /// PSHEAR by PID: (MID, T, NSM, F1, F2, card).
    pub pshear: HashMap<u64, (u64, [f64; 4], &'a Card)>,
    /// CSHEAR cards with their four grids.
    pub cshear: Vec<(&'a Card, [usize; 4])>,
}

/// The raw records of the solution cards.
pub(super) struct SolutionCards<'a> {
    /// EIGRL/EIGR by SID.
    pub eigen: BTreeMap<u64, &'a Card>,
    /// PARAM,WTMASS (1 when absent).
    pub wtmass: f64,
}

impl Default for SolutionCards<'_> {
    fn default() -> Self {
        SolutionCards {
            eigen: BTreeMap::new(),
            wtmass: 1.0,
        }
    }
}

/// The load cards of a deck, gathered while the bulk data is read.
#[derive(Default)]
pub(crate) struct LoadCards<'a> {
    pub cards: Vec<&'a Card>,
    /// TEMP and TEMPD: temperature sets (module `temperature`; a thermal preload's).
    pub temperatures: Vec<&'a Card>,
}

/// Corner thicknesses of one shell element card.
#[derive(Debug, Clone)]
pub(super) struct ElementThickness {
    /// Index of the element in the model.
    pub elem: usize,
    /// T1..Tn as given (blank = the property's T).
    pub corners: Vec<Option<f64>>,
    /// TFLAG = 1: corners are relative to the property's T.
    pub relative: bool,
    /// File and line, for messages.
    pub file: String,
    pub line: usize,
}

/// THETA or MCID of a shell element card as given.
#[derive(Debug, Clone)]
pub(super) struct ElementAxis {
    /// Index of the element in the model.
    pub elem: usize,
    /// THETA (real, degrees) or MCID (integer).
    pub value: ThetaOrMcid,
    /// File and line, for messages.
    pub file: String,
    pub line: usize,
}

/// The THETA/MCID field.
#[derive(Debug, Clone, Copy)]
pub(super) enum ThetaOrMcid {
    Theta(f64),
    Mcid(u64),
}
