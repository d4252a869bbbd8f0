//! Strict JSON (RFC 8259) for `manifest.json` and `recipe.json`, as SPEC.md §4.1 reads it:
//! at most [`MAX_DEPTH`] nested arrays and objects, no member name twice in one object, no lone
//! surrogate, numbers converted to the nearest binary64 (so `1e999` is +∞ and the consistency
//! rules, not the parser, refuse it) or, written without fraction and exponent, read exactly as
//! integers. A general JSON library differs on each of these (last duplicate wins, a depth of
//! 128, "number out of range"), and two readers must see one file.
//!
//! [`Json`] implements [`serde::Deserializer`], so the manifest and recipe types keep their
//! derives: a member of another JSON type is an error, unknown members are skipped, a struct
//! is only ever read from an object and a fixed array only from an array of its length.
use serde::de::{self, DeserializeSeed, MapAccess, SeqAccess, Unexpected, Visitor};

/// Deepest nesting of arrays and objects (the top-level value is at depth 1).
pub const MAX_DEPTH: usize = 64;

/// A parsed JSON value. Numbers keep their text, converted when a type asks for one.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Json {
    Null,
    Bool(bool),
    Number(String),
    String(String),
    Array(Vec<Json>),
    Object(Vec<(String, Json)>),
}

/// Why a text is not JSON, or a value not of the type asked for.
#[derive(Debug)]
pub(crate) struct Error(String);

impl std::fmt::Display for Error {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for Error {}

impl de::Error for Error {
    fn custom<T: std::fmt::Display>(msg: T) -> Self {
        Error(msg.to_string())
    }
}

impl Json {
    /// The member `key` of an object.
    pub fn get(&self, key: &str) -> Option<&Json> {
        match self {
            Json::Object(m) => m.iter().find(|(k, _)| k == key).map(|(_, v)| v),
            _ => None,
        }
    }

    /// An integer written without fraction and exponent, in 0…2⁶⁴−1 (`-0` is 0).
    pub fn as_u64(&self) -> Option<u64> {
        match self {
            Json::Number(t) if !t.contains(['.', 'e', 'E']) => {
                if t == "-0" {
                    Some(0)
                } else {
                    t.parse().ok()
                }
            }
            _ => None,
        }
    }

    /// Any number, as the nearest binary64 (±∞ beyond its range).
    pub fn as_f64(&self) -> Option<f64> {
        match self {
            // The grammar checked the text; Rust's conversion is correctly rounded.
            Json::Number(t) => t.parse().ok(),
            _ => None,
        }
    }

    fn unexpected(&self) -> Unexpected<'_> {
        match self {
            Json::Null => Unexpected::Unit,
            Json::Bool(b) => Unexpected::Bool(*b),
            Json::Number(t) => match self.as_f64() {
                Some(v) if t.contains(['.', 'e', 'E']) => Unexpected::Float(v),
                _ => Unexpected::Other("integer"),
            },
            Json::String(s) => Unexpected::Str(s),
            Json::Array(_) => Unexpected::Seq,
            Json::Object(_) => Unexpected::Map,
        }
    }
}

/// Parses `text` as one JSON value (whitespace around it allowed).
pub(crate) fn parse(text: &str) -> Result<Json, Error> {
    let mut p = Parser {
        b: text.as_bytes(),
        at: 0,
    };
    let v = p.value(0)?;
    p.ws();
    if p.at != p.b.len() {
        return Err(p.fail("text after the JSON value"));
    }
    Ok(v)
}

struct Parser<'a> {
    b: &'a [u8],
    at: usize,
}

impl Parser<'_> {
    fn fail(&self, what: &str) -> Error {
        Error(format!("{what} at byte {}", self.at))
    }

    fn ws(&mut self) {
        while matches!(self.b.get(self.at), Some(b' ' | b'\t' | b'\n' | b'\r')) {
            self.at += 1;
        }
    }

    fn eat(&mut self, c: u8) -> bool {
        let hit = self.b.get(self.at) == Some(&c);
        self.at += usize::from(hit);
        hit
    }

    fn literal(&mut self, word: &str, v: Json) -> Result<Json, Error> {
        if self.b[self.at..].starts_with(word.as_bytes()) {
            self.at += word.len();
            Ok(v)
        } else {
            Err(self.fail("not a JSON value"))
        }
    }

    /// A value whose enclosing arrays and objects number `depth`.
    fn value(&mut self, depth: usize) -> Result<Json, Error> {
        self.ws();
        match self.b.get(self.at) {
            Some(b'n') => self.literal("null", Json::Null),
            Some(b't') => self.literal("true", Json::Bool(true)),
            Some(b'f') => self.literal("false", Json::Bool(false)),
            Some(b'"') => self.string().map(Json::String),
            Some(b'-' | b'0'..=b'9') => self.number(),
            Some(b'[' | b'{') if depth >= MAX_DEPTH => Err(self.fail(&format!(
                "arrays and objects nested deeper than {MAX_DEPTH}"
            ))),
            Some(b'[') => {
                self.at += 1;
                let mut items = Vec::new();
                self.ws();
                if !self.eat(b']') {
                    loop {
                        items.push(self.value(depth + 1)?);
                        self.ws();
                        if self.eat(b']') {
                            break;
                        }
                        if !self.eat(b',') {
                            return Err(self.fail("expected , or ]"));
                        }
                    }
                }
                Ok(Json::Array(items))
            }
            Some(b'{') => {
                self.at += 1;
                let mut members: Vec<(String, Json)> = Vec::new();
                let mut names = std::collections::HashSet::new();
                self.ws();
                if !self.eat(b'}') {
                    loop {
                        self.ws();
                        if self.b.get(self.at) != Some(&b'"') {
                            return Err(self.fail("expected a member name"));
                        }
                        let key = self.string()?;
                        if !names.insert(key.clone()) {
                            return Err(self.fail(&format!("member {key:?} occurs twice")));
                        }
                        self.ws();
                        if !self.eat(b':') {
                            return Err(self.fail("expected :"));
                        }
                        members.push((key, self.value(depth + 1)?));
                        self.ws();
                        if self.eat(b'}') {
                            break;
                        }
                        if !self.eat(b',') {
                            return Err(self.fail("expected , or }"));
                        }
                    }
                }
                Ok(Json::Object(members))
            }
            _ => Err(self.fail("not a JSON value")),
        }
    }

    fn digits(&mut self) -> usize {
        let start = self.at;
        while matches!(self.b.get(self.at), Some(b'0'..=b'9')) {
            self.at += 1;
        }
        self.at - start
    }

    /// `-? (0 | [1-9][0-9]*) (. [0-9]+)? ([eE] [+-]? [0-9]+)?`
    fn number(&mut self) -> Result<Json, Error> {
        let start = self.at;
        self.eat(b'-');
        let lead_zero = self.b.get(self.at) == Some(&b'0');
        let n = self.digits();
        if n == 0 || (lead_zero && n > 1) {
            return Err(self.fail("malformed number"));
        }
        if self.eat(b'.') && self.digits() == 0 {
            return Err(self.fail("malformed number"));
        }
        if self.eat(b'e') || self.eat(b'E') {
            let _ = self.eat(b'+') || self.eat(b'-');
            if self.digits() == 0 {
                return Err(self.fail("malformed number"));
            }
        }
        // ASCII digits and signs only: the slice is valid UTF-8.
        Ok(Json::Number(
            String::from_utf8_lossy(&self.b[start..self.at]).into_owned(),
        ))
    }

    fn hex4(&mut self) -> Result<u32, Error> {
        let h = self
            .b
            .get(self.at..self.at + 4)
            .and_then(|h| std::str::from_utf8(h).ok())
            .filter(|h| h.bytes().all(|c| c.is_ascii_hexdigit()))
            .and_then(|h| u32::from_str_radix(h, 16).ok())
            .ok_or_else(|| self.fail("malformed \\u escape"))?;
        self.at += 4;
        Ok(h)
    }

    fn string(&mut self) -> Result<String, Error> {
        self.at += 1; // the opening quote
        let mut s = String::new();
        loop {
            let start = self.at;
            while matches!(self.b.get(self.at), Some(&c) if c >= 0x20 && c != b'"' && c != b'\\') {
                self.at += 1;
            }
            // The text is a &str and the run stops only at ASCII bytes: a whole UTF-8 run.
            s.push_str(&String::from_utf8_lossy(&self.b[start..self.at]));
            match self.b.get(self.at) {
                Some(b'"') => {
                    self.at += 1;
                    return Ok(s);
                }
                Some(b'\\') => {
                    self.at += 1;
                    let c = self.b.get(self.at).copied();
                    self.at += 1;
                    let ch = match c {
                        Some(b'"') => '"',
                        Some(b'\\') => '\\',
                        Some(b'/') => '/',
                        Some(b'b') => '\u{8}',
                        Some(b'f') => '\u{c}',
                        Some(b'n') => '\n',
                        Some(b'r') => '\r',
                        Some(b't') => '\t',
                        Some(b'u') => {
                            let hi = self.hex4()?;
                            let code = if (0xD800..0xDC00).contains(&hi) {
                                if !(self.eat(b'\\') && self.eat(b'u')) {
                                    return Err(self.fail("lone surrogate in a string"));
                                }
                                let lo = self.hex4()?;
                                if !(0xDC00..0xE000).contains(&lo) {
                                    return Err(self.fail("lone surrogate in a string"));
                                }
                                0x10000 + ((hi - 0xD800) << 10) + (lo - 0xDC00)
                            } else {
                                hi
                            };
                            char::from_u32(code)
                                .ok_or_else(|| self.fail("lone surrogate in a string"))?
                        }
                        _ => return Err(self.fail("malformed escape")),
                    };
                    s.push(ch);
                }
                Some(_) => return Err(self.fail("control character in a string")),
                None => return Err(self.fail("unterminated string")),
            }
        }
    }
}

struct Seq<'a>(std::slice::Iter<'a, Json>);

impl<'de> SeqAccess<'de> for Seq<'de> {
    type Error = Error;
    fn next_element_seed<T: DeserializeSeed<'de>>(
        &mut self,
        seed: T,
    ) -> Result<Option<T::Value>, Error> {
        self.0.next().map(|v| seed.deserialize(v)).transpose()
    }
}

struct Map<'a> {
    members: std::slice::Iter<'a, (String, Json)>,
    value: Option<&'a Json>,
}

impl<'de> MapAccess<'de> for Map<'de> {
    type Error = Error;
    fn next_key_seed<K: DeserializeSeed<'de>>(
        &mut self,
        seed: K,
    ) -> Result<Option<K::Value>, Error> {
        let Some((k, v)) = self.members.next() else {
            return Ok(None);
        };
        self.value = Some(v);
        seed.deserialize(de::value::BorrowedStrDeserializer::<Error>::new(k))
            .map(Some)
    }
    fn next_value_seed<V: DeserializeSeed<'de>>(&mut self, seed: V) -> Result<V::Value, Error> {
        let v = self
            .value
            .take()
            .ok_or_else(|| Error("value before key".into()))?;
        seed.deserialize(v)
    }
}

impl<'de> de::Deserializer<'de> for &'de Json {
    type Error = Error;

    fn deserialize_any<V: Visitor<'de>>(self, v: V) -> Result<V::Value, Error> {
        match self {
            Json::Null => v.visit_unit(),
            Json::Bool(b) => v.visit_bool(*b),
            Json::Number(t) => match (self.as_u64(), t.parse::<i64>()) {
                (Some(u), _) => v.visit_u64(u),
                (None, Ok(i)) if !t.contains(['.', 'e', 'E']) => v.visit_i64(i),
                // a number always converts to f64 (±∞ beyond its range)
                _ => v.visit_f64(self.as_f64().unwrap_or(f64::NAN)),
            },
            Json::String(s) => v.visit_borrowed_str(s),
            Json::Array(_) => self.deserialize_seq(v),
            Json::Object(_) => self.deserialize_map(v),
        }
    }

    fn deserialize_option<V: Visitor<'de>>(self, v: V) -> Result<V::Value, Error> {
        match self {
            Json::Null => v.visit_none(),
            _ => v.visit_some(self),
        }
    }

    fn deserialize_f64<V: Visitor<'de>>(self, v: V) -> Result<V::Value, Error> {
        match self.as_f64() {
            Some(x) => v.visit_f64(x),
            None => Err(de::Error::invalid_type(self.unexpected(), &v)),
        }
    }

    fn deserialize_f32<V: Visitor<'de>>(self, v: V) -> Result<V::Value, Error> {
        self.deserialize_f64(v)
    }

    fn deserialize_u64<V: Visitor<'de>>(self, v: V) -> Result<V::Value, Error> {
        match self.as_u64() {
            Some(x) => v.visit_u64(x),
            None => Err(de::Error::invalid_type(self.unexpected(), &v)),
        }
    }

    fn deserialize_u32<V: Visitor<'de>>(self, v: V) -> Result<V::Value, Error> {
        self.deserialize_u64(v)
    }

    fn deserialize_u16<V: Visitor<'de>>(self, v: V) -> Result<V::Value, Error> {
        self.deserialize_u64(v)
    }

    fn deserialize_u8<V: Visitor<'de>>(self, v: V) -> Result<V::Value, Error> {
        self.deserialize_u64(v)
    }

    fn deserialize_seq<V: Visitor<'de>>(self, v: V) -> Result<V::Value, Error> {
        let Json::Array(items) = self else {
            return Err(de::Error::invalid_type(self.unexpected(), &v));
        };
        let mut seq = Seq(items.iter());
        let out = v.visit_seq(&mut seq)?;
        match seq.0.len() {
            0 => Ok(out),
            _ => Err(de::Error::invalid_length(items.len(), &"fewer elements")),
        }
    }

    fn deserialize_tuple<V: Visitor<'de>>(self, _len: usize, v: V) -> Result<V::Value, Error> {
        self.deserialize_seq(v)
    }

    fn deserialize_map<V: Visitor<'de>>(self, v: V) -> Result<V::Value, Error> {
        let Json::Object(members) = self else {
            return Err(de::Error::invalid_type(self.unexpected(), &v));
        };
        v.visit_map(Map {
            members: members.iter(),
            value: None,
        })
    }

    fn deserialize_struct<V: Visitor<'de>>(
        self,
        _name: &'static str,
        _fields: &'static [&'static str],
        v: V,
    ) -> Result<V::Value, Error> {
        self.deserialize_map(v)
    }

    fn deserialize_ignored_any<V: Visitor<'de>>(self, v: V) -> Result<V::Value, Error> {
        v.visit_unit()
    }

    serde::forward_to_deserialize_any! {
        bool i8 i16 i32 i64 i128 u128 char str string bytes byte_buf unit unit_struct
        newtype_struct tuple_struct enum identifier
    }
}

/// Deserializes `T` from a parsed value.
pub(crate) fn from_json<'a, T: serde::Deserialize<'a>>(v: &'a Json) -> Result<T, Error> {
    T::deserialize(v)
}

/// `#[serde(deserialize_with)]` for members written `name?: T` (SPEC §5.11): absent is `None`
/// (with `#[serde(default)]`), present is a `T` — `null` is not one.
pub(crate) fn present<'de, D: de::Deserializer<'de>, T: serde::Deserialize<'de>>(
    d: D,
) -> Result<Option<T>, D::Error> {
    T::deserialize(d).map(Some)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_are_nearest_binary64_or_exact_integers() {
        let v = parse(r#"[1e999, -1e999, 18446744073709551615, -0, 1.5e-400, 0.1]"#).unwrap();
        let Json::Array(a) = v else { panic!() };
        assert_eq!(a[0].as_f64(), Some(f64::INFINITY));
        assert_eq!(a[1].as_f64(), Some(f64::NEG_INFINITY));
        assert_eq!(a[2].as_u64(), Some(u64::MAX));
        assert_eq!(a[3].as_u64(), Some(0));
        assert_eq!(a[4].as_f64(), Some(0.0));
        assert_eq!(a[5].as_f64(), Some(0.1));
        assert_eq!(a[0].as_u64(), None);
        for bad in ["01", "1.", ".5", "1e", "+1", "-", "NaN", "Infinity", "0x10"] {
            assert!(parse(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn duplicates_depth_and_surrogates_are_refused() {
        assert!(parse(r#"{"a": 1, "b": {"c": 1, "c": 2}}"#)
            .unwrap_err()
            .0
            .contains("occurs twice"));
        let deep = |n: usize| format!("{}{}", "[".repeat(n), "]".repeat(n));
        assert!(parse(&deep(MAX_DEPTH)).is_ok());
        assert!(parse(&deep(MAX_DEPTH + 1)).is_err());
        assert!(parse(&deep(100_000)).is_err());
        assert!(parse(r#""\ud800""#).is_err());
        assert!(parse(r#""\udc00\ud800""#).is_err());
        assert_eq!(
            parse(r#""\ud83d\ude00 \u00e9""#).unwrap(),
            Json::String("😀 é".into())
        );
        assert!(parse("\"a\u{1}\"").is_err());
        assert!(parse("{} x").is_err());
        assert!(parse("[1,]").is_err());
    }

    #[test]
    fn hostile_texts_parse_in_linear_time() {
        // 400,000 members, the last a duplicate; 2 MB of escaped quotes never closed.
        let members: Vec<String> = (0..400_000).map(|i| format!("\"k{i}\": 1")).collect();
        let text = format!("{{{}, \"k7\": 2}}", members.join(", "));
        let start = std::time::Instant::now();
        assert!(parse(&text).unwrap_err().0.contains("\"k7\" occurs twice"));
        assert!(parse(&"\"\\\"".repeat(1_000_000)).is_err());
        assert!(start.elapsed().as_secs() < 5, "{:?}", start.elapsed());
    }

    #[test]
    fn types_are_strict() {
        #[derive(serde::Deserialize, Debug)]
        #[allow(dead_code)]
        struct S {
            a: [f64; 2],
            b: u32,
            #[serde(default, deserialize_with = "present")]
            c: Option<f64>,
        }
        let ok = |t: &str| from_json::<S>(&parse(t).unwrap()).map_err(|e| e.0);
        assert!(ok(r#"{"a": [1, 2e0], "b": 7, "x": {"y": [null]}}"#).is_ok());
        assert!(ok(r#"{"a": [1, 2, 3], "b": 7}"#).is_err());
        assert!(ok(r#"{"a": [1], "b": 7}"#).is_err());
        assert!(ok(r#"{"a": [1, 2], "b": 4294967296}"#).is_err());
        assert!(ok(r#"{"a": [1, 2], "b": 7.0}"#).is_err());
        assert!(ok(r#"{"a": [1, 2], "b": 7, "c": null}"#).is_err());
        assert!(ok(r#"[[1, 2], 7]"#).is_err());
        assert!(ok(r#"{"b": 7}"#).unwrap_err().contains("missing field `a`"));
    }
}
