//! Nastran case control: the part of a deck between `CEND` and `BEGIN BULK` that says which
//! bulk-data sets a run uses. Read here: `TITLE`, `SUBCASE`, `SPC`, `MPC`, `METHOD`, `LOAD`,
//! `STATSUB(PRELOAD)`, `TEMP(LOAD)`, `K2GG` and `M2GG` (global, i.e. above the first subcase,
//! or inside a subcase, which overrides the global value). What every other command is — a
//! refusal (`K2PP`, `M2PP`, …; and `STATSUB(BUCKLE)` here), a note (`B2GG`, `B2PP`, `P2G`, …;
//! output and solution control go unsaid) — is the catalogue's (`cards::commands`).
//!
//! `K2GG = KAX`, `K2GG = 2.0*KAX, KBX` (MSC QRG "K2GG"): the DMIG matrices added to the g-set
//! stiffness, each times its factor (default 1); `M2GG` alike for the mass (module `dmig`).
//!
//! `STATSUB(PRELOAD) = n` in the modes' subcase (MSC QRG "STATSUB"; SOL 103 with differential
//! stiffness) names static subcase n, whose `LOAD` and `TEMP(LOAD)` (module `temperature`) are
//! the preload of the modes: that subcase is a load case, not an analysis of its own, so it
//! takes no part in the rule below; its `SPC` must be the modes' (the preload is solved on the
//! modes' supports).
//!
//! Nastran's rule (MSC QRG, "Case Control Commands"): a bulk-data SPC set is applied only when
//! `SPC = n` selects it; no `SPC` command means no SPC set; `MPC = n` alike for MPC sets. A deck
//! whose subcases select different constraint or eigenvalue sets describes several analyses;
//! the build needs one.

use super::cards::{Category, Rule, NOT_READ};
use crate::import::error::{parse_err, ImportError};

/// Reason of the refusal of a buckling preload.
const BUCKLE: &str =
    "a buckling preload (SOL 105): flexbody reduces normal modes; use STATSUB(PRELOAD)";
use crate::import::text::Loc;

/// A `NAME = n` selection and where it was written.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Select {
    pub id: u64,
    pub loc: Loc,
}

impl Select {
    /// The error of a selection the bulk data does not define: `command = id` selects `what`,
    /// which none of `cards` defines.
    pub(crate) fn undefined(
        &self,
        files: &[String],
        command: &str,
        what: &str,
        cards: &str,
    ) -> ImportError {
        parse_err(
            &files[self.loc.file as usize],
            self.loc.line as usize,
            format!("{command} = {}", self.id),
            format!(
                "the case control selects {what} {}, but the bulk data has no {cards} with that id",
                self.id
            ),
        )
    }
}

/// The selections of one scope (the global part or one subcase).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub(crate) struct Scope {
    pub spc: Option<Select>,
    pub mpc: Option<Select>,
    pub method: Option<Select>,
    pub load: Option<Select>,
    /// `STATSUB(PRELOAD) = n`: the static subcase preloading these modes.
    pub statsub: Option<Select>,
    /// `TEMP(LOAD) = n` (or `TEMP(BOTH)`, `TEMP = n`): a thermal load set.
    pub temp_load: Option<Select>,
}

/// One `SUBCASE n` block.
#[derive(Debug, Clone)]
pub(crate) struct Subcase {
    pub id: u64,
    pub loc: Loc,
    pub scope: Scope,
}

/// `K2GG = …` or `M2GG = …`: DMIG matrices added to the g-set stiffness or mass.
#[derive(Debug, Clone)]
pub(crate) struct MatrixSelection {
    /// `M2GG` (mass), else `K2GG` (stiffness).
    pub mass: bool,
    /// (factor, DMIG name), in the command's order.
    pub terms: Vec<(f64, String)>,
    /// The subcase it is written in (`None`: above the first subcase).
    pub subcase: Option<u64>,
    pub loc: Loc,
}

/// The parsed case control.
#[derive(Debug, Clone, Default)]
pub(crate) struct CaseControl {
    /// The deck has a case control section (a `BEGIN BULK` line); bare bulk data has none.
    pub present: bool,
    pub title: Option<String>,
    pub global: Scope,
    pub subcases: Vec<Subcase>,
    /// Commands that change the body and are not modelled: (command, why, where).
    pub refused: Vec<(String, &'static str, Loc)>,
    /// Commands that cannot change the body: (command, why, where).
    pub noted: Vec<(String, &'static str, Loc)>,
    /// `K2GG` and `M2GG` commands, in deck order.
    pub matrices: Vec<MatrixSelection>,
    /// The executive control's `SOL` (its value, upper case, and where).
    pub sol: Option<(String, Loc)>,
}

/// Executive control statements (before `CEND`; also skipped in a deck without `CEND`).
const EXECUTIVE: &[&str] = &[
    "ALTER",
    "APP",
    "ASSIGN",
    "CEND",
    "CHKPNT",
    "COMPILE",
    "COMPILER",
    "DIAG",
    "DOMAINSOLVER",
    "ECHOOFF",
    "ECHOON",
    "ENDALTER",
    "ENDJOB",
    "EXPAND",
    "GEOMCHECK",
    "ID",
    "INCLUDE",
    "INIT",
    "LINK",
    "MALTER",
    "MDLPRM",
    "NASTRAN",
    "RESTART",
    "SOL",
    "TIME",
];

/// Reason of the refusal of a PARAM the bulk data would honour, given in the case control.
const PARAM_IN_CASE: &str = "a PARAM that changes the body, given in the case control: this \
                             importer reads it in the bulk data; move it there";

/// A case control `PARAM,NAME,value` line: a PARAM that is a note passes; one that the bulk
/// data honours or refuses, or no table names, is refused (command, why, where).
fn case_param(upper: &str, loc: Loc) -> Option<(String, &'static str, Loc)> {
    let name = upper[5..]
        .trim_start_matches([' ', ',', '='])
        .split([',', ' '])
        .next()
        .unwrap_or("");
    let key = format!("PARAM:{name}");
    match super::cards::param(name) {
        Some((_, _, Rule::Note | Rule::NoteWhy(_))) => None,
        Some((_, _, Rule::Refuse(why))) => Some((key, why, loc)),
        Some((_, _, Rule::Read(_))) => Some((key, PARAM_IN_CASE, loc)),
        _ => Some((key, NOT_READ, loc)),
    }
}

/// The first word of a command line, upper case: up to a blank, `=`, `(` or `,`.
fn first_word(upper: &str) -> &str {
    upper
        .split(|c: char| c.is_whitespace() || c == '=' || c == '(' || c == ',')
        .next()
        .unwrap_or("")
}

/// The selections the build uses: of the one (or the chosen) subcase, global values filled in.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct Effective {
    pub subcase: Option<u64>,
    pub scope: Scope,
    /// The static subcase `STATSUB(PRELOAD)` names: its id, where it starts, its selections.
    pub preload: Option<(u64, Loc, Scope)>,
}

fn err(files: &[String], loc: Loc, entity: &str, msg: String) -> ImportError {
    parse_err(&files[loc.file as usize], loc.line as usize, entity, msg)
}

/// Parse the lines before `BEGIN BULK` (executive control up to `CEND`, then case control).
pub(crate) fn parse(
    lines: &[(String, Loc)],
    present: bool,
    files: &[String],
) -> Result<CaseControl, ImportError> {
    let mut cc = CaseControl {
        present,
        ..Default::default()
    };
    let start = lines
        .iter()
        .position(|(l, _)| l.trim().eq_ignore_ascii_case("CEND"))
        .map_or(0, |k| k + 1);
    // the SOL statement: before CEND, or anywhere in a deck without CEND
    let executive = if start > 0 { &lines[..start] } else { lines };
    for (l, loc) in executive {
        let upper = l.trim().to_ascii_uppercase();
        if first_word(&upper) == "SOL" {
            cc.sol = Some((
                upper[3..].trim().trim_start_matches(',').trim().to_owned(),
                *loc,
            ));
        }
    }
    // Logical lines: a trailing comma continues a command on the next line.
    let mut logical: Vec<(String, Loc)> = Vec::new();
    let mut open = false;
    for (l, loc) in &lines[start..] {
        let t = l.trim();
        if t.is_empty() {
            continue;
        }
        match logical.last_mut() {
            Some(last) if open => last.0.push_str(t),
            _ => logical.push((t.to_owned(), *loc)),
        }
        open = t.ends_with(',');
    }
    let mut current: Option<usize> = None;
    for (text, loc) in logical {
        let upper = text.to_ascii_uppercase();
        let word = first_word(&upper);
        if EXECUTIVE.contains(&word) {
            continue;
        }
        // the plotter's and XY-plotter's commands follow OUTPUT(PLOT), OUTPUT(XYPLOT), …
        if word == "OUTPUT" && (upper.contains("PLOT") || upper.contains("XY")) {
            break;
        }
        if word == "PARAM" {
            if let Some(refusal) = case_param(&upper, loc) {
                cc.refused.push(refusal);
            }
            continue;
        }
        match super::cards::command(word) {
            Some((_, _, Rule::Command)) => {}
            Some((name, category, rule @ (Rule::Note | Rule::NoteWhy(_)))) => {
                // output and solution control go unsaid; the others would act in another
                // analysis (damping, loads, response): a note each
                if !matches!(category, Category::Output | Category::Solution) {
                    let why = match rule {
                        Rule::NoteWhy(why) => why,
                        _ => category.why(),
                    };
                    cc.noted.push(((*name).to_owned(), why, loc));
                }
            }
            Some((name, _, Rule::Refuse(why))) => {
                cc.refused.push(((*name).to_owned(), why, loc));
                continue;
            }
            Some((_, _, Rule::Geometry | Rule::Read(_))) | None => {
                cc.refused.push((word.to_owned(), NOT_READ, loc));
                continue;
            }
        }
        if word == "SUBCASE" {
            // `SUBCASE n`, also written `SUBCASE = n` (ZONA's and other decks; pyNastran reads it)
            let id = upper[7..]
                .trim()
                .trim_start_matches('=')
                .trim()
                .parse::<u64>()
                .map_err(|_| err(files, loc, "SUBCASE", format!("bad subcase id in '{text}'")))?;
            if let Some(prev) = cc.subcases.iter().find(|s| s.id == id) {
                return Err(err(
                    files,
                    loc,
                    &format!("SUBCASE {id}"),
                    format!(
                        "subcase {id} defined twice (also on line {})",
                        prev.loc.line
                    ),
                ));
            }
            cc.subcases.push(Subcase {
                id,
                loc,
                scope: Scope::default(),
            });
            current = Some(cc.subcases.len() - 1);
            continue;
        }
        let Some((key, value)) = text.split_once('=') else {
            continue;
        };
        let value = value.trim();
        if word == "TITLE" && current.is_none() {
            cc.title = Some(value.to_owned());
            continue;
        }
        let describer: String = (key.chars())
            .filter(|c| !c.is_whitespace())
            .collect::<String>()
            .to_ascii_uppercase();
        if word == "STATSUB" && describer.contains("BUCKLE") {
            // a refused STATSUB still names its static subcase: not an analysis of its own
            cc.refused.push(("STATSUB(BUCKLE)".to_owned(), BUCKLE, loc));
        }
        if matches!(word, "K2GG" | "M2GG") {
            let terms = matrix_terms(value).ok_or_else(|| {
                err(
                    files,
                    loc,
                    word,
                    format!("{word} = '{value}': expected DMIG names, each with an optional factor (2.0*KAX, KBX)"),
                )
            })?;
            cc.matrices.push(MatrixSelection {
                mass: word == "M2GG",
                terms,
                subcase: current.map(|k| cc.subcases[k].id),
                loc,
            });
            continue;
        }
        let slot = match word {
            "SPC" => 0,
            "METHOD" | "METH" if !describer.contains("FLUID") => 1,
            "LOAD" => 2,
            "MPC" => 3,
            "STATSUB" => 4,
            // TEMP(INIT)/TEMP(MATERIAL) set material temperatures (refused elsewhere when a
            // material depends on them); TEMP(LOAD), TEMP(BOTH) and TEMP = n also load
            "TEMP" | "TEMPERATURE" if !describer.contains("INIT") && !describer.contains("MAT") => {
                5
            }
            _ => continue,
        };
        let id = value.parse::<u64>().map_err(|_| {
            err(
                files,
                loc,
                word,
                format!("{word} = '{value}': expected a set id (a positive integer)"),
            )
        })?;
        let scope = match current {
            Some(k) => &mut cc.subcases[k].scope,
            None => &mut cc.global,
        };
        let s = Some(Select { id, loc });
        match slot {
            0 => scope.spc = s,
            1 => scope.method = s,
            2 => scope.load = s,
            3 => scope.mpc = s,
            4 => scope.statsub = s,
            _ => scope.temp_load = s,
        }
    }
    Ok(cc)
}

/// The terms of a `K2GG`/`M2GG` value: `NAME`, `s*NAME`, comma-separated, optionally in
/// parentheses; `None` when a term is not of that form.
fn matrix_terms(value: &str) -> Option<Vec<(f64, String)>> {
    let inner = value.trim();
    let inner = inner
        .strip_prefix('(')
        .and_then(|v| v.strip_suffix(')'))
        .unwrap_or(inner);
    let name_ok = |n: &str| {
        n.chars().next().is_some_and(|c| c.is_ascii_alphabetic())
            && n.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
    };
    inner
        .split(',')
        .map(|t| {
            let t = t.trim();
            let (factor, name) = match t.split_once('*') {
                Some((f, n)) => (super::fields::nastran_real(f.trim())?, n.trim()),
                None => (1.0, t),
            };
            (name_ok(name) && factor.is_finite()).then(|| (factor, name.to_ascii_uppercase()))
        })
        .collect()
}

impl CaseControl {
    /// The `K2GG` and `M2GG` that apply to subcase `subcase`: its own, else the global one
    /// (the last of a scope, for each of the two).
    pub(crate) fn matrix_selections(&self, subcase: Option<u64>) -> Vec<&MatrixSelection> {
        [false, true]
            .into_iter()
            .filter_map(|mass| {
                let of = |scope: Option<u64>| {
                    (self.matrices.iter())
                        .rev()
                        .find(|m| m.mass == mass && m.subcase == scope)
                };
                subcase.and_then(|s| of(Some(s))).or_else(|| of(None))
            })
            .collect()
    }

    /// The selections of subcase `k` with the global ones filled in.
    fn scope_of(&self, k: usize) -> Scope {
        let s = self.subcases[k].scope;
        Scope {
            spc: s.spc.or(self.global.spc),
            mpc: s.mpc.or(self.global.mpc),
            method: s.method.or(self.global.method),
            load: s.load.or(self.global.load),
            statsub: s.statsub.or(self.global.statsub),
            temp_load: s.temp_load.or(self.global.temp_load),
        }
    }

    /// The load sets the case control applies (`LOAD = n`): of subcase `choice`, or of every
    /// subcase (each subcase is a load case of the scene; loads may differ between subcases).
    pub(crate) fn load_selections(&self, choice: Option<u64>) -> Vec<Select> {
        let mut out: Vec<Select> = Vec::new();
        if self.subcases.is_empty() {
            out.extend(self.global.load);
        } else {
            for (k, s) in self.subcases.iter().enumerate() {
                if choice.is_none_or(|c| c == s.id) {
                    if let Some(l) = self.scope_of(k).load {
                        if !out.iter().any(|o| o.id == l.id) {
                            out.push(l);
                        }
                    }
                }
            }
        }
        out
    }

    /// The selections the build uses. `choice` picks a subcase; without it every subcase must
    /// select the same SPC and METHOD sets — except the static subcases a `STATSUB(PRELOAD)`
    /// names, which are the preload of the others (module doc).
    pub(crate) fn effective(
        &self,
        choice: Option<u64>,
        files: &[String],
        main_file: &str,
    ) -> Result<Effective, ImportError> {
        let (subcase, k) = self.chosen(choice, files, main_file)?;
        let scope = match k {
            Some(k) => self.scope_of(k),
            None => self.global,
        };
        // a refused STATSUB(BUCKLE) is reported with the refused cards (or dropped on purpose)
        let preload = if self.refused.iter().any(|r| r.0.starts_with("STATSUB")) {
            None
        } else {
            self.preload_of(k, scope, files)?
        };
        Ok(Effective {
            subcase,
            scope,
            preload,
        })
    }

    /// The ids of the subcases another subcase's `STATSUB(PRELOAD)` names.
    fn static_subcases(&self) -> Vec<u64> {
        (0..self.subcases.len())
            .filter_map(|k| self.scope_of(k).statsub.map(|s| s.id))
            .filter(|&id| self.subcases.iter().any(|s| s.id == id))
            .collect()
    }

    /// The subcase the build uses (its id when the deck names one, and its index; `None`: the
    /// global scope).
    fn chosen(
        &self,
        choice: Option<u64>,
        files: &[String],
        main_file: &str,
    ) -> Result<(Option<u64>, Option<usize>), ImportError> {
        let show = |s: Option<Select>| s.map_or("none".to_owned(), |s| s.id.to_string());
        let mpc = |s: Scope| s.mpc.map_or(String::new(), |m| format!(", MPC = {}", m.id));
        if let Some(n) = choice {
            if self.subcases.is_empty() {
                if n == 1 {
                    return Ok((None, None));
                }
                return Err(parse_err(
                    main_file,
                    1,
                    "SUBCASE",
                    format!("subcase {n} asked for, but the deck has no SUBCASE (its one case is subcase 1)"),
                ));
            }
            let k = self
                .subcases
                .iter()
                .position(|s| s.id == n)
                .ok_or_else(|| {
                    let ids: Vec<String> = self.subcases.iter().map(|s| s.id.to_string()).collect();
                    parse_err(
                        main_file,
                        self.subcases[0].loc.line as usize,
                        "SUBCASE",
                        format!(
                            "subcase {n} asked for, but the deck has subcases {}",
                            ids.join(", ")
                        ),
                    )
                })?;
            return Ok((Some(n), Some(k)));
        }
        let statics = self.static_subcases();
        let analyses: Vec<usize> = (0..self.subcases.len())
            .filter(|&k| !statics.contains(&self.subcases[k].id))
            .collect();
        let Some(&k0) = analyses.first() else {
            return Ok((None, None));
        };
        let (first, s0) = (&self.subcases[k0], self.scope_of(k0));
        for &k in &analyses[1..] {
            let (sc, s) = (&self.subcases[k], self.scope_of(k));
            let ids = |s: Scope| {
                (
                    s.spc.map(|x| x.id),
                    s.method.map(|x| x.id),
                    s.mpc.map(|x| x.id),
                    s.statsub.map(|x| x.id),
                )
            };
            if ids(s) != ids(s0) {
                return Err(err(
                    files,
                    sc.loc,
                    &format!("SUBCASE {}", sc.id),
                    format!(
                        "subcases {} (SPC = {}, METHOD = {}{}) and {} (SPC = {}, METHOD = {}{}) describe different analyses; pick one with --subcase {} or --subcase {}",
                        first.id,
                        show(s0.spc),
                        show(s0.method),
                        mpc(s0),
                        sc.id,
                        show(s.spc),
                        show(s.method),
                        mpc(s),
                        first.id,
                        sc.id
                    ),
                ));
            }
        }
        let one = analyses.len() == 1;
        Ok((one.then_some(first.id), Some(k0)))
    }

    /// The static subcase `scope`'s `STATSUB(PRELOAD)` names, checked: it exists, is not the
    /// modes' own subcase (`k`), selects a LOAD or a TEMP(LOAD) and holds the body as the modes'
    /// subcase does.
    fn preload_of(
        &self,
        k: Option<usize>,
        scope: Scope,
        files: &[String],
    ) -> Result<Option<(u64, Loc, Scope)>, ImportError> {
        let Some(sel) = scope.statsub else {
            return Ok(None);
        };
        let here = |why: String| {
            err(
                files,
                sel.loc,
                &format!("STATSUB(PRELOAD) = {}", sel.id),
                why,
            )
        };
        let j = (self.subcases.iter().position(|s| s.id == sel.id)).ok_or_else(|| {
            here(format!(
                "the deck has no SUBCASE {} to preload the modes",
                sel.id
            ))
        })?;
        if Some(j) == k {
            return Err(here(
                "names the modes' own subcase: the preload is a static subcase of its own".into(),
            ));
        }
        let mut st = self.scope_of(j);
        st.statsub = None;
        let id = |s: Option<Select>| s.map(|x| x.id);
        let show = |s: Option<Select>| s.map_or("none".to_owned(), |s| s.id.to_string());
        if id(st.spc) != id(scope.spc) || id(st.mpc) != id(scope.mpc) {
            return Err(here(format!(
                "static subcase {} holds the body by SPC = {} (MPC = {}), the modes' subcase by SPC = {} (MPC = {}): flexbody solves the preload on the modes' supports, give both subcases the same SPC and MPC",
                sel.id,
                show(st.spc),
                show(st.mpc),
                show(scope.spc),
                show(scope.mpc)
            )));
        }
        if st.load.is_none() && st.temp_load.is_none() {
            return Err(here(format!(
                "static subcase {} selects no LOAD and no TEMP(LOAD): nothing preloads the modes",
                sel.id
            )));
        }
        Ok(Some((sel.id, self.subcases[j].loc, st)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn lines(text: &str) -> Vec<(String, Loc)> {
        text.lines()
            .enumerate()
            .map(|(i, l)| {
                (
                    l.to_owned(),
                    Loc {
                        file: 0,
                        line: i as u32 + 1,
                    },
                )
            })
            .collect()
    }

    #[test]
    fn global_and_subcase_selections() {
        let files = vec!["d.bdf".to_owned()];
        let text = "SOL 103\nCEND\nTITLE = Two cases\nMETHOD = 1\nSPCFORCES = ALL\nSUBCASE 1\n  SPC = 1\nSUBCASE 2\n  SPC=2\n  METHOD(STRUCTURE) = 3\n";
        let cc = parse(&lines(text), true, &files).unwrap();
        assert_eq!(cc.title.as_deref(), Some("Two cases"));
        assert_eq!(cc.global.method.unwrap().id, 1);
        assert_eq!(cc.subcases.len(), 2);
        let e = cc.effective(None, &files, "d.bdf").unwrap_err().to_string();
        assert!(
            e.contains("d.bdf:8: SUBCASE 2") && e.contains("SPC = 1") && e.contains("SPC = 2"),
            "{e}"
        );
        let one = cc.effective(Some(1), &files, "d.bdf").unwrap();
        assert_eq!(
            (one.scope.spc.unwrap().id, one.scope.method.unwrap().id),
            (1, 1)
        );
        let two = cc.effective(Some(2), &files, "d.bdf").unwrap();
        assert_eq!(
            (two.scope.spc.unwrap().id, two.scope.method.unwrap().id),
            (2, 3)
        );
        assert!(cc.effective(Some(7), &files, "d.bdf").is_err());
    }

    /// `SUBCASE = n` (ZONA's decks, pyNastran's models/aero/zona) is `SUBCASE n`.
    #[test]
    fn subcase_id_may_follow_an_equals_sign() {
        let files = vec!["d.bdf".to_owned()];
        let text = "SOL 103\nCEND\nSUBCASE = 7\n  SPC = 1\nSUBCASE=8\n  SPC = 1\n";
        let cc = parse(&lines(text), true, &files).unwrap();
        let ids: Vec<u64> = cc.subcases.iter().map(|s| s.id).collect();
        assert_eq!(ids, [7, 8]);
        let bad = parse(&lines("CEND\nSUBCASE = x\n"), true, &files).unwrap_err();
        assert!(bad.to_string().contains("bad subcase id"), "{bad}");
    }
}
