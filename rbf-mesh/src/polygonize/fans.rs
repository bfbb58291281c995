//! The triangles around each vertex, for the simplification's collapses and flips: every
//! vertex's list in one array (a slice each, with room to grow), instead of a heap allocation
//! per vertex. A list that outgrows its room moves to the end of the array with twice the room;
//! the space it leaves is not reused (lists grow rarely and little).

/// The triangles around each vertex.
pub(crate) struct Fans {
    /// Where each vertex's list starts in `data`, how long it is, and its room.
    start: Vec<u32>,
    len: Vec<u32>,
    room: Vec<u32>,
    data: Vec<u32>,
}

impl Fans {
    /// The fans of `vertices` vertices under `triangles` (triangle t in the lists of its three
    /// corners, in order of t).
    pub(crate) fn new(vertices: usize, triangles: &[[u32; 3]]) -> Self {
        let mut len = vec![0u32; vertices];
        for t in triangles {
            for &v in t {
                len[v as usize] += 1;
            }
        }
        // Room for a few more: a vertex that stays takes the other's triangles.
        let room: Vec<u32> = len.iter().map(|&l| l + l / 2 + 2).collect();
        let mut start = Vec::with_capacity(vertices);
        let mut end = 0u32;
        for &r in &room {
            start.push(end);
            end += r;
        }
        let mut data = vec![0u32; end as usize];
        len.fill(0);
        for (t, tri) in triangles.iter().enumerate() {
            for &v in tri {
                let v = v as usize;
                data[(start[v] + len[v]) as usize] = t as u32;
                len[v] += 1;
            }
        }
        Self {
            start,
            len,
            room,
            data,
        }
    }

    /// The triangles around v (dead ones included until removed).
    #[inline]
    pub(crate) fn of(&self, v: u32) -> &[u32] {
        let v = v as usize;
        let s = self.start[v] as usize;
        &self.data[s..s + self.len[v] as usize]
    }

    /// Whether v has no triangles.
    pub(crate) fn is_empty(&self, v: u32) -> bool {
        self.len[v as usize] == 0
    }

    /// Adds triangle t to v's list.
    pub(crate) fn push(&mut self, v: u32, t: u32) {
        let i = v as usize;
        if self.len[i] == self.room[i] {
            let (s, l) = (self.start[i] as usize, self.len[i] as usize);
            let moved = self.data.len();
            self.data.extend_from_within(s..s + l);
            self.data.resize(moved + 2 * l.max(2), 0);
            self.start[i] = moved as u32;
            self.room[i] = 2 * l.max(2) as u32;
        }
        let at = (self.start[i] + self.len[i]) as usize;
        self.data[at] = t;
        self.len[i] += 1;
    }

    /// Keeps in v's list the triangles `keep` accepts, in order.
    pub(crate) fn retain(&mut self, v: u32, mut keep: impl FnMut(u32) -> bool) {
        let i = v as usize;
        let s = self.start[i] as usize;
        let mut kept = 0;
        for k in 0..self.len[i] as usize {
            let t = self.data[s + k];
            if keep(t) {
                self.data[s + kept] = t;
                kept += 1;
            }
        }
        self.len[i] = kept as u32;
    }

    /// Empties v's list into `out` (cleared first).
    pub(crate) fn take_into(&mut self, v: u32, out: &mut Vec<u32>) {
        out.clear();
        out.extend_from_slice(self.of(v));
        self.len[v as usize] = 0;
    }
}
