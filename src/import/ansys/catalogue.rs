//! The catalogue: what the reader does with every command and element type a `CDWRITE`
//! archive can hold — the rule "honoured or refused, never dropped" as two tables, each row a
//! name, a [`Category`] and a [`Disposition`]. A command or element type in no table is
//! refused by its line. `docs/ansys-commands.md` is generated from the tables ([`markdown`]; a
//! test keeps the page equal to it).

/// What the reader does with a command or an element type.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Disposition {
    /// Read into the model (the text says how, for the documentation).
    Honoured(&'static str),
    /// Not read: it cannot change the body (the reason); one note per command name.
    Note(&'static str),
    /// Refused, with the reason.
    Refused(&'static str),
}

/// What a row is about: the documentation's headings.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub(crate) enum Category {
    Mesh,
    Material,
    Constraint,
    Load,
    Analysis,
    Session,
}

impl Category {
    const ALL: [Category; 6] = [
        Category::Mesh,
        Category::Material,
        Category::Constraint,
        Category::Load,
        Category::Analysis,
        Category::Session,
    ];

    pub(crate) fn title(self) -> &'static str {
        match self {
            Category::Mesh => "nodes, elements, element types, components",
            Category::Material => "materials, real constants, sections",
            Category::Constraint => "constraints",
            Category::Load => "loads",
            Category::Analysis => "analysis settings",
            Category::Session => "session, output and GUI settings",
        }
    }
}

use Category as C;
use Disposition::{Honoured as H, Note as N, Refused as R};

const SESSION: &str = "a session, output or GUI setting: no effect on the body";
const ATTRIBUTE: &str =
    "the active attribute for elements made later in a session; EBLOCK gives every element its own";
const DAMPING: &str =
    "damping of a response analysis: the body's modal damping is chosen with --damping";
const SOLUTION: &str = "a solution control of a nonlinear or transient analysis: no effect on \
                        the body's normal modes";
const ROTATION: &str = "a rotating reference frame (spin softening, gyroscopic terms): not \
                        formed here (when nonzero)";
const BODY_LOAD: &str = "a body load (nodal or element temperatures, heat generation…): ANSYS \
                         evaluates temperature-dependent materials and forms thermal strains at \
                         it; not read";
const NODAL_ROTATION: &str = "rotates nodal coordinate systems after the NBLOCK (CDWRITE writes \
                              the angles in the NBLOCK, which are read): not read";
const WORKING_PLANE: &str = "the working plane of a session: the archive's coordinates are global";

const OUTPUT: &str = "an output control of ANSYS's own solution: no effect on the body";
const SELECTION: &str = "a selection of a session: the archive's commands name their entities \
                         (D, F, CE and CP on ALL or a component, which would act on a selection, \
                         are refused)";
const SOLID_MODEL: &str = "the solid model (geometry: keypoints, lines, areas, volumes and their \
                           attributes), not the mesh: no effect on the body";
const SOLID_MODEL_LOAD: &str = "a load on the solid model (ANSYS transfers it to the mesh when it \
                                solves): not read; a body load refused as BF";
const TB_DATA: &str = "the data of the preceding TB table: read or refused with its TB";

/// Every command, sorted by name (the name as the archive writes it, upper case).
pub(crate) const COMMANDS: &[(&str, Category, Disposition)] = &[
    ("*DIM", C::Session, N("a parameter array (Workbench's scratch folders, GUI state): no effect on the body")),
    ("*ELSE", C::Session, N("CDWRITE's preamble: the archive is read whole, its NUMOFF have no effect on one archive")),
    ("*ENDIF", C::Session, N("CDWRITE's preamble: the archive is read whole, its NUMOFF have no effect on one archive")),
    ("*IF", C::Session, N("CDWRITE's preamble: the archive is read whole, its NUMOFF have no effect on one archive")),
    ("*SET", C::Session, N("a scalar parameter (GUI colours and fonts, status flags): no effect on the body")),
    ("/AUX15", C::Session, N("the IGES import processor of a session (CDWRITE's IGES option): no effect on the body")),
    ("/COM", C::Session, N("a comment")),
    ("/GO", C::Session, N(SESSION)),
    ("/GOPR", C::Session, N(SESSION)),
    ("/NOPR", C::Session, N(SESSION)),
    ("/PREP7", C::Session, N(SESSION)),
    ("/SOLU", C::Session, N(SESSION)),
    ("/TITLE", C::Session, N("the title: no effect on the body")),
    ("/UNITS", C::Session, N("a label of the unit system: the build's --units says the archive's units")),
    ("ACEL", C::Load, H("a scene load named ACEL: the inertia load of the acceleration (ACEL,0,0,9.81 is gravity along −z); zero: nothing")),
    ("ALPHAD", C::Analysis, N(DAMPING)),
    ("ANTYPE", C::Analysis, N("the analysis type: the body is the structure's normal modes whatever the archive's analysis")),
    ("ASATTR", C::Mesh, N(SOLID_MODEL)),
    ("AUTOTS", C::Analysis, N(SOLUTION)),
    ("BETAD", C::Analysis, N(DAMPING)),
    ("BF", C::Load, R(BODY_LOAD)),
    ("BFA", C::Load, R(SOLID_MODEL_LOAD)),
    ("BFE", C::Load, R(BODY_LOAD)),
    ("BFK", C::Load, R(SOLID_MODEL_LOAD)),
    ("BFL", C::Load, R(SOLID_MODEL_LOAD)),
    ("BFUNIF", C::Load, N("a uniform temperature: no effect on a linear body whose material tables are read at the reference temperature")),
    ("BFV", C::Load, R(SOLID_MODEL_LOAD)),
    ("CE", C::Constraint, H("a constraint equation: an MPC Σ cᵢ uᵢ = 0 on the nodes' dofs in their nodal coordinate systems (a nonzero constant is refused)")),
    ("CGLOC", C::Analysis, R(ROTATION)),
    ("CGOMEGA", C::Analysis, R(ROTATION)),
    ("CLOCAL", C::Mesh, H("a local coordinate system relative to the active one (as LOCAL when that is Cartesian); the archive's coordinates and nodal angles are written global, so it orients only the orthotropic solids whose ESYS names it (one relative to a curvilinear active system: refused for them)")),
    ("CM", C::Mesh, N("a component made from a session's selection: not read (CDWRITE writes every component as a CMBLOCK, which is read)")),
    ("CMBLOCK", C::Mesh, H("a node component becomes a node set (usable as an --interface name); an element component an element set")),
    ("CMDEL", C::Mesh, H("deletes a component read before it (a CMBLOCK) by name")),
    ("CMSEL", C::Session, N(SELECTION)),
    ("CNVTOL", C::Analysis, N(SOLUTION)),
    ("CP", C::Constraint, H("a coupled set: MPCs making the listed nodes' dof (in their nodal coordinate systems) equal to the first node's")),
    ("CRPLIM", C::Analysis, N(SOLUTION)),
    ("CSCIR", C::Mesh, N("the singularity of a local cylindrical or spherical system: no effect (the archive's coordinates and nodal angles are written global)")),
    ("CSYS", C::Mesh, H("the active coordinate system, which a following CLOCAL is relative to; the archive's coordinates are global")),
    ("D", C::Constraint, H("a zero displacement (UX…ROTZ, ALL; in the node's nodal coordinate system) held as a reference condition, as the other formats' SPCs; a nonzero value is refused")),
    ("DBLOCK", C::Constraint, H("a block of D constraints (node, dof label, value, imaginary value; format (i9,a6,2(pg16.9))): each record read as D")),
    ("DCGOMG", C::Analysis, R(ROTATION)),
    ("DMPOPT", C::Analysis, N(OUTPUT)),
    ("DMPRAT", C::Analysis, N(DAMPING)),
    ("DMPSTR", C::Analysis, N(DAMPING)),
    ("DOF", C::Session, N("the active dof labels: the elements give their dofs")),
    ("DOMEGA", C::Analysis, R(ROTATION)),
    ("EBLOCK", C::Mesh, H("elements (SOLID and contact layouts), formed by their type and KEYOPTs (table below)")),
    ("EMUNIT", C::Analysis, N("the units of an electromagnetic analysis: no effect on the body")),
    ("EN", C::Mesh, H("the end line of an EBLOCK")),
    ("EQSLV", C::Analysis, N("ANSYS's equation solver: no effect on the body")),
    ("ERESX", C::Session, N(SESSION)),
    ("ESEL", C::Session, N(SELECTION)),
    ("ESYS", C::Mesh, N("the element coordinate system of elements created after it: the archive's EBLOCK holds each element's own ESYS field, which is read (an orthotropic solid's material axes are its LOCAL system's; a curvilinear one refused for them; a system no LOCAL defines refused)")),
    ("ET", C::Mesh, H("an element type (table below)")),
    ("ETBLOCK", C::Mesh, H("element types as a block (MAPDL 2022 and later): type number, element number and KEYOPT(1)…KEYOPT(18) per record, as ET and KEYOPT (a nonzero 19th column refused)")),
    ("EXTOPT", C::Session, N("an extrusion option of the solid modeller: no effect on the mesh")),
    ("F", C::Load, H("a nodal force or moment (FX…MZ, in the node's nodal coordinate system): a scene load named F")),
    ("FC", C::Material, N("failure criteria of a material (stress and strain limits): post-processing data, no effect on the body")),
    ("FCUM", C::Load, N("how a session accumulates repeated nodal forces: CDWRITE writes each force once")),
    ("FINISH", C::Session, N(SESSION)),
    ("IRLF", C::Analysis, N("inertia relief of a static analysis: the body's reference conditions are chosen with --reference")),
    ("KBC", C::Analysis, N(SOLUTION)),
    ("KEYOP", C::Mesh, H("an element type's KEYOPT (as CDWRITE writes KEYOPT)")),
    ("KEYOPT", C::Mesh, H("an element type's KEYOPT")),
    ("KPATTR", C::Mesh, N(SOLID_MODEL)),
    ("KUSE", C::Analysis, N(SOLUTION)),
    ("LCATTR", C::Mesh, N(SOLID_MODEL)),
    ("LOCAL", C::Mesh, H("a local coordinate system (also CDWRITE's LOC/ANG/PRM lines): the archive's coordinates and nodal angles are written global, so it orients only the orthotropic solids whose EBLOCK ESYS names it (their material axes: the Cartesian system's axes after THXY about Z, THYZ about the new X, THZX about the new Y; a cylindrical or spherical one refused for them)")),
    ("LUMPM", C::Analysis, H("LUMPM,ON: lumped mass (the default is ANSYS's consistent mass); --mass overrides")),
    ("MAT", C::Mesh, N(ATTRIBUTE)),
    ("MODCONTROL", C::Analysis, N("a modal output control: no effect on the body")),
    ("MODOPT", C::Analysis, H("the mode count and band of the build when --modes/--fmax do not say")),
    ("MP", C::Material, H("a material constant (the MPDATA labels below)")),
    ("MPDATA", C::Material, H("EX, EY, EZ, PRXY/NUXY…, GXY…, DENS: an isotropic material, or an orthotropic one for solids (all nine constants, Poisson's ratios major PRij or minor NUij, not both; a missing one or a D not positive definite refused by name; orthotropic shells, beams, links and SOLID185's B-bar refused); thermal, damping and friction labels are noted; a temperature table is read at TREF or refused")),
    ("MPTEMP", C::Material, H("the temperatures of the following MPDATA")),
    ("MXPAND", C::Analysis, N("the modes ANSYS expands for its own results: no effect on the body (MODOPT, --modes, --fmax say which modes)")),
    ("N", C::Mesh, H("the end line of an NBLOCK (N,R5.3,LOC,-1)")),
    ("NANG", C::Mesh, R(NODAL_ROTATION)),
    ("NBLOCK", C::Mesh, H("nodes; the rotation angles THXY, THYZ, THZX (first about nodal Z, then the new X, then the new Y) give the node's nodal coordinate system, in which D, F, CE and CP on it are read")),
    ("NCNV", C::Analysis, N(SOLUTION)),
    ("NEQIT", C::Analysis, N(SOLUTION)),
    ("NLDIAG", C::Analysis, N(OUTPUT)),
    ("NLGEOM", C::Analysis, N("large deflection of a nonlinear analysis: the body is linear about the undeformed state (an ANSYS archive's preload is not read: PSTRES,ON is refused)")),
    ("NMODIF", C::Mesh, R("modifies a node's coordinates or rotation angles after the NBLOCK: not read")),
    ("NORA", C::Mesh, R(NODAL_ROTATION)),
    ("NROTAT", C::Mesh, R(NODAL_ROTATION)),
    ("NSEL", C::Session, N(SELECTION)),
    ("NSUBST", C::Analysis, N(SOLUTION)),
    ("NUMOFF", C::Session, N("an id offset for a later archive: no effect on one archive")),
    ("OMEGA", C::Analysis, R(ROTATION)),
    ("OUTPR", C::Analysis, N(OUTPUT)),
    ("OUTRES", C::Analysis, N(OUTPUT)),
    ("PSTRES", C::Analysis, H("OFF: no effect; ON (prestress effects of the archive's own static solution) refused: an ANSYS archive's preload is not formed here")),
    ("QRDOPT", C::Analysis, N("an option of the QR-damped eigensolver: no effect on the body")),
    ("R", C::Material, H("a real constant set (MASS21's masses, COMBIN14's stiffness, SHELL181's legacy thickness TK(I)…TK(L))")),
    ("REAL", C::Mesh, N(ATTRIBUTE)),
    ("RLBLOCK", C::Material, H("real constant sets (MASS21's masses, COMBIN14's stiffness, SHELL181's legacy thickness)")),
    ("SECBLOCK", C::Material, H("a SHELL section's layers as CDWRITE writes them (SECBLOCK,NLAYERS, then per layer thickness, material, angle, integration points: read as SECDATA); of any other section (a beam section's own mesh) refused")),
    ("SECCONTROL", C::Material, H("a LINK section's added mass per length (LINK180); a SHELL section's added mass per area and user transverse shear stiffnesses E11, E22, E12 (SHELL281's; SHELL181 on such a section refused), a drill stiffness factor other than 1 refused; a BEAM section's added mass per length (user transverse shear stiffnesses TXZ, TXY refused)")),
    ("SECDATA", C::Material, H("a LINK section's area (LINK180); a SHELL section's layer (thickness, material; 3, 5, 7 or 9 points; layers of one material are one homogeneous shell, of several materials refused); a BEAM section's data (ASEC: A, Iyy, Iyz, Izz, Iw, J, CGy, CGz, SHy, SHz — Iyz and the centroid and shear centre off the node refused; RECT: B, H; CSOLID: R; CTUBE: Ri, Ro); the data of other sections is not read (their SECTYPE is refused)")),
    ("SECNUM", C::Mesh, N(ATTRIBUTE)),
    ("SECOFFSET", C::Material, H("a SHELL section's offset: MID (the default), TOP and BOT read (SHELL281 formed offset; SHELL181 on an offset section refused), USER refused; a BEAM section's: CENT (the default) read, SHRC and ORIGIN for CSOLID and CTUBE (the same point), others refused")),
    ("SECTYPE", C::Material, H("LINK sections (LINK180's area and added mass), SHELL sections (SHELL181's and SHELL281's thickness, material, added mass; SHELL281's offset and transverse shear), BEAM sections of subtype ASEC, RECT, CSOLID, CTUBE (BEAM188's); other beam subtypes, tapered (TAPER) and other sections refused by line")),
    ("SF", C::Load, R("a surface load on nodes (the faces of the selected elements they span): not read; CDWRITE writes element surface loads as SFE")),
    ("SFE", C::Load, H("a pressure on an element face (SOLID185/186 faces 1…6, SOLID187 1…4, SHELL181 1 and 2): the scene load named SFE, a uniform traction per face; a varying pressure keeps the load with a problem (not applied); other labels, imaginary values, shell edges, element lists and the archive's R5.0 form refused")),
    ("SFEBLOCK", C::Load, H("a block of element surface loads: a label that cannot load a structure (FSIN, the fluid–solid interface flag; CONV, HFLUX, RAD, RDSF: thermal; IMPD, SHLD, MXWF, CHRGS, INF, PORT: acoustic or electromagnetic) noted with its records; PRES read as SFE (each record element, LKEY, KVAL, VAL1…VAL4; a KVAL 2 record of zeros adds nothing); other labels refused")),
    ("SHPP", C::Session, N("element shape checking of a session: no effect on the body")),
    ("SOLVE", C::Session, N("solves the archive's own analysis: the body is built from the model, not from ANSYS's solution")),
    ("STEF", C::Analysis, N("the Stefan–Boltzmann constant of a radiation analysis: no effect on the body")),
    ("TB", C::Material, H("a material table, by its label: failure criteria (FCLI), friction (FRIC), plasticity (PLAS, BISO, MISO, BKIN, MKIN, KINH, NLISO, CHAB), creep (CREEP, RATE) and damage (DMGI, DMGE) noted — they do not change the linear body at its undeformed state; elastic (ELAS), anisotropic elastic (ANEL), hyperelastic (HYPE), viscoelastic (PRONY, SHIFT), multilinear elastic (MELAS) and every other label refused (they define or change the elastic stiffness)")),
    ("TBDAT", C::Material, N(TB_DATA)),
    ("TBDATA", C::Material, N(TB_DATA)),
    ("TBFIELD", C::Material, N(TB_DATA)),
    ("TBIN", C::Material, N(TB_DATA)),
    ("TBPT", C::Material, N(TB_DATA)),
    ("TBTEM", C::Material, N(TB_DATA)),
    ("TBTEMP", C::Material, N(TB_DATA)),
    ("THOPT", C::Analysis, N(SOLUTION)),
    ("TIME", C::Analysis, N(SOLUTION)),
    ("TIMINT", C::Analysis, N(SOLUTION)),
    ("TINTP", C::Analysis, N(SOLUTION)),
    ("TOFFST", C::Material, N("the offset of absolute zero for thermal analyses: no effect on a body whose tables are read at TREF")),
    ("TREF", C::Material, H("the reference temperature at which temperature tables are read")),
    ("TRNOPT", C::Analysis, N(SOLUTION)),
    ("TSHAP", C::Mesh, N("the active target segment shape of a session (TSHAP,PILO): the EBLOCK writes each TARGE170 record's shape key")),
    ("TSHAPE", C::Mesh, N("the active target segment shape of a session (as TSHAP)")),
    ("TYPE", C::Mesh, N(ATTRIBUTE)),
    ("WPCSYS", C::Session, N(WORKING_PLANE)),
    ("WPLANE", C::Session, N(WORKING_PLANE)),
    ("WPOFFS", C::Session, N(WORKING_PLANE)),
    ("WPROTA", C::Session, N(WORKING_PLANE)),
    ("WPSTYL", C::Session, N(WORKING_PLANE)),
];

/// Element types by number: name and disposition (KEYOPTs in the text).
pub(crate) const ELEMENT_TYPES: &[(u32, &str, Disposition)] = &[
    (14, "COMBIN14", H("spring: KEYOPT(2)=0 with KEYOPT(3)=0, the 3-D longitudinal spring along I→J (as Abaqus SPRINGA); KEYOPT(2)=1…3, the 1-D spring between UX, UY or UZ of I and J (as Nastran CELAS2); K from the real constant set (K = 0: no stiffness), damping CV1/CV2 not read (a note); refused: torsional and 2-D (KEYOPT(3)=1, 2), rotational 1-D (KEYOPT(2)=4…6; no element read here gives rotations stiffness or mass), thermal/pressure (KEYOPT(2)=7, 8), an initial length or preload, coincident nodes of the 3-D spring")),
    (21, "MASS21", H("a point mass: KEYOPT(3)=0 with MASSX = MASSY = MASSZ, or KEYOPT(3)=2 (mass only), from its real constant set, with its rotary inertias IXX, IYY, IZZ on a node an MPC184 rigid beam joins; refused: rotary inertias elsewhere (no other element read here gives a node rotational stiffness), directional masses, KEYOPT(2)=1 (nodal frame) and the 2-D forms are refused")),
    (45, "SOLID45", H("archived 8-node brick (MAPDL Archived Elements Theory Reference §1.6): KEYOPT(1)=0 (the default) with 8 unique nodes Wilson's incompatible modes with Taylor's correction (the modified extra shape functions) on 2×2×2 points and the trilinear mass on the same points — SOLID185 KEYOPT(2)=3's element; KEYOPT(1)=1 the trilinear brick on 2×2×2 points (C3D8), refused beside bricks with incompatible modes in one archive (they are formed for the whole body); collapsed into ANSYS's wedge (K = L, O = P) the brick as written on 2×2×2 points, as SOLID185's wedge; refused by line: KEYOPT(2)=1 (one point with Flanagan–Belytschko hourglass control: its hourglass stiffness is not given), the collapsed pyramid and tetrahedron, KEYOPTs other than the output controls KEYOPT(5), KEYOPT(6)")),
    (92, "SOLID92", R("archived 10-node tetrahedron: its Theory Reference page (the integration points of its stiffness and mass) was not at hand, so whether it is SOLID187's element cannot be told here (docs/ansys.md); SOLID187 is formed")),
    (95, "SOLID95", H("archived 20-node brick (MAPDL Archived Elements Theory Reference §1.17): stiffness and mass on Irons' 14 points with KEYOPT(11)=0 (the default) — SOLID186 KEYOPT(2)=1's element — or on 2×2×2 points with KEYOPT(11)=1 (SOLID186 KEYOPT(2)=0's stiffness, its mass on the same 2×2×2 points); degenerate wedge, tetrahedron and pyramid as SOLID186's; refused by line: KEYOPT(3)=1 (this type's mass lumped while flexbody lumps the whole body or none), dropped mid-side nodes, KEYOPTs other than the output controls KEYOPT(5), KEYOPT(6)")),
    (152, "SURF152", R("surface effect element: formulation not formed here")),
    (153, "SURF153", R("surface effect element: formulation not formed here")),
    (154, "SURF154", R("surface effect element: formulation not formed here")),
    (156, "SURF156", R("surface effect element: formulation not formed here")),
    (169, "TARGE169", R("bonded contact target: formulation not formed here")),
    (170, "TARGE170", H("a pilot node (TSHAPE,PILO: the shape key 19 or 99, one node, KEYOPT(2)=1) of a surface-based constraint with the CONTA173/174/175 records of its real constant set (the contact types below); KEYOPT(4) the pilot dofs: 0 or 111111, or for a force-distributed constraint any pattern of 0 and 1 read from the units digit (UX, UY, UZ, ROTX, ROTY, ROTZ: 111 the translations, as ANSYS's field shows); and target faces TRIA, QUAD, TRI6, QUA8 (shape keys 6…9) of bonded contact between surfaces: each contact node within the pinball (a negative PINB) tied to its nearest target face point by the face's shape functions (as *TIE, ADJUST=NO), the nodes outside left free with a note; refused by line: a pilot with target faces (a rigid target surface), other target shapes, the contact layout (its shape not written), KEYOPT(2)=0 on a pilot, other KEYOPTs")),
    (171, "CONTA171", R("bonded contact: formulation not formed here")),
    (172, "CONTA172", R("bonded contact: formulation not formed here")),
    (173, "CONTA173", H("4-node contact face of a surface-based constraint, as CONTA174 (3-node triangle when K = L)")),
    (174, "CONTA174", H("8-node contact face of a surface-based constraint with a TARGE170 pilot of its real constant set, MPC bonded (KEYOPT(2)=2, KEYOPT(12)=5): KEYOPT(4)=2 rigid (an RBE2 from the pilot to the contact nodes' translations, as CERIG), KEYOPT(4)=1 force-distributed (an RBE3 at the pilot over the contact nodes' translations weighted by their consistent face areas ∫N dA); refused by line: standard, rough, no-separation and bonded-initial contact, penalty, augmented Lagrange and Lagrange multipliers (ANSYS forms them with its contact stiffness), other KEYOPT(4), KEYOPTs other than 2, 4, 12, 8, 10, real constants ICONT, CNOF and PINB with a pilot; against TARGE170 faces (KEYOPT(4)=2, KEYOPT(12)=5): bonded contact between solids (TARGE170 above), KEYOPT(9)=1 (the initial gap excluded: bonded as placed) or any KEYOPT(9) where no tied node has a gap; refused there: bonded initial (KEYOPT(12)=6), other detection options, ANSYS's default or a positive PINB (depth-based, not reproduced), a gap under a KEYOPT(9) that includes it, shell-solid and shell-shell assemblies (ANSYS ties the shell rotations too), a symmetric couple unless on congruent meshes (each contact node of both sets on a target node, the same node pairs: then formed once; otherwise which of the two ANSYS keeps changes the body)")),
    (175, "CONTA175", H("node contact of a surface-based constraint: KEYOPT(4)=0 rigid (an RBE2 from the TARGE170 pilot of its real constant set to the node's translations), MPC bonded (KEYOPT(2)=2, KEYOPT(12)=5); the force-distributed form and every other contact refused by line, as CONTA174")),
    (177, "CONTA177", R("bonded contact: formulation not formed here")),
    (178, "CONTA178", R("node-to-node contact: formulation not formed here")),
    (180, "LINK180", H("2-node spar: axial stiffness only, consistent mass ρAL/6·[2 1; 1 2] on each translation (lumped ρAL/2), as the rod without torsion (Nastran CROD with J = 0); area and added mass from its LINK section or real constants AREA, ADDMAS; tension- or compression-only (KEYOPT(3)=1, 2, TENSKEY) refused")),
    (181, "SHELL181", H("4-node shell, KEYOPT(3)=2 (full integration with incompatible modes): MITC4 bending and transverse shear, QM6 membrane, with ANSYS's transverse shear factor 1/(1 + A/(160 000 t²)) and drilling penalty (1/200 of that shear rigidity), as ANSYS's element forces show (docs/ansys.md); the degenerate triangle (K = L) the same element with nodes K and L at one point, as ANSYS's element strain and kinetic energies show; consistent mass with the rotary inertia ρt³/12 on the bending rotations; a homogeneous shell section (SECTYPE SHELL, MID offset) or legacy thickness TK(I); refused by line: KEYOPT(3)=0 (the default, reduced integration with hourglass control), the membrane option KEYOPT(1)=1, other KEYOPTs but KEYOPT(8), repeated nodes other than K = L, laminates and offsets")),
    (182, "PLANE182", R("a 2-D element: a body is three-dimensional")),
    (183, "PLANE183", R("a 2-D element: a body is three-dimensional")),
    (184, "MPC184", H("rigid link (KEYOPT(1)=0): the linearized constraint keeping the distance of I and J, e·(u_J − u_I) = 0, one linear MPC; rigid beam (KEYOPT(1)=1): J follows the rigid motion of I in all six dofs, an RBE2; KEYOPT(2)=0 or 1 (direct elimination, Lagrange multipliers: the same constraint); the slider and joints (other KEYOPT(1)) are refused")),
    (185, "SOLID185", H("8-node brick: KEYOPT(2)=0 (the default) the B-bar method — each of the 2×2×2 points' volumetric strain replaced by the element's mean dilatation (Hughes 1980) — and, collapsed into ANSYS's wedge (K = L, O = P), the brick as written fully integrated, as ANSYS's element forces show; KEYOPT(2)=3 (simplified enhanced strain) Wilson's incompatible modes with Taylor's correction on 2×2×2 points, as Abaqus C3D8I condensed; mass of the compatible brick on 2×2×2; refused by line naming KEYOPT(2): uniform reduced with hourglass control (1), enhanced strain (2); the collapsed pyramid and tetrahedron, and any collapsed KEYOPT(2)=3 brick, refused")),
    (186, "SOLID186", H("20-node brick: KEYOPT(2)=0 (the default) uniform reduced 2×2×2 integration as Abaqus C3D20R, KEYOPT(2)=1 full integration on Irons' 14 points, mass on the 14 points; degenerate wedge as the 15-node wedge (3 × 3 points), tetrahedron as the 10-node tetrahedron (4 points), pyramid as ANSYS's 13-node pyramid (2×2×2 points; each shown against ANSYS's strain energies); dropped mid-side nodes are refused by line")),
    (187, "SOLID187", H("10-node tetrahedron as Abaqus C3D10; written with its 4 corner nodes only (mid-side nodes dropped: straight edges, linear displacement) it is exactly the 4-node tetrahedron C3D4")),
    (188, "BEAM188", H("2-node beam, KEYOPT(3)=0 (linear, the default) with six dofs per node: linear functions for displacements and rotations, stiffness on 1 point along the length (one-point shear), consistent mass on 2 points with the section's rotary inertia, lumped mass (LUMPM) on the translations only (MAPDL Theory Reference §13.188); KEYOPT(3)=2 (quadratic) as BEAM189 on ANSYS's internal node, made at the middle of IJ; KEYOPT(3)=3 (cubic) on ANSYS's two internal nodes, made at 1/3 and 2/3 of IJ: cubic functions for displacements and rotations, stiffness on 3 points along the length, consistent mass on 4 points with the section's rotary inertia; orientation node K (the element z axis toward K); sections SECTYPE BEAM ASEC (the user's A, Iyy, Izz, J; shear factor 1), RECT, CSOLID, CTUBE (closed-form constants, docs/ansys.md); refused by line: the warping dof KEYOPT(1)=1, LUMPM,ON with KEYOPT(3)=2 or 3 (ANSYS's lumping of them not established), no K on a section whose orientation matters, other section subtypes, offsets off the centroid")),
    (189, "BEAM189", H("3-node beam (I, J, mid node K, orientation node L), six dofs per node: quadratic functions for displacements and rotations, stiffness on 2 points along the length, consistent mass on 3 points with the section's rotary inertia (MAPDL Theory Reference §13.189; VM50's published frequency shows ASEC's shear factor 1 and the rotary inertia); the same sections and orientation as BEAM188; refused by line: the warping dof KEYOPT(1)=1, a mid node off the middle of IJ (curved), lumped mass (ANSYS's lumping not established)")),
    (190, "SOLSH190", R("solid shell: formulation not formed here")),
    (200, "MESH200", N("a meshing-only element: it carries no stiffness or mass")),
    (281, "SHELL281", H("8-node shell: the serendipity shell on 2 × 2 points (membrane, bending and transverse shear, k = 5/6 or the section's SECCONTROL stiffnesses), the section's TOP/BOT offset as a rigid shift of the mid-surface, as ANSYS's element forces show (docs/ansys.md); consistent mass on the 2 × 2 points; a homogeneous shell section; refused by line: the membrane option KEYOPT(1)=1, other KEYOPTs but KEYOPT(8), the triangle K = L = O, LUMPM,ON")),
    (285, "SOLID285", R("4-node mixed u-P tetrahedron: its nodal hydrostatic pressure HDSP is a fourth dof shared between elements (not condensable element by element) and the stabilization of its equal-order interpolation is not documented at hand; not formed here (docs/ansys.md)")),
    (288, "PIPE288", R("pipe: formulation not formed here")),
    (289, "PIPE289", R("pipe: formulation not formed here")),
];

/// The row of a command name (upper case), if listed.
pub(crate) fn command(name: &str) -> Option<(Category, Disposition)> {
    COMMANDS
        .binary_search_by(|r| r.0.cmp(name))
        .ok()
        .map(|i| (COMMANDS[i].1, COMMANDS[i].2))
}

/// The element type with this number (`ET,1,186`) or name (`ET,1,SOLID186`).
pub(crate) fn element_type(key: &str) -> Option<(u32, &'static str, Disposition)> {
    let key = key.trim().to_ascii_uppercase();
    let by_number = key.parse::<u32>().ok();
    ELEMENT_TYPES
        .iter()
        .find(|r| Some(r.0) == by_number || r.1 == key)
        .copied()
}

fn disposition_text(d: Disposition) -> String {
    match d {
        Disposition::Honoured(how) => format!("honoured: {how}"),
        Disposition::Note(why) => format!("note: {why}"),
        Disposition::Refused(why) => format!("refused: {why}"),
    }
}

/// `docs/ansys-commands.md`: both tables (a test keeps the page equal).
pub fn markdown() -> String {
    let mut s = String::from(
        "# ANSYS: what the importer does with each archive command and element type\n\n\
         Generated from the catalogue (`src/import/ansys/catalogue.rs`) by \
         `cargo test --lib ansys::catalogue` with `FLEXBODY_BLESS=1`; a test keeps this page \
         equal to it. Every command and element type a `CDWRITE` archive (`.cdb`) can hold is \
         *honoured* (read into the model), a *note* (it cannot change the body's stiffness, \
         mass or constraints; the build reports one note per command with its lines) or \
         *refused* (the import stops with every refused line of the archive; `--ignore NAME` \
         drops a command or element type on purpose). A name in no table is refused by its \
         line. See `docs/ansys.md` for the element formulations and the `.full` reader.\n",
    );
    for cat in Category::ALL {
        let rows: Vec<_> = COMMANDS.iter().filter(|r| r.1 == cat).collect();
        s.push_str(&format!(
            "\n## Commands: {} ({})\n\n| command | disposition |\n|---|---|\n",
            cat.title(),
            rows.len()
        ));
        for (name, _, d) in rows {
            s.push_str(&format!("| {name} | {} |\n", disposition_text(*d)));
        }
    }
    s.push_str(&format!(
        "\n## Element types ({})\n\n| number | name | disposition |\n|---|---|---|\n",
        ELEMENT_TYPES.len()
    ));
    for (n, name, d) in ELEMENT_TYPES {
        s.push_str(&format!("| {n} | {name} | {} |\n", disposition_text(*d)));
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tables_are_sorted_and_unique() {
        assert!(COMMANDS.windows(2).all(|w| w[0].0 < w[1].0));
        assert!(ELEMENT_TYPES.windows(2).all(|w| w[0].0 < w[1].0));
        assert!(COMMANDS.iter().all(|r| r.0 == r.0.to_ascii_uppercase()));
    }

    /// `docs/ansys-commands.md` is the catalogue's page (`FLEXBODY_BLESS=1` rewrites it).
    #[test]
    fn documentation_page_is_generated_from_the_catalogue() {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/docs/ansys-commands.md");
        let page = markdown();
        if std::env::var_os("FLEXBODY_BLESS").is_some() {
            std::fs::write(path, &page).expect("docs/ansys-commands.md is writable");
        }
        let on_disk = std::fs::read_to_string(path).unwrap_or_default();
        assert!(
            on_disk == page,
            "docs/ansys-commands.md differs from the catalogue: regenerate it with \
             FLEXBODY_BLESS=1 cargo test --lib ansys::catalogue"
        );
    }
}
