//! NumPy `.npz` archives written without Python: each entry a `.npy` file (format 1.0: magic,
//! a Python-literal header padded to 64 bytes, little-endian data), zipped like `numpy.savez`.
//! Objects that numpy itself pickles (a dict holding an array) are written as a short pickle
//! (protocol 3) that rebuilds the array with `numpy.array(numpy.ndarray(shape, '<f8', bytes))`.
use crate::write::{zip_entries, Compression, DEFAULT_DEFLATE_LEVEL};

/// One value of an archive entry.
#[derive(Debug, Clone, PartialEq)]
pub enum NpyValue {
    /// `float64` array, row-major, of the given shape (empty shape: a scalar).
    F64 {
        /// Shape (product = data length).
        shape: Vec<usize>,
        /// Values, row-major.
        data: Vec<f64>,
    },
    /// `int64` array, row-major, of the given shape.
    I64 {
        /// Shape (product = data length).
        shape: Vec<usize>,
        /// Values, row-major.
        data: Vec<i64>,
    },
    /// A 0-d unicode string array (`<U{n}`), what `numpy.savez` makes of a `str`.
    Str(String),
    /// A pickled Python dict of string keys (what `numpy.savez` makes of a `dict`).
    Dict(Vec<(String, PyValue)>),
}

/// A value inside a pickled dict.
#[derive(Debug, Clone, PartialEq)]
pub enum PyValue {
    /// A Python `str`.
    Str(String),
    /// A writable `float64` numpy array of the given shape, row-major.
    F64Array {
        /// Shape.
        shape: Vec<usize>,
        /// Values, row-major.
        data: Vec<f64>,
    },
}

/// The `.npz` bytes of `entries` (name without `.npy`, value), in the given order.
pub fn npz_bytes(entries: &[(&str, NpyValue)]) -> zip::result::ZipResult<Vec<u8>> {
    let files: Vec<(String, Vec<u8>)> = entries
        .iter()
        .map(|(name, v)| (format!("{name}.npy"), npy_bytes(v)))
        .collect();
    zip_entries(&files, Compression::Deflate(DEFAULT_DEFLATE_LEVEL))
}

/// One `.npy` file (format version 1.0).
pub fn npy_bytes(v: &NpyValue) -> Vec<u8> {
    let (descr, shape, data): (String, Vec<usize>, Vec<u8>) = match v {
        NpyValue::F64 { shape, data } => (
            "'<f8'".into(),
            shape.clone(),
            data.iter().flat_map(|x| x.to_le_bytes()).collect(),
        ),
        NpyValue::I64 { shape, data } => (
            "'<i8'".into(),
            shape.clone(),
            data.iter().flat_map(|x| x.to_le_bytes()).collect(),
        ),
        NpyValue::Str(s) => {
            let chars: Vec<char> = s.chars().collect();
            let n = chars.len().max(1);
            let mut bytes: Vec<u8> = chars
                .iter()
                .flat_map(|c| u32::from(*c).to_le_bytes())
                .collect();
            bytes.resize(4 * n, 0);
            (format!("'<U{n}'"), Vec::new(), bytes)
        }
        NpyValue::Dict(items) => ("'|O'".into(), Vec::new(), pickle_dict(items)),
    };
    let shape_text = match shape.len() {
        0 => "()".to_string(),
        1 => format!("({},)", shape[0]),
        _ => format!(
            "({})",
            shape
                .iter()
                .map(|s| s.to_string())
                .collect::<Vec<_>>()
                .join(", ")
        ),
    };
    let mut header =
        format!("{{'descr': {descr}, 'fortran_order': False, 'shape': {shape_text}, }}");
    // magic (6) + version (2) + header length (2) + header, padded with spaces to 64 bytes,
    // ending in a newline (numpy's own layout).
    let total = 10 + header.len() + 1;
    header.push_str(&" ".repeat((64 - total % 64) % 64));
    header.push('\n');
    let mut out = Vec::with_capacity(10 + header.len() + data.len());
    out.extend_from_slice(b"\x93NUMPY\x01\x00");
    // The header is ASCII and short (< 200 bytes for any shape we write).
    out.extend_from_slice(&(header.len() as u16).to_le_bytes());
    out.extend_from_slice(header.as_bytes());
    out.extend_from_slice(&data);
    out
}

/// Pickle protocol 3 of a dict with string keys.
fn pickle_dict(items: &[(String, PyValue)]) -> Vec<u8> {
    let mut p = vec![0x80, 3, b'}', b'('];
    for (key, value) in items {
        pickle_str(&mut p, key);
        match value {
            PyValue::Str(s) => pickle_str(&mut p, s),
            PyValue::F64Array { shape, data } => {
                // numpy.array(numpy.ndarray(shape, '<f8', buffer)): a writable copy.
                p.extend_from_slice(b"cnumpy\narray\n");
                p.extend_from_slice(b"cnumpy\nndarray\n");
                p.push(b'(');
                for &s in shape {
                    pickle_int(&mut p, s as i64);
                }
                p.push(b't');
                pickle_str(&mut p, "<f8");
                let bytes: Vec<u8> = data.iter().flat_map(|x| x.to_le_bytes()).collect();
                p.push(b'B'); // BINBYTES, 4-byte length
                p.extend_from_slice(&(bytes.len() as u32).to_le_bytes());
                p.extend_from_slice(&bytes);
                p.push(0x87); // TUPLE3
                p.push(b'R'); // REDUCE: the read-only view
                p.push(0x85); // TUPLE1
                p.push(b'R'); // REDUCE: numpy.array(view)
            }
        }
    }
    p.push(b'u'); // SETITEMS
    p.push(b'.'); // STOP
    p
}

fn pickle_str(p: &mut Vec<u8>, s: &str) {
    p.push(b'X'); // BINUNICODE
    p.extend_from_slice(&(s.len() as u32).to_le_bytes());
    p.extend_from_slice(s.as_bytes());
}

fn pickle_int(p: &mut Vec<u8>, v: i64) {
    if let Ok(small) = i32::try_from(v) {
        p.push(b'J'); // BININT
        p.extend_from_slice(&small.to_le_bytes());
    } else {
        p.push(0x8a); // LONG1
        p.push(8);
        p.extend_from_slice(&v.to_le_bytes());
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The header numpy writes for `np.save(f, np.zeros((2, 3)))`, byte for byte.
    #[test]
    fn npy_header_matches_numpy() {
        let b = npy_bytes(&NpyValue::F64 {
            shape: vec![2, 3],
            data: vec![0.0; 6],
        });
        let expect = "{'descr': '<f8', 'fortran_order': False, 'shape': (2, 3), }";
        assert_eq!(&b[..8], b"\x93NUMPY\x01\x00");
        let len = u16::from_le_bytes([b[8], b[9]]) as usize;
        assert_eq!((10 + len) % 64, 0);
        let header = std::str::from_utf8(&b[10..10 + len]).unwrap();
        assert_eq!(header.trim_end(), expect);
        assert!(header.ends_with('\n'));
        assert_eq!(b.len(), 10 + len + 48);
    }
}
