//! The archive's lines as commands and blocks: a command is a comma-separated line
//! (`NAME,field,field,…`, a `!` comment stripped); a block command (`NBLOCK`, `EBLOCK`,
//! `CMBLOCK`, `RLBLOCK`, `CE,R5.0,DEFI`) is followed by a Fortran format line and fixed-width
//! records, read here by the widths the format line gives (as `CDWRITE` writes them; the
//! MAPDL Command Reference's `NBLOCK`/`EBLOCK`/`CMBLOCK`/`RLBLOCK` describe the records).

use crate::import::error::{parse_err, ImportError};
use crate::import::text::{bad_number, parse_f64};

/// One command line: its upper-case name and its fields after the name (trimmed).
#[derive(Debug, Clone)]
pub(super) struct Command<'a> {
    /// 1-based line.
    pub line: usize,
    /// Upper-case command name (`/COM`, `*SET`, `NBLOCK`, `D`, …).
    pub name: String,
    /// Fields after the name, trimmed (may be empty strings).
    pub fields: Vec<&'a str>,
}

impl Command<'_> {
    /// Field `i` (0-based after the name), trimmed; "" when absent.
    pub fn field(&self, i: usize) -> &str {
        self.fields.get(i).copied().unwrap_or("")
    }

    /// Field `i` as a real (blank = 0, as APDL reads a blank numeric field).
    pub fn real(&self, file: &str, i: usize) -> Result<f64, ImportError> {
        let s = self.field(i);
        if s.is_empty() {
            return Ok(0.0);
        }
        parse_f64(s).ok_or_else(|| parse_err(file, self.line, &self.name, bad_number(s)))
    }

    /// Field `i` as an integer (a real with no fraction is accepted, `2.` = 2; blank = 0).
    pub fn int(&self, file: &str, i: usize) -> Result<i64, ImportError> {
        let s = self.field(i);
        if s.is_empty() {
            return Ok(0);
        }
        int_of(s).ok_or_else(|| {
            parse_err(
                file,
                self.line,
                &self.name,
                format!("field {} '{s}' is not an integer", i + 2),
            )
        })
    }
}

/// Whether a command's first field marks CDWRITE's own form of the command: `R5.0`, `R5.3`…
/// in a blocked archive (the default), `UNBL` in an unblocked one (`CDWRITE,…,UNBLOCKED`);
/// e.g. `MPTEMP,R5.0,…` and `MPTEMP,UNBL,…` are the same record.
pub(super) fn archive_form(field: &str) -> bool {
    let f = field.trim();
    f.eq_ignore_ascii_case("UNBL")
        || (f.len() > 2 && f[..2].eq_ignore_ascii_case("R5") && f[2..].starts_with('.'))
}

/// An integer field, also written as a real without fraction.
fn int_of(s: &str) -> Option<i64> {
    let s = s.trim();
    s.parse::<i64>().ok().or_else(|| {
        let v = parse_f64(s)?;
        (v.fract() == 0.0 && v.abs() < 9.0e15).then_some(v as i64)
    })
}

/// The command of a line, or `None` for a blank or comment-only line.
pub(super) fn command(text: &str, line: usize) -> Option<Command<'_>> {
    let body = strip_comment(text).trim_end();
    if body.trim().is_empty() {
        return None;
    }
    let mut parts = body.split(',');
    let name = parts.next().unwrap_or("").trim().to_ascii_uppercase();
    let fields = parts.map(str::trim).collect();
    Some(Command { line, name, fields })
}

/// The line without its `!` comment (a `!` inside quotes is text).
fn strip_comment(text: &str) -> &str {
    let mut quoted = false;
    for (i, c) in text.char_indices() {
        match c {
            '\'' => quoted = !quoted,
            '!' if !quoted => return &text[..i],
            _ => {}
        }
    }
    text
}

/// The field widths of a Fortran format line such as `(3i9,6e21.13e3)`, `(19i10)`,
/// `(1i7,2i9,6e21.13)` (an archive written by Workbench: the node number narrower than the two
/// columns after it), `(2i9,19a9)` (`ETBLOCK`) or `(i9,a6,2(pg16.9))` (`DBLOCK`: text columns,
/// a scale factor `p`, a repeated group): every column's width, and how many integer columns
/// lead and how many real columns there are.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Layout {
    /// Integer columns before the first column of another kind.
    pub ints: usize,
    /// Real columns (e, g, f, d).
    pub reals: usize,
    /// Every column's width, in order.
    pub widths: Vec<usize>,
}

/// Read a format line (the line after a block command).
pub(super) fn layout(file: &str, line: usize, text: &str) -> Result<Layout, ImportError> {
    let bad = || {
        parse_err(
            file,
            line,
            "format",
            format!(
                "'{}' is not a block format such as (3i9,6e21.13e3)",
                text.trim()
            ),
        )
    };
    let t = text.trim();
    let inner = t
        .strip_prefix('(')
        .and_then(|s| s.strip_suffix(')'))
        .ok_or_else(bad)?;
    let mut kinds = Vec::new();
    format_items(&inner.to_ascii_lowercase(), &mut kinds, 0).ok_or_else(bad)?;
    if kinds.is_empty() || kinds.len() > 256 {
        return Err(bad());
    }
    Ok(Layout {
        ints: kinds.iter().take_while(|(k, _)| *k == 'i').count(),
        reals: kinds.iter().filter(|(k, _)| "egfd".contains(*k)).count(),
        widths: kinds.iter().map(|&(_, w)| w).collect(),
    })
}

/// The columns (kind, width) of a format's items, comma-separated, each `[n]kw[.d[eE]]`, `[n]ak`
/// or `n(items)`, an item's scale factor `p` skipped; `None` for anything else.
fn format_items(items: &str, out: &mut Vec<(char, usize)>, depth: usize) -> Option<()> {
    if depth > 2 {
        return None;
    }
    let mut rest = items.trim();
    while !rest.is_empty() {
        let digits = rest
            .find(|c: char| !c.is_ascii_digit())
            .unwrap_or(rest.len());
        let count: usize = if digits == 0 {
            1
        } else {
            rest[..digits].parse().ok()?
        };
        if count == 0 || count > 256 {
            return None;
        }
        let after = &rest[digits..];
        let (kinds, next) = if let Some(group) = after.strip_prefix('(') {
            let close = group.find(')')?;
            let mut inner = Vec::new();
            format_items(&group[..close], &mut inner, depth + 1)?;
            (inner, &group[close + 1..])
        } else {
            let end = after.find(',').unwrap_or(after.len());
            let item = after[..end].trim().trim_start_matches('p');
            let kind = item.chars().next()?;
            if !"iegfda".contains(kind) {
                return None;
            }
            let width: usize = item[1..].split('.').next()?.parse().ok()?;
            if width == 0 || width > 64 {
                return None;
            }
            (vec![(kind, width)], &after[end..])
        };
        for _ in 0..count {
            out.extend_from_slice(&kinds);
        }
        if out.len() > 256 {
            return None;
        }
        rest = next.trim_start().trim_start_matches(',').trim_start();
    }
    Some(())
}

/// The fixed-width fields of a record line: `ints` integer columns then `reals` real columns;
/// columns past the line's end are absent (`None`).
pub(super) fn columns<'a>(text: &'a str, lay: &Layout) -> Vec<Option<&'a str>> {
    let bytes = text.trim_end_matches(['\r', '\n']);
    let mut out = Vec::with_capacity(lay.widths.len());
    let mut at = 0;
    for &w in &lay.widths {
        let end = (at + w).min(bytes.len());
        let s = bytes.get(at..end).map(str::trim).filter(|s| !s.is_empty());
        out.push(s);
        at += w;
    }
    out
}

/// A block record: its 1-based line and its columns (`None` when blank or past the line's end).
pub(super) type Record<'a> = (usize, Vec<Option<&'a str>>);

/// An integer column (blank = 0).
pub(super) fn int_col(
    file: &str,
    line: usize,
    what: &str,
    col: Option<&str>,
) -> Result<i64, ImportError> {
    match col {
        None => Ok(0),
        Some(s) => {
            int_of(s).ok_or_else(|| parse_err(file, line, what, format!("'{s}' is not an integer")))
        }
    }
}

/// A real column (blank = 0).
pub(super) fn real_col(
    file: &str,
    line: usize,
    what: &str,
    col: Option<&str>,
) -> Result<f64, ImportError> {
    match col {
        None => Ok(0.0),
        Some(s) => parse_f64(s).ok_or_else(|| parse_err(file, line, what, bad_number(s))),
    }
}

/// One node record of an `NBLOCK`.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct NodeRecord {
    pub line: usize,
    pub id: u64,
    pub x: [f64; 3],
    /// The nodal coordinate system's rotation angles THXY, THYZ, THZX (degrees).
    pub angles: [f64; 3],
}

/// One element record of an `EBLOCK`.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct ElementRecord {
    pub line: usize,
    pub id: u64,
    pub mat: i64,
    pub etype: i64,
    pub real: i64,
    pub section: i64,
    pub esys: i64,
    /// The SOLID layout's field 8, the coded shape key (TARGE170's segment shape: 19 or 99
    /// `TSHAPE,PILO`, as ansys-mapdl-reader reads it); `None` in the contact layout.
    pub shape: Option<i64>,
    /// Node ids as written (0 = a dropped mid-side node).
    pub nodes: Vec<u64>,
}

/// The lines of the file, 1-based line numbers, with a cursor.
pub(super) struct Lines<'a> {
    lines: Vec<&'a str>,
    next: usize,
    pub file: String,
}

impl<'a> Lines<'a> {
    pub fn new(file: &str, text: &'a str) -> Lines<'a> {
        Lines {
            lines: text.lines().collect(),
            next: 0,
            file: file.to_owned(),
        }
    }

    /// The next line and its 1-based number.
    pub fn next_line(&mut self) -> Option<(usize, &'a str)> {
        let l = *self.lines.get(self.next)?;
        self.next += 1;
        Some((self.next, l))
    }

    /// Skip the lines after a command that are data, not commands (a format line `(…)` or
    /// numbers): the records of a command not read.
    pub fn skip_data_lines(&mut self) {
        while let Some(l) = self.lines.get(self.next) {
            let t = l.trim_start();
            let data = t.starts_with('(')
                || t.starts_with(|c: char| c.is_ascii_digit() || "+-.".contains(c));
            if !data {
                return;
            }
            self.next += 1;
        }
    }

    /// Skip an `SFEBLOCK`'s format line and records, and its end line `SFE,…,-1` when it
    /// follows them.
    pub fn skip_sfeblock(&mut self) {
        self.skip_data_lines();
        self.sfeblock_end();
    }

    /// An `SFEBLOCK`'s format line and records (each record's line and columns), up to its end
    /// line `SFE,…,-1` (read) or a `-1` line; a command line ends the records too, unread.
    pub fn sfeblock(&mut self, start: usize) -> Result<Vec<Record<'a>>, ImportError> {
        let lay = self.format(start, "SFEBLOCK")?;
        let mut out = Vec::new();
        while let Some(text) = self.lines.get(self.next).copied() {
            let t = text.trim();
            if t.starts_with("-1") {
                self.next += 1;
                return Ok(out);
            }
            if t.starts_with(|c: char| c.is_ascii_alphabetic() || c == '/' || c == '*') {
                break;
            }
            self.next += 1;
            if !t.is_empty() {
                out.push((self.next, columns(text, &lay)));
            }
        }
        self.sfeblock_end();
        Ok(out)
    }

    /// The end line `SFE,…,-1` of an `SFEBLOCK`, read when it is the next line.
    fn sfeblock_end(&mut self) {
        let end = self
            .lines
            .get(self.next)
            .and_then(|l| command(l, self.next + 1));
        if end.is_some_and(|c| c.name == "SFE" && c.fields.contains(&"-1")) {
            self.next += 1;
        }
    }

    /// A block's next record line (its number and text), or an error naming the block begun
    /// at `start` when the file ends.
    pub fn record(&mut self, start: usize, block: &str) -> Result<(usize, &'a str), ImportError> {
        self.required(start, block)
    }

    /// The next line, or an error: the block started at `start` ended early.
    fn required(&mut self, start: usize, block: &str) -> Result<(usize, &'a str), ImportError> {
        let file = self.file.clone();
        self.next_line().ok_or_else(|| {
            parse_err(
                &file,
                start,
                block,
                "the file ends inside the block (its records or its end line -1 are missing)",
            )
        })
    }

    /// The block's format line.
    fn format(&mut self, start: usize, block: &str) -> Result<Layout, ImportError> {
        let (n, text) = self.required(start, block)?;
        layout(&self.file, n, text)
    }

    /// A block's format line and its records up to the end line `-1`: each record's line and
    /// columns (`ETBLOCK`, `DBLOCK`).
    pub fn records(&mut self, start: usize, block: &str) -> Result<Vec<Record<'a>>, ImportError> {
        let lay = self.format(start, block)?;
        let mut out = Vec::new();
        loop {
            let (n, text) = self.required(start, block)?;
            let t = text.trim();
            if t.is_empty() {
                continue;
            }
            if t.starts_with("-1") {
                return Ok(out);
            }
            out.push((n, columns(text, &lay)));
        }
    }

    /// `NBLOCK,NUMFIELD,Solkey,…`: node records up to the end line (`-1` or `N,R5.3,LOC,-1`).
    pub fn nblock(&mut self, start: usize) -> Result<Vec<NodeRecord>, ImportError> {
        let lay = self.format(start, "NBLOCK")?;
        let mut out = Vec::new();
        loop {
            let (n, text) = self.required(start, "NBLOCK")?;
            let t = text.trim();
            if t.is_empty() {
                continue;
            }
            if t.starts_with('N') || t.starts_with('n') || t.starts_with("-1") {
                return Ok(out);
            }
            let cols = columns(text, &lay);
            let id = int_col(&self.file, n, "NBLOCK node", cols[0])?;
            if id <= 0 {
                return Err(parse_err(&self.file, n, "NBLOCK", format!("node id {id}")));
            }
            let mut reals = [0.0; 6];
            for (k, r) in reals.iter_mut().enumerate() {
                *r = real_col(
                    &self.file,
                    n,
                    &format!("NBLOCK node {id}"),
                    cols.get(lay.ints + k).copied().flatten(),
                )?;
            }
            out.push(NodeRecord {
                line: n,
                id: id as u64,
                x: [reals[0], reals[1], reals[2]],
                angles: [reals[3], reals[4], reals[5]],
            });
        }
    }

    /// `EBLOCK,NUM_NODES,Solkey,…`: element records up to the end line `-1`. `solid`: the
    /// SOLID layout (11 attribute fields, then nodes, continued on the next line past 8);
    /// otherwise the layout of contact/surface elements (element, type, real, material, esys,
    /// nodes).
    pub fn eblock(&mut self, start: usize, solid: bool) -> Result<Vec<ElementRecord>, ImportError> {
        let lay = self.format(start, "EBLOCK")?;
        let mut out = Vec::new();
        loop {
            let (n, text) = self.required(start, "EBLOCK")?;
            if text.trim().is_empty() {
                continue;
            }
            let cols = columns(text, &lay);
            let file = self.file.clone();
            let f = |k: usize| int_col(&file, n, "EBLOCK", cols.get(k).copied().flatten());
            if f(0)? == -1 {
                return Ok(out);
            }
            let record = if solid {
                let count = f(8)?;
                if !(1..=64).contains(&count) {
                    return Err(parse_err(
                        &self.file,
                        n,
                        "EBLOCK",
                        format!("field 9 (the number of nodes) is {count}"),
                    ));
                }
                let mut nodes = Vec::with_capacity(count as usize);
                for k in 11..lay.ints.min(11 + count as usize) {
                    nodes.push(f(k)?);
                }
                while nodes.len() < count as usize {
                    let (m, more) = self.required(start, "EBLOCK")?;
                    let cols = columns(more, &lay);
                    let want = count as usize - nodes.len();
                    for col in cols.iter().take(want.min(lay.ints)) {
                        nodes.push(int_col(&self.file, m, "EBLOCK", *col)?);
                    }
                }
                ElementRecord {
                    line: n,
                    id: f(10)?.max(0) as u64,
                    mat: f(0)?,
                    etype: f(1)?,
                    real: f(2)?,
                    section: f(3)?,
                    esys: f(4)?,
                    shape: Some(f(7)?),
                    nodes: nodes.into_iter().map(|v| v.max(0) as u64).collect(),
                }
            } else {
                let nodes = (5..lay.ints)
                    .filter_map(|k| cols.get(k).copied().flatten())
                    .map(|s| int_col(&self.file, n, "EBLOCK", Some(s)).map(|v| v.max(0) as u64))
                    .collect::<Result<Vec<_>, _>>()?;
                ElementRecord {
                    line: n,
                    id: f(0)?.max(0) as u64,
                    etype: f(1)?,
                    real: f(2)?,
                    mat: f(3)?,
                    section: 0,
                    esys: f(4)?,
                    shape: None,
                    nodes,
                }
            };
            if record.id == 0 {
                return Err(parse_err(&self.file, n, "EBLOCK", "element id 0"));
            }
            out.push(record);
        }
    }

    /// `CMBLOCK,Cname,Entity,NUMITEMS`: the items (a negative item −b after a makes the range
    /// a..b).
    pub fn cmblock(&mut self, start: usize, count: usize) -> Result<Vec<u64>, ImportError> {
        let lay = self.format(start, "CMBLOCK")?;
        let mut raw: Vec<i64> = Vec::with_capacity(count.min(1 << 20));
        while raw.len() < count {
            let (n, text) = self.required(start, "CMBLOCK")?;
            for col in columns(text, &lay).into_iter().flatten() {
                if raw.len() < count {
                    raw.push(int_col(&self.file, n, "CMBLOCK", Some(col))?);
                }
            }
        }
        let mut out: Vec<u64> = Vec::with_capacity(raw.len());
        for (k, &v) in raw.iter().enumerate() {
            match (v, out.last().copied()) {
                (v, Some(a)) if v < 0 && k > 0 => {
                    let b = v.unsigned_abs();
                    if b < a || b - a > crate::import::budget::expansion_limit(1 << 24) {
                        return Err(parse_err(
                            &self.file,
                            start,
                            "CMBLOCK",
                            format!("range {a} to {b} is not ascending or too long"),
                        ));
                    }
                    out.extend(a + 1..=b);
                }
                (v, _) if v > 0 => out.push(v as u64),
                (v, _) => {
                    return Err(parse_err(
                        &self.file,
                        start,
                        "CMBLOCK",
                        format!("item {v} is not an id"),
                    ))
                }
            }
        }
        Ok(out)
    }

    /// `RLBLOCK,NUMSETS,…`: each set's number and values (two format lines, then per set a line
    /// `set, count, up to 6 values` and continuation lines of 7).
    pub fn rlblock(
        &mut self,
        start: usize,
        sets: usize,
    ) -> Result<Vec<(i64, Vec<f64>)>, ImportError> {
        let first = self.format(start, "RLBLOCK")?;
        let next = self.format(start, "RLBLOCK")?;
        let mut out = Vec::new();
        for _ in 0..sets {
            let (n, text) = self.required(start, "RLBLOCK")?;
            let cols = columns(text, &first);
            let set = int_col(&self.file, n, "RLBLOCK", cols[0])?;
            let count = int_col(&self.file, n, "RLBLOCK", cols.get(1).copied().flatten())?;
            if !(0..=10_000).contains(&count) {
                return Err(parse_err(
                    &self.file,
                    n,
                    "RLBLOCK",
                    format!("{count} values"),
                ));
            }
            let mut values = Vec::new();
            let mut row = cols[first.ints..].to_vec();
            let mut at = n;
            while values.len() < count as usize {
                if row.is_empty() {
                    let (m, more) = self.required(start, "RLBLOCK")?;
                    row = columns(more, &next);
                    at = m;
                }
                let c = row.remove(0);
                values.push(real_col(&self.file, at, "RLBLOCK", c)?);
            }
            out.push((set, values));
        }
        Ok(out)
    }

    /// `CE,R5.0,DEFI,NTERM,NCE,CONST` followed by `CE,R5.0,NODE,n,lab,coef[,n,lab,coef]`
    /// lines: the terms (node id, dof label, coefficient).
    pub fn ce_terms(
        &mut self,
        start: usize,
        count: usize,
    ) -> Result<Vec<(u64, String, f64, usize)>, ImportError> {
        let mut out = Vec::new();
        while out.len() < count {
            let (n, text) = self.required(start, "CE")?;
            let c = command(text, n).ok_or_else(|| {
                parse_err(
                    &self.file,
                    n,
                    "CE",
                    "a blank line inside a constraint equation",
                )
            })?;
            if c.name != "CE" || !c.field(1).eq_ignore_ascii_case("NODE") {
                return Err(parse_err(
                    &self.file,
                    n,
                    &c.name,
                    format!(
                        "expected a CE,R5.0,NODE line of the constraint equation begun at \
                         line {start}"
                    ),
                ));
            }
            for k in (2..c.fields.len()).step_by(3) {
                if c.field(k).is_empty() || out.len() >= count {
                    continue;
                }
                let node = c.int(&self.file, k)?;
                if node <= 0 {
                    return Err(parse_err(&self.file, n, "CE", format!("node {node}")));
                }
                out.push((
                    node as u64,
                    c.field(k + 1).to_ascii_uppercase(),
                    c.real(&self.file, k + 2)?,
                    n,
                ));
            }
        }
        Ok(out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn format_lines_give_the_widths() {
        let l = layout("f", 1, "(3i9,6e21.13e3)").unwrap();
        assert_eq!((l.ints, l.reals), (3, 6));
        assert_eq!(l.widths, [9, 9, 9, 21, 21, 21, 21, 21, 21]);
        let l = layout("f", 1, "(19i10)").unwrap();
        assert_eq!((l.ints, l.reals, l.widths.clone()), (19, 0, vec![10; 19]));
        // Workbench 2019 R1 (ansys-mapdl-reader's workbench_193.cdb): the node number in 7
        let l = layout("f", 1, "(1i7,2i9,6e21.13)").unwrap();
        assert_eq!(l.widths[..4], [7, 9, 9, 21]);
        let line = " 219712        0        0  9.8936757830530E-02 -8.0709219224048E-04";
        let c = columns(line, &l);
        assert_eq!(
            (c[0], c[3], c[4]),
            (
                Some("219712"),
                Some("9.8936757830530E-02"),
                Some("-8.0709219224048E-04")
            )
        );
        // ETBLOCK and DBLOCK (CDWRITE of MAPDL 2022 and later)
        let l = layout("f", 1, "(2i9,19a9)").unwrap();
        assert_eq!((l.ints, l.reals, l.widths.len()), (2, 0, 21));
        let l = layout("f", 1, "(i9,a6,2(pg16.9))").unwrap();
        assert_eq!(
            (l.ints, l.reals, l.widths.clone()),
            (1, 2, vec![9, 6, 16, 16])
        );
        let c = columns("        1  UZ    0.00000000      0.00000000    ", &l);
        assert_eq!(
            (c[0], c[1], c[2]),
            (Some("1"), Some("UZ"), Some("0.00000000"))
        );
        assert!(layout("f", 1, "(2(3(4(i9))))").is_err());
        assert!(layout("f", 1, "(0i9)").is_err());
        assert!(layout("f", 1, "3i9").is_err());
    }

    #[test]
    fn columns_split_touching_numbers() {
        let l = layout("f", 1, "(3i8,6e20.13)").unwrap();
        let line =
            "    1041      14       0 5.9375753402710E+00 7.6067792251706E-03-2.5005263090134E-01";
        let c = columns(line, &l);
        assert_eq!(c[0], Some("1041"));
        assert_eq!(c[5], Some("-2.5005263090134E-01"));
        assert_eq!(c[6], None);
    }

    #[test]
    fn comments_and_fields() {
        let c = command("CMBLOCK,NCOMP2  ,NODE,      42  ! users node component", 7).unwrap();
        assert_eq!(
            (c.name.as_str(), c.field(0), c.field(2)),
            ("CMBLOCK", "NCOMP2", "42")
        );
        assert!(command("   ! only a comment", 1).is_none());
    }
}
