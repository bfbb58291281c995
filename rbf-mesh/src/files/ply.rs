//! PLY: ASCII, binary little- and big-endian in; binary little-endian (doubles) out.

use std::path::Path;

use super::{at_byte, at_line, number};
use crate::{MeshError, TriMesh};

/// Vertex positions, triangles, and vertex normals when the vertices carry `nx ny nz`.
type Parts = (Vec<[f64; 3]>, Vec<[u32; 3]>, Option<Vec<[f64; 3]>>);

#[derive(Clone, Copy, PartialEq)]
enum Format {
    Ascii,
    Little,
    Big,
}

#[derive(Clone, Copy)]
enum Scalar {
    I8,
    U8,
    I16,
    U16,
    I32,
    U32,
    F32,
    F64,
}

impl Scalar {
    fn parse(name: &str) -> Option<Scalar> {
        Some(match name {
            "char" | "int8" => Scalar::I8,
            "uchar" | "uint8" => Scalar::U8,
            "short" | "int16" => Scalar::I16,
            "ushort" | "uint16" => Scalar::U16,
            "int" | "int32" => Scalar::I32,
            "uint" | "uint32" => Scalar::U32,
            "float" | "float32" => Scalar::F32,
            "double" | "float64" => Scalar::F64,
            _ => return None,
        })
    }
    fn size(self) -> usize {
        match self {
            Scalar::I8 | Scalar::U8 => 1,
            Scalar::I16 | Scalar::U16 => 2,
            Scalar::I32 | Scalar::U32 | Scalar::F32 => 4,
            Scalar::F64 => 8,
        }
    }
}

enum Property {
    Scalar(String, Scalar),
    List(String, Scalar, Scalar),
}

struct Element {
    name: String,
    count: u64,
    properties: Vec<Property>,
}

impl Element {
    /// The fewest bytes one instance can take in a binary file.
    fn min_size(&self) -> u64 {
        self.properties
            .iter()
            .map(|p| match p {
                Property::Scalar(_, s) | Property::List(_, s, _) => s.size() as u64,
            })
            .sum::<u64>()
            .max(1)
    }
}

/// A reader of values, ASCII or binary, that knows where it is.
struct Body<'a> {
    path: &'a Path,
    format: Format,
    bytes: &'a [u8],
    pos: usize,
    line: usize,
}

impl Body<'_> {
    fn error(&self, message: impl Into<String>) -> MeshError {
        match self.format {
            Format::Ascii => at_line(self.path, self.line, message),
            _ => at_byte(self.path, self.pos as u64, message),
        }
    }

    fn read(&mut self, s: Scalar) -> Result<f64, MeshError> {
        if self.format == Format::Ascii {
            return self.token();
        }
        let n = s.size();
        let Some(raw) = self.bytes.get(self.pos..self.pos + n) else {
            return Err(self.error("the file ends in the middle of the data"));
        };
        let mut b = [0u8; 8];
        b[..n].copy_from_slice(raw);
        if self.format == Format::Big {
            b[..n].reverse();
        }
        self.pos += n;
        Ok(match s {
            Scalar::I8 => b[0] as i8 as f64,
            Scalar::U8 => b[0] as f64,
            Scalar::I16 => i16::from_le_bytes([b[0], b[1]]) as f64,
            Scalar::U16 => u16::from_le_bytes([b[0], b[1]]) as f64,
            Scalar::I32 => i32::from_le_bytes([b[0], b[1], b[2], b[3]]) as f64,
            Scalar::U32 => u32::from_le_bytes([b[0], b[1], b[2], b[3]]) as f64,
            Scalar::F32 => f32::from_le_bytes([b[0], b[1], b[2], b[3]]) as f64,
            Scalar::F64 => f64::from_le_bytes(b),
        })
    }

    fn token(&mut self) -> Result<f64, MeshError> {
        while let Some(&c) = self.bytes.get(self.pos) {
            if c == b'\n' {
                self.line += 1;
            }
            if !c.is_ascii_whitespace() {
                break;
            }
            self.pos += 1;
        }
        let start = self.pos;
        while self
            .bytes
            .get(self.pos)
            .is_some_and(|c| !c.is_ascii_whitespace())
        {
            self.pos += 1;
        }
        if start == self.pos {
            return Err(self.error("the file ends in the middle of the data"));
        }
        let token = String::from_utf8_lossy(&self.bytes[start..self.pos]);
        number(&token).ok_or_else(|| self.error(format!("`{token}` is not a finite number")))
    }
}

fn header(path: &Path, bytes: &[u8]) -> Result<(Format, Vec<Element>, usize, usize), MeshError> {
    let mut format = None;
    let mut elements: Vec<Element> = Vec::new();
    let mut pos = 0;
    let mut line = 0;
    loop {
        let Some(end) = bytes[pos..].iter().position(|&c| c == b'\n') else {
            return Err(at_line(path, line + 1, "the header has no `end_header`"));
        };
        line += 1;
        let text = String::from_utf8_lossy(&bytes[pos..pos + end]);
        pos += end + 1;
        let words: Vec<&str> = text.split_whitespace().collect();
        let bad = |m: &str| at_line(path, line, m.to_string());
        match words.as_slice() {
            ["ply"] if line == 1 => {}
            _ if line == 1 => return Err(bad("not a PLY file (no `ply` on the first line)")),
            ["format", f, _] => {
                format = Some(match *f {
                    "ascii" => Format::Ascii,
                    "binary_little_endian" => Format::Little,
                    "binary_big_endian" => Format::Big,
                    other => return Err(bad(&format!("unknown format `{other}`"))),
                })
            }
            ["comment", ..] | ["obj_info", ..] | [] => {}
            ["element", name, count] => {
                let count = count
                    .parse()
                    .map_err(|_| bad("the element count is not a number"))?;
                elements.push(Element {
                    name: name.to_string(),
                    count,
                    properties: Vec::new(),
                });
            }
            ["property", "list", c, t, name] => {
                let (Some(c), Some(t)) = (Scalar::parse(c), Scalar::parse(t)) else {
                    return Err(bad("unknown property type"));
                };
                let Some(e) = elements.last_mut() else {
                    return Err(bad("a property before any element"));
                };
                e.properties.push(Property::List(name.to_string(), c, t));
            }
            ["property", t, name] => {
                let Some(t) = Scalar::parse(t) else {
                    return Err(bad(&format!("unknown property type `{t}`")));
                };
                let Some(e) = elements.last_mut() else {
                    return Err(bad("a property before any element"));
                };
                e.properties.push(Property::Scalar(name.to_string(), t));
            }
            ["end_header"] => break,
            _ => return Err(bad(&format!("unexpected header line `{text}`"))),
        }
    }
    let format = format.ok_or_else(|| at_line(path, line, "the header has no `format` line"))?;
    Ok((format, elements, pos, line))
}

/// The number of vertices the header declares (`bytes` may be the file's first bytes only).
pub(super) fn vertex_count(path: &Path, bytes: &[u8]) -> Result<u64, MeshError> {
    let (_, elements, _, _) = header(path, bytes)?;
    Ok(elements
        .iter()
        .find(|e| e.name == "vertex")
        .map_or(0, |e| e.count))
}

pub(super) fn read(path: &Path, bytes: &[u8]) -> Result<Parts, MeshError> {
    let (format, elements, start, line) = header(path, bytes)?;
    let mut body = Body {
        path,
        format,
        bytes,
        pos: start,
        line: line + 1,
    };
    let mut positions = Vec::new();
    let mut triangles = Vec::new();
    let mut normals = Vec::new();
    let has_normals = elements.iter().any(|e| {
        e.name == "vertex"
            && ["nx", "ny", "nz"].iter().all(|n| {
                e.properties
                    .iter()
                    .any(|p| matches!(p, Property::Scalar(name, _) if name == n))
            })
    });
    for e in &elements {
        let remaining = (bytes.len() - body.pos) as u64;
        // Each instance takes at least one byte (two in ASCII: a digit and a separator).
        let fits = match format {
            Format::Ascii => e.count <= remaining / 2 + 1,
            _ => e.count <= remaining / e.min_size(),
        };
        if !fits {
            return Err(body.error(format!(
                "the header declares {} `{}` elements, more than the {remaining} bytes left can hold",
                e.count, e.name
            )));
        }
        let is_vertex = e.name == "vertex";
        let is_face = e.name == "face";
        if is_vertex {
            positions.reserve(e.count as usize);
        }
        for index in 0..e.count {
            let mut p = [f64::NAN; 3];
            let mut given = [false; 3];
            let mut n = [0.0; 3];
            for prop in &e.properties {
                match prop {
                    Property::Scalar(name, s) => {
                        let v = body.read(*s)?;
                        if is_vertex {
                            match name.as_str() {
                                "x" => (p[0], given[0]) = (v, true),
                                "y" => (p[1], given[1]) = (v, true),
                                "z" => (p[2], given[2]) = (v, true),
                                "nx" => n[0] = v,
                                "ny" => n[1] = v,
                                "nz" => n[2] = v,
                                _ => {}
                            }
                        }
                    }
                    Property::List(name, c, t) => {
                        let n = body.read(*c)?;
                        if !(0.0..=1e6).contains(&n) || n.fract() != 0.0 {
                            return Err(body.error(format!("a list of {n} entries")));
                        }
                        let mut corners = Vec::with_capacity(n as usize);
                        for _ in 0..n as usize {
                            let v = body.read(*t)?;
                            if v < 0.0 || v.fract() != 0.0 || v > u32::MAX as f64 {
                                return Err(body.error(format!("`{v}` is not a vertex index")));
                            }
                            corners.push(v as u32);
                        }
                        if is_face && (name == "vertex_indices" || name == "vertex_index") {
                            if corners.len() < 3 {
                                return Err(body.error("a face with fewer than three vertices"));
                            }
                            for k in 1..corners.len() - 1 {
                                triangles.push([corners[0], corners[k], corners[k + 1]]);
                            }
                        }
                    }
                }
            }
            if is_vertex {
                if !given.iter().all(|&g| g) {
                    return Err(body.error("a vertex without x, y and z"));
                }
                if !p.iter().chain(&n).all(|v| v.is_finite()) {
                    return Err(body.error(format!(
                        "vertex {index} has a coordinate or normal that is not a finite number"
                    )));
                }
                positions.push(p);
                if has_normals {
                    normals.push(n);
                }
            }
        }
    }
    Ok((positions, triangles, has_normals.then_some(normals)))
}

pub(super) fn write(mesh: &TriMesh) -> Vec<u8> {
    let normals = mesh.normals();
    let mut header = format!(
        "ply\nformat binary_little_endian 1.0\ncomment written by rbf\nelement vertex {}\nproperty double x\nproperty double y\nproperty double z\n",
        mesh.positions().len()
    );
    if normals.is_some() {
        header.push_str("property double nx\nproperty double ny\nproperty double nz\n");
    }
    header.push_str(&format!(
        "element face {}\nproperty list uchar int vertex_indices\nend_header\n",
        mesh.triangles().len()
    ));
    let mut out = header.into_bytes();
    for (i, p) in mesh.positions().iter().enumerate() {
        for c in p {
            out.extend_from_slice(&c.to_le_bytes());
        }
        if let Some(n) = normals {
            for c in n[i] {
                out.extend_from_slice(&c.to_le_bytes());
            }
        }
    }
    for t in mesh.triangles() {
        out.push(3);
        for &i in t {
            out.extend_from_slice(&(i as i32).to_le_bytes());
        }
    }
    out
}
