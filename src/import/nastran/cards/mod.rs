//! The catalogue: what the reader does with every bulk data entry of MSC Nastran's Quick
//! Reference Guide (and Simcenter/NX additions), every PARAM and every case control command —
//! the rule "honoured or refused, never dropped" as three tables, each row a name, a
//! [`Category`] and a [`Rule`]:
//!
//! * [`Rule::Geometry`], [`Rule::Read`]: honoured (one reader function per card family, as
//!   pyNastran has one class per card; adding a card touches its row and its family's file).
//! * [`Rule::Note`], [`Rule::NoteWhy`]: not read because it cannot change the body's
//!   stiffness, mass, constraints or preload in a normal-modes analysis; reported as one note
//!   per category naming each card with its lines.
//! * [`Rule::Refuse`], and **every name in no table** (a typo, a private card): refused. The
//!   import stops with one error listing every refused card of the deck with file:line
//!   ([`crate::import::ImportError::Refused`]), unless the user drops it on purpose
//!   ([`crate::import::ImportOptions::ignore_cards`]).
//!
//! Bulk data: [`bulk::CARDS`]; PARAMs ([`params::PARAMS`], known as `PARAM:NAME`); case control
//! commands ([`commands::COMMANDS`]). `docs/nastran-cards.md` is generated from the three
//! tables ([`markdown`]; a test keeps the page equal to it), and `docs/nastran-qrg-entries.txt`
//! is the list of entries the bulk table was checked against.

pub(super) mod bulk;
pub(super) mod commands;
pub(super) mod mdlprm;
pub(super) mod params;
mod rule;

use super::fields::C;
pub(super) use rule::{Row, Rule};

/// What a catalogue row is about: the heading of the documentation's tables and, for the
/// cards not read, the note that gathers them (one note per category and deck).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub(crate) enum Category {
    Grids,
    Element,
    Property,
    Material,
    Mass,
    Rigid,
    Constraint,
    DofSet,
    StaticLoad,
    Eigen,
    Solution,
    Damping,
    Dynamic,
    Random,
    Aeroelastic,
    Optimization,
    Output,
    Thermal,
    MaterialTable,
    Nonlinear,
    Superelement,
    Matrix,
    Axisymmetric,
    Acoustic,
    Cyclic,
    Parametric,
    Rotordynamic,
}

impl Category {
    /// Every category, in the order of the documentation.
    pub(crate) const ALL: [Category; 27] = [
        Category::Grids,
        Category::Element,
        Category::Property,
        Category::Material,
        Category::Mass,
        Category::Rigid,
        Category::Constraint,
        Category::DofSet,
        Category::StaticLoad,
        Category::Eigen,
        Category::Solution,
        Category::Damping,
        Category::Dynamic,
        Category::Random,
        Category::Aeroelastic,
        Category::Optimization,
        Category::Output,
        Category::Thermal,
        Category::MaterialTable,
        Category::Nonlinear,
        Category::Superelement,
        Category::Matrix,
        Category::Axisymmetric,
        Category::Acoustic,
        Category::Cyclic,
        Category::Parametric,
        Category::Rotordynamic,
    ];

    /// The category's name in notes and in the documentation.
    pub(crate) fn title(self) -> &'static str {
        match self {
            Category::Grids => "grids and coordinate systems",
            Category::Element => "elements",
            Category::Property => "element properties",
            Category::Material => "materials",
            Category::Mass => "masses",
            Category::Rigid => "rigid elements and multipoint constraints",
            Category::Constraint => "single-point constraints",
            Category::DofSet => "degree-of-freedom sets",
            Category::StaticLoad => "static loads",
            Category::Eigen => "eigenvalue methods",
            Category::Solution => "solution control",
            Category::Damping => "damping",
            Category::Dynamic => "dynamic loads and tables",
            Category::Random => "random response",
            Category::Aeroelastic => "aeroelastic",
            Category::Optimization => "optimization",
            Category::Output => "output and plotting",
            Category::Thermal => "thermal and heat transfer",
            Category::MaterialTable => "material tables",
            Category::Nonlinear => "contact and nonlinear (SOL 106/129/400)",
            Category::Superelement => "superelement bookkeeping",
            Category::Matrix => "direct matrix input",
            Category::Axisymmetric => "axisymmetric and conical models",
            Category::Acoustic => "acoustics and fluids",
            Category::Cyclic => "cyclic symmetry",
            Category::Parametric => "p-elements and geometric meshing",
            Category::Rotordynamic => "rotordynamics",
        }
    }

    /// Why the cards of this category that are notes cannot change the body.
    pub(crate) fn why(self) -> &'static str {
        match self {
            Category::Damping => DAMPING,
            Category::Dynamic => "excitations, steps and tables of response analyses: the normal modes, and so the body, are computed without them",
            Category::Random => "random-response input (spectral densities and their tables), applied after the modes",
            Category::Aeroelastic => "the aerodynamic model, its splines to the structure and the trim, flutter and gust requests: aerodynamic loads on the structure, not part of its stiffness, mass or constraints",
            Category::Optimization => "the design model and responses of SOL 200: outside SOL 200 the analysis model is the cards as written",
            Category::StaticLoad => "a load of a static or response load case: the normal modes neither carry nor are held by it (the scene's loads and a STATSUB preload are the cards the case control selects)",
            Category::Output | Category::Solution => OUTPUT,
            Category::Thermal => THERMAL,
            Category::MaterialTable => "a material table acts only through a MATTi or MATS1 that names it (a MATTi on a material in use is refused)",
            Category::Nonlinear => "contact and nonlinear analysis data: used by nonlinear solutions or when a case control command selects them (those commands and solutions are refused); a linear normal-modes analysis has none",
            Category::Superelement => "superelement bookkeeping: the body is the deck's own grids and elements as written",
            Category::Eigen => "the eigenvalue method of another analysis (buckling, complex modes) or mode tracking",
            Category::Matrix => "a matrix only a DMAP alter or an aeroelastic solution reads",
            Category::Constraint | Category::DofSet => "a set that does not hold the body in a normal-modes analysis",
            Category::Property => "a property only an element type refused where it appears would use: by itself it forms nothing",
            _ => OUTPUT,
        }
    }
}

/// Reason of the notes on damping cards and fields.
pub(super) const DAMPING: &str =
    "damping: a real normal-modes analysis has none (give the body damping with --damping)";
/// Reason of the notes on output and bookkeeping cards and fields.
pub(super) const OUTPUT: &str = "output, plotting or bookkeeping: does not change the body";
/// Reason of the notes on thermal cards.
const THERMAL: &str = "heat transfer and thermal data: no thermal strain or temperature-dependent property enters the modes, and a normal-modes analysis has no thermal load (a thermal preload is a STATSUB(PRELOAD) static subcase with TEMP(LOAD))";

/// The reason of the refusal of a card, PARAM or command no table names.
pub(super) const NOT_READ: &str =
    "not read by this importer, and it may change the body's stiffness, mass or constraints";

/// Look `name` up in a sorted table.
fn lookup<'t>(table: &'t [Row], name: &str) -> Option<&'t Row> {
    table
        .binary_search_by(|(n, _, _)| (*n).cmp(name))
        .ok()
        .map(|k| &table[k])
}

/// The name a card is known by in notes, refusals and `ignore_cards`: the card name, or
/// `PARAM:NAME` for a PARAM.
pub(super) fn key(g: &C) -> String {
    if g.card.name == "PARAM" {
        format!("PARAM:{}", g.text(0).to_ascii_uppercase())
    } else {
        g.card.name.clone()
    }
}

/// The row of a card (a PARAM's from [`params::PARAMS`]); `None`: refused as not read.
pub(super) fn row(g: &C) -> Option<&'static Row> {
    match g.card.name.as_str() {
        "PARAM" => lookup(params::PARAMS, &g.text(0).to_ascii_uppercase()),
        name => lookup(bulk::CARDS, name),
    }
}

/// The row of case control command `word` (upper case): its name, or an abbreviation of four
/// letters or more (Nastran reads the first four); `None`: refused as not read.
pub(super) fn command(word: &str) -> Option<&'static Row> {
    lookup(commands::COMMANDS, word).or_else(|| {
        (word.len() >= 4)
            .then(|| commands::COMMANDS.iter().find(|r| r.0.starts_with(word)))
            .flatten()
    })
}

/// The row of PARAM `name` (upper case); `None`: refused as not read.
pub(super) fn param(name: &str) -> Option<&'static Row> {
    lookup(params::PARAMS, name)
}

/// The rule of a card; `None`: refused as not read.
pub(super) fn rule(g: &C) -> Option<&'static Rule> {
    row(g).map(|r| &r.2)
}

/// The disposition of a rule as the documentation states it.
fn disposition(rule: &Rule) -> String {
    match rule {
        Rule::Geometry | Rule::Read(_) | Rule::Command => "honoured".to_owned(),
        Rule::Note => "note".to_owned(),
        Rule::NoteWhy(why) => format!("note: {why}"),
        Rule::Refuse(why) => format!("refused: {why}"),
    }
}

/// `docs/nastran-cards.md`: the three tables, by category (a test keeps the page equal).
pub fn markdown() -> String {
    let mut s = String::from(
        "# Nastran: what the importer does with each card, PARAM and command\n\n\
         Generated from the catalogue (`src/import/nastran/cards/`) by \
         `cargo test --lib nastran::cards` with `FLEXBODY_BLESS=1`; a test keeps this page \
         equal to it. Every name is *honoured* (read into the model), a *note* (it cannot \
         change the body's stiffness, mass, constraints or preload in a normal-modes analysis; \
         the build reports one note per category with the cards' lines) or *refused* (the \
         import stops with every refused card of the deck and its line; `--ignore NAME` drops \
         a card on purpose). A name in no table is refused. The bulk data table was checked \
         against `docs/nastran-qrg-entries.txt`.\n\n\
         **Solutions.** `SOL 103` (`SEMODES`; NASTRAN-95's rigid format 3) is the body's \
         normal modes, with a static preload when `STATSUB(PRELOAD)` names a static subcase. \
         A linear response solution (101, 107–112, 144–146 and their names) builds the same \
         structure's normal modes, with a note. Every other solution is refused by its line: \
         buckling (105), nonlinear (106, 129, 400–402, 600, 700: also modes after a \
         nonlinear preload), NASTRAN-95's rigid format 13 (normal modes with differential \
         stiffness) and 4, heat transfer, cyclic symmetry, design optimization (200) and any \
         unknown solution; `--ignore SOL` builds the unloaded normal modes anyway.\n\n\
         **Format by content.** Without `--format`, a file's format comes from its content \
         (`*KEYWORD` lines: Abaqus/CalculiX; bulk data cards, `BEGIN BULK`, `CEND`, `SOL`: \
         Nastran; `$MeshFormat`: Gmsh). `.dat` and unknown extensions take the content's \
         format; `.inp`, `.bdf`, `.nas`, `.blk`, `.bulk`, `.msh` must agree with it (else an \
         error names the content's format and `--format`). A file that looks like none, or a \
         `.flexbody` file, is refused as not a model.\n",
    );
    let sections: [(&str, &[Row]); 3] = [
        ("Bulk data entries", bulk::CARDS),
        (
            "PARAM names (`PARAM,NAME`; `--ignore PARAM:NAME`)",
            params::PARAMS,
        ),
        (
            "Case control commands (abbreviated to four letters or more as Nastran allows)",
            commands::COMMANDS,
        ),
    ];
    for (title, table) in sections {
        s.push_str(&format!("\n## {title}\n"));
        for cat in Category::ALL {
            let rows: Vec<&Row> = table.iter().filter(|r| r.1 == cat).collect();
            if rows.is_empty() {
                continue;
            }
            s.push_str(&format!("\n### {} ({})\n\n", cat.title(), rows.len()));
            if rows
                .iter()
                .any(|r| matches!(r.2, Rule::Note | Rule::NoteWhy(_)))
            {
                s.push_str(&format!("Notes: {}.\n\n", cat.why()));
            }
            s.push_str("| name | disposition |\n|---|---|\n");
            for (name, _, rule) in rows {
                s.push_str(&format!("| {name} | {} |\n", disposition(rule)));
            }
        }
    }
    s.push_str(
        "\n## MDLPRM parameters (`MDLPRM, NAME1, V1, NAME2, V2, …`; `--ignore MDLPRM`)\n\n\
         Each pair of an MDLPRM card is read by its row: a note (any value), or honoured at \
         the values that keep MSC's default behaviour (a blank value is the default) and \
         refused at any other. A name in no row is refused.\n\n\
         | name | disposition |\n|---|---|\n",
    );
    for (name, _, rule) in mdlprm::MODEL_PARAMS {
        s.push_str(&format!("| {name} | {} |\n", mdlprm::disposition(rule)));
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn card_tables_are_sorted_and_unique() {
        for table in [bulk::CARDS, params::PARAMS, commands::COMMANDS] {
            for w in table.windows(2) {
                assert!(w[0].0 < w[1].0, "{} before {}", w[0].0, w[1].0);
            }
        }
        for w in mdlprm::MODEL_PARAMS.windows(2) {
            assert!(w[0].0 < w[1].0, "{} before {}", w[0].0, w[1].0);
        }
        assert!(matches!(
            lookup(bulk::CARDS, "GRID"),
            Some((_, _, Rule::Geometry))
        ));
        assert!(matches!(
            lookup(bulk::CARDS, "CDAMP1"),
            Some((_, Category::Damping, Rule::Note))
        ));
        assert!(
            lookup(bulk::CARDS, "NOSUCH").is_none() && lookup(params::PARAMS, "NOSUCH").is_none()
        );
    }

    /// The catalogue names at least 95 % of the entries of the list it was checked against
    /// (`docs/nastran-qrg-entries.txt`: pyNastran 1.4.1's bulk data names; measured 100 %).
    #[test]
    fn catalogue_names_the_reference_list() {
        let list = include_str!("../../../../docs/nastran-qrg-entries.txt");
        let names: Vec<&str> = (list.lines())
            .map(str::trim)
            .filter(|l| !l.is_empty() && !l.starts_with('#'))
            .collect();
        assert!(names.len() > 400, "{}", names.len());
        let missing: Vec<&str> = (names.iter().copied())
            .filter(|n| lookup(bulk::CARDS, n).is_none())
            .collect();
        let named = 1.0 - missing.len() as f64 / names.len() as f64;
        assert!(
            named >= 0.95,
            "{:.1} % named; missing {missing:?}",
            named * 100.0
        );
    }

    /// `docs/nastran-cards.md` is the catalogue's page (`FLEXBODY_BLESS=1` rewrites it).
    #[test]
    fn documentation_page_is_generated_from_the_catalogue() {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/docs/nastran-cards.md");
        let page = markdown();
        if std::env::var_os("FLEXBODY_BLESS").is_some() {
            std::fs::write(path, &page).expect("docs/nastran-cards.md is writable");
        }
        let on_disk = std::fs::read_to_string(path).unwrap_or_default();
        assert!(
            on_disk == page,
            "docs/nastran-cards.md differs from the catalogue: regenerate it with \
             FLEXBODY_BLESS=1 cargo test --lib nastran::cards"
        );
    }
}
