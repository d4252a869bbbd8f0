//! Nastran bulk-data lexer: turns the text of a deck into cards (name + data fields with the line
//! of every field), handling small field (8 columns), large field (`NAME*`, 16 columns), free
//! field (commas), explicit (`+`, `*`) and implicit (blank first field) continuations, `$`
//! comments, `BEGIN BULK` / `ENDDATA` and `INCLUDE`.

use std::path::Path;

use crate::import::error::ImportError;
use crate::import::text::{read_text, Loc};

/// One data field: its text (trimmed) and the line it is on.
#[derive(Debug, Clone)]
pub(crate) struct Field {
    pub text: String,
    pub line: u32,
}

/// A bulk-data card.
#[derive(Debug, Clone)]
pub(crate) struct Card {
    /// Upper-case name without the large-field `*` (e.g. `GRID`).
    pub name: String,
    /// Data fields in order (Nastran fields 2–9 of the first line, then 2–9 of each continuation).
    pub fields: Vec<Field>,
    /// First line of the card.
    pub loc: Loc,
}

/// Expand tabs to 8-column stops (Nastran small-field convention).
fn expand_tabs(line: &str) -> String {
    let mut out = String::with_capacity(line.len() + 16);
    for c in line.chars() {
        if c == '\t' {
            let n = 8 - out.len() % 8;
            out.extend(std::iter::repeat_n(' ', n));
        } else {
            out.push(c);
        }
    }
    out
}

/// Fixed-width fields of `s` starting at column `start`, `n` fields of `w` columns.
fn fixed_fields(s: &str, start: usize, w: usize, n: usize, line: u32, out: &mut Vec<Field>) {
    for k in 0..n {
        let a = start + k * w;
        let b = (a + w).min(s.len());
        let text = if a < s.len() {
            s.get(a..b).unwrap_or("").trim()
        } else {
            ""
        };
        out.push(Field {
            text: text.to_owned(),
            line,
        });
    }
}

/// Lexer state across files.
pub(crate) struct Lexer {
    pub files: Vec<String>,
    pub cards: Vec<Card>,
    /// Lines of the main file before `BEGIN BULK` (executive and case control), comments
    /// stripped, with files named by `INCLUDE` there read in place.
    pub case_lines: Vec<(String, Loc)>,
    /// The main file has a `BEGIN BULK` line (so it is a whole deck, not bare bulk data).
    pub has_case_control: bool,
    /// Bytes of all files lexed (the input budget's base, see `import::budget`).
    pub bytes: u64,
}

impl Lexer {
    pub(crate) fn new(main: &str) -> Lexer {
        Lexer {
            files: vec![main.to_owned()],
            cards: Vec::new(),
            case_lines: Vec::new(),
            has_case_control: false,
            bytes: 0,
        }
    }

    fn err(&self, loc: Loc, entity: &str, msg: String) -> ImportError {
        crate::import::error::parse_err(
            &self.files[loc.file as usize],
            loc.line as usize,
            entity,
            msg,
        )
    }

    /// The file `INCLUDE 'name'` in `including` names: a relative name from the including
    /// file's folder or, when no such file exists there, from the main deck's folder (MSC
    /// resolves a relative INCLUDE from the job's folder, so nested includes written for it —
    /// pyNastran's models/Satellite_V02 — name files from there).
    fn include_path(&self, including: &Path, name: &str) -> std::path::PathBuf {
        let own = including.parent().unwrap_or(Path::new(".")).join(name);
        if own.exists() {
            return own;
        }
        let main = Path::new(&self.files[0]).parent().unwrap_or(Path::new("."));
        let from_main = main.join(name);
        if from_main.exists() {
            from_main
        } else {
            own
        }
    }

    /// `INCLUDE 'file'` in the executive or case control: the file's lines are case control.
    fn case_include(
        &mut self,
        parent: &Path,
        t: &str,
        loc: Loc,
        depth: usize,
    ) -> Result<(), ImportError> {
        let name = t[7..].trim().trim_matches('\'').trim_matches('"').trim();
        if name.is_empty() {
            return Err(self.err(loc, "INCLUDE", "missing file name".into()));
        }
        if depth >= 16 {
            return Err(self.err(
                loc,
                "INCLUDE",
                "includes nested deeper than 16 (cycle?)".into(),
            ));
        }
        let full = self.include_path(parent, name);
        let text = read_text(&full).map_err(|e| match e {
            ImportError::Io { file, source } => {
                self.err(loc, "INCLUDE", format!("cannot read {file}: {source}"))
            }
            e => e,
        })?;
        self.files.push(full.display().to_string());
        let file = self.files.len() as u32 - 1;
        for (i, raw) in text.lines().enumerate() {
            let line = raw.split('$').next().unwrap_or("");
            let sub = Loc {
                file,
                line: i as u32 + 1,
            };
            let t = line.trim_start();
            if t.get(..7)
                .is_some_and(|h| h.eq_ignore_ascii_case("INCLUDE"))
            {
                self.case_include(&full, t, sub, depth + 1)?;
            } else if !t.is_empty() {
                self.case_lines.push((line.trim_end().to_owned(), sub));
            }
        }
        Ok(())
    }

    /// Lex `path` (file index `file`). In the main file, text before `BEGIN BULK` is skipped
    /// when such a line exists. Returns true when `ENDDATA` was met.
    pub(crate) fn lex_file(
        &mut self,
        path: &Path,
        file: u32,
        depth: usize,
    ) -> Result<bool, ImportError> {
        let text = read_text(path)?;
        self.bytes += text.len() as u64;
        let upper_starts =
            |l: &str, p: &str| l.get(..p.len()).is_some_and(|h| h.eq_ignore_ascii_case(p));
        let mut in_bulk = depth > 0
            || !text.lines().any(|l| {
                upper_starts(l.trim_start(), "BEGIN BULK")
                    || upper_starts(l.trim_start(), "BEGIN SUPER")
            });
        if depth == 0 && !in_bulk {
            self.has_case_control = true;
        }
        let lines: Vec<&str> = text.split('\n').collect();
        let mut i = 0;
        while i < lines.len() {
            let lineno = i as u32 + 1;
            let loc = Loc { file, line: lineno };
            let raw = lines[i].strip_suffix('\r').unwrap_or(lines[i]);
            i += 1;
            let owned;
            let mut line = raw;
            if line.contains('\t') {
                owned = expand_tabs(line);
                line = &owned;
            }
            let line = match line.find('$') {
                Some(p) => &line[..p],
                None => line,
            };
            if line.trim().is_empty() {
                continue;
            }
            let t = line.trim_start();
            if in_bulk && !line.is_ascii() {
                return Err(self.err(loc, "card", "non-ASCII character in bulk data".into()));
            }
            if !in_bulk {
                if upper_starts(t, "BEGIN BULK") || upper_starts(t, "BEGIN SUPER") {
                    in_bulk = true;
                } else if upper_starts(t, "INCLUDE") {
                    self.case_include(path, t, loc, 0)?;
                } else {
                    self.case_lines.push((line.trim_end().to_owned(), loc));
                }
                continue;
            }
            if upper_starts(t, "ENDDATA") {
                return Ok(true);
            }
            if upper_starts(t, "INCLUDE") && !line.starts_with(' ') {
                // INCLUDE 'file' — the quoted name may continue on following lines.
                let mut spec = t[7..].trim().to_owned();
                while spec.starts_with('\'') && spec.matches('\'').count() < 2 && i < lines.len() {
                    spec.push_str(lines[i].trim());
                    i += 1;
                }
                let name = spec.trim().trim_matches('\'').trim_matches('"').trim();
                if name.is_empty() {
                    return Err(self.err(loc, "INCLUDE", "missing file name".into()));
                }
                if depth >= 16 {
                    return Err(self.err(
                        loc,
                        "INCLUDE",
                        "includes nested deeper than 16 (cycle?)".into(),
                    ));
                }
                let full = self.include_path(path, name);
                self.files.push(full.display().to_string());
                let idx = self.files.len() as u32 - 1;
                let ended = self.lex_file(&full, idx, depth + 1).map_err(|e| match e {
                    ImportError::Io { file, source } => {
                        self.err(loc, "INCLUDE", format!("cannot read {file}: {source}"))
                    }
                    e => e,
                })?;
                if ended {
                    return Ok(true);
                }
                continue;
            }
            let first = line.as_bytes()[0];
            // a free-field continuation may also start with blanks before its comma
            // ("       , 0., 0.02, …", as MSC's own test decks write TABDMP1 and DLOAD)
            let is_cont = matches!(first, b'+' | b'*' | b',')
                || line[..line.len().min(8)].trim().is_empty()
                || line.trim_start().starts_with(',');
            if is_cont {
                let Some(card) = self.cards.last_mut().filter(|c| c.loc.file == file) else {
                    return Err(self.err(
                        loc,
                        "card",
                        "continuation line without a parent card".into(),
                    ));
                };
                // Pad the previous line(s) to a full set of data fields (4 per large-field line).
                let unit = if first == b'*' { 4 } else { 8 };
                let n = card.fields.len().div_ceil(unit).max(1) * unit;
                let last_line = card.fields.last().map_or(lineno, |f| f.line);
                card.fields.resize(
                    n,
                    Field {
                        text: String::new(),
                        line: last_line,
                    },
                );
                if line.contains(',') {
                    for f in line.split(',').skip(1).take(8) {
                        card.fields.push(Field {
                            text: f.trim().to_owned(),
                            line: lineno,
                        });
                    }
                } else if first == b'*' {
                    fixed_fields(line, 8, 16, 4, lineno, &mut card.fields);
                } else {
                    fixed_fields(line, 8, 8, 8, lineno, &mut card.fields);
                }
                continue;
            }
            // A new card.
            let (name, fields) = if line[..line.len().min(10)].contains(',') {
                let mut it = line.split(',');
                let name = it.next().unwrap_or("").trim().to_owned();
                let fields = it
                    .take(8)
                    .map(|f| Field {
                        text: f.trim().to_owned(),
                        line: lineno,
                    })
                    .collect();
                (name, fields)
            } else {
                let name = line[..line.len().min(8)].trim().to_owned();
                let mut fields = Vec::with_capacity(8);
                if name.ends_with('*') {
                    fixed_fields(line, 8, 16, 4, lineno, &mut fields);
                } else {
                    fixed_fields(line, 8, 8, 8, lineno, &mut fields);
                }
                (name, fields)
            };
            let name = name.trim_end_matches('*').to_ascii_uppercase();
            self.cards.push(Card { name, fields, loc });
        }
        Ok(false)
    }
}
