//! Periodic rough surfaces on a uniform square-cell grid: generated Gaussian random surfaces, a
//! measured height table, their summary, and the combined surface of two rough bodies.

use super::fft::Fft2;
use super::MAX_GRID_SIDE;
use crate::{ensure_finite, SolveError};
use rustfft::num_complex::Complex;

/// Heights `z` (m, towards the counter-surface) on an `nx × ny` periodic grid of square cells of
/// side `spacing` (m); row-major, `heights[j * nx + i]` at `x = i·spacing`, `y = j·spacing`.
#[derive(Debug, Clone, PartialEq)]
pub struct RoughSurface {
    pub nx: usize,
    pub ny: usize,
    pub spacing: f64,
    pub heights: Vec<f64>,
}

/// Height statistics of a surface (about its mean plane).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfaceSummary {
    /// Root-mean-square height Rq (Sq), m.
    pub rq: f64,
    /// Arithmetic mean deviation Ra (Sa), m.
    pub ra: f64,
    /// Root-mean-square gradient `√⟨(∂z/∂x)² + (∂z/∂y)²⟩` (central differences), dimensionless.
    pub rms_slope: f64,
    /// Highest point above the mean plane, m.
    pub peak: f64,
    /// Deepest point below the mean plane (positive), m.
    pub valley: f64,
}

fn check_grid(nx: usize, ny: usize, spacing: f64) -> Result<(), SolveError> {
    if !(4..=MAX_GRID_SIDE).contains(&nx) || !(4..=MAX_GRID_SIDE).contains(&ny) {
        return Err(SolveError::invalid(
            "RoughSurface.nx",
            format!("grid sides must be in 4..={MAX_GRID_SIDE} (got {nx}×{ny})"),
        ));
    }
    if !(spacing.is_finite() && spacing > 0.0) {
        return Err(SolveError::invalid("RoughSurface.spacing", "must be finite and > 0"));
    }
    Ok(())
}

impl RoughSurface {
    /// A measured height table (row-major, `nx` values per row), shifted to zero mean. The
    /// table is taken as one period of a periodic surface.
    pub fn from_table(nx: usize, ny: usize, spacing: f64, heights: Vec<f64>) -> Result<Self, SolveError> {
        check_grid(nx, ny, spacing)?;
        if heights.len() != nx * ny {
            return Err(SolveError::invalid(
                "RoughSurface.heights",
                format!("{} values for a {nx}×{ny} grid", heights.len()),
            ));
        }
        if heights.iter().any(|h| !h.is_finite()) {
            return Err(SolveError::invalid("RoughSurface.heights", "every height must be finite"));
        }
        let mut s = RoughSurface { nx, ny, spacing, heights };
        s.remove_mean();
        Ok(s)
    }

    /// A Gaussian random surface with the Gaussian autocorrelation
    /// `R(r) = Rq² exp(−r²/β²)` (β = `correlation_length`, the lag at which `R` falls to `1/e`):
    /// white Gaussian noise (SplitMix64 + Box–Muller, deterministic from `seed`) filtered in
    /// Fourier space by `√PSD ∝ exp(−|k|²β²/8)`, then shifted to zero mean and scaled to `rq`
    /// exactly. Isotropic; its rms slope is `2 Rq/β` in the continuum (less when β spans few
    /// cells).
    pub fn gaussian(
        nx: usize,
        ny: usize,
        spacing: f64,
        rq: f64,
        correlation_length: f64,
        seed: u64,
    ) -> Result<Self, SolveError> {
        check_grid(nx, ny, spacing)?;
        if !(rq.is_finite() && rq > 0.0) {
            return Err(SolveError::invalid("RoughSurface.rq", "must be finite and > 0"));
        }
        if !(correlation_length.is_finite() && correlation_length > 0.0) {
            return Err(SolveError::invalid("RoughSurface.correlation_length", "must be finite and > 0"));
        }
        let lmax = (nx.max(ny)) as f64 * spacing;
        if correlation_length > 0.25 * lmax {
            return Err(SolveError::invalid(
                "RoughSurface.correlation_length",
                "must be at most a quarter of the domain side (a periodic sample needs several correlation lengths)",
            ));
        }
        let mut rng = SplitMix64(seed);
        let fft = Fft2::new(nx, ny);
        let mut buf: Vec<Complex<f64>> = (0..nx * ny).map(|_| Complex::new(rng.gaussian(), 0.0)).collect();
        let mut work = fft.workspace();
        fft.forward(&mut buf, &mut work);
        // buf is now in the transposed spectral layout [i * ny + j].
        let (kx, ky) = (fft.wavenumbers_x(spacing), fft.wavenumbers_y(spacing));
        let b2 = correlation_length * correlation_length;
        for i in 0..nx {
            for j in 0..ny {
                let k2 = kx[i] * kx[i] + ky[j] * ky[j];
                buf[i * ny + j] *= (-k2 * b2 / 8.0).exp();
            }
        }
        fft.inverse(&mut buf, &mut work);
        let mut s = RoughSurface { nx, ny, spacing, heights: buf.iter().map(|c| c.re).collect() };
        s.remove_mean();
        let cur = s.summary().rq;
        if !(cur > 0.0) {
            return Err(SolveError::invalid("RoughSurface.correlation_length", "the filtered surface is flat"));
        }
        for h in &mut s.heights {
            *h *= rq / cur;
        }
        ensure_finite("RoughSurface.heights", &s.heights)?;
        Ok(s)
    }

    /// The equivalent rough surface of two rough bodies on the same grid against a rigid flat:
    /// the sum of their heights (seed 001 §"Asperity contact component"; Johnson §13.1).
    pub fn combined(&self, other: &RoughSurface) -> Result<Self, SolveError> {
        if self.nx != other.nx || self.ny != other.ny || (self.spacing - other.spacing).abs() > 1e-12 * self.spacing {
            return Err(SolveError::invalid("RoughSurface", "combined surfaces need the same grid and spacing"));
        }
        let heights = self.heights.iter().zip(&other.heights).map(|(a, b)| a + b).collect();
        RoughSurface::from_table(self.nx, self.ny, self.spacing, heights)
    }

    /// Number of nodes.
    pub fn len(&self) -> usize {
        self.nx * self.ny
    }

    /// Always false for a checked surface (kept for clippy's `len` rule).
    pub fn is_empty(&self) -> bool {
        self.heights.is_empty()
    }

    /// Domain side lengths `(Lx, Ly)`, m.
    pub fn lengths(&self) -> (f64, f64) {
        (self.nx as f64 * self.spacing, self.ny as f64 * self.spacing)
    }

    fn remove_mean(&mut self) {
        let mean = self.heights.iter().sum::<f64>() / self.heights.len() as f64;
        for h in &mut self.heights {
            *h -= mean;
        }
    }

    /// Rq, Ra, rms slope, peak and valley about the mean plane.
    pub fn summary(&self) -> SurfaceSummary {
        let n = self.len() as f64;
        let mean = self.heights.iter().sum::<f64>() / n;
        let (mut s2, mut s1, mut peak, mut valley, mut g2) = (0.0, 0.0, f64::MIN, f64::MAX, 0.0);
        for j in 0..self.ny {
            for i in 0..self.nx {
                let z = self.heights[j * self.nx + i] - mean;
                s2 += z * z;
                s1 += z.abs();
                peak = peak.max(z);
                valley = valley.min(z);
                let (ip, im) = ((i + 1) % self.nx, (i + self.nx - 1) % self.nx);
                let (jp, jm) = ((j + 1) % self.ny, (j + self.ny - 1) % self.ny);
                let dx = (self.heights[j * self.nx + ip] - self.heights[j * self.nx + im]) / (2.0 * self.spacing);
                let dy = (self.heights[jp * self.nx + i] - self.heights[jm * self.nx + i]) / (2.0 * self.spacing);
                g2 += dx * dx + dy * dy;
            }
        }
        SurfaceSummary { rq: (s2 / n).sqrt(), ra: s1 / n, rms_slope: (g2 / n).sqrt(), peak, valley: -valley }
    }

    /// Peak-to-valley height, m.
    pub(crate) fn peak_to_valley(&self) -> f64 {
        let (lo, hi) = self.heights.iter().fold((f64::MAX, f64::MIN), |(lo, hi), &z| (lo.min(z), hi.max(z)));
        hi - lo
    }

    /// Checks a surface built by hand (fields are public).
    pub(crate) fn check(&self) -> Result<(), SolveError> {
        check_grid(self.nx, self.ny, self.spacing)?;
        if self.heights.len() != self.nx * self.ny {
            return Err(SolveError::invalid("RoughSurface.heights", "length must be nx·ny"));
        }
        ensure_finite("RoughSurface.heights", &self.heights)
            .map_err(|_| SolveError::invalid("RoughSurface.heights", "every height must be finite"))?;
        if !(self.peak_to_valley() > 0.0) {
            return Err(SolveError::invalid("RoughSurface.heights", "the surface is flat"));
        }
        Ok(())
    }
}

/// SplitMix64 (Steele, Lea & Flood 2014): a tiny, well-mixed deterministic generator.
struct SplitMix64(u64);

impl SplitMix64 {
    fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    /// Uniform in (0, 1].
    fn uniform(&mut self) -> f64 {
        ((self.next_u64() >> 11) as f64 + 1.0) * (1.0 / (1u64 << 53) as f64)
    }
    /// Standard normal (Box–Muller, one of the pair).
    fn gaussian(&mut self) -> f64 {
        let (u1, u2) = (self.uniform(), self.uniform());
        (-2.0 * u1.ln()).sqrt() * (2.0 * std::f64::consts::PI * u2).cos()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rough_gaussian_surface_has_requested_rq_and_slope() {
        let beta = 8.0e-6;
        let s = RoughSurface::gaussian(256, 256, 0.5e-6, 0.2e-6, beta, 7).unwrap();
        let m = s.summary();
        assert!((m.rq - 0.2e-6).abs() < 1e-12);
        // Continuum rms slope 2 Rq/β = 0.05; central differences over β = 16 cells lose ~1 %;
        // one 128 µm sample scatters by a few per cent.
        assert!((m.rms_slope / (2.0 * 0.2e-6 / beta) - 1.0).abs() < 0.08, "{m:?}");
        // Gaussian heights: Ra/Rq = √(2/π) = 0.798.
        assert!((m.ra / m.rq - 0.798).abs() < 0.03, "{m:?}");
        // deterministic
        let t = RoughSurface::gaussian(256, 256, 0.5e-6, 0.2e-6, beta, 7).unwrap();
        assert_eq!(s, t);
    }

    #[test]
    fn rough_table_checks() {
        assert!(RoughSurface::from_table(4, 4, 1e-6, vec![0.0; 15]).is_err());
        assert!(RoughSurface::from_table(2000, 4, 1e-6, vec![0.0; 8000]).is_err());
        let s = RoughSurface::from_table(4, 4, 1e-6, (0..16).map(|i| i as f64 * 1e-9).collect()).unwrap();
        assert!(s.heights.iter().sum::<f64>().abs() < 1e-20);
        let c = s.combined(&s).unwrap();
        assert!((c.summary().rq - 2.0 * s.summary().rq).abs() < 1e-18);
    }
}
