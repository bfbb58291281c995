//! STL: ASCII and binary in (vertices welded by exact position); binary out.

use std::collections::HashMap;
use std::path::Path;

use super::{at_byte, at_line, number};
use crate::{MeshError, TriMesh};
use rbf_core::vec3::{cross, norm, sub};

type Parts = (Vec<[f64; 3]>, Vec<[u32; 3]>);

/// Joins corners at identical positions into shared vertices, as STL stores none.
#[derive(Default)]
struct Welder {
    positions: Vec<[f64; 3]>,
    index: HashMap<[u64; 3], u32>,
}

impl Welder {
    fn vertex(&mut self, p: [f64; 3]) -> u32 {
        // +0.0 and −0.0 are the same place.
        let key = p.map(|c| if c == 0.0 { 0 } else { c.to_bits() });
        *self.index.entry(key).or_insert_with(|| {
            self.positions.push(p);
            (self.positions.len() - 1) as u32
        })
    }
}

pub(super) fn read(path: &Path, bytes: &[u8]) -> Result<Parts, MeshError> {
    if bytes.len() >= 84 {
        let n = u32::from_le_bytes([bytes[80], bytes[81], bytes[82], bytes[83]]) as u64;
        if 84 + 50 * n == bytes.len() as u64 {
            return read_binary(path, bytes, n);
        }
    }
    if bytes.trim_ascii_start().starts_with(b"solid") {
        return read_ascii(path, bytes);
    }
    if bytes.len() >= 84 {
        let n = u32::from_le_bytes([bytes[80], bytes[81], bytes[82], bytes[83]]);
        return Err(at_byte(
            path,
            80,
            format!(
                "binary STL declares {n} triangles ({} bytes) but the file has {} bytes",
                84 + 50 * n as u64,
                bytes.len()
            ),
        ));
    }
    Err(at_byte(
        path,
        0,
        "neither ASCII STL (`solid …`) nor binary STL (too short)",
    ))
}

fn read_binary(path: &Path, bytes: &[u8], n: u64) -> Result<Parts, MeshError> {
    let mut w = Welder::default();
    let mut triangles = Vec::with_capacity(n as usize);
    for (t, rec) in bytes[84..].chunks_exact(50).enumerate() {
        let f = |k: usize| f32::from_le_bytes([rec[k], rec[k + 1], rec[k + 2], rec[k + 3]]) as f64;
        let mut tri = [0u32; 3];
        for (c, v) in tri.iter_mut().enumerate() {
            let o = 12 + 12 * c;
            let p = [f(o), f(o + 4), f(o + 8)];
            if !p.iter().all(|x| x.is_finite()) {
                return Err(at_byte(
                    path,
                    84 + 50 * t as u64 + o as u64,
                    "a coordinate is not finite",
                ));
            }
            *v = w.vertex(p);
        }
        triangles.push(tri);
    }
    Ok((w.positions, triangles))
}

fn read_ascii(path: &Path, bytes: &[u8]) -> Result<Parts, MeshError> {
    let text = std::str::from_utf8(bytes)
        .map_err(|e| at_byte(path, e.valid_up_to() as u64, "not UTF-8 text"))?;
    let mut w = Welder::default();
    let mut triangles = Vec::new();
    let mut corners: Vec<u32> = Vec::with_capacity(3);
    for (i, raw) in text.lines().enumerate() {
        let line = i + 1;
        let words: Vec<&str> = raw.split_whitespace().collect();
        match words.as_slice() {
            ["vertex", x, y, z] => {
                let (Some(x), Some(y), Some(z)) = (number(x), number(y), number(z)) else {
                    return Err(at_line(path, line, "a vertex needs three finite numbers"));
                };
                if corners.len() == 3 {
                    return Err(at_line(path, line, "a facet with more than three vertices"));
                }
                corners.push(w.vertex([x, y, z]));
            }
            ["vertex", ..] => return Err(at_line(path, line, "a vertex needs three numbers")),
            ["endloop"] => {
                if corners.len() != 3 {
                    return Err(at_line(path, line, "a facet without three vertices"));
                }
                triangles.push([corners[0], corners[1], corners[2]]);
                corners.clear();
            }
            ["solid", ..]
            | ["endsolid", ..]
            | ["facet", ..]
            | ["outer", "loop"]
            | ["endfacet"]
            | [] => {}
            _ => return Err(at_line(path, line, format!("unexpected `{}`", raw.trim()))),
        }
    }
    Ok((w.positions, triangles))
}

pub(super) fn write(mesh: &TriMesh) -> Vec<u8> {
    let mut out = Vec::with_capacity(84 + 50 * mesh.triangles().len());
    let mut header = [0u8; 80];
    let title = b"binary STL written by rbf";
    header[..title.len()].copy_from_slice(title);
    out.extend_from_slice(&header);
    out.extend_from_slice(&(mesh.triangles().len() as u32).to_le_bytes());
    for t in 0..mesh.triangles().len() {
        let [a, b, c] = mesh.corners(t);
        let n = cross(sub(b, a), sub(c, a));
        let l = norm(n);
        let n = if l > 0.0 { n.map(|x| x / l) } else { [0.0; 3] };
        for v in [n, a, b, c] {
            for x in v {
                out.extend_from_slice(&(x as f32).to_le_bytes());
            }
        }
        out.extend_from_slice(&[0, 0]);
    }
    out
}
