//! The one error type of every importer: each failure names the file, the 1-based line and the
//! entity (card or keyword plus its id) it is about, so a user can jump to the offending record.

use super::ccx_matrices::CcxMatrixError;

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
    /// A CalculiX matrix dump could not be read.
    #[error(transparent)]
    CcxMatrix(#[from] CcxMatrixError),
}

impl ImportError {
    /// The file the error is about, when known.
    pub fn file(&self) -> Option<&str> {
        match self {
            ImportError::Io { file, .. }
            | ImportError::Parse { file, .. }
            | ImportError::UnknownFormat { file } => Some(file),
            ImportError::CcxMatrix(_) => None,
        }
    }

    /// The 1-based line, for record errors.
    pub fn line(&self) -> Option<usize> {
        match self {
            ImportError::Parse { line, .. } => Some(*line),
            _ => None,
        }
    }

    /// The entity (card/keyword and id), for record errors.
    pub fn entity(&self) -> Option<&str> {
        match self {
            ImportError::Parse { entity, .. } => Some(entity),
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
