//! Typed access to the fields of a Nastran card, with errors naming file, line and `CARD id`.

use super::lex::Card;
use crate::import::error::{parse_err, ImportError};

/// Nastran real: `1.5`, `1.5E3`, `1.5+3` (implicit exponent), `1.5D3`, `.5`, `1.`; `None`
/// also when out of [`crate::import::budget::MAX_ABS_REAL`] (e.g. `0.1e400`, which overflows).
pub(crate) fn nastran_real(s: &str) -> Option<f64> {
    nastran_real_unbounded(s).and_then(crate::import::budget::in_range)
}

fn nastran_real_unbounded(s: &str) -> Option<f64> {
    let s = s.trim();
    if s.is_empty() || !s.bytes().any(|b| b.is_ascii_digit()) {
        return None;
    }
    if !s
        .bytes()
        .all(|b| b.is_ascii_digit() || b"+-.eEdD".contains(&b))
    {
        return None;
    }
    if let Ok(v) = s.parse::<f64>() {
        return Some(v);
    }
    let s = s.replace(['d', 'D'], "E");
    if let Ok(v) = s.parse::<f64>() {
        return Some(v);
    }
    let b = s.as_bytes();
    let pos = (1..b.len()).rev().find(|&i| {
        (b[i] == b'+' || b[i] == b'-') && !matches!(b[i - 1], b'e' | b'E' | b'+' | b'-')
    })?;
    format!("{}E{}", &s[..pos], &s[pos..]).parse().ok()
}

/// How many ids `THRU` ranges may expand to: per card, and over all cards of the deck (what is
/// left). See `import::budget`.
pub(crate) struct ThruBudget {
    pub per_card: u64,
    pub left: std::cell::Cell<u64>,
}

impl ThruBudget {
    /// The budget of a deck of `bytes` bytes.
    pub(crate) fn for_bytes(bytes: u64) -> ThruBudget {
        ThruBudget {
            per_card: crate::import::budget::expansion_limit(bytes),
            left: std::cell::Cell::new(crate::import::budget::total_expansion_limit(bytes)),
        }
    }
}

/// A card plus the name of its file, for messages.
pub(crate) struct C<'a> {
    pub card: &'a Card,
    pub file: &'a str,
}

impl<'a> C<'a> {
    /// The card with the name of the file it is in (`files` as the lexer numbered them).
    pub(crate) fn new(card: &'a Card, files: &'a [String]) -> C<'a> {
        C {
            card,
            file: &files[card.loc.file as usize],
        }
    }

    pub(crate) fn text(&self, k: usize) -> &'a str {
        self.card.fields.get(k).map_or("", |f| f.text.as_str())
    }

    pub(crate) fn line(&self, k: usize) -> usize {
        self.card
            .fields
            .get(k)
            .map_or(self.card.loc.line, |f| f.line) as usize
    }

    pub(crate) fn entity(&self) -> String {
        let id = self.text(0);
        if id.is_empty() {
            self.card.name.clone()
        } else {
            format!("{} {}", self.card.name, id)
        }
    }

    pub(crate) fn err(&self, k: usize, msg: impl Into<String>) -> ImportError {
        parse_err(self.file, self.line(k), self.entity(), msg)
    }

    pub(crate) fn err_card(&self, msg: impl Into<String>) -> ImportError {
        parse_err(self.file, self.card.loc.line as usize, self.entity(), msg)
    }

    /// Integer field; blank → `None`.
    pub(crate) fn int(&self, k: usize) -> Result<Option<i64>, ImportError> {
        let s = self.text(k);
        if s.is_empty() {
            return Ok(None);
        }
        s.parse::<i64>()
            .map(Some)
            .map_err(|_| self.err(k, format!("field {}: bad integer '{s}'", k + 2)))
    }

    /// Required integer field.
    pub(crate) fn req_int(&self, k: usize, what: &str) -> Result<i64, ImportError> {
        self.int(k)?
            .ok_or_else(|| self.err(k, format!("field {} ({what}) is blank", k + 2)))
    }

    /// Required non-negative id.
    pub(crate) fn id(&self, k: usize, what: &str) -> Result<u64, ImportError> {
        let v = self.req_int(k, what)?;
        u64::try_from(v).map_err(|_| self.err(k, format!("field {} ({what}) is negative", k + 2)))
    }

    /// Real field; blank → `None`.
    pub(crate) fn real(&self, k: usize) -> Result<Option<f64>, ImportError> {
        let s = self.text(k);
        if s.is_empty() {
            return Ok(None);
        }
        nastran_real(s).map(Some).ok_or_else(|| {
            let why = crate::import::budget::bad_number(s, nastran_real_unbounded(s));
            self.err(k, format!("field {}: {why}", k + 2))
        })
    }

    /// Real field with a default for blank.
    pub(crate) fn real_or(&self, k: usize, default: f64) -> Result<f64, ImportError> {
        Ok(self.real(k)?.unwrap_or(default))
    }

    /// Integer ids from field `start` on, expanding `a THRU b`; blank fields are skipped; stops
    /// at the first real number (e.g. RBE2 ALPHA) or keyword other than THRU.
    /// Expansion is bounded by `budget`, checked before the ids are materialized.
    pub(crate) fn id_list(
        &self,
        start: usize,
        budget: &ThruBudget,
    ) -> Result<Vec<(u64, usize)>, ImportError> {
        let mut out = Vec::new();
        let mut k = start;
        let n = self.card.fields.len();
        while k < n {
            let s = self.text(k);
            if s.is_empty() {
                k += 1;
                continue;
            }
            if s.eq_ignore_ascii_case("THRU") {
                let Some(&(a, _)) = out.last() else {
                    return Err(self.err(k, "THRU without a start id"));
                };
                let b = self.id(k + 1, "THRU end")?;
                if b < a {
                    return Err(self.err(k, format!("bad THRU range {a}..{b}")));
                }
                let more = b - a;
                let card_total = (out.len() as u64).saturating_add(more);
                if card_total > budget.per_card || more > budget.left.get() {
                    return Err(self.err(
                        k,
                        format!(
                            "THRU range {a}..{b} would expand the card to {card_total} ids: more than the input budget allows ({} per card, {} left for the deck; see flexbody::import::budget)",
                            budget.per_card,
                            budget.left.get()
                        ),
                    ));
                }
                budget.left.set(budget.left.get() - more);
                out.extend((a + 1..=b).map(|i| (i, k)));
                k += 2;
                continue;
            }
            match s.parse::<u64>() {
                Ok(v) => out.push((v, k)),
                Err(_)
                    if nastran_real_unbounded(s).is_some()
                        || s.chars().all(|c| c.is_ascii_alphabetic()) =>
                {
                    break
                }
                Err(_) => return Err(self.err(k, format!("field {}: bad id '{s}'", k + 2))),
            }
            k += 1;
        }
        Ok(out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nastran_reals() {
        assert_eq!(nastran_real("2.5900-3"), Some(2.59e-3));
        assert_eq!(nastran_real("3.0000+7"), Some(3.0e7));
        assert_eq!(nastran_real(".283"), Some(0.283));
        assert_eq!(nastran_real("1."), Some(1.0));
        assert_eq!(nastran_real("-.5-2"), Some(-0.005));
        assert_eq!(nastran_real("1.0E-3"), Some(1e-3));
        assert_eq!(nastran_real("1.5D3"), Some(1500.0));
        assert_eq!(nastran_real("nan"), None);
        assert_eq!(nastran_real("1.2.3"), None);
        assert_eq!(nastran_real("abc"), None);
        assert_eq!(
            (nastran_real("0.1e400"), nastran_real("1.+200")),
            (None, None)
        );
        assert_eq!(nastran_real("1.-200"), Some(1e-200));
    }
}
