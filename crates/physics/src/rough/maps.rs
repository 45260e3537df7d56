//! The precalculated asperity maps of seed 001: the pressure–film curve `p̄_a(h)` (eq. 9, 11–12)
//! and the micro-slip friction map `μ_a(h, δx)` (eq. 19), with monotone C¹ interpolants and the
//! derivatives the mixed-lubrication Newton solver needs.
//!
//! Per film `h_i` the normal contact is solved with the mean gap `h_i` (eq. 9); then the
//! tangential problem for `δx_ij = s_j δx_gs(h_i)`, `s_j = j/(n−1)`, where `δx_gs(h_i)` is the
//! gross-sliding displacement (stick area zero, `μ_a = μ_lim`, exact for the discrete problem).
//! Interpolation (seed 001 interpolates its map by cubic splines; here shape-preserving):
//! `ln p̄_a` and `ln δx_gs` monotone-cubic in `h`; per film `μ_a/μ_lim` monotone-cubic in `s`,
//! blended linearly in `h` between neighbouring films (a blend of increasing functions of `s`
//! is increasing: the map is monotone in `δx` everywhere).

use super::normal::{NormalControl, NormalSolver};
use super::pchip::Pchip;
use super::tangential::TangentialSolver;
use super::{ContactLimits, RoughMaterial, RoughOptions, RoughSurface, SurfaceSummary};
use crate::{ensure_finite, Convergence, Observer, SolveError, Termination};
use rayon::prelude::*;

/// The grids of the maps.
#[derive(Debug, Clone, PartialEq)]
pub struct MapGrids {
    /// Film thicknesses (mean gaps) `h`, m: positive, distinct, below the highest summit; 2..=200.
    pub films: Vec<f64>,
    /// Points of the displacement axis per film, including `δx = 0` and `δx = δx_gs`; 3..=200.
    pub displacement_points: usize,
}

impl MapGrids {
    /// `films` values evenly spaced from `0.25 Rq` to `min(3 Rq, 0.9 × peak height)`.
    pub fn auto(summary: &SurfaceSummary, films: usize, displacement_points: usize) -> Self {
        let (lo, hi) = (0.25 * summary.rq, (3.0 * summary.rq).min(0.9 * summary.peak));
        let n = films.max(2);
        MapGrids {
            films: (0..n).map(|i| lo + (hi - lo) * i as f64 / (n - 1) as f64).collect(),
            displacement_points,
        }
    }
}

/// The asperity pressure–film curve and friction map of one rough contact pair.
#[derive(Debug, Clone, PartialEq)]
pub struct AsperityMaps {
    /// Film thickness (mean gap) `h_i`, m, increasing.
    pub film: Vec<f64>,
    /// Mean asperity pressure `p̄_a(h_i)`, Pa (eq. 11).
    pub mean_pressure: Vec<f64>,
    /// Separation `d` of the flat from the mean plane at `h_i`, m.
    pub separation: Vec<f64>,
    /// Real contact area fraction at `h_i`.
    pub contact_fraction: Vec<f64>,
    /// Area fraction at the plastic limit at `h_i`.
    pub plastic_fraction: Vec<f64>,
    /// Gross-sliding displacement `δx_gs(h_i)`, m.
    pub gross_sliding_displacement: Vec<f64>,
    /// `s_j = δx/δx_gs` of the displacement axis, `0..=1`.
    pub displacement_fraction: Vec<f64>,
    /// `δx_ij = s_j δx_gs(h_i)`, m.
    pub displacement: Vec<Vec<f64>>,
    /// `μ_a(h_i, δx_ij)` (eq. 18–19).
    pub friction: Vec<Vec<f64>>,
    /// Stick nodes over contact nodes at `(h_i, δx_ij)`.
    pub stick_fraction: Vec<Vec<f64>>,
    /// `μ_a,lim`.
    pub friction_limit: f64,
    /// `p_a,lim`, Pa.
    pub pressure_limit: f64,
    /// Iterations summed over every solve, the worst residual (relative, as in [`RoughOptions`]).
    pub convergence: Convergence,
    pressure_curve: Pchip,
    gross_curve: Pchip,
    rows: Vec<Pchip>,
}

/// Most films and displacement points a map may have.
pub const MAX_MAP_POINTS: usize = 200;

impl AsperityMaps {
    /// Solves the normal contact at every film (sequentially, lightest load first, each
    /// warm-started from the previous) and the tangential problems at every film (films in
    /// parallel with rayon, each displacement warm-started from the previous) and builds the
    /// interpolants. Work: `films` normal solves (each a few separation-controlled CG solves) and
    /// `films × (displacement_points − 2)` tangential CG solves, each iteration one periodic
    /// convolution (two real FFTs) of the grid. Memory: one pressure field per film plus about
    /// twelve grid-sized arrays per worker thread, `(films + 12·threads) × nx·ny × 8` bytes.
    pub fn build(
        surface: &RoughSurface,
        material: &RoughMaterial,
        limits: ContactLimits,
        grids: &MapGrids,
        options: &RoughOptions,
        observer: &dyn Observer,
    ) -> Result<Self, SolveError> {
        limits.check()?;
        let nf = grids.films.len();
        if !(2..=MAX_MAP_POINTS).contains(&nf) {
            return Err(SolveError::invalid("MapGrids.films", format!("needs 2..={MAX_MAP_POINTS} films")));
        }
        for (i, &h) in grids.films.iter().enumerate() {
            if !(h.is_finite() && h > 0.0) {
                return Err(SolveError::invalid(format!("MapGrids.films[{i}]"), "must be finite and > 0"));
            }
            if i > 0 && h <= grids.films[i - 1] {
                return Err(SolveError::invalid(format!("MapGrids.films[{i}]"), "films must increase"));
            }
        }
        let nd = grids.displacement_points;
        if !(3..=MAX_MAP_POINTS).contains(&nd) {
            return Err(SolveError::invalid("MapGrids.displacement_points", format!("must be in 3..={MAX_MAP_POINTS}")));
        }
        let normal = NormalSolver::new(surface, material, limits.pressure, options)?;
        let total_solves = (nf * (nd - 1)) as f64;
        // Normal contacts, lightest load (largest film) first.
        let mut normals = Vec::with_capacity(nf);
        let mut warm: Option<Vec<f64>> = None;
        for (k, i) in (0..nf).rev().enumerate() {
            observer.check()?;
            observer.progress(k as f64 / total_solves, "asperity normal contact");
            let mut c = normal.solve(NormalControl::MeanGap(grids.films[i]), warm.as_deref(), observer)?;
            if !(c.mean_pressure > 0.0) {
                return Err(SolveError::invalid(
                    format!("MapGrids.films[{i}]"),
                    format!(
                        "no asperity contact at this film: it must be below the highest summit ({:.4e} m)",
                        surface.heights.iter().cloned().fold(f64::MIN, f64::max)
                    ),
                ));
            }
            c.gap = Vec::new(); // not needed further; keeps a map build's memory at one field per film
            warm = Some(c.pressure.clone());
            normals.push(c);
        }
        normals.reverse();
        drop(normal);
        let s: Vec<f64> = (0..nd).map(|j| j as f64 / (nd - 1) as f64).collect();
        let done = std::sync::atomic::AtomicUsize::new(nf);
        // Tangential maps, films in parallel.
        let rows: Vec<(f64, Vec<f64>, Vec<f64>, u32, f64, bool)> = normals
            .par_iter()
            .map(|c| {
                let t = TangentialSolver::new(surface, material, c, limits.friction, options)?;
                let (mut mu, mut stick) = (vec![0.0; nd], vec![1.0; nd]);
                let (mut iters, mut worst, mut stalled) = (0u32, 0.0f64, false);
                let mut warm: Option<Vec<f64>> = None;
                for j in 1..nd - 1 {
                    observer.check()?;
                    let r = t.solve(s[j] * t.gross_sliding, warm.as_deref(), observer)?;
                    mu[j] = r.friction_coefficient;
                    stick[j] = r.stick_fraction;
                    iters = iters.saturating_add(r.convergence.iterations);
                    worst = worst.max(r.convergence.residual);
                    stalled |= r.convergence.termination == Termination::Stalled;
                    warm = Some(r.traction);
                    let k = done.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                    observer.progress(k as f64 / total_solves, "asperity micro-slip map");
                }
                mu[nd - 1] = limits.friction;
                stick[nd - 1] = 0.0;
                Ok((t.gross_sliding, mu, stick, iters, worst, stalled))
            })
            .collect::<Result<_, SolveError>>()?;
        let film = grids.films.clone();
        let mean_pressure: Vec<f64> = normals.iter().map(|c| c.mean_pressure).collect();
        let gross: Vec<f64> = rows.iter().map(|r| r.0).collect();
        let mut friction: Vec<Vec<f64>> = Vec::with_capacity(nf);
        for r in &rows {
            // The partial-slip force grows with δx; the running maximum only removes
            // differences at the solver tolerance, so the interpolant stays monotone.
            let mut m = r.1.clone();
            for j in 1..nd {
                m[j] = m[j].max(m[j - 1]).min(limits.friction);
            }
            friction.push(m);
        }
        let mut iterations = 0u32;
        let mut residual = 0.0f64;
        let mut stalled = false;
        for c in &normals {
            iterations = iterations.saturating_add(c.convergence.iterations);
            residual = residual.max(c.convergence.residual);
            stalled |= c.convergence.termination == Termination::Stalled;
        }
        for r in &rows {
            iterations = iterations.saturating_add(r.3);
            residual = residual.max(r.4);
            stalled |= r.5;
        }
        ensure_finite("asperity mean pressure", &mean_pressure)?;
        ensure_finite("gross sliding displacement", &gross)?;
        ensure_finite("asperity friction", friction.iter().flatten())?;
        let pressure_curve = Pchip::new(film.clone(), mean_pressure.iter().map(|p| p.ln()).collect());
        let gross_curve = Pchip::new(film.clone(), gross.iter().map(|d| d.ln()).collect());
        let row_curves = friction.iter().map(|m| Pchip::new(s.clone(), m.iter().map(|v| v / limits.friction).collect())).collect();
        observer.progress(1.0, "asperity maps");
        Ok(AsperityMaps {
            separation: normals.iter().map(|c| c.separation).collect(),
            contact_fraction: normals.iter().map(|c| c.contact_fraction).collect(),
            plastic_fraction: normals.iter().map(|c| c.plastic_fraction).collect(),
            displacement: gross.iter().map(|g| s.iter().map(|sj| sj * g).collect()).collect(),
            displacement_fraction: s,
            stick_fraction: rows.iter().map(|r| r.2.clone()).collect(),
            gross_sliding_displacement: gross,
            film,
            mean_pressure,
            friction,
            friction_limit: limits.friction,
            pressure_limit: limits.pressure,
            convergence: Convergence {
                iterations,
                residual,
                tolerance: options.tolerance,
                termination: if stalled { Termination::Stalled } else { Termination::Converged },
            },
            pressure_curve,
            gross_curve,
            rows: row_curves,
        })
    }

    /// `(p̄_a, dp̄_a/dh)` at film `h` (m), Pa and Pa/m: monotone cubic in `ln p̄_a`; outside the
    /// film grid `ln p̄_a` continues linearly (exponential decay for thick films, as the
    /// pressure–separation law of Gaussian surfaces), capped at `p_a,lim` for thin films.
    pub fn mean_pressure(&self, h: f64) -> (f64, f64) {
        let (y, dy) = self.pressure_curve.eval(h);
        let p = y.exp();
        if !(p < self.pressure_limit) {
            return (self.pressure_limit, 0.0);
        }
        (p, p * dy)
    }

    /// Gross-sliding displacement `δx_gs(h)`, m (film clamped to the grid).
    pub fn gross_sliding(&self, h: f64) -> f64 {
        let h = h.clamp(self.film[0], self.film[self.film.len() - 1]);
        self.gross_curve.eval(h).0.exp()
    }

    /// `(μ_a, ∂μ_a/∂δx)` at film `h` (m, clamped to the grid) and rigid tangential displacement
    /// `δx` (m; odd in `δx`), `∂μ_a/∂δx` in 1/m: `μ_lim` with zero slope from `|δx| ≥ δx_gs(h)`.
    pub fn friction(&self, h: f64, delta: f64) -> (f64, f64) {
        let nf = self.film.len();
        let h = h.clamp(self.film[0], self.film[nf - 1]);
        let gross = self.gross_sliding(h);
        let a = delta.abs();
        let sign = if delta < 0.0 { -1.0 } else { 1.0 };
        if a >= gross {
            return (sign * self.friction_limit, 0.0);
        }
        let s = a / gross;
        let i = self.film.partition_point(|&v| v <= h).saturating_sub(1).min(nf - 2);
        let w = ((h - self.film[i]) / (self.film[i + 1] - self.film[i])).clamp(0.0, 1.0);
        let (f0, d0) = self.rows[i].eval(s);
        let (f1, d1) = self.rows[i + 1].eval(s);
        let f = ((1.0 - w) * f0 + w * f1).clamp(0.0, 1.0);
        let df = ((1.0 - w) * d0 + w * d1).max(0.0);
        (sign * self.friction_limit * f, self.friction_limit * df / gross)
    }
}
