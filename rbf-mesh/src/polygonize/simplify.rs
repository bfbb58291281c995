//! Fewer and better triangles than the Kuhn lattice gives: its six tetrahedra per cube put a
//! vertex on every crossed diagonal as well as on the crossed axis edges (about twice the
//! vertices of marching cubes on the same lattice), and where the surface passes near a lattice
//! point they crowd around it, within a hair of each other, with needle triangles between them.
//!
//! Edges are collapsed shortest first, one end merged into the other (no vertex moves, so every
//! vertex stays on the surface where root finding puts it). A collapse is made only when the
//! link condition holds (the two ends share exactly the two neighbours across the edge) and no
//! triangle would fold onto another, which keeps a closed manifold closed and its topology
//! unchanged;
//! when no remaining triangle turns by more than 60° or (for edges longer than [`SHORT`] of a
//! cell, whose collapse moves a corner noticeably) is left with an angle below [`MIN_ANGLE`]
//! that it did not already have; and never at the mesh's border (where the box cuts an open
//! surface). It stops when the
//! vertices are down to the target (about marching cubes' count) and every edge shorter than a
//! fraction of the cell is gone, or no allowed collapse remains.

use rayon::prelude::*;

use super::fans::Fans;
use rbf_core::vec3::{Vec3, cross, dot, norm, sub};

/// Smallest angle, in degrees, that a collapse may create.
pub(crate) const MIN_ANGLE: f64 = 10.0;
/// Edges shorter than this fraction of a cell are collapsed whatever the vertex count.
const SHORT: f64 = 0.2;
/// No edge longer than this fraction of a cell is collapsed.
const LONGEST: f64 = 1.0;

/// Collapses edges of the mesh until at most `target` vertices remain (or no allowed collapse
/// of an edge shorter than [`LONGEST`] cells does). Returns, per old vertex, the vertex it was
/// merged into (itself if kept), and the triangles left (on old indices).
///
/// A large mesh is first collapsed in parts, in parallel (see [`collapse_in_parts`]), then as
/// a whole.
pub(crate) fn collapse(
    positions: &[Vec3],
    triangles: Vec<[u32; 3]>,
    cell: f64,
    target: usize,
) -> (Vec<u32>, Vec<[u32; 3]>) {
    let n = positions.len();
    // Triangles in the order of their vertices (the lattice's): the checks then walk memory
    // that is near in the lattice, which takes the collapse about two thirds of the time on a
    // mesh too large for the caches (a small one, as the studio's, only pays for the sort).
    let mut triangles = triangles;
    if n >= 2 * PART {
        triangles.par_sort_unstable_by_key(|t| t[0].min(t[1]).min(t[2]));
    }
    let (mut merged, triangles) = collapse_in_parts(positions, triangles, cell, target);
    let (merged_whole, triangles) =
        collapse_whole(positions, &vec![false; n], triangles, cell, target);
    for v in 0..n {
        if merged[v] as usize == v {
            merged[v] = merged_whole[v];
        }
    }
    // Follow chains of merges to the vertex that survived.
    for v in 0..n {
        let mut r = merged[v];
        while merged[r as usize] != r {
            r = merged[r as usize];
        }
        merged[v] = r;
    }
    (merged, triangles)
}

/// Lists shorter than this are sorted in one thread: rayon's sort then only adds its overhead
/// (and WebAssembly, the studio's, has one thread).
pub(crate) const PARALLEL_SORT: usize = 1 << 16;

/// Vertices in each part of [`collapse_in_parts`], at least.
const PART: usize = 16_384;

/// Collapses a large mesh in up to eight parts at once. Vertices are numbered along the
/// lattice (x, then y, then z), so consecutive ranges of them are slabs of the box. A part is
/// a range with the triangles wholly in it; the vertices of triangles that cross from one part
/// to another are frozen (neither removed nor kept in place of another), so that every check a
/// part makes sees all the triangles it concerns. The parts are fixed by the vertex count, not
/// by the threads, so the mesh does not depend on the machine.
fn collapse_in_parts(
    positions: &[Vec3],
    triangles: Vec<[u32; 3]>,
    cell: f64,
    target: usize,
) -> (Vec<u32>, Vec<[u32; 3]>) {
    let n = positions.len();
    let parts = (n / PART).min(8);
    let mut merged: Vec<u32> = (0..n as u32).collect();
    if parts < 2 {
        return (merged, triangles);
    }
    // In u64: products of counts can pass u32 where usize is 32 bits (WebAssembly).
    let part_of = |v: u32| (v as u64 * parts as u64 / n as u64) as usize;
    let first = |p: usize| (p as u64 * n as u64).div_ceil(parts as u64) as usize;
    let mut frozen = vec![false; n];
    let mut inside: Vec<Vec<[u32; 3]>> = vec![Vec::new(); parts];
    let mut seam = Vec::new();
    for t in triangles {
        let p = part_of(t[0]);
        if t.iter().all(|&v| part_of(v) == p) {
            inside[p].push(t);
        } else {
            for v in t {
                frozen[v as usize] = true;
            }
            seam.push(t);
        }
    }
    let collapsed: Vec<(Vec<u32>, Vec<[u32; 3]>)> = inside
        .into_par_iter()
        .enumerate()
        .map(|(p, tris)| {
            let (lo, hi) = (first(p), first(p + 1));
            let local = tris.into_iter().map(|t| t.map(|v| v - lo as u32)).collect();
            let part_target = (target as u64 * (hi - lo) as u64 / n as u64) as usize;
            let (merged, tris) = collapse_whole(
                &positions[lo..hi],
                &frozen[lo..hi],
                local,
                cell,
                part_target,
            );
            (
                merged.into_iter().map(|v| v + lo as u32).collect(),
                tris.into_iter().map(|t| t.map(|v| v + lo as u32)).collect(),
            )
        })
        .collect();
    let mut triangles = seam;
    for (p, (part_merged, part_triangles)) in collapsed.into_iter().enumerate() {
        merged[first(p)..first(p + 1)].copy_from_slice(&part_merged);
        triangles.extend(part_triangles);
    }
    (merged, triangles)
}

/// [`collapse`] in one piece, leaving `frozen` vertices alone. Merges are not yet followed
/// to their ends.
fn collapse_whole(
    positions: &[Vec3],
    frozen: &[bool],
    triangles: Vec<[u32; 3]>,
    cell: f64,
    target: usize,
) -> (Vec<u32>, Vec<[u32; 3]>) {
    let n = positions.len();
    let mut triangles = triangles;
    let mut alive = vec![true; triangles.len()];
    let mut around = Fans::new(n, &triangles);
    let mut merged: Vec<u32> = (0..n as u32).collect();
    let mut vertices = (0..n as u32).filter(|&v| !around.is_empty(v)).count();
    // Collapses, then flips of what collapses cannot reach, then collapses of what flips freed.
    for _ in 0..2 {
        collapse_edges(
            positions,
            frozen,
            cell,
            target,
            &mut triangles,
            &mut alive,
            &mut around,
            &mut merged,
            &mut vertices,
        );
        flip_slivers(positions, frozen, &mut triangles, &alive, &mut around);
    }
    let kept = triangles
        .into_iter()
        .zip(alive)
        .filter_map(|(t, a)| a.then_some(t))
        .collect();
    (merged, kept)
}

/// Collapses edges, shortest first (see the module's documentation).
#[allow(clippy::too_many_arguments)]
fn collapse_edges(
    positions: &[Vec3],
    frozen: &[bool],
    cell: f64,
    target: usize,
    triangles: &mut [[u32; 3]],
    alive: &mut [bool],
    around: &mut Fans,
    merged: &mut [u32],
    vertices: &mut usize,
) {
    let length = |a: u32, b: u32| norm(sub(positions[a as usize], positions[b as usize]));
    let short = SHORT * cell;
    // Edges by length, sorted once: an edge made by a collapse waits for the next call.
    let longest = if *vertices <= target {
        short
    } else {
        LONGEST * cell
    };
    let mut edges: Vec<(f64, u32, u32)> = triangles
        .iter()
        .zip(alive.iter())
        .filter(|(_, a)| **a)
        .flat_map(|(tri, _)| (0..3).map(move |k| (tri[k], tri[(k + 1) % 3])))
        // Each inner edge appears once each way round; border edges are refused anyway.
        .filter(|&(a, b)| a < b)
        .map(|(a, b)| (length(a, b), a, b))
        .filter(|e| e.0 < longest)
        .collect();
    // Lengths are positive, so their bits sort as they do; the ends break ties, so that the
    // order is the same whichever sort runs.
    let key = |e: &(f64, u32, u32)| (e.0.to_bits(), e.1, e.2);
    if edges.len() >= PARALLEL_SORT {
        edges.par_sort_unstable_by_key(key);
    } else {
        edges.sort_unstable_by_key(key);
    }
    let mut scratch = Scratch::new(positions.len());
    let mut moved = Vec::new();
    for (l, a, b) in edges {
        if *vertices <= target && l >= short {
            break;
        }
        if merged[a as usize] != a || merged[b as usize] != b {
            continue;
        }
        if frozen[a as usize] || frozen[b as usize] {
            continue;
        }
        for (from, to) in [(a, b), (b, a)] {
            let across = match collapsible(
                positions,
                cell,
                &*triangles,
                &*around,
                from,
                to,
                &mut scratch,
            ) {
                Ok(across) => across,
                Err(Refusal::Edge) => break,
                Err(Refusal::Direction) => continue,
            };
            // Merge `from` into `to`.
            for &t in &across {
                alive[t as usize] = false;
                // The vertex across keeps only live triangles in its list.
                for w in triangles[t as usize] {
                    if w != from && w != to {
                        around.retain(w, |u| u != t);
                    }
                }
            }
            around.take_into(from, &mut moved);
            for &t in &moved {
                if !alive[t as usize] {
                    continue;
                }
                for v in triangles[t as usize].iter_mut() {
                    if *v == from {
                        *v = to;
                    }
                }
                around.push(to, t);
            }
            around.retain(to, |t| alive[t as usize]);
            merged[from as usize] = to;
            *vertices -= 1;
            break;
        }
    }
}

/// Buffers reused by every [`collapsible`] check, so that checks allocate nothing.
struct Scratch {
    /// A mark per vertex: the vertices marked with the current mark are a set, emptied in
    /// O(1) by taking the next mark.
    mark: Vec<u32>,
    current: u32,
}

impl Scratch {
    fn new(vertices: usize) -> Self {
        Self {
            mark: vec![0; vertices],
            current: 0,
        }
    }

    /// A new, empty set.
    fn next_mark(&mut self) -> u32 {
        if self.current == u32::MAX {
            self.mark.fill(0);
            self.current = 0;
        }
        self.current += 1;
        self.current
    }
}

/// Calls `visit` for each vertex joined to v by an edge (a vertex once per triangle it shares
/// with v). The fans hold live triangles only: a collapse takes the two that vanish out of
/// every list, a flip moves its two between lists.
fn for_each_neighbour(triangles: &[[u32; 3]], around: &Fans, v: u32, mut visit: impl FnMut(u32)) {
    for &t in around.of(v) {
        for w in triangles[t as usize] {
            if w != v {
                visit(w);
            }
        }
    }
}

/// Marks the vertices joined to v by an edge with a new mark; returns the mark and how many
/// they are.
fn mark_neighbours(
    triangles: &[[u32; 3]],
    around: &Fans,
    v: u32,
    scratch: &mut Scratch,
) -> (u32, usize) {
    let m = scratch.next_mark();
    let mut count = 0;
    for_each_neighbour(triangles, around, v, |w| {
        if scratch.mark[w as usize] != m {
            scratch.mark[w as usize] = m;
            count += 1;
        }
    });
    (m, count)
}

/// How many of the vertices joined to v by an edge carry mark `m`.
fn count_marked_neighbours(
    triangles: &[[u32; 3]],
    around: &Fans,
    v: u32,
    m: u32,
    scratch: &mut Scratch,
) -> usize {
    // Each one counted is moved to a new mark, so that it counts once.
    let counted = scratch.next_mark();
    let mut count = 0;
    for_each_neighbour(triangles, around, v, |w| {
        if scratch.mark[w as usize] == m {
            scratch.mark[w as usize] = counted;
            count += 1;
        }
    });
    count
}

/// Why a collapse was refused.
enum Refusal {
    /// Not an inner edge, or the link condition fails: the other way round too.
    Edge,
    /// Not this way round (`from` on the border, or a triangle would turn or thin).
    Direction,
}

/// If merging `from` into `to` is allowed, the two triangles that vanish.
fn collapsible(
    positions: &[Vec3],
    cell: f64,
    triangles: &[[u32; 3]],
    around: &Fans,
    from: u32,
    to: u32,
    scratch: &mut Scratch,
) -> Result<[u32; 2], Refusal> {
    let fan = around.of(from);
    let (mut shared, mut sharing) = ([0u32; 2], 0);
    for &t in fan {
        if triangles[t as usize].contains(&to) {
            if sharing < 2 {
                shared[sharing] = t;
            }
            sharing += 1;
        }
    }
    if sharing != 2 {
        return Err(Refusal::Edge); // the border, or not an edge
    }
    // Every edge at `from` must have two triangles (no border vertex is removed): a closed fan
    // has as many triangles as neighbours, an open one a neighbour more.
    let (ring, ring_size) = mark_neighbours(triangles, around, from, scratch);
    if ring_size != fan.len() {
        return Err(Refusal::Direction);
    }
    // Link condition: the ends' common neighbours are the two vertices across the edge.
    let opposite = shared.map(|t| {
        triangles[t as usize]
            .into_iter()
            .find(|&w| w != from && w != to)
            .unwrap_or(from)
    });
    let common = count_marked_neighbours(triangles, around, to, ring, scratch);
    if common != 2 || opposite[0] == opposite[1] {
        return Err(Refusal::Edge);
    }
    // A fold: two triangles back to back, as when a tetrahedron-like piece collapses, which
    // the link condition alone lets through. Under it the only vertices joined to both ends
    // are the two across, so a triangle made by the merge can only repeat one at `to` as
    // (to, across, across), made from (from, across, across).
    let across_both = |t: u32, v: u32| {
        let tri = triangles[t as usize];
        tri.contains(&v) && tri.contains(&opposite[0]) && tri.contains(&opposite[1])
    };
    if fan.iter().any(|&t| across_both(t, from))
        && around.of(to).iter().any(|&t| across_both(t, to))
    {
        return Err(Refusal::Direction);
    }
    // No triangle may turn over or become a sliver. A triangle too small to have a reliable
    // normal of its own is compared with the area-weighted normal around `from`.
    let p = |v: u32| positions[v as usize];
    let normal_of = |t: [u32; 3]| cross(sub(p(t[1]), p(t[0])), sub(p(t[2]), p(t[0])));
    let around_normal = || {
        fan.iter().fold([0.0; 3], |sum, &t| {
            let n = normal_of(triangles[t as usize]);
            [sum[0] + n[0], sum[1] + n[1], sum[2] + n[2]]
        })
    };
    let tiny = 1e-8 * cell * cell;
    let short = norm(sub(p(from), p(to))) < SHORT * cell;
    for &t in fan {
        if shared.contains(&t) {
            continue;
        }
        let old = triangles[t as usize];
        let new = old.map(|v| if v == from { to } else { v });
        let (mut n_old, n_new) = (normal_of(old), normal_of(new));
        if norm(n_old) < tiny {
            n_old = around_normal();
        }
        let (l_old, l_new) = (norm(n_old), norm(n_new));
        if !(l_new > 0.0) || dot(n_old, n_new) < 0.5 * l_old * l_new {
            return Err(Refusal::Direction);
        }
        // A short edge's collapse moves a vertex too little to matter; longer ones must not
        // make slivers. A triangle left with no angle under the least is never refused (and
        // its test takes no square root).
        if !short && is_sliver(new.map(p)) {
            let before = largest_cosine(old.map(p));
            if largest_cosine(new.map(p)) > min_cosine().max(before) {
                return Err(Refusal::Direction);
            }
        }
    }
    Ok(shared)
}

/// Flips the longest edge of each triangle with an angle below [`MIN_ANGLE`] (a cap: one
/// vertex near its opposite edge, which no short edge can remove) when the flip raises the
/// smallest angle of the pair, turns neither triangle by more than 60° and makes no edge twice.
fn flip_slivers(
    positions: &[Vec3],
    frozen: &[bool],
    triangles: &mut [[u32; 3]],
    alive: &[bool],
    around: &mut Fans,
) {
    let p = |v: u32| positions[v as usize];
    let normal_of = |t: [u32; 3]| cross(sub(p(t[1]), p(t[0])), sub(p(t[2]), p(t[0])));
    // Only slivers, and the triangles that flips make, are looked at again.
    let mut candidates: Vec<usize> = (0..triangles.len())
        .filter(|&t| alive[t] && is_sliver(triangles[t].map(p)))
        .collect();
    for _pass in 0..3 {
        let mut flipped = 0;
        let mut again = Vec::new();
        for &t1 in &candidates {
            if !alive[t1] || !is_sliver(triangles[t1].map(p)) {
                continue;
            }
            again.push(t1);
            // The longest edge a → b, and c across it.
            let tri = triangles[t1];
            let k = (0..3)
                .max_by(|&i, &j| {
                    let l = |k: usize| norm(sub(p(tri[(k + 1) % 3]), p(tri[k])));
                    l(i).total_cmp(&l(j))
                })
                .unwrap_or(0);
            let (a, b, c) = (tri[k], tri[(k + 1) % 3], tri[(k + 2) % 3]);
            if frozen[a as usize] || frozen[b as usize] || frozen[c as usize] {
                continue;
            }
            let Some(&t2) = around.of(b).iter().find(|&&t| {
                let o = triangles[t as usize];
                t as usize != t1
                    && alive[t as usize]
                    && (0..3).any(|i| o[i] == b && o[(i + 1) % 3] == a)
            }) else {
                continue;
            };
            let t2 = t2 as usize;
            let Some(d) = triangles[t2].into_iter().find(|&w| w != a && w != b) else {
                continue;
            };
            let exists = around
                .of(c)
                .iter()
                .any(|&t| alive[t as usize] && triangles[t as usize].contains(&d));
            if exists || c == d || frozen[d as usize] {
                continue;
            }
            let (new1, new2) = ([c, a, d], [d, b, c]);
            let old_normal = {
                let (x, y) = (normal_of(tri), normal_of(triangles[t2]));
                [x[0] + y[0], x[1] + y[1], x[2] + y[2]]
            };
            let turned = [new1, new2].iter().any(|&t| {
                let n = normal_of(t);
                !(dot(n, old_normal) > 0.5 * norm(n) * norm(old_normal))
            });
            let before = largest_cosine(tri.map(p)).max(largest_cosine(triangles[t2].map(p)));
            let after = largest_cosine(new1.map(p)).max(largest_cosine(new2.map(p)));
            if turned || after >= before {
                continue;
            }
            triangles[t1] = new1;
            triangles[t2] = new2;
            around.retain(a, |t| t as usize != t2);
            around.retain(b, |t| t as usize != t1);
            around.push(c, t2 as u32);
            around.push(d, t1 as u32);
            again.push(t2);
            flipped += 1;
        }
        if flipped == 0 {
            break;
        }
        again.sort_unstable();
        again.dedup();
        candidates = again;
    }
}

/// The cosine of [`MIN_ANGLE`].
fn min_cosine() -> f64 {
    MIN_ANGLE.to_radians().cos()
}

/// Whether a triangle has an angle below [`MIN_ANGLE`] (or is degenerate), without a square
/// root: the cosine at a corner exceeds c when a·b > 0 and (a·b)² > c² |a|² |b|².
fn is_sliver(t: [Vec3; 3]) -> bool {
    let c = min_cosine();
    (0..3).any(|k| {
        let (a, b) = (sub(t[(k + 1) % 3], t[k]), sub(t[(k + 2) % 3], t[k]));
        let (ab, aa, bb) = (dot(a, b), dot(a, a), dot(b, b));
        !(aa > 0.0 && bb > 0.0) || (ab > 0.0 && ab * ab > c * c * aa * bb)
    })
}

/// The cosine of a triangle's smallest angle (1 for a degenerate one).
pub(crate) fn largest_cosine(t: [Vec3; 3]) -> f64 {
    (0..3)
        .map(|k| {
            let (a, b) = (sub(t[(k + 1) % 3], t[k]), sub(t[(k + 2) % 3], t[k]));
            let c = dot(a, b) / (dot(a, a) * dot(b, b)).sqrt();
            if c.is_finite() { c } else { 1.0 }
        })
        .fold(-1.0, f64::max)
}

/// Flips an edge of each triangle that faces against its vertices' normals (root finding moved
/// its vertices after a collapse decided on their estimates) when the flip leaves both
/// triangles facing with their normals and makes no edge twice. Returns how many remain.
pub(crate) fn unfold(positions: &[Vec3], normals: &[Vec3], triangles: &mut [[u32; 3]]) -> usize {
    let p = |v: u32| positions[v as usize];
    let facing = |t: [u32; 3]| {
        let n = cross(sub(p(t[1]), p(t[0])), sub(p(t[2]), p(t[0])));
        t.iter().map(|&v| dot(n, normals[v as usize])).sum::<f64>() > 0.0
    };
    let folded: Vec<usize> = (0..triangles.len())
        .filter(|&t| !facing(triangles[t]))
        .collect();
    if folded.is_empty() {
        return 0;
    }
    let mut edges: std::collections::HashMap<(u32, u32), usize> = std::collections::HashMap::new();
    for (i, t) in triangles.iter().enumerate() {
        for k in 0..3 {
            edges.insert((t[k], t[(k + 1) % 3]), i);
        }
    }
    let mut left = 0;
    for t1 in folded {
        let tri = triangles[t1];
        if facing(tri) {
            continue;
        }
        let mut fixed = false;
        for k in 0..3 {
            let (a, b, c) = (tri[k], tri[(k + 1) % 3], tri[(k + 2) % 3]);
            let Some(&t2) = edges.get(&(b, a)) else {
                continue;
            };
            let Some(d) = triangles[t2].into_iter().find(|&w| w != a && w != b) else {
                continue;
            };
            if c == d || edges.contains_key(&(c, d)) || edges.contains_key(&(d, c)) {
                continue;
            }
            let (new1, new2) = ([c, a, d], [d, b, c]);
            if !(facing(new1) && facing(new2)) {
                continue;
            }
            let old2 = triangles[t2];
            for old in [tri, old2] {
                for k in 0..3 {
                    edges.remove(&(old[k], old[(k + 1) % 3]));
                }
            }
            triangles[t1] = new1;
            triangles[t2] = new2;
            for (t, new) in [(t1, new1), (t2, new2)] {
                for k in 0..3 {
                    edges.insert((new[k], new[(k + 1) % 3]), t);
                }
            }
            fixed = true;
            break;
        }
        left += usize::from(!fixed);
    }
    left
}
