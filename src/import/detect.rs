//! A model file's format from its content where the extension is not decisive: Abaqus/CalculiX
//! keyword lines (`*NODE`, `*HEADING`, …), Nastran cards and statements (`BEGIN BULK`, `CEND`,
//! `SOL`, `GRID`, any card of the catalogue), ANSYS archives' `NBLOCK`/`EBLOCK`, Gmsh's
//! `$MeshFormat`. `.inp`, `.bdf`, `.nas`,
//! `.blk`, `.bulk`, `.cdb` and `.msh` name a format, which the content must not contradict; `.dat`
//! (Nastran's and Abaqus's) and other extensions take the content's. A file that looks like
//! none (a README named `.inp`) or is a flexbody output file is an error saying so; an empty
//! file is the error `file:1: empty file`.

use std::io::Read;
use std::path::Path;

use super::{Format, ImportError};

/// How much of a file is looked at.
const SNIFFED_BYTES: u64 = 4 << 20;

/// What a file's content looks like.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Content {
    /// A model in this format.
    Model(Format),
    /// A zip archive: a `.flexbody` file (or another archive), not a model.
    Archive,
    /// None of the formats.
    Nothing,
}

/// The format `path` is read in when no format is forced (module doc).
pub(super) fn format_of(path: &Path) -> Result<Format, ImportError> {
    let file = path.display().to_string();
    let mut head = Vec::new();
    std::fs::File::open(path)
        .and_then(|f| f.take(SNIFFED_BYTES).read_to_end(&mut head))
        .map_err(|source| ImportError::Io {
            file: file.clone(),
            source,
        })?;
    if head.iter().all(u8::is_ascii_whitespace) {
        // an empty file is no model of any format, whatever its extension says
        return Err(super::error::parse_err(&file, 1, "file", "empty file"));
    }
    let by_extension = Format::from_extension(path);
    let decisive = path.extension().and_then(|e| e.to_str()).is_some_and(|e| {
        matches!(
            e.to_ascii_lowercase().as_str(),
            "inp" | "bdf" | "nas" | "blk" | "bulk" | "msh" | "cdb" | "full"
        )
    });
    match content(&head) {
        Content::Archive => Err(ImportError::NotAModel {
            file,
            what: "a zip archive — a .flexbody file is flexbody's output, not a model: read it \
                   with `flexbody inspect` or `flexbody check` (build takes a model: .inp, .bdf, .cdb, .full, \
                   .msh; --format names its format)"
                .into(),
        }),
        // an archive without a mesh block (a CDWRITE of commands only) is still an archive
        Content::Nothing if by_extension == Some(Format::Ansys) => Ok(Format::Ansys),
        Content::Nothing => Err(ImportError::NotAModel {
            file,
            what: "it does not look like an Abaqus/CalculiX deck (no *KEYWORD line), a Nastran \
                   deck (no bulk data card, no BEGIN BULK), an ANSYS archive (no NBLOCK/EBLOCK) or a \
                   Gmsh mesh (no $MeshFormat)"
                .into(),
        }),
        Content::Model(found) => match by_extension {
            Some(named) if decisive && named != found => Err(ImportError::FormatMismatch {
                file,
                extension: name(named),
                content: name(found),
                option: option(found),
            }),
            _ => Ok(found),
        },
    }
}

/// A format's name in messages.
fn name(f: Format) -> &'static str {
    match f {
        Format::Abaqus => "Abaqus/CalculiX",
        Format::Nastran => "Nastran",
        Format::Gmsh => "Gmsh",
        Format::Ansys => "ANSYS",
        Format::AnsysFull => "ANSYS full file",
    }
}

/// The `--format` value of a format.
fn option(f: Format) -> &'static str {
    match f {
        Format::Abaqus => "inp",
        Format::Nastran => "bdf",
        Format::Gmsh => "msh",
        Format::Ansys => "cdb",
        Format::AnsysFull => "full",
    }
}

/// What the first bytes of a file look like: lines counted as Abaqus keywords or Nastran cards
/// and statements, the more frequent deciding.
fn content(head: &[u8]) -> Content {
    if head.starts_with(b"PK\x03\x04") {
        return Content::Archive;
    }
    // an ANSYS binary file: a 100-word standard header record whose file number (its third
    // word) is 4 for a full file
    if head.get(..4) == Some(&100i32.to_le_bytes()) && head.get(8..12) == Some(&4i32.to_le_bytes())
    {
        return Content::Model(Format::AnsysFull);
    }
    let text = String::from_utf8_lossy(head);
    let lines = text.lines().map(str::trim).filter(|l| !l.is_empty());
    if lines.clone().next() == Some("$MeshFormat") {
        return Content::Model(Format::Gmsh);
    }
    // an NBLOCK or EBLOCK header is an ANSYS archive's alone (its *SET and *IF lines would
    // otherwise count as Abaqus keywords)
    if lines.clone().any(super::ansys::is_block_header) {
        return Content::Model(Format::Ansys);
    }
    let (mut abaqus, mut nastran) = (0usize, 0usize);
    for line in lines {
        let bytes = line.as_bytes();
        if bytes[0] == b'*' {
            // a keyword is letters and blanks up to a comma (a Nastran large-field
            // continuation, `*N1  …` or `*  1.0`, is not)
            let keyword = line[1..].split(',').next().unwrap_or("").trim_end();
            if keyword.len() >= 3
                && bytes.get(1).is_some_and(u8::is_ascii_alphabetic)
                && keyword
                    .bytes()
                    .all(|b| b.is_ascii_alphabetic() || b == b' ')
            {
                abaqus += 1;
            }
            continue;
        }
        let word = line
            .split(|c: char| c.is_whitespace() || c == ',' || c == '*' || c == '=')
            .next()
            .unwrap_or("")
            .to_ascii_uppercase();
        let statement = matches!(word.as_str(), "CEND" | "SOL" | "ENDDATA")
            || line.to_ascii_uppercase().starts_with("BEGIN BULK");
        if statement || (word.len() >= 3 && super::nastran::is_card_name(&word)) {
            nastran += 1;
        }
    }
    match abaqus.cmp(&nastran) {
        _ if abaqus + nastran == 0 => Content::Nothing,
        std::cmp::Ordering::Greater => Content::Model(Format::Abaqus),
        std::cmp::Ordering::Less => Content::Model(Format::Nastran),
        std::cmp::Ordering::Equal => Content::Nothing,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn content_names_the_format() {
        let abaqus = b"** a deck\n*HEADING\nplate\n*NODE\n1, 0., 0., 0.\n*ELEMENT, TYPE=C3D8\n";
        assert_eq!(content(abaqus), Content::Model(Format::Abaqus));
        let nastran = b"SOL 103\nCEND\nBEGIN BULK\nGRID,1,,0.,0.,0.\nCQUAD4,1,1,1,2,3,4\n";
        assert_eq!(content(nastran), Content::Model(Format::Nastran));
        let bare = b"$ bulk\nGRID           1               0.      0.      0.\n";
        assert_eq!(content(bare), Content::Model(Format::Nastran));
        assert_eq!(
            content(b"$MeshFormat\n4.1 0 8\n"),
            Content::Model(Format::Gmsh)
        );
        assert_eq!(content(b"PK\x03\x04rest"), Content::Archive);
        let cdb =
            b"/PREP7\n*SET,_BUTTON ,  1.0\n*IF,_CDRDOFF,EQ,1,THEN\nET,1,186\nNBLOCK,6,SOLID,1,1\n";
        assert_eq!(content(cdb), Content::Model(Format::Ansys));
        let full = [100i32, i32::MIN, 4, -1].map(i32::to_le_bytes).concat();
        assert_eq!(content(&full), Content::Model(Format::AnsysFull));
        let readme = b"# My model\n\nRun it with the solver of your choice.\n";
        assert_eq!(content(readme), Content::Nothing);
    }
}
