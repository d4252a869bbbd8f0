//! The one error type of every importer: each failure names the file, the 1-based line and the
//! entity (card or keyword plus its id) it is about, so a user can jump to the offending record.

use std::path::PathBuf;

/// An import failure.
#[derive(Debug, thiserror::Error)]
pub enum ImportError {
    /// The file could not be opened or read.
    #[error("{file}: cannot read: {source}")]
    Io {
        /// File.
        file: String,
        /// Cause.
        #[source]
        source: std::io::Error,
    },
    /// A record is malformed or refers to something that does not exist.
    #[error("{file}:{line}: {entity}: {message}")]
    Parse {
        /// File the record is in.
        file: String,
        /// 1-based line number of the record (its first line for multi-line records).
        line: usize,
        /// The card/keyword and id, e.g. `CTETRA 12`, `*ELEMENT 73`, `$Nodes`.
        entity: String,
        /// What is wrong.
        message: String,
    },
    /// The format could not be inferred from the file name.
    #[error("{file}: cannot tell the format from the extension; pass a format (inp, bdf, msh)")]
    UnknownFormat {
        /// File.
        file: String,
    },
    /// The extension names one format, the content looks like another.
    #[error("{file}: the extension says {extension} but the content looks like {content}; pass --format {option} to read it as {content} (or rename the file)")]
    FormatMismatch {
        /// File.
        file: String,
        /// The extension's format.
        extension: &'static str,
        /// The format the content looks like.
        content: &'static str,
        /// The `--format` value of the content's format.
        option: &'static str,
    },
    /// The file is not a model at all.
    #[error("{file}: not a model file: {what}")]
    NotAModel {
        /// File.
        file: String,
        /// What it is, or what it lacks.
        what: String,
    },
    /// A CalculiX matrix dump could not be read.
    #[error(transparent)]
    CcxMatrix(#[from] CcxMatrixError),
    /// Cards or keywords that can change the body's stiffness, mass, constraints or preload
    /// which the importer does not model: every one of the deck, with its place ("honoured or
    /// refused, never dropped"). [`crate::import::ImportOptions::ignore_cards`] drops them on
    /// purpose.
    #[error("{}", refusal_text(file, cards))]
    Refused {
        /// The main model file.
        file: String,
        /// Every refused card, in deck order.
        cards: Vec<RefusedCard>,
    },
}

/// One card or keyword the importer refuses.
#[derive(Debug, Clone, PartialEq)]
pub struct RefusedCard {
    /// File it is in.
    pub file: String,
    /// 1-based line.
    pub line: usize,
    /// The card and its id, e.g. `CGAP 12`, `PARAM SNORM`.
    pub entity: String,
    /// The name that drops it on purpose in `ignore_cards` (`--ignore`): `CGAP`, `PARAM:SNORM`.
    pub key: String,
    /// Why it is refused.
    pub reason: String,
}

/// At most this many refused cards are listed one per line; the rest are counted per card.
const LISTED_REFUSALS: usize = 100;

/// The message of [`ImportError::Refused`]: one line per card (up to [`LISTED_REFUSALS`]),
/// then the counts of the rest, then how to drop them on purpose.
fn refusal_text(file: &str, cards: &[RefusedCard]) -> String {
    let mut s = format!(
        "{file}: {} card(s) or keyword(s) that can change the body's stiffness, mass, \
         constraints or preload are not supported (each is honoured or refused, never dropped):",
        cards.len()
    );
    for c in cards.iter().take(LISTED_REFUSALS) {
        s.push_str(&format!(
            "\n  {}:{}: {}: {}",
            c.file, c.line, c.entity, c.reason
        ));
    }
    let mut rest: std::collections::BTreeMap<&str, usize> = Default::default();
    for c in cards.iter().skip(LISTED_REFUSALS) {
        *rest.entry(&c.key).or_default() += 1;
    }
    if !rest.is_empty() {
        let list: Vec<String> = rest.iter().map(|(k, n)| format!("{n} {k}")).collect();
        s.push_str(&format!("\n  … and {}", list.join(", ")));
    }
    // a line without a card name has no name to ignore it by
    let mut keys: Vec<&str> = (cards.iter())
        .map(|c| c.key.as_str())
        .filter(|k| !k.is_empty())
        .collect();
    keys.sort_unstable();
    keys.dedup();
    if !keys.is_empty() {
        s.push_str(&format!(
            "\nto drop them on purpose (an element variant VARIANT=BASE: to read it as its base \
             type), ignore them by name: --ignore {} (recorded in the recipe)",
            keys.join(",")
        ));
    }
    s
}

impl ImportError {
    /// The file the error is about, when known.
    pub fn file(&self) -> Option<&str> {
        match self {
            ImportError::Io { file, .. }
            | ImportError::Parse { file, .. }
            | ImportError::UnknownFormat { file }
            | ImportError::FormatMismatch { file, .. }
            | ImportError::NotAModel { file, .. } => Some(file),
            // the first refused card's file, so that file() and line() name one place
            ImportError::Refused { file, cards } => Some(cards.first().map_or(file, |c| &c.file)),
            ImportError::CcxMatrix(_) => None,
        }
    }

    /// The 1-based line, for record errors.
    pub fn line(&self) -> Option<usize> {
        match self {
            ImportError::Parse { line, .. } => Some(*line),
            ImportError::Refused { cards, .. } => cards.first().map(|c| c.line),
            _ => None,
        }
    }

    /// The entity (card/keyword and id), for record errors.
    pub fn entity(&self) -> Option<&str> {
        match self {
            ImportError::Parse { entity, .. } => Some(entity),
            ImportError::Refused { cards, .. } => cards.first().map(|c| c.entity.as_str()),
            _ => None,
        }
    }
}

/// Shorthand to build an [`ImportError::Parse`].
pub(crate) fn parse_err(
    file: &str,
    line: usize,
    entity: impl Into<String>,
    message: impl Into<String>,
) -> ImportError {
    ImportError::Parse {
        file: file.to_owned(),
        line,
        entity: entity.into(),
        message: message.into(),
    }
}

/// Errors reading a CalculiX matrix dump (`import::ccx_matrices`); each names the file and line.
#[derive(Debug, thiserror::Error)]
pub enum CcxMatrixError {
    /// The file could not be read.
    #[error("{path}: cannot read: {source}")]
    Io {
        /// File.
        path: PathBuf,
        /// Cause.
        source: std::io::Error,
    },
    /// A line does not have the expected shape.
    #[error("{path}:{line}: {message}")]
    Syntax {
        /// File.
        path: PathBuf,
        /// 1-based line number.
        line: usize,
        /// What is wrong.
        message: String,
    },
}
