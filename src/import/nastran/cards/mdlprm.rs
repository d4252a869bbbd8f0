//! The MDLPRM table: MSC Nastran's model parameters (`MDLPRM, NAME1, V1, NAME2, V2, …`, MSC
//! QRG "MDLPRM"; the names as pyNastran 1.4 reads them). Each name is a note (any value leaves
//! the body as built: output, the HDF5 database, the linear solver's settings, aeroelastic
//! splines, nonlinear-only controls) or honoured only at the values that keep MSC's default
//! behaviour, which is the behaviour flexbody models; any other value is refused with the
//! reason. A name in no row is refused.

use super::Category::{self, *};

/// What the reader does with an MDLPRM parameter.
pub(in crate::import::nastran) enum ModelParamRule {
    /// Any value: it cannot change the body, for this reason.
    Note(&'static str),
    /// Honoured at these values (MSC's default behaviour, the one flexbody forms; numbers
    /// compare as numbers, words case-insensitively); another value is refused for the reason.
    Only(&'static [&'static str], &'static str),
}

use ModelParamRule::{Note, Only};

/// An MDLPRM row: name, category, rule.
pub(in crate::import::nastran) type ModelParamRow = (&'static str, Category, ModelParamRule);

/// Reason of the notes on the HDF5 output parameters.
const HDF5: &str = "what MSC writes to its HDF5 results database (.h5): output only";
/// Reason of the notes on the sparse solver parameters.
const SOLVER: &str =
    "a setting of MSC's linear equation solver (PARDISO, pivoting): the same K and M are factored";
/// Reason of the refusal of a formulation switch.
const FORMULATION: &str = "a non-default value changes the element formulation MSC forms (flexbody forms MSC's default one): not modelled";
/// Reason of the refusal of the weld/fastener/mass partitioning parameters.
const PARTITION: &str = "a non-default value deletes or partitions connection elements or masses before the analysis: not modelled";

/// Every MDLPRM name with its rule, sorted by name (checked by a test).
pub(in crate::import::nastran) const MODEL_PARAMS: &[ModelParamRow] = &[
    ("BRTOBM", Element, Only(&["0"], "BRTOBM converts CBAR elements to CBEAM: a non-default value changes the bar formulation: not modelled")),
    ("BUSHRT", Element, Only(&["0"], FORMULATION)),
    ("COMPN1", Property, Only(&[], "changes how composite (PCOMP) properties are formed: not modelled")),
    ("DBCTOLE", Output, Note("a tolerance of the database's model checks: output only")),
    ("DCFLTEXP", Solution, Note(SOLVER)),
    ("DELELAS", Element, Only(&[], PARTITION)),
    ("DELFAST", Element, Only(&[], PARTITION)),
    ("DELMASS", Mass, Only(&[], PARTITION)),
    ("DELSEAM", Element, Only(&[], PARTITION)),
    ("DELWELD", Element, Only(&[], PARTITION)),
    ("GEV1417", Solution, Only(&["0"], FORMULATION)),
    ("GNLSTN", Nonlinear, Note("the strain measure of a geometric nonlinear analysis: a linear normal-modes analysis has none")),
    ("H5GM34", Output, Note(HDF5)),
    ("H5INFO", Output, Note(HDF5)),
    ("H5MDL", Output, Note(HDF5)),
    ("H5MTX", Output, Note(HDF5)),
    ("H5NORDOF", Output, Note(HDF5)),
    ("H5XHH", Output, Note(HDF5)),
    ("HDF5", Output, Note(HDF5)),
    ("IGNSHBDN", Element, Only(&["0"], FORMULATION)),
    ("INTOUT", Output, Note("output of interpolated results: output only")),
    ("LMT2MPC", Rigid, Note("Lagrange-multiplier rigid elements turned into MPCs: the same constraints (flexbody eliminates rigid elements either way)")),
    ("MLTSPLIN", Aeroelastic, Note("how several aeroelastic splines on one grid combine: aerodynamic loads only")),
    ("MPCF129", Nonlinear, Note("MPC forces of a nonlinear transient analysis (SOL 129): output only")),
    ("NLDIFF", Nonlinear, Note("differential stiffness of a nonlinear analysis: a linear normal-modes analysis has none")),
    ("NONUPIV", Solution, Note(SOLVER)),
    ("NSGRDS4", Element, Only(&["0"], "changes the shell normals at grids (as PARAM SNORM does): not modelled")),
    ("OFFDEF", Element, Only(&["LROFF"], "only LROFF is honoured (offsets that follow the large rotations of a geometric nonlinear analysis: a linear analysis has none); the other options change how element offsets enter the stiffness or mass: not modelled")),
    ("PEXTS4", Element, Only(&[], FORMULATION)),
    ("PIVTHRSH", Solution, Note(SOLVER)),
    ("PRDIDPVT", Solution, Note(SOLVER)),
    ("PRDITRFN", Solution, Note(SOLVER)),
    ("PRDMTYPE", Solution, Note(SOLVER)),
    ("PRDOOC", Solution, Note(SOLVER)),
    ("PRDWMTCH", Solution, Note(SOLVER)),
    ("PRTELAS", Element, Only(&["NO"], PARTITION)),
    ("PRTFAST", Element, Only(&["NO"], PARTITION)),
    ("PRTMASS", Mass, Only(&["NO"], PARTITION)),
    ("PRTSEAM", Element, Only(&["NO"], PARTITION)),
    ("PRTWELD", Element, Only(&["NO"], PARTITION)),
    ("QR6ROT", Element, Only(&["0"], FORMULATION)),
    ("QRSHEAR", Element, Only(&["0"], FORMULATION)),
    ("RDBOTH", Output, Note("which database MSC reads its restart model from: bookkeeping")),
    ("RELAXF", Nonlinear, Note("a relaxation factor of nonlinear iterations: a linear normal-modes analysis has none")),
    ("REUPSE", Superelement, Note("reuse of an upstream superelement's results: bookkeeping")),
    ("RMRBE3RT", Rigid, Only(&["0"], "a non-default value changes the rotations of RBE3 reference grids: not modelled")),
    ("RSTIGNDP", Output, Note("restart bookkeeping: does not change the body")),
    ("SHEARP", Element, Only(&["GARVEY"], "only the default GARVEY shear panel is formed (CSHEAR as MSC's default panel): HARDER is not modelled")),
    ("SHRTOQ4", Element, Only(&["0"], "SHRTOQ4 forms CSHEAR panels as CQUAD4 shells: a non-default value changes the panels' stiffness: not modelled")),
    ("SPBLNDX", Aeroelastic, Note("a blending index of aeroelastic splines: aerodynamic loads only")),
    ("STREQCNT", Output, Note("stress output of equivalence counts: output only")),
    ("TWBRBML", Element, Only(&["0"], FORMULATION)),
];

/// The row of MDLPRM parameter `name` (upper case); `None`: refused as not read.
pub(in crate::import::nastran) fn model_param(name: &str) -> Option<&'static ModelParamRow> {
    MODEL_PARAMS
        .binary_search_by(|(n, _, _)| (*n).cmp(name))
        .ok()
        .map(|k| &MODEL_PARAMS[k])
}

/// Whether `value` is one of `accepted` (numbers compare as numbers, words case-insensitively).
pub(in crate::import::nastran) fn is_accepted(value: &str, accepted: &[&str]) -> bool {
    let number = crate::import::nastran::fields::nastran_real;
    accepted.iter().any(|a| match (number(value), number(a)) {
        (Some(v), Some(a)) => v == a,
        _ => value.eq_ignore_ascii_case(a),
    })
}

/// The disposition of an MDLPRM row as the documentation states it.
pub(super) fn disposition(rule: &ModelParamRule) -> String {
    match rule {
        Note(why) => format!("note: {why}"),
        Only([], why) => format!("refused: {why}"),
        Only(values, why) => format!("honoured at {}; else refused: {why}", values.join(", ")),
    }
}
