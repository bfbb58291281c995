//! NumPy `.npy` files: two-dimensional arrays of `float64` or `float32` in, either byte order,
//! C or Fortran order (what `numpy.save` writes for point sets); arrays of any shape out.

use std::path::Path;

use crate::{Location, MeshError};

/// A matrix read from `.npy`, row-major.
#[derive(Clone, Debug, PartialEq)]
pub struct Matrix {
    /// Rows (points).
    pub rows: usize,
    /// Columns (numbers per point).
    pub cols: usize,
    /// `rows × cols` numbers, row by row.
    pub data: Vec<f64>,
}

/// The numbers' layout and where they start, from the header of an `.npy` file (`bytes` may be
/// the file's first bytes only).
pub(super) struct Header {
    little: bool,
    size: usize,
    fortran: bool,
    pub(super) rows: usize,
    pub(super) cols: usize,
    body: usize,
}

/// Reads the header of a two-dimensional float64 or float32 array.
pub(super) fn header(path: &Path, bytes: &[u8]) -> Result<Header, MeshError> {
    let bad = |offset: usize, message: String| MeshError::Parse {
        file: path.into(),
        location: Location::Byte(offset as u64),
        message,
    };
    if bytes.len() < 10 || &bytes[..6] != b"\x93NUMPY" {
        return Err(bad(0, "not a NumPy .npy file (no \\x93NUMPY magic)".into()));
    }
    let (header_len, start) = match bytes[6] {
        1 => (
            usize::from(u16::from_le_bytes([bytes[8], bytes[9]])),
            10_usize,
        ),
        2 | 3 if bytes.len() >= 12 => (
            u32::from_le_bytes([bytes[8], bytes[9], bytes[10], bytes[11]]) as usize,
            12,
        ),
        v => return Err(bad(6, format!(".npy version {v} is not supported"))),
    };
    let header = bytes
        .get(start..start.saturating_add(header_len))
        .and_then(|h| std::str::from_utf8(h).ok())
        .ok_or_else(|| bad(start, "the header is cut short or not text".into()))?;
    let field = |key: &str| -> Option<&str> {
        let at = header.find(&format!("'{key}'"))? + key.len() + 2;
        let rest = header[at..].trim_start().strip_prefix(':')?.trim_start();
        Some(rest)
    };
    let descr = field("descr")
        .and_then(|r| r.strip_prefix('\'')?.split('\'').next())
        .ok_or_else(|| bad(start, "the header has no 'descr'".into()))?;
    let (little, size) = match descr {
        "<f8" | "=f8" | "|f8" => (true, 8),
        ">f8" => (false, 8),
        "<f4" | "=f4" | "|f4" => (true, 4),
        ">f4" => (false, 4),
        other => {
            return Err(bad(
                start,
                format!("numbers of type '{other}': save the array as float64 or float32"),
            ));
        }
    };
    let fortran = field("fortran_order").is_some_and(|r| r.starts_with("True"));
    let shape: Vec<usize> = field("shape")
        .and_then(|r| r.strip_prefix('(')?.split(')').next())
        .map(|s| {
            s.split(',')
                .map(str::trim)
                .filter(|t| !t.is_empty())
                .map(|t| t.parse::<usize>())
                .collect::<Result<Vec<_>, _>>()
        })
        .and_then(Result::ok)
        .ok_or_else(|| bad(start, "the header's 'shape' does not read".into()))?;
    let [rows, cols] = shape[..] else {
        return Err(bad(
            start,
            format!("an array of shape {shape:?}: give a two-dimensional array, one point a row"),
        ));
    };
    Ok(Header {
        little,
        size,
        fortran,
        rows,
        cols,
        body: start + header_len,
    })
}

/// Reads a two-dimensional `.npy` array of floats; `path` names it in errors.
///
/// ```
/// // numpy.save of [[1, 2, 3], [4, 5, 6]] as float64.
/// let header = "{'descr': '<f8', 'fortran_order': False, 'shape': (2, 3), }";
/// let mut bytes = b"\x93NUMPY\x01\x00".to_vec();
/// let padded = format!("{header:<117}\n");
/// bytes.extend_from_slice(&(padded.len() as u16).to_le_bytes());
/// bytes.extend_from_slice(padded.as_bytes());
/// for v in [1.0f64, 2.0, 3.0, 4.0, 5.0, 6.0] {
///     bytes.extend_from_slice(&v.to_le_bytes());
/// }
/// let m = rbf_mesh::read_npy_matrix("points.npy".as_ref(), &bytes).unwrap();
/// assert_eq!((m.rows, m.cols, m.data[5]), (2, 3, 6.0));
/// ```
pub fn read_npy_matrix(path: &Path, bytes: &[u8]) -> Result<Matrix, MeshError> {
    let bad = |offset: usize, message: String| MeshError::Parse {
        file: path.into(),
        location: Location::Byte(offset as u64),
        message,
    };
    let Header {
        little,
        size,
        fortran,
        rows,
        cols,
        body,
    } = header(path, bytes)?;
    let count = rows.checked_mul(cols);
    let expected = count.and_then(|c| c.checked_mul(size));
    if expected != Some(bytes.len().saturating_sub(body)) {
        return Err(bad(
            body,
            format!(
                "the shape ({rows}, {cols}) of {size}-byte numbers needs {} bytes of data, the file has {}",
                expected.map_or("more".to_string(), |e| e.to_string()),
                bytes.len().saturating_sub(body)
            ),
        ));
    }
    let values = bytes[body..]
        .chunks_exact(size)
        .map(|b| match (size, little) {
            (8, true) => f64::from_le_bytes(b.try_into().unwrap_or_default()),
            (8, false) => f64::from_be_bytes(b.try_into().unwrap_or_default()),
            (_, true) => f64::from(f32::from_le_bytes(b.try_into().unwrap_or_default())),
            (_, false) => f64::from(f32::from_be_bytes(b.try_into().unwrap_or_default())),
        });
    let mut data: Vec<f64> = values.collect();
    if fortran && rows > 1 && cols > 1 {
        // Column-major on disk: transpose to rows.
        let columns = data;
        data = (0..rows * cols)
            .map(|k| columns[(k % cols) * rows + k / cols])
            .collect();
    }
    Ok(Matrix { rows, cols, data })
}

/// The first bytes of a version-1 `.npy` file: magic, header length and the header of an
/// array of `descr` numbers (`<f8`, `<f4`) of `shape` in C order, padded to 64 bytes.
pub(crate) fn npy_preamble(descr: &str, shape: &[usize]) -> Vec<u8> {
    let dims: Vec<String> = shape.iter().map(usize::to_string).collect();
    // A one-dimensional shape is written `(n,)`.
    let shape = match dims.len() {
        1 => format!("({},)", dims[0]),
        _ => format!("({})", dims.join(", ")),
    };
    let mut header = format!("{{'descr': '{descr}', 'fortran_order': False, 'shape': {shape}, }}");
    // Magic (6) + version (2) + length (2) + header, padded with spaces to a multiple of 64
    // and ended by a newline.
    let unpadded = 10 + header.len() + 1;
    header.push_str(&" ".repeat((64 - unpadded % 64) % 64));
    header.push('\n');
    let mut out = b"\x93NUMPY\x01\x00".to_vec();
    out.extend_from_slice(&(header.len() as u16).to_le_bytes());
    out.extend_from_slice(header.as_bytes());
    out
}

/// The bytes of an `.npy` file holding `data` (little-endian float64, C order) as an array of
/// `shape`; `numpy.load` reads it.
///
/// ```
/// let bytes = rbf_mesh::npy_f64_bytes(&[2, 3], &[1.0, 2.0, 3.0, 4.0, 5.0, 6.0]);
/// let m = rbf_mesh::read_npy_matrix("out.npy".as_ref(), &bytes).unwrap();
/// assert_eq!((m.rows, m.cols, m.data[4]), (2, 3, 5.0));
/// ```
pub fn npy_f64_bytes(shape: &[usize], data: &[f64]) -> Vec<u8> {
    let mut out = npy_preamble("<f8", shape);
    out.reserve(8 * data.len());
    for v in data {
        out.extend_from_slice(&v.to_le_bytes());
    }
    out
}
