//! Wavefront OBJ through tobj, after a pass that gives malformed lines their line numbers.

use std::fmt::Write as _;
use std::path::Path;

use super::{at_line, number};
use crate::{MeshError, TriMesh};

type Parts = (Vec<[f64; 3]>, Vec<[u32; 3]>);

/// Checks the lines tobj would read, so that errors name a line: `v` needs three finite
/// numbers, `f` at least three corners whose vertex, texture and normal indices refer to
/// `v`, `vt` and `vn` lines defined so far (tobj multiplied a huge normal index into an
/// overflow: found by the obj fuzz target).
fn validate(path: &Path, text: &str) -> Result<(), MeshError> {
    let mut vertices: i64 = 0;
    let (mut textures, mut normals): (i64, i64) = (0, 0);
    for (i, raw) in text.lines().enumerate() {
        let line = i + 1;
        let mut tokens = raw.split_whitespace();
        match tokens.next() {
            Some("v") => {
                let coords: Vec<&str> = tokens.take(3).collect();
                if coords.len() < 3 {
                    return Err(at_line(path, line, "a vertex needs three coordinates"));
                }
                if let Some(t) = coords.iter().find(|t| number(t).is_none()) {
                    return Err(at_line(path, line, format!("`{t}` is not a finite number")));
                }
                vertices += 1;
            }
            Some("vt") => textures += 1,
            Some("vn") => normals += 1,
            Some("f") => {
                let corners: Vec<&str> = tokens.collect();
                if corners.len() < 3 {
                    return Err(at_line(path, line, "a face needs at least three vertices"));
                }
                for c in corners {
                    let mut parts = c.split('/');
                    let index = parts.next().unwrap_or("");
                    let Ok(v) = index.parse::<i64>() else {
                        return Err(at_line(path, line, format!("`{c}` is not a vertex index")));
                    };
                    let resolved = if v < 0 { vertices + v + 1 } else { v };
                    if v == 0 || resolved < 1 || resolved > vertices {
                        return Err(at_line(
                            path,
                            line,
                            format!(
                                "vertex index {v} is out of range: {vertices} vertices are defined so far"
                            ),
                        ));
                    }
                    for (part, defined, what) in [
                        (parts.next(), textures, "texture coordinates"),
                        (parts.next(), normals, "normals"),
                    ] {
                        let Some(part) = part.filter(|p| !p.is_empty()) else {
                            continue;
                        };
                        let resolved = part
                            .parse::<i64>()
                            .ok()
                            .map(|k| if k < 0 { defined + k + 1 } else { k });
                        if !resolved.is_some_and(|k| (1..=defined).contains(&k)) {
                            return Err(at_line(
                                path,
                                line,
                                format!(
                                    "`{c}`: index {part} is out of range: {defined} {what} are defined so far"
                                ),
                            ));
                        }
                    }
                }
            }
            _ => {}
        }
    }
    Ok(())
}

pub(super) fn read(path: &Path, bytes: &[u8]) -> Result<Parts, MeshError> {
    let text = std::str::from_utf8(bytes)
        .map_err(|e| super::at_byte(path, e.valid_up_to() as u64, "not UTF-8 text"))?;
    validate(path, text)?;
    let options = tobj::LoadOptions {
        triangulate: true,
        single_index: false,
        ignore_points: true,
        ignore_lines: true,
    };
    let mut reader = std::io::BufReader::new(bytes);
    let (models, _) = tobj::load_obj_buf(&mut reader, &options, |_| {
        Err(tobj::LoadError::OpenFileFailed)
    })
    .map_err(|e| at_line(path, 0, format!("{e}")))?;
    let mut positions = Vec::new();
    let mut triangles = Vec::new();
    // Each object of the file gets its own vertices from tobj; concatenate them.
    for m in models {
        let base = positions.len() as u32;
        positions.extend(m.mesh.positions.chunks_exact(3).map(|p| [p[0], p[1], p[2]]));
        triangles.extend(
            m.mesh
                .indices
                .chunks_exact(3)
                .map(|t| [t[0] + base, t[1] + base, t[2] + base]),
        );
    }
    Ok((positions, triangles))
}

pub(super) fn write(mesh: &TriMesh) -> Vec<u8> {
    let mut s = String::from("# written by rbf\n");
    s += &lines(mesh.positions(), |s, p| {
        let _ = writeln!(s, "v {} {} {}", p[0], p[1], p[2]);
    });
    if let Some(normals) = mesh.normals() {
        s += &lines(normals, |s, n| {
            let _ = writeln!(s, "vn {} {} {}", n[0], n[1], n[2]);
        });
        s += &lines(mesh.triangles(), |s, t| {
            let [a, b, c] = t.map(|i| i + 1);
            let _ = writeln!(s, "f {a}//{a} {b}//{b} {c}//{c}");
        });
    } else {
        s += &lines(mesh.triangles(), |s, t| {
            let [a, b, c] = t.map(|i| i + 1);
            let _ = writeln!(s, "f {a} {b} {c}");
        });
    }
    s.into_bytes()
}

/// The lines `line` writes for each item, in order, formatted in parallel chunks (shortest
/// round-trip formatting of floats is most of the writer's time).
fn lines<T: Sync>(items: &[T], line: impl Fn(&mut String, &T) + Sync) -> String {
    use rayon::prelude::*;
    let chunks: Vec<String> = items
        .par_chunks(8192)
        .map(|chunk| {
            let mut s = String::with_capacity(chunk.len() * 60);
            for item in chunk {
                line(&mut s, item);
            }
            s
        })
        .collect();
    chunks.concat()
}
