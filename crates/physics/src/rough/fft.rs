//! Periodic convolution on the surface grid by 2-D FFT (rustfft along rows, a transpose, rustfft
//! along columns): the influence-coefficient products `u = K p` of the normal and tangential
//! problems, with `K` given by its Fourier multiplier (the periodic half-space response).

use rustfft::num_complex::Complex;
use rustfft::{Fft, FftPlanner};
use std::sync::Arc;

pub(crate) struct Fft2 {
    nx: usize,
    ny: usize,
    fx: Arc<dyn Fft<f64>>,
    ix: Arc<dyn Fft<f64>>,
    fy: Arc<dyn Fft<f64>>,
    iy: Arc<dyn Fft<f64>>,
}

/// Buffers of one user of an [`Fft2`] (one per thread).
pub(crate) struct Workspace {
    tmp: Vec<Complex<f64>>,
    pub(crate) scratch: Vec<Complex<f64>>,
}

impl Fft2 {
    pub(crate) fn new(nx: usize, ny: usize) -> Self {
        let mut planner = FftPlanner::new();
        Fft2 {
            nx,
            ny,
            fx: planner.plan_fft_forward(nx),
            ix: planner.plan_fft_inverse(nx),
            fy: planner.plan_fft_forward(ny),
            iy: planner.plan_fft_inverse(ny),
        }
    }

    pub(crate) fn workspace(&self) -> Workspace {
        let s = [&self.fx, &self.ix, &self.fy, &self.iy].iter().map(|f| f.get_inplace_scratch_len()).max().unwrap_or(0);
        Workspace { tmp: vec![Complex::new(0.0, 0.0); self.nx * self.ny], scratch: vec![Complex::new(0.0, 0.0); s] }
    }

    /// Angular wavenumbers `2π m/L` of the x index (m wrapped to `[−n/2, n/2)`), rad/m.
    pub(crate) fn wavenumbers_x(&self, spacing: f64) -> Vec<f64> {
        wavenumbers(self.nx, spacing)
    }
    pub(crate) fn wavenumbers_y(&self, spacing: f64) -> Vec<f64> {
        wavenumbers(self.ny, spacing)
    }

    /// Row-major `[j·nx + i]` in, spectrum in the transposed layout `[i·ny + j]` out.
    pub(crate) fn forward(&self, buf: &mut [Complex<f64>], w: &mut Workspace) {
        self.fx.process_with_scratch(buf, &mut w.scratch);
        transpose(buf, &mut w.tmp, self.nx, self.ny);
        self.fy.process_with_scratch(&mut w.tmp, &mut w.scratch);
        buf.copy_from_slice(&w.tmp);
    }

    /// Transposed spectrum in, row-major values out, normalised (inverse of [`Fft2::forward`]).
    pub(crate) fn inverse(&self, buf: &mut [Complex<f64>], w: &mut Workspace) {
        self.iy.process_with_scratch(buf, &mut w.scratch);
        transpose(buf, &mut w.tmp, self.ny, self.nx);
        self.ix.process_with_scratch(&mut w.tmp, &mut w.scratch);
        let s = 1.0 / (self.nx * self.ny) as f64;
        for (b, t) in buf.iter_mut().zip(&w.tmp) {
            *b = t * s;
        }
    }
}

fn wavenumbers(n: usize, spacing: f64) -> Vec<f64> {
    let l = n as f64 * spacing;
    (0..n)
        .map(|m| {
            let m = if m < n.div_ceil(2) { m as f64 } else { m as f64 - n as f64 };
            2.0 * std::f64::consts::PI * m / l
        })
        .collect()
}

/// `src` holds `rows` rows of `cols` values; `dst` gets its transpose (`cols` rows of `rows`).
fn transpose(src: &[Complex<f64>], dst: &mut [Complex<f64>], cols: usize, rows: usize) {
    const B: usize = 32;
    for r0 in (0..rows).step_by(B) {
        for c0 in (0..cols).step_by(B) {
            for r in r0..(r0 + B).min(rows) {
                for c in c0..(c0 + B).min(cols) {
                    dst[c * rows + r] = src[r * cols + c];
                }
            }
        }
    }
}

/// A periodic convolution operator given by a real, even Fourier multiplier (so that real input
/// gives real output and the operator is symmetric).
pub(crate) struct Convolution {
    fft: Fft2,
    /// Multiplier in the transposed spectral layout `[i·ny + j]`.
    multiplier: Vec<f64>,
    /// Diagonal of the operator (the self-influence coefficient), mean of the multiplier.
    pub(crate) diagonal: f64,
}

impl Convolution {
    /// `multiplier(kx, ky)` at each grid wavenumber (rad/m).
    pub(crate) fn new(nx: usize, ny: usize, spacing: f64, multiplier: impl Fn(f64, f64) -> f64) -> Self {
        let fft = Fft2::new(nx, ny);
        let (kx, ky) = (fft.wavenumbers_x(spacing), fft.wavenumbers_y(spacing));
        let mut m = vec![0.0; nx * ny];
        for i in 0..nx {
            for j in 0..ny {
                m[i * ny + j] = multiplier(kx[i], ky[j]);
            }
        }
        let diagonal = m.iter().sum::<f64>() / m.len() as f64;
        Convolution { fft, multiplier: m, diagonal }
    }

    /// The operator of a real kernel given in space, row-major `[j·nx + i]`, that is even in both
    /// directions (`k[i] = k[nx − i]`, `k[j] = k[ny − j]`): its multiplier is the (real) DFT of
    /// the kernel. Used by the DC-FFT of the 2-D EHL solver (`physics::ehl::twod`), whose
    /// wrap-around influence coefficients are such a kernel.
    pub(crate) fn from_kernel(nx: usize, ny: usize, kernel: &[f64]) -> Self {
        let fft = Fft2::new(nx, ny);
        let mut buf: Vec<Complex<f64>> = kernel.iter().map(|&v| Complex::new(v, 0.0)).collect();
        let mut w = fft.workspace();
        fft.forward(&mut buf, &mut w);
        let multiplier: Vec<f64> = buf.iter().map(|c| c.re).collect();
        Convolution { fft, multiplier, diagonal: kernel[0] }
    }

    pub(crate) fn workspace(&self) -> ConvWorkspace {
        let (nx, ny) = (self.fft.nx, self.fft.ny);
        let z = Complex::new(0.0, 0.0);
        let real = nx % 2 == 0 && ny % 2 == 0;
        ConvWorkspace {
            buf: if real { Vec::new() } else { vec![z; nx * ny] },
            rows: if real { vec![z; nx * ny / 2] } else { Vec::new() },
            half: if real { vec![z; (nx / 2 + 1) * ny] } else { Vec::new() },
            fft: self.fft.workspace(),
        }
    }

    /// `out = K x`.
    pub(crate) fn apply(&self, x: &[f64], out: &mut [f64], w: &mut ConvWorkspace) {
        if w.rows.is_empty() { self.apply_complex(x, out, w) } else { self.apply_real(x, out, w, self.fft.ny, self.fft.ny) }
    }

    /// [`Convolution::apply`] of an `x` that is zero beyond its first `rows_in` rows, `out`
    /// wanted in its first `rows_out` rows only (the rest left as they were): the x transforms of
    /// the zero row pairs and of the unwanted output pairs are skipped (a padded DC-FFT product,
    /// `ehl::twod::elastic`). The same arithmetic on the rows computed: bit-identical to `apply`.
    pub(crate) fn apply_rows(&self, x: &[f64], out: &mut [f64], w: &mut ConvWorkspace, rows_in: usize, rows_out: usize) {
        if w.rows.is_empty() { self.apply_complex(x, out, w) } else { self.apply_real(x, out, w, rows_in, rows_out) }
    }

    /// The plain complex transform (odd grid sides).
    fn apply_complex(&self, x: &[f64], out: &mut [f64], w: &mut ConvWorkspace) {
        for (b, &v) in w.buf.iter_mut().zip(x) {
            *b = Complex::new(v, 0.0);
        }
        self.fft.forward(&mut w.buf, &mut w.fft);
        for (b, &m) in w.buf.iter_mut().zip(&self.multiplier) {
            *b *= m;
        }
        self.fft.inverse(&mut w.buf, &mut w.fft);
        for (o, b) in out.iter_mut().zip(&w.buf) {
            *o = b.re;
        }
    }

    /// Real input on even grids at half the cost: two rows packed as one complex row for the
    /// x transforms (`C = A + iB`, `A_k = (C_k + C̄_{n−k})/2`, `B_k = (C_k − C̄_{n−k})/(2i)`),
    /// only the `nx/2 + 1` non-negative x wavenumbers transformed along y; the multiplier is real
    /// and even, so the inverse rebuilds the Hermitian row spectra and unpacks the same way.
    /// `rows_in`/`rows_out`: see [`Convolution::apply_rows`].
    fn apply_real(&self, x: &[f64], out: &mut [f64], w: &mut ConvWorkspace, rows_in: usize, rows_out: usize) {
        let (nx, ny) = (self.fft.nx, self.fft.ny);
        let (h, pairs) = (nx / 2 + 1, ny / 2);
        let (pin, pout) = (rows_in.div_ceil(2).min(pairs), rows_out.div_ceil(2).min(pairs));
        let (rows, half, scratch) = (&mut w.rows, &mut w.half, &mut w.fft.scratch);
        for jp in 0..pin {
            let (r0, r1) = (&x[2 * jp * nx..(2 * jp + 1) * nx], &x[(2 * jp + 1) * nx..(2 * jp + 2) * nx]);
            for (i, c) in rows[jp * nx..(jp + 1) * nx].iter_mut().enumerate() {
                *c = Complex::new(r0[i], r1[i]);
            }
        }
        self.fft.fx.process_with_scratch(&mut rows[..pin * nx], scratch);
        let minus_half_i = Complex::new(0.0, -0.5);
        for jp in 0..pin {
            let r = &rows[jp * nx..(jp + 1) * nx];
            for k in 0..h {
                let (c, cc) = (r[k], r[(nx - k) % nx].conj());
                half[k * ny + 2 * jp] = (c + cc) * 0.5;
                half[k * ny + 2 * jp + 1] = (c - cc) * minus_half_i;
            }
        }
        // The zero rows' spectra (the transform of zeros, exactly).
        if pin < pairs {
            for k in 0..h {
                half[k * ny + 2 * pin..(k + 1) * ny].iter_mut().for_each(|b| *b = Complex::new(0.0, 0.0));
            }
        }
        self.fft.fy.process_with_scratch(half, scratch);
        for (b, &m) in half.iter_mut().zip(&self.multiplier[..h * ny]) {
            *b *= m;
        }
        self.fft.iy.process_with_scratch(half, scratch);
        let i1 = Complex::new(0.0, 1.0);
        for jp in 0..pout {
            let r = &mut rows[jp * nx..(jp + 1) * nx];
            for (k, c) in r.iter_mut().enumerate() {
                let (a, b) = if k < h {
                    (half[k * ny + 2 * jp], half[k * ny + 2 * jp + 1])
                } else {
                    (half[(nx - k) * ny + 2 * jp].conj(), half[(nx - k) * ny + 2 * jp + 1].conj())
                };
                *c = a + i1 * b;
            }
        }
        self.fft.ix.process_with_scratch(&mut rows[..pout * nx], scratch);
        let s = 1.0 / (nx * ny) as f64;
        for jp in 0..pout {
            for i in 0..nx {
                let c = rows[jp * nx + i];
                out[2 * jp * nx + i] = c.re * s;
                out[(2 * jp + 1) * nx + i] = c.im * s;
            }
        }
    }
}

pub(crate) struct ConvWorkspace {
    buf: Vec<Complex<f64>>,
    rows: Vec<Complex<f64>>,
    half: Vec<Complex<f64>>,
    fft: Workspace,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rough_real_convolution_equals_the_complex_one() {
        for (nx, ny) in [(8, 6), (250, 40), (16, 16)] {
            let op = Convolution::new(nx, ny, 1e-6, |kx, ky| {
                let k = (kx * kx + ky * ky).sqrt();
                if k > 0.0 { (1.0 - 0.3 * kx * kx / (k * k)) / k } else { 0.0 }
            });
            let x: Vec<f64> = (0..nx * ny).map(|i| ((i * 7919) % 101) as f64 - 50.0).collect();
            let (mut a, mut b) = (vec![0.0; nx * ny], vec![0.0; nx * ny]);
            let mut w = op.workspace();
            op.apply(&x, &mut a, &mut w);
            let mut wc = op.workspace();
            wc.buf = vec![Complex::new(0.0, 0.0); nx * ny];
            op.apply_complex(&x, &mut b, &mut wc);
            let scale = b.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            let err = a.iter().zip(&b).fold(0.0f64, |m, (p, q)| m.max((p - q).abs()));
            assert!(err <= 1e-12 * scale, "{nx}×{ny}: {err} of {scale}");
        }
    }
}
