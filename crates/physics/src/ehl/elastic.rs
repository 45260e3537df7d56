//! Elastic deflection of the half-space under a line load distribution, in the Hertzian
//! dimensionless variables of [`super`]: `V(X) = (1/π) ∫ ln|X − X'| P(X') dX'`, so that the film is
//! `H = H0 + X²/2 − V` (seed 000 eq. 3 reduced to a line contact; Johnson eq. 2.25b).
//!
//! The pressure is taken piecewise constant on the cells of the (graded) grid — cell `j` spans the
//! midpoints between node `j` and its neighbours — and the integral over each cell is exact. The
//! Newton solver needs the whole influence matrix in its Jacobian anyway (the film at every node
//! depends on the pressure at every node), so the deflection is a dense product: `O(n²)` against
//! the `O(n³)` factorisation that dominates each Newton step.

/// Dense influence matrix, stored by columns: `col(j)[i] = ∫_{cell j} ln|X_i − X'| dX'`.
#[derive(Debug, Clone)]
pub struct Kernel {
    n: usize,
    by_column: Vec<f64>,
}

impl Kernel {
    /// The influence matrix of the nodes `x` (increasing). Cell `j` spans the midpoints
    /// `[m_j, m_{j+1}]` (`m_0 = x_0`, `m_n = x_{n−1}`), so `K_ij = F(x_i − m_j) − F(x_i − m_{j+1})`
    /// with `F(s) = s (ln|s| − 1)`: `n (n + 1)` logarithms.
    pub fn new(x: &[f64]) -> Self {
        let n = x.len();
        // ∫ ln|s| ds = s (ln|s| − 1); zero at s = 0.
        let f = |s: f64| if s == 0.0 { 0.0 } else { s * (s.abs().ln() - 1.0) };
        let mut mid = Vec::with_capacity(n + 1);
        mid.push(x[0]);
        for j in 1..n {
            mid.push(0.5 * (x[j - 1] + x[j]));
        }
        mid.push(x[n - 1]);
        let mut by_column = vec![0.0; n * n];
        let mut row = vec![0.0; n + 1];
        for i in 0..n {
            for (r, m) in row.iter_mut().zip(&mid) {
                *r = f(x[i] - m);
            }
            for j in 0..n {
                by_column[j * n + i] = row[j] - row[j + 1];
            }
        }
        Kernel { n, by_column }
    }

    /// `∫_{cell j} ln|X_i − X'| dX'` for every `i`.
    #[inline]
    pub fn column(&self, j: usize) -> &[f64] {
        &self.by_column[j * self.n..(j + 1) * self.n]
    }

    /// `V_i = (1/π) Σ_j K_ij P_j` for every node, written into `out`: a dense product over the
    /// columns from the first to the last non-zero `P_j` (faer's matrix–vector product, which
    /// picks the widest SIMD instructions of the machine at run time).
    pub fn deflection(&self, p: &[f64], out: &mut [f64]) {
        let n = self.n;
        let Some(j0) = p.iter().position(|&v| v != 0.0) else {
            out.iter_mut().for_each(|v| *v = 0.0);
            return;
        };
        let j1 = p.iter().rposition(|&v| v != 0.0).map_or(n, |j| j + 1);
        let k = faer::MatRef::from_column_major_slice(&self.by_column, n, n).subcols(j0, j1 - j0);
        let rhs = faer::MatRef::from_column_major_slice(&p[j0..j1], j1 - j0, 1);
        let dst = faer::MatMut::from_column_major_slice_mut(&mut out[..n], n, 1);
        faer::linalg::matmul::matmul(dst, faer::Accum::Replace, k, rhs, std::f64::consts::FRAC_1_PI, faer::Par::Seq);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The Hertzian pressure `sqrt(1 − X²)` deflects the surface into `X²/2 + const` inside the
    /// contact (that is what makes the dry film flat), on uniform and graded grids.
    #[test]
    fn hertz_pressure_flattens_the_film() {
        let n = 1201;
        for graded in [false, true] {
            let x: Vec<f64> = (0..n)
                .map(|i| {
                    let s = -1.0 + 2.0 * i as f64 / (n - 1) as f64;
                    if graded { 2.0 * (s + 0.3 * s * (1.0 - s * s)) } else { 2.0 * s }
                })
                .collect();
            let p: Vec<f64> = x.iter().map(|&x| (1.0 - x * x).max(0.0).sqrt()).collect();
            let k = Kernel::new(&x);
            let mut v = vec![0.0; n];
            k.deflection(&p, &mut v);
            let centre = n / 2;
            for i in 0..n {
                let gap = x[i] * x[i] / 2.0 - v[i] + v[centre];
                if x[i].abs() < 0.9 {
                    assert!(gap.abs() < 5e-4, "graded {graded}: gap {gap} at X = {}", x[i]);
                }
            }
            assert!(x[n - 1] * x[n - 1] / 2.0 - v[n - 1] + v[centre] > 0.1);
        }
    }
}
