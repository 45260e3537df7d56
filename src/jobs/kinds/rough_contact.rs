//! `rough_contact`: the dry contact of a rough surface pair against its own mean plane (seed 001
//! eq. 8–12): the asperity pressure–gap curve `p̄_a(h)` that the cam kinds take as
//! `asperities.pressure_gap_curve` (mixed lubrication), with the real contact and plastic area
//! fractions at each film. Physics: `physics::rough` (FFT influence coefficients on a periodic
//! grid, bound-constrained Polonsky–Keer conjugate gradient with the plastic cap).
//!
//! The surface is generated (Gaussian heights of given Rq with a Gaussian autocorrelation of
//! given correlation length, reproducible from `seed`) or given as a height table; two rough
//! bodies are one surface of the summed heights against a flat (the composite Rq).

use super::common::Material;
use crate::jobs::cost::Cost;
use crate::jobs::kind::{Kind, Limits, Validation};
use crate::physics::rough::{
    gross_sliding_displacement as gross_sliding_displacement_of, solve_normal, solve_tangential, MapGrids, NormalControl, RoughMaterial, RoughOptions,
    RoughSurface, TangentialContact,
};
use crate::physics::{ensure_finite, Convergence, Observer, SolveError, Termination};
use serde::{Deserialize, Serialize};
use serde_json::{json, Value};
use utoipa::ToSchema;

pub struct RoughContact;

/// The rough surface (composite of both bodies).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(tag = "type", rename_all = "snake_case", deny_unknown_fields)]
pub enum SurfaceSpec {
    /// Gaussian heights with a Gaussian autocorrelation `Rq² exp(−r²/β²)`.
    Gaussian {
        /// RMS height Rq, m (composite of the two bodies: `sqrt(Rq1² + Rq2²)`).
        rq: f64,
        /// Correlation length β, m.
        correlation_length: f64,
        /// Grid points per side (16 to 512; the domain is periodic).
        points: usize,
        /// Grid spacing, m.
        spacing: f64,
        /// Seed of the random heights (the same seed gives the same surface).
        #[serde(default)]
        seed: u64,
    },
    /// A measured height table, row-major (`heights[j·nx + i]`), m; the mean is removed.
    Table { nx: usize, ny: usize, spacing: f64, heights: Vec<f64> },
}

/// Spec of a `rough_contact` job (SI units).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct RoughContactSpec {
    pub surface: SurfaceSpec,
    /// Elastic constants of body 1. Default: steel.
    #[serde(default)]
    pub material_1: Material,
    /// Elastic constants of body 2. Default: steel.
    #[serde(default)]
    pub material_2: Material,
    /// Plastic limit of the local contact pressure, Pa (seed 001 Table 1: 6e9). Default: elastic.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub plastic_limit: Option<f64>,
    /// Films (mean gaps) at which the curve is computed, m, ascending. Default: 12 films from
    /// 0.25 Rq to the smaller of 3 Rq and 0.9 of the highest summit.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub films: Option<Vec<f64>>,
    /// Relative tolerance of the contact solver. Default 1e-7.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tolerance: Option<f64>,
    /// Limiting (Coulomb) friction coefficient μ_a,lim of the asperity contacts (seed 001
    /// Table 1: 0.12). Present: each film also gets the tangential stick–slip solution (seed 001
    /// eq. 14–21) — its gross-sliding displacement and the exponent of the micro-slip shape —
    /// the inputs of the cam kinds' `asperities.model: micro_slip`. Triples the work.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub friction_limit: Option<f64>,
}

/// One film of the curve.
#[derive(Debug, Clone, PartialEq, Serialize, ToSchema)]
pub struct GapRow {
    /// Film (mean gap), m.
    pub film: f64,
    /// Mean asperity pressure p̄_a, Pa (seed 001 eq. 11).
    pub mean_pressure: f64,
    /// Separation of the flat from the mean plane, m.
    pub separation: f64,
    /// Real contact area fraction.
    pub contact_fraction: f64,
    /// Fraction of the area at the plastic limit.
    pub plastic_fraction: f64,
    /// Largest local pressure, Pa.
    pub max_pressure: f64,
    /// Rigid tangential displacement at which the whole contact slides, δx_gs, m (with
    /// `friction_limit`): `asperities.gross_sliding_displacement` of the cam kinds.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub gross_sliding_displacement: Option<f64>,
    /// Exponent n of `μ_a/μ_lim = 1 − (1 − δx/δx_gs)^n` fitted (mean of ln(1 − μ_a/μ_lim)/ln(1 − s))
    /// to the stick–slip solutions at δx_gs/4 and δx_gs/2 (with `friction_limit`):
    /// `asperities.micro_slip_exponent` of the cam kinds.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub micro_slip_exponent: Option<f64>,
}

/// The curve in the form `asperities.pressure_gap_curve` of the cam kinds takes.
#[derive(Debug, Clone, PartialEq, Serialize, ToSchema)]
pub struct GapCurve {
    /// m.
    pub film: Vec<f64>,
    /// Pa.
    pub pressure: Vec<f64>,
}

/// The micro-slip map in the form `asperities.micro_slip_map` of the cam kinds takes (with
/// `friction_limit`): the touching films' gross-sliding displacements and exponents, the
/// exponents held to the cam kinds' range 2–8 (below 2, at thick films where few asperities
/// touch, the local law's curvature is unbounded; `rows` keep the fitted values).
#[derive(Debug, Clone, PartialEq, Serialize, ToSchema)]
pub struct GapMap {
    /// m.
    pub film: Vec<f64>,
    /// m.
    pub gross_sliding_displacement: Vec<f64>,
    /// Exponent of the micro-slip law, dimensionless.
    pub exponent: Vec<f64>,
}

/// Surface statistics.
#[derive(Debug, Clone, PartialEq, Serialize, ToSchema)]
pub struct SurfaceStats {
    /// m.
    pub rq: f64,
    /// m.
    pub ra: f64,
    /// RMS slope, dimensionless.
    pub rms_slope: f64,
    /// Highest point above the mean plane, m.
    pub peak: f64,
}

/// Result of a `rough_contact` job.
#[derive(Debug, Clone, PartialEq, Serialize, ToSchema)]
pub struct RoughContactResult {
    pub surface: SurfaceStats,
    /// E*, Pa.
    pub contact_modulus: f64,
    pub rows: Vec<GapRow>,
    /// Paste into `asperities.pressure_gap_curve` (films where the asperities touch).
    pub pressure_gap_curve: GapCurve,
    /// Paste into `asperities.micro_slip_map` (with `friction_limit`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub micro_slip_map: Option<GapMap>,
    #[schema(value_type = crate::jobs::schemas::ConvergenceDoc)]
    pub convergence: Convergence,
}

/// Points per side of the surface grid.
fn grid(spec: &RoughContactSpec) -> (usize, usize) {
    match &spec.surface {
        SurfaceSpec::Gaussian { points, .. } => (*points, *points),
        SurfaceSpec::Table { nx, ny, .. } => (*nx, *ny),
    }
}

impl Kind for RoughContact {
    const NAME: &'static str = "rough_contact";
    const SOLVER_VERSION: &'static str = "rough_contact-3";
    const DESCRIPTION: &'static str = "Dry contact of a rough surface pair (generated Gaussian or measured heights): \
        the asperity pressure–gap curve of mixed lubrication with contact and plastic area fractions (seed 001 eq. 8–12).";
    const TABLES: &'static [&'static str] = &["rows"];
    const KEY_FIGURES: &'static [&'static str] = &["/surface/rq", "/surface/rms_slope", "/contact_modulus"];
    type Spec = RoughContactSpec;
    type Output = RoughContactResult;

    fn example() -> Value {
        json!({
            "surface": {"type": "gaussian", "rq": 0.207e-6, "correlation_length": 8e-6, "points": 128, "spacing": 0.5e-6, "seed": 1},
            "material_1": {"youngs_modulus": 200e9}, "material_2": {"youngs_modulus": 200e9},
            "plastic_limit": 6e9
        })
    }

    fn bound_examples() -> Vec<Value> {
        // The optional fields, and a measured surface (the Gaussian one's fields removed).
        let table = json!({"type": "table", "nx": 16, "ny": 16, "heights": vec![0.0; 256],
            "rq": null, "correlation_length": null, "points": null, "seed": null});
        vec![
            crate::jobs::kind::example_with::<Self>(json!({"films": [1e-7, 2e-7], "tolerance": 1e-7, "friction_limit": 0.12})),
            crate::jobs::kind::example_with::<Self>(json!({"surface": table})),
        ]
    }

    fn validate(spec: &RoughContactSpec, limits: &Limits, v: &mut Validation) {
        match &spec.surface {
            SurfaceSpec::Gaussian { rq, correlation_length, points, spacing, .. } => {
                v.in_range("/surface/rq", *rq, 1e-10, 1e-4);
                v.positive("/surface/spacing", *spacing);
                v.check(*correlation_length > 0.0 && correlation_length.is_finite(), "/surface/correlation_length", "must be a finite number > 0");
                v.check((16..=512).contains(points), "/surface/points", "must be 16 to 512");
            }
            SurfaceSpec::Table { nx, ny, spacing, heights } => {
                v.positive("/surface/spacing", *spacing);
                v.check((16..=512).contains(nx) && (16..=512).contains(ny), "/surface/nx", "nx and ny must be 16 to 512");
                v.items("/surface/heights", heights.len(), 16 * 16, Some(512 * 512));
                v.check(heights.len() == nx.saturating_mul(*ny), "/surface/heights", "needs nx·ny heights");
                v.check(heights.iter().all(|h| h.is_finite()), "/surface/heights", "must be finite");
            }
        }
        spec.material_1.validate("/material_1", v);
        spec.material_2.validate("/material_2", v);
        if let Some(p) = spec.plastic_limit {
            v.in_range("/plastic_limit", p, 1e6, 1e11);
        }
        if let Some(t) = spec.tolerance {
            v.in_range("/tolerance", t, 1e-12, 1e-2);
        }
        if let Some(m) = spec.friction_limit {
            v.in_range("/friction_limit", m, 1e-3, 2.0);
        }
        if let Some(f) = &spec.films {
            v.items("/films", f.len(), 1, Some(64));
            v.check(f.iter().all(|h| h.is_finite() && *h > 0.0) && f.windows(2).all(|w| w[1] > w[0]), "/films", "must be positive and strictly ascending");
        }
        let (nx, ny) = grid(spec);
        v.limit("/surface", nx.saturating_mul(ny), limits.max_grid_nodes, "the number of surface points");
    }

    fn cost(spec: &RoughContactSpec) -> Cost {
        // Work and memory: a normal solve is O(n log n) per CG iteration and the iterations grow
        // with the grid: ≈ 2.5 s·(n/512²)^1.7 per film (the seed 001 surface: 0.19 s at 128² for
        // 12 films, 0.038 s at 64²; `cargo bench --bench cost`); memory ≈ 18 arrays of n doubles (16
        // measured before the CG kept its previous iterate and that iterate's K x: issue 40).
        let films = spec.films.as_ref().map_or(12, |f| f.len());
        let (nx, ny) = grid(spec);
        let n = nx as f64 * ny as f64;
        let per_film = if spec.friction_limit.is_some() { 3.0 } else { 1.0 };
        let seconds = per_film * films as f64 * 2.5 * (n / (512.0 * 512.0)).powf(1.7);
        Cost::new(seconds, 18.0 * 8.0 * n)
            .work_at("/films", format!("{films} contact solves on a {nx}×{ny} surface"))
            .memory_at("/surface", format!("the contact solver on a {nx}×{ny} surface"))
    }

    fn solve(spec: &RoughContactSpec, observer: &dyn Observer) -> Result<RoughContactResult, SolveError> {
        let surface = match &spec.surface {
            SurfaceSpec::Gaussian { rq, correlation_length, points, spacing, seed } => {
                RoughSurface::gaussian(*points, *points, *spacing, *rq, *correlation_length, *seed)
            }
            SurfaceSpec::Table { nx, ny, spacing, heights } => RoughSurface::from_table(*nx, *ny, *spacing, heights.clone()),
        }
        .map_err(|e| e.in_spec(|f| if f.starts_with("RoughSurface") { Some("/surface".to_string()) } else { None }))?;
        let material = RoughMaterial::new(spec.material_1.elastic(), spec.material_2.elastic())?;
        let summary = surface.summary();
        let films = spec.films.clone().unwrap_or_else(|| MapGrids::auto(&summary, 12, 2).films);
        let options = RoughOptions { tolerance: spec.tolerance.unwrap_or(RoughOptions::default().tolerance), ..RoughOptions::default() };
        let limit = spec.plastic_limit.unwrap_or(f64::INFINITY);
        let mut rows = Vec::with_capacity(films.len());
        let mut iterations = 0;
        let mut residual: f64 = 0.0;
        // Thickest film first: each solve starts from the previous pressure.
        let mut warm: Option<Vec<f64>> = None;
        for (k, &h) in films.iter().enumerate().rev() {
            observer.check()?;
            observer.progress((films.len() - 1 - k) as f64 / films.len() as f64, "normal contact");
            let c = solve_normal(&surface, &material, limit, NormalControl::MeanGap(h), &options, warm.as_deref(), observer)
                .map_err(|e| e.in_spec(|_| Some(format!("/films/{k}"))))?;
            iterations += c.convergence.iterations;
            residual = residual.max(c.convergence.residual);
            let (mut gross_sliding_displacement, mut micro_slip_exponent) = (None, None);
            if let (Some(mu), true) = (spec.friction_limit, c.mean_pressure > 0.0) {
                let at = |e: SolveError| e.in_spec(|_| Some(format!("/films/{k}")));
                let dgs = gross_sliding_displacement_of(&surface, &material, &c, mu).map_err(at)?;
                let quarter = solve_tangential(&surface, &material, &c, mu, 0.25 * dgs, &options, None, observer).map_err(at)?;
                let half = solve_tangential(&surface, &material, &c, mu, 0.5 * dgs, &options, Some(&quarter.traction), observer).map_err(at)?;
                iterations += quarter.convergence.iterations + half.convergence.iterations;
                residual = residual.max(quarter.convergence.residual).max(half.convergence.residual);
                let fit = |t: &TangentialContact, s: f64| (1.0 - t.friction_coefficient.abs() / mu).max(1e-12).ln() / (1.0 - s).ln();
                gross_sliding_displacement = Some(dgs);
                micro_slip_exponent = Some(0.5 * (fit(&quarter, 0.25) + fit(&half, 0.5)));
            }
            rows.push(GapRow {
                gross_sliding_displacement,
                micro_slip_exponent,
                film: h,
                mean_pressure: c.mean_pressure,
                separation: c.separation,
                contact_fraction: c.contact_fraction,
                plastic_fraction: c.plastic_fraction,
                max_pressure: c.max_pressure,
            });
            warm = Some(c.pressure);
        }
        rows.reverse();
        ensure_finite("rough contact", rows.iter().flat_map(|r| [&r.mean_pressure, &r.separation, &r.contact_fraction]))?;
        let touching: Vec<&GapRow> = rows.iter().filter(|r| r.mean_pressure > 0.0).collect();
        // A curve the cam kinds accept: positive and non-increasing pressures.
        let mut curve = GapCurve { film: Vec::new(), pressure: Vec::new() };
        for r in touching {
            if curve.pressure.last().is_none_or(|&p| r.mean_pressure <= p) {
                curve.film.push(r.film);
                curve.pressure.push(r.mean_pressure);
            }
        }
        let mut map = GapMap { film: Vec::new(), gross_sliding_displacement: Vec::new(), exponent: Vec::new() };
        for r in &rows {
            if let (Some(d), Some(n), true) = (r.gross_sliding_displacement, r.micro_slip_exponent, r.mean_pressure > 0.0) {
                if (1e-12..=1e-3).contains(&d) && n.is_finite() {
                    map.film.push(r.film);
                    map.gross_sliding_displacement.push(d);
                    map.exponent.push(n.clamp(2.0, 8.0));
                }
            }
        }
        let micro_slip_map = (spec.friction_limit.is_some() && !map.film.is_empty()).then_some(map);
        Ok(RoughContactResult {
            micro_slip_map,
            surface: SurfaceStats { rq: summary.rq, ra: summary.ra, rms_slope: summary.rms_slope, peak: summary.peak },
            contact_modulus: material.contact_modulus(),
            rows,
            pressure_gap_curve: curve,
            convergence: Convergence { iterations, residual, tolerance: options.tolerance, termination: Termination::Converged },
        })
    }
}
