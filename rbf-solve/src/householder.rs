//! The Householder QR of the polynomial block P (K × m, m = D + 1) in compact WY form,
//! Q = H₀H₁…H_{m−1} = I − V T Vᵀ, which splits weights into the m directions that the side
//! conditions Pᵀw = 0 fix and the K − m directions where the kernel block is definite.

/// Q = I − V T Vᵀ and R of P = Q [R; 0].
pub(crate) struct Reflector {
    rows: usize,
    m: usize,
    /// V, column-major K × m; column k is zero above row k.
    v: Vec<f64>,
    /// T, m × m upper triangular, row-major.
    t: Vec<f64>,
    /// R, m × m upper triangular, row-major.
    r: Vec<f64>,
}

impl Reflector {
    /// Factors P given column-major (K × m).
    pub(crate) fn new(mut p: Vec<f64>, rows: usize, m: usize) -> Self {
        let k_rows = rows;
        let mut v = vec![0.0; k_rows * m];
        let mut tau = vec![0.0; m];
        for k in 0..m {
            let col = &p[k * k_rows + k..(k + 1) * k_rows];
            let norm = col.iter().map(|x| x * x).sum::<f64>().sqrt();
            let alpha = if col[0] >= 0.0 { -norm } else { norm };
            let vk = &mut v[k * k_rows..(k + 1) * k_rows];
            vk[k..].copy_from_slice(col);
            vk[k] -= alpha;
            let vv: f64 = vk[k..].iter().map(|x| x * x).sum();
            tau[k] = if vv > 0.0 { 2.0 / vv } else { 0.0 };
            // Apply H_k to columns k..m of P.
            for j in k..m {
                let pj = &mut p[j * k_rows..(j + 1) * k_rows];
                let dot: f64 = vk[k..].iter().zip(&pj[k..]).map(|(a, b)| a * b).sum();
                let s = tau[k] * dot;
                for (x, a) in pj[k..].iter_mut().zip(&vk[k..]) {
                    *x -= s * a;
                }
            }
        }
        let mut r = vec![0.0; m * m];
        for i in 0..m {
            for j in i..m {
                r[i * m + j] = p[j * k_rows + i];
            }
        }
        // T[0..k, k] = −τ_k T[0..k, 0..k] V[:, 0..k]ᵀ v_k, T[k, k] = τ_k.
        let mut t = vec![0.0; m * m];
        for k in 0..m {
            let vk = &v[k * k_rows..(k + 1) * k_rows];
            let z: Vec<f64> = (0..k)
                .map(|i| {
                    let vi = &v[i * k_rows..(i + 1) * k_rows];
                    vi.iter().zip(vk).map(|(a, b)| a * b).sum()
                })
                .collect();
            for i in 0..k {
                let s: f64 = (i..k).map(|j| t[i * m + j] * z[j]).sum();
                t[i * m + k] = -tau[k] * s;
            }
            t[k * m + k] = tau[k];
        }
        Self {
            rows: k_rows,
            m,
            v,
            t,
            r,
        }
    }

    pub(crate) fn v(&self) -> &[f64] {
        &self.v
    }

    /// T (row-major m × m).
    pub(crate) fn t(&self) -> &[f64] {
        &self.t
    }

    /// R[i][j].
    pub(crate) fn r(&self, i: usize, j: usize) -> f64 {
        self.r[i * self.m + j]
    }

    /// Vᵀx.
    fn vt(&self, x: &[f64]) -> Vec<f64> {
        (0..self.m)
            .map(|k| {
                let vk = &self.v[k * self.rows..(k + 1) * self.rows];
                vk[k..].iter().zip(&x[k..]).map(|(a, b)| a * b).sum()
            })
            .collect()
    }

    /// x ← x − V y.
    fn sub_v(&self, x: &mut [f64], y: &[f64]) {
        for (k, yk) in y.iter().enumerate() {
            let vk = &self.v[k * self.rows..(k + 1) * self.rows];
            for (xi, vi) in x[k..].iter_mut().zip(&vk[k..]) {
                *xi -= yk * vi;
            }
        }
    }

    /// x ← Qᵀx = x − V Tᵀ Vᵀ x.
    pub(crate) fn apply_qt(&self, x: &mut [f64]) {
        let z = self.vt(x);
        let m = self.m;
        let y: Vec<f64> = (0..m)
            .map(|i| (0..=i).map(|j| self.t[j * m + i] * z[j]).sum())
            .collect();
        self.sub_v(x, &y);
    }

    /// x ← Qx = x − V T Vᵀ x.
    pub(crate) fn apply_q(&self, x: &mut [f64]) {
        let z = self.vt(x);
        let m = self.m;
        let y: Vec<f64> = (0..m)
            .map(|i| (i..m).map(|j| self.t[i * m + j] * z[j]).sum())
            .collect();
        self.sub_v(x, &y);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn q_is_orthogonal_and_triangularizes_p() {
        let rows = 7;
        let m = 3;
        let p: Vec<f64> = (0..rows * m)
            .map(|i| ((i * 37 % 11) as f64 - 5.0) / 3.0)
            .collect();
        let q = Reflector::new(p.clone(), rows, m);
        // Qᵀ P = [R; 0].
        for j in 0..m {
            let mut col = p[j * rows..(j + 1) * rows].to_vec();
            q.apply_qt(&mut col);
            for i in 0..rows {
                let expected = if i < m { q.r(i, j) } else { 0.0 };
                assert!((col[i] - expected).abs() < 1e-12, "({i},{j})");
            }
        }
        // Q Qᵀ x = x.
        let x: Vec<f64> = (0..rows).map(|i| i as f64 * 0.7 - 1.0).collect();
        let mut y = x.clone();
        q.apply_qt(&mut y);
        q.apply_q(&mut y);
        for (a, b) in x.iter().zip(&y) {
            assert!((a - b).abs() < 1e-12);
        }
    }
}
