//! Hertzian scales, domain and undeformed gap of the 2-D problems: elliptic point contacts and the
//! finite (crowned) line contact of seed 000.

use super::{Ehl2dInput, Ehl2dOptions, Geometry2d};
use crate::contact::{hertz_line, hertz_point};
use crate::ehl::formulas::{moes_central, nijenbanning_central, point_moes_groups, Groups};
use crate::SolveError;

/// Scales and dimensionless coefficients of one problem (see [`super`] for the equations).
#[derive(Debug, Clone)]
pub(crate) struct Scales {
    /// Length scale `a`, m: the Hertzian semi-axis along x (point) or the Hertzian half-width at
    /// the peak load per length of the slice model (finite line).
    pub a: f64,
    /// Pressure scale: the Hertzian peak pressure, Pa.
    pub p_ref: f64,
    /// Reduced radius in the entrainment direction, m.
    pub rx: f64,
    /// `λ = 12 η0 u_m R_x²/(a³ p_ref)`.
    pub lambda: f64,
    /// Deflection coefficient `c = 2 p_ref R_x/(π E' a)`.
    pub c_def: f64,
    /// Load target `∫∫ P dX dY = F/(p_ref a²)`.
    pub load: f64,
    /// Film estimate `H = h R_x/a²` (closed form).
    pub h_est: f64,
    /// Semi-axis of the Hertzian footprint across the entrainment in units of `a` (point), or the
    /// half-length of the roller in units of `a` (finite).
    pub ky: f64,
    /// Moes `M`, `L` (point: Nijenbanning's; finite: line groups at the peak load per length).
    pub moes_m: f64,
    pub moes_l: f64,
    /// Half-length of the loaded zone across the entrainment, units of `a` (the Hertzian semi-axis
    /// or the slice model's loaded half-length): shapes the cold-start pressure.
    pub loaded: f64,
    /// The slice model's rigid approach of a finite roller, units of `a²/R_x` (0 for points):
    /// the cold start loads slice `Y` in proportion to `(δ − S(Y))⁺`.
    pub approach: f64,
}

pub(crate) fn scales(input: &Ehl2dInput) -> Result<Scales, SolveError> {
    let ep = input.effective_modulus;
    let lub = &input.lubricant;
    let eta0 = lub.viscosity_at(0.0, input.temperature);
    let um = input.entrainment_velocity.abs();
    let f = input.load;
    let pi = std::f64::consts::PI;
    let (a, p_ref, rx, ky, h_est, m, l, loaded, approach) = match input.geometry {
        Geometry2d::Point { rx, ry } => {
            // Hertz with E* = E'/2 (contact::hertz_point takes Johnson's E*).
            let hz = hertz_point(f, rx, ry, 0.5 * ep).map_err(|_| SolveError::invalid("Ehl2dInput.geometry", "radii must be > 0"))?;
            let (ax, ay) = if rx >= ry { (hz.semi_major, hz.semi_minor) } else { (hz.semi_minor, hz.semi_major) };
            let (m, l, u_sum) = point_moes_groups(f, rx, ep, um, eta0, lub.pressure_viscosity);
            let hc = nijenbanning_central(m, l, rx / ry) * rx * u_sum.sqrt();
            (ax, hz.max_pressure, rx, ay / ax, hc * rx / (ax * ax), m, l, ay / ax, 0.0)
        }
        Geometry2d::Finite { rx, crown } => {
            let cc = crown.distribute(f, rx, 0.5 * ep);
            let w = cc.peak_load_per_length.max(f / crown.length);
            let hz = hertz_line(w, rx, 0.5 * ep);
            let g = Groups::new(w, rx, ep, um, eta0, lub.pressure_viscosity);
            let hc = moes_central(g.moes_m, g.moes_l) * rx * (2.0 * g.speed).sqrt();
            let b = hz.half_width;
            (b, hz.max_pressure, rx, 0.5 * crown.length / b, hc * rx / (b * b), g.moes_m, g.moes_l, (0.5 * cc.effective_length.min(crown.length) / b).max(1.0), cc.approach * rx / (b * b))
        }
    };
    let lambda = 12.0 * eta0 * um * rx * rx / (a * a * a * p_ref);
    let c_def = 2.0 * p_ref * rx / (pi * ep * a);
    let load = f / (p_ref * a * a);
    let s = Scales { a, p_ref, rx, lambda, c_def, load, h_est, ky, moes_m: m, moes_l: l, loaded, approach };
    if ![a, p_ref, lambda, c_def, load, h_est, ky].iter().all(|v| v.is_finite() && *v > 0.0) {
        return Err(SolveError::invalid("Ehl2dInput", "the contact scales are not finite and positive (check load, radii, modulus, speed)"));
    }
    Ok(s)
}

/// The computational domain in units of `a`: `[x_in, x_out] × [y_lo, y_hi]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Domain {
    pub x_in: f64,
    pub x_out: f64,
    pub y_lo: f64,
    pub y_hi: f64,
}

pub(crate) fn domain(input: &Ehl2dInput, options: &Ehl2dOptions, s: &Scales) -> Domain {
    let sq = (2.0 * s.h_est).sqrt();
    let inlet = options.inlet.unwrap_or_else(|| (10.0 * sq).clamp(3.5, 12.0));
    let outlet = options.outlet.unwrap_or_else(|| (1.5 * sq).clamp(1.5, 4.0));
    let (y_lo, y_hi) = match input.geometry {
        Geometry2d::Point { .. } => {
            let side = options.side.unwrap_or_else(|| (1.8 * s.ky + 0.5 * sq).max(1.5));
            (-side, side)
        }
        Geometry2d::Finite { .. } => (-s.ky, s.ky),
    };
    Domain { x_in: -inlet, x_out: outlet, y_lo, y_hi }
}

/// Undeformed gap across the entrainment, `S(Y)` in units of `a²/R_x` (`H = H0 + X²/2 + S + W`).
pub(crate) fn side_gap(input: &Ehl2dInput, s: &Scales, y: f64) -> f64 {
    match input.geometry {
        Geometry2d::Point { rx, ry } => 0.5 * (rx / ry) * y * y,
        Geometry2d::Finite { crown, .. } => crown.gap(y * s.a) * s.rx / (s.a * s.a),
    }
}

/// The uniform node grid of a domain: spacings, node positions (units of `a`) and the undeformed
/// gap `X²/2 + S(Y)` at each node (row-major `[j·nx + i]`). The EHL and the dry solver build their
/// nodes here, so both solutions of one input sit on the same nodes.
pub(crate) struct NodeGrid {
    pub dx: f64,
    pub dy: f64,
    pub x: Vec<f64>,
    pub y: Vec<f64>,
    pub geom: Vec<f64>,
}

pub(crate) fn node_grid(input: &Ehl2dInput, s: &Scales, d: Domain, nx: usize, ny: usize) -> NodeGrid {
    let dx = (d.x_out - d.x_in) / (nx - 1) as f64;
    let dy = (d.y_hi - d.y_lo) / (ny - 1) as f64;
    let x: Vec<f64> = (0..nx).map(|i| d.x_in + i as f64 * dx).collect();
    let y: Vec<f64> = (0..ny).map(|j| d.y_lo + j as f64 * dy).collect();
    let mut geom = vec![0.0; nx * ny];
    for j in 0..ny {
        let sy = side_gap(input, s, y[j]);
        for i in 0..nx {
            geom[j * nx + i] = 0.5 * x[i] * x[i] + sy;
        }
    }
    NodeGrid { dx, dy, x, y, geom }
}
