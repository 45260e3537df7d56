//! Thermal line-contact EHL (seed 000 eq. 2, 4–5, 7–9): the generalized Reynolds equation with
//! effective density/viscosity integrals across the film, the film energy equation and heat
//! conduction into the two moving solids, coupled to the Newton solver of [`super::newton`].
//!
//! # Equations
//! Body 1 (the cam) is the surface `z = 0` moving at `u1`, body 2 (the roller) `z = h` at `u2`.
//! * **Film velocity** of a Newtonian (or Eyring, see below) film with viscosity varying across
//!   it: `τ(z) = τ_1 + z ∂p/∂x`, `∂u/∂z = τ/η`, so with `F0(z) = ∫0^z dz'/η` and
//!   `F1(z) = ∫0^z z'/η dz'`: `u = u1 + τ_1 F0 + ∂p/∂x F1`, `τ_1 = (u2 − u1 − ∂p/∂x F1(h))/F0(h)`.
//! * **Generalized Reynolds** (seed 000 eq. 2, Yang & Wen 1990): the mass flow is
//!   `m = (h/2)(u1 ρ*_1 + u2 ρ*_2) − (ρ/η)_e h³/12 ∂p/∂x` with `ρ_e = (1/h)∫ρ`,
//!   `ρ'_e = (1/h²)∫ρ F0`, `ρ''_e = (1/h³)∫ρ F1`, `η_e = h/F0(h)`, `η'_e = h²/F1(h)`,
//!   `(ρ/η)_e = 12(η_e ρ'_e/η'_e − ρ''_e)`, `ρ*_1 = 2(ρ_e − ρ'_e η_e)`, `ρ*_2 = 2ρ'_e η_e`. The
//!   Newton solver takes them as multipliers of its isothermal coefficients
//!   ([`ThermalFactors`]): `(ρ/η)_e/(ρ/η)_iso`, `(u1 ρ*_1 + u2 ρ*_2)/(2 u_m ρ_iso)` and
//!   `ρ_e/ρ_iso`, where `iso` is the lubricant at the inlet temperature and the node's pressure.
//!   Isothermal columns give exactly 1, 1, 1.
//! * **Film energy** (seed 000 eq. 7): `c_f ρ (u ∂T/∂x + ∂T/∂t) = k_f ∂²T/∂z² +
//!   (T ρ0 C3/ρ) u ∂p/∂x + η (∂u/∂z)²`: convection along the film, conduction across it,
//!   compressive heating of the Dowson–Higginson density (eq. 5, `∂ρ/∂T = −ρ0 C3`) and shear
//!   heating, with the vertical convection `−q ∂T/∂z` of eq. 7 from continuity. On the film's
//!   stretched levels `ζ = z/h` the two convection terms become
//!   `ρu ∂T/∂x|_ζ − (1/h) ∂M/∂x|_ζ ∂T/∂ζ` with `M = h ∫0^ζ ρu dζ'`.
//! * **Solids** (seed 000 eq. 8): `c_s ρ_s (u_s ∂T/∂x + ∂T/∂t) = k_s ∂²T/∂z²` in each body to
//!   the depth `d` (seed 000: `d = 3.15 b`) where `T = T0`; `T = T0` where the film and the
//!   solids enter the domain; temperature and heat flux continuous at the surfaces.
//! * **Viscosity and density** at each point: Roelands/Barus with temperature (eq. 4) and
//!   Dowson–Higginson with the thermal term (eq. 5), from [`Lubricant`].
//! * **Traction** (eq. 9): the surface shear stresses `τ_1` and `τ(h)` integrated along `x`.
//!
//! With an Eyring stress `τ_E` the film is the generalized Newtonian fluid of Yang & Wen: the
//! viscosity in every integral above is the effective `η* = η (τ/τ_E)/sinh(τ/τ_E)` at the
//! point's shear stress. Each column's stress `τ_1 + z ∂p/∂x` is solved exactly at the current
//! temperatures (the shear rates integrate to `u2 − u1`, [`eyring_column`]); an earlier form
//! lagged the stress by one sweep, which cannot converge where `τ > 1.9 τ_E` (the map
//! `s ← A s/sinh s` has the slope `1 − s coth s` at its fixed point) and ran away at the seed 001
//! nose. A limiting shear stress is not applied; a film hotter than the inlet by
//! [`MAX_TEMPERATURE_RISE`] ends the solve as a runaway (typed error).
//!
//! # Method
//! A column of nodes across cam, film and roller at every grid node of the EHL solution (the
//! solids graded geometrically from the surface towards the depth `d`, the film on
//! [`ThermalOptions::film_points`] uniform levels). Each column's equation is a finite-volume
//! conduction balance across it (flux continuity at the surfaces is built in), with upwind
//! convection along `x` by the sign of each node's velocity; columns are solved by the Thomas
//! algorithm in alternating Gauss–Seidel sweeps along `x` (reverse flow in the inlet and
//! surfaces moving in opposite directions need both sweep directions), the temperature-dependent
//! viscosity and heating updated between sweeps. The pressure and film come from the Newton
//! solver with the current [`ThermalFactors`]; the two are iterated until the films and the
//! temperature stop changing ([`ThermalOptions::tolerance`]).

use super::newton::{Engine, Prediction};
use super::{EhlInput, EhlOptions, EhlSolution, Rheology, TractionResult};
use crate::lubricant::{DensityModel, Lubricant, DH_C3};
use crate::thermal::ThermalSolid;
use crate::{Convergence, Observer, SolveError, Termination};
use serde::{Deserialize, Serialize};

/// Thermal properties of the lubricant.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct FilmHeat {
    /// Conductivity `k_f`, W/(m·K).
    pub conductivity: f64,
    /// Specific heat `c_f`, J/(kg·K).
    pub specific_heat: f64,
}

impl FilmHeat {
    /// Seed 000 Table 1: `k_f = 0.14` W/(m·K), `c_f = 1700` J/(kg·K).
    pub const SEED000: FilmHeat = FilmHeat { conductivity: 0.14, specific_heat: 1700.0 };
}

/// Thermal properties of the film and the two bodies (body 1 at `z = 0`, body 2 at `z = h`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ThermalBodies {
    pub film: FilmHeat,
    pub body_1: ThermalSolid,
    pub body_2: ThermalSolid,
}

impl ThermalBodies {
    /// Seed 000 Table 1: the oil and two steel bodies.
    pub const SEED000: ThermalBodies = ThermalBodies { film: FilmHeat::SEED000, body_1: ThermalSolid::STEEL, body_2: ThermalSolid::STEEL };
}

/// Resolution, tolerance and iteration caps of the thermal model.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ThermalOptions {
    /// Levels across the film, both surfaces included (≥ 3).
    pub film_points: usize,
    /// Nodes in each solid from its surface to the depth `d`, both included (≥ 4).
    pub solid_points: usize,
    /// Depth `d` of the solids' thermal layer in Hertzian half-widths (seed 000: 3.15).
    pub solid_depth: f64,
    /// Relative change of the films (and 100× it of the largest temperature rise) between two
    /// coupling iterations at which the coupled solve stops.
    pub tolerance: f64,
    /// Most coupling iterations (energy ↔ Reynolds).
    pub max_iterations: u32,
    /// Most Gauss–Seidel sweeps of one energy solve.
    pub max_sweeps: u32,
    /// Largest temperature change of a sweep, relative to the largest temperature rise, at which
    /// an energy solve stops.
    pub sweep_tolerance: f64,
    /// The energy equation is solved where the film is at most this multiple of the minimum film
    /// (the contact and the near inlet and outlet); beyond, the oil and the solids are at the inlet
    /// temperature. The far inlet of a thick film (the Newton domain reaches 40 half-widths
    /// upstream) only recirculates heat: measured effect on the films below 0.1 % at 10.
    pub film_extent: f64,
    /// How the nonlinear energy equations are iterated (see [`EnergyIteration`]).
    pub iteration: EnergyIteration,
}

/// The iteration of the energy equations' nonlinearity (viscosity, velocities and heating
/// depend on the temperature).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum EnergyIteration {
    /// Gauss–Seidel sweeps updating the film's properties column by column, frozen after
    /// [`FREEZE_AFTER`] sweeps (stops on a noise floor of ≈ 2 % of the rise where the heating
    /// feeds back strongly).
    Sweeps,
    /// Outer fixed-point iteration on the temperature field with Anderson mixing (Walker & Ni,
    /// SIAM J. Numer. Anal. 49 (2011), type II, depth [`ANDERSON_DEPTH`]): each outer step
    /// updates every column's properties once at the current field and solves the then linear
    /// equations by sweeps (shear heating linearised about the outer iterate); the mixing cures
    /// the period-2 alternation of the hot mid-film and converges to the self-consistent field.
    /// The inlet and exit columns hold their mass flow (see [`HOLD_FLOW_PRESSURE`]); a solve that
    /// does not settle falls back to the sweeps. Not the default: on single contacts it agrees
    /// with the sweeps to 1e-4 (`thermal_ehl::energy_iterations_agree`), but on the seed 000
    /// cycle's traction tables (energy at a fixed pressure, other sliding) Newtonian layers in the
    /// Hertzian zone run away (|u| up to 66 m/s with surfaces at ≈ 2.5 m/s) and most solves fell
    /// back (BENCHMARKS.md, "Thermal EHL", issue 14 fourth session).
    Anderson,
}

impl Default for ThermalOptions {
    fn default() -> Self {
        ThermalOptions { film_points: 7, solid_points: 16, solid_depth: 3.15, tolerance: 1e-3, max_iterations: 40, max_sweeps: 200, sweep_tolerance: 1e-4, film_extent: 30.0, iteration: EnergyIteration::Sweeps }
    }
}

/// Multipliers of the Newton solver's isothermal coefficients at positions `x` (m): see the
/// module docs. Beyond the ends the end values hold.
#[derive(Debug, Clone, PartialEq)]
pub struct ThermalFactors {
    pub x: Vec<f64>,
    pub poiseuille: Vec<f64>,
    pub wedge: Vec<f64>,
    pub mass: Vec<f64>,
}

/// The temperature field, K, on the columns of one EHL grid.
#[derive(Debug, Clone, PartialEq)]
pub struct TemperatureField {
    /// Column positions, m.
    pub x: Vec<f64>,
    /// Film temperature at `film_points` uniform levels `ζ = z/h` (row-major: `x` then `ζ`).
    pub film: Vec<f64>,
    /// Body 1 temperature from its surface (first) to the depth `d`, at `solid_points` levels.
    pub body_1: Vec<f64>,
    /// Body 2 likewise.
    pub body_2: Vec<f64>,
    pub film_points: usize,
    pub solid_points: usize,
}

impl TemperatureField {
    fn uniform(x: &[f64], t: f64, nz: usize, ns: usize) -> Self {
        let n = x.len();
        TemperatureField { x: x.to_vec(), film: vec![t; n * nz], body_1: vec![t; n * ns], body_2: vec![t; n * ns], film_points: nz, solid_points: ns }
    }

    /// The field moved onto columns `x` (m), linear in `x`, the end columns held beyond the ends.
    fn resampled(&self, x: &[f64]) -> Self {
        let (nz, ns) = (self.film_points, self.solid_points);
        let mut out = TemperatureField::uniform(x, 0.0, nz, ns);
        let m = self.x.len();
        for (i, &xi) in x.iter().enumerate() {
            let j = self.x.partition_point(|&v| v <= xi).clamp(1, m - 1);
            let t = ((xi - self.x[j - 1]) / (self.x[j] - self.x[j - 1])).clamp(0.0, 1.0);
            let mix = |v: &[f64], k: usize, w: usize| v[(j - 1) * w + k] * (1.0 - t) + v[j * w + k] * t;
            for k in 0..nz {
                out.film[i * nz + k] = mix(&self.film, k, nz);
            }
            for k in 0..ns {
                out.body_1[i * ns + k] = mix(&self.body_1, k, ns);
                out.body_2[i * ns + k] = mix(&self.body_2, k, ns);
            }
        }
        out
    }

    /// All temperatures as one vector (body 1, film, body 2).
    fn flat(&self) -> Vec<f64> {
        let mut v = Vec::with_capacity(self.body_1.len() + self.film.len() + self.body_2.len());
        v.extend_from_slice(&self.body_1);
        v.extend_from_slice(&self.film);
        v.extend_from_slice(&self.body_2);
        v
    }

    /// The inverse of [`Self::flat`].
    fn set_flat(&mut self, v: &[f64]) {
        let (a, b) = (self.body_1.len(), self.film.len());
        self.body_1.copy_from_slice(&v[..a]);
        self.film.copy_from_slice(&v[a..a + b]);
        self.body_2.copy_from_slice(&v[a + b..]);
    }

    /// Largest film temperature, K.
    pub fn film_max(&self) -> f64 {
        self.film.iter().fold(f64::NEG_INFINITY, |a, &b| a.max(b))
    }

    /// Film temperature across the film at column `i`.
    pub fn film_column(&self, i: usize) -> &[f64] {
        &self.film[i * self.film_points..(i + 1) * self.film_points]
    }

    /// Largest surface temperature of body 1 and of body 2, K.
    pub fn surface_max(&self) -> (f64, f64) {
        let ns = self.solid_points;
        let n = self.x.len();
        let max = |v: &[f64]| (0..n).map(|i| v[i * ns]).fold(f64::NEG_INFINITY, f64::max);
        (max(&self.body_1), max(&self.body_2))
    }
}

/// Heat flows per unit contact length, W/m, and temperatures of one energy solve.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ThermalSummary {
    /// Largest film temperature, K.
    pub film_temperature_max: f64,
    /// Largest surface temperature of body 1 (cam) and body 2, K.
    pub surface_temperature_max_1: f64,
    pub surface_temperature_max_2: f64,
    /// Mean film temperature weighted by pressure, K (the film's temperature where it carries load).
    pub film_temperature_mean: f64,
    /// Heat generated in the film (shear + compression), W/m.
    pub heat_generated: f64,
    /// Heat taken up by body 1 and body 2 (carried out of the domain and conducted to the depth
    /// `d`, plus stored in a transient step), W/m.
    pub heat_to_body_1: f64,
    pub heat_to_body_2: f64,
    /// Heat carried out of the domain by the film, W/m.
    pub heat_convected: f64,
    /// `|generated − (to bodies + convected)| / generated` (0 without heat).
    pub energy_balance_error: f64,
    /// Gauss–Seidel sweeps of the last energy solve.
    pub sweeps: u32,
    /// The last sweep's largest temperature change relative to the largest rise (below
    /// `sweep_tolerance` when converged; up to 500× that when the sweeps stalled).
    pub sweep_change: f64,
}

/// One energy solve at a fixed pressure and film.
#[derive(Debug, Clone)]
pub struct EnergySolution {
    pub field: TemperatureField,
    pub factors: ThermalFactors,
    /// Surface shear forces per unit length (eq. 9) and the sliding friction coefficient.
    pub traction: TractionResult,
    pub summary: ThermalSummary,
}

/// What the energy equation needs besides the pressure and film.
#[derive(Debug, Clone, Copy)]
pub struct EnergyInput<'a> {
    /// Surface velocities of body 1 (`z = 0`) and body 2 (`z = h`), m/s.
    pub velocity_1: f64,
    pub velocity_2: f64,
    pub lubricant: &'a Lubricant,
    /// Inlet (ambient) temperature `T0`, K.
    pub inlet_temperature: f64,
    pub bodies: &'a ThermalBodies,
    /// Hertzian half-width `b`, m (sets the solids' depth).
    pub half_width: f64,
    /// Load per unit length, N/m (friction coefficient).
    pub load_per_length: f64,
    pub rheology: &'a Rheology,
    /// The previous time step's field and the time step, s (transient); `None`: steady.
    pub previous: Option<(&'a TemperatureField, f64)>,
    /// A field to start the sweeps from (any grid); `None`: the inlet temperature.
    pub warm: Option<&'a TemperatureField>,
}

/// Film quantities of one column at the current temperatures.
struct Column {
    /// Effective viscosity at the film levels, Pa·s, relative to `eta_ref`.
    eta: Vec<f64>,
    /// The Newtonian viscosity at the levels' temperatures (under-relaxed between sweeps),
    /// relative to `eta_ref`; `eta` is this times the Eyring factor.
    eta_n: Vec<f64>,
    rho: Vec<f64>,
    u: Vec<f64>,
    /// Shear stress at the film levels, Pa.
    tau: Vec<f64>,
    /// `−∂ ln η/∂T` at the film levels, 1/K.
    beta: Vec<f64>,
}

/// Eyring film across one column (Yang & Wen's generalized Newtonian fluid; Eyring's law
/// `γ̇ = (τ_E/η) sinh(τ/τ_E)`, e.g. Johnson & Tevaarwerk 1977): the shear stress
/// `τ(z) = τ_1 + (∂p/∂x) z` (momentum across a thin film) whose shear rate integrates,
/// trapezoidally over the levels as `F0`/`F1` do, to the surface speed difference `du`. Writes
/// the effective viscosities `η* = τ/γ̇ = η (τ/τ_E)/sinh(τ/τ_E)` relative to `eta_ref` into
/// `eta`, so the Newtonian-form velocities and stresses built from them are the Eyring ones.
/// `eta_n`: the Newtonian viscosities relative to `eta_ref`. Where no stress is found (not
/// expected: the constraint is monotone in `τ_1`) the Newtonian values stay.
fn eyring_column(eta_n: &[f64], eta_ref: f64, dz: f64, du: f64, px: f64, te: f64, eta: &mut [f64]) {
    let nz = eta_n.len();
    let weight = |k: usize| if k == 0 || k == nz - 1 { 0.5 * dz } else { dz };
    // Stresses in units of τ_E: s_k = t + c_k.
    let c: Vec<f64> = (0..nz).map(|k| px * dz * k as f64 / te).collect();
    let cmax = c.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    // g(t) = Σ w_k (τ_E/η_k) sinh(t + c_k) − du and its derivative; increasing in t.
    let g = |t: f64| -> (f64, f64) {
        let (mut v, mut d) = (-du, 0.0);
        for k in 0..nz {
            let a = weight(k) * te / (eta_n[k] * eta_ref);
            let s = t + c[k];
            v += a * s.sinh();
            d += a * s.cosh();
        }
        (v, d)
    };
    let limit = 700.0 - cmax;
    if limit <= 1.0 {
        return;
    }
    // Bracket the root by doubling outwards from ±1.
    let (mut lo, mut hi) = (-1.0f64, 1.0f64);
    while g(lo).0 > 0.0 && lo > -limit {
        lo = (2.0 * lo).max(-limit);
    }
    while g(hi).0 < 0.0 && hi < limit {
        hi = (2.0 * hi).min(limit);
    }
    let (glo, ghi) = (g(lo).0, g(hi).0);
    if !(glo <= 0.0 && ghi >= 0.0) {
        return;
    }
    // Safeguarded Newton: a Newton step inside the bracket, else bisection.
    let mut t = 0.5 * (lo + hi);
    for _ in 0..200 {
        let (v, d) = g(t);
        if !v.is_finite() || v > 0.0 {
            hi = t;
        } else {
            lo = t;
        }
        // Converged at this t: the speed difference met to 1e-13 of itself (of the Poiseuille
        // part's scale in pure rolling) or the bracket closed.
        if v.abs() <= 1e-13 * du.abs().max(1e-9) || hi - lo < 1e-13 * (1.0 + t.abs()) {
            break;
        }
        let step = t - v / d;
        t = if v.is_finite() && d.is_finite() && d > 0.0 && step > lo && step < hi { step } else { 0.5 * (lo + hi) };
    }
    for k in 0..nz {
        let s = (t + c[k]).abs();
        let factor = if s > 1e-8 { s / s.sinh() } else { 1.0 };
        eta[k] = (eta_n[k] * factor).max(1e-300);
    }
}

/// Depths of the solid nodes from the surface: `d (g^k − 1)/(g^(m) − 1)`, the ratio `g` chosen so
/// the first cell is a fifth of the thermal penetration depth `√(κ 2b/|u|)` (at least uniform).
fn solid_depths(d: f64, ns: usize, penetration: f64) -> Vec<f64> {
    let m = (ns - 1) as i32;
    let first = (penetration / 5.0).min(d / m as f64);
    let cell = |g: f64| if (g - 1.0).abs() < 1e-12 { d / m as f64 } else { d * (g - 1.0) / (g.powi(m) - 1.0) };
    let (mut lo, mut hi) = (1.0, 3.0);
    if cell(hi) > first {
        lo = hi;
    } else {
        for _ in 0..60 {
            let mid = 0.5 * (lo + hi);
            if cell(mid) > first {
                lo = mid;
            } else {
                hi = mid;
            }
        }
    }
    let g = lo;
    (0..ns).map(|k| if (g - 1.0).abs() < 1e-12 { d * k as f64 / m as f64 } else { d * (g.powi(k as i32) - 1.0) / (g.powi(m) - 1.0) }).collect()
}

/// Sweeps after which an energy solve freezes the film's properties (see [`energy`]).
const FREEZE_AFTER: u32 = 40;

/// Mixing depth of [`EnergyIteration::Anderson`].
const ANDERSON_DEPTH: usize = 5;
/// Columns below this fraction of the peak pressure hold their mass flow (Anderson).
const HOLD_FLOW_PRESSURE: f64 = 0.3;
/// Share of `ThermalOptions::max_sweeps` an Anderson solve may use before the sweeps take over.
const ANDERSON_SWEEP_SHARE: f64 = 0.5;
/// Most linear sweeps of one Anderson outer step.
const ANDERSON_INNER_SWEEPS: u32 = 30;

/// Anderson mixing, type II (Walker & Ni 2011): from the last `depth + 1` pairs `(x_i, g_i =
/// G(x_i))` with residuals `f_i = g_i − x_i`, `γ = argmin ‖f_k − ΔF γ‖₂` (column-pivoted QR,
/// which also handles a rank-deficient history) and `x_{k+1} = g_k − ΔG γ`.
struct AndersonMixer {
    depth: usize,
    g: std::collections::VecDeque<Vec<f64>>,
    f: std::collections::VecDeque<Vec<f64>>,
}

impl AndersonMixer {
    fn new(depth: usize) -> Self {
        AndersonMixer { depth, g: Default::default(), f: Default::default() }
    }

    fn clear(&mut self) {
        self.g.clear();
        self.f.clear();
    }

    fn next(&mut self, x: &[f64], g: &[f64]) -> Vec<f64> {
        use faer::linalg::solvers::SolveLstsq;
        self.f.push_back(g.iter().zip(x).map(|(a, b)| a - b).collect());
        self.g.push_back(g.to_vec());
        if self.g.len() > self.depth + 1 {
            self.g.pop_front();
            self.f.pop_front();
        }
        let m = self.g.len() - 1;
        if m == 0 {
            return g.to_vec();
        }
        let n = g.len();
        let fk = &self.f[m];
        let df = faer::Mat::from_fn(n, m, |r, c| self.f[c + 1][r] - self.f[c][r]);
        let rhs = faer::Mat::from_fn(n, 1, |r, _| fk[r]);
        let gamma = df.col_piv_qr().solve_lstsq(&rhs);
        let mut out = g.to_vec();
        for c in 0..m {
            let w = gamma[(c, 0)];
            if !w.is_finite() {
                // A degenerate history: plain fixed-point step, history restarted.
                self.clear();
                return g.to_vec();
            }
            for (r, o) in out.iter_mut().enumerate() {
                *o -= w * (self.g[c + 1][r] - self.g[c][r]);
            }
        }
        out
    }
}

/// Thomas algorithm for `a_i x_{i−1} + b_i x_i + c_i x_{i+1} = r_i` (in place into `r`).
fn thomas(a: &[f64], b: &mut [f64], c: &[f64], r: &mut [f64]) {
    let n = b.len();
    for i in 1..n {
        let w = a[i] / b[i - 1];
        b[i] -= w * c[i - 1];
        r[i] -= w * r[i - 1];
    }
    r[n - 1] /= b[n - 1];
    for i in (0..n - 1).rev() {
        r[i] = (r[i] - c[i] * r[i + 1]) / b[i];
    }
}

/// Solve the energy equations (seed 000 eq. 7–8) on the columns of `(x, p, h)` (m, Pa, m).
/// With [`EnergyIteration::Anderson`], a solve that does not converge within
/// [`ANDERSON_SWEEP_SHARE`] of `max_sweeps` (the mixing cycles, or a layer's flow runs away at
/// the fixed pressure) is solved again from the same start by [`EnergyIteration::Sweeps`].
pub fn energy(x: &[f64], p: &[f64], h: &[f64], input: &EnergyInput, options: &ThermalOptions) -> Result<EnergySolution, SolveError> {
    if options.iteration != EnergyIteration::Anderson {
        return energy_iterated(x, p, h, input, options);
    }
    let budget = ((options.max_sweeps as f64 * ANDERSON_SWEEP_SHARE) as u32).max(1);
    match energy_iterated(x, p, h, input, &ThermalOptions { max_sweeps: budget, ..*options }) {
        Ok(s) => Ok(s),
        Err(SolveError::NotConverged { .. }) => {
            energy_iterated(x, p, h, input, &ThermalOptions { iteration: EnergyIteration::Sweeps, ..*options })
        }
        Err(e) => Err(e),
    }
}

fn energy_iterated(x: &[f64], p: &[f64], h: &[f64], input: &EnergyInput, options: &ThermalOptions) -> Result<EnergySolution, SolveError> {
    let n = x.len();
    let nz = options.film_points;
    let ns = options.solid_points;
    if n < 3 || nz < 3 || ns < 4 {
        return Err(SolveError::invalid("ThermalOptions", "needs ≥ 3 columns, ≥ 3 film points and ≥ 4 solid points"));
    }
    let lub = input.lubricant;
    let t0 = input.inlet_temperature;
    let (u1, u2) = (input.velocity_1, input.velocity_2);
    let bodies = input.bodies;
    let (kf, cf) = (bodies.film.conductivity, bodies.film.specific_heat);
    let b = input.half_width;
    let d = options.solid_depth * b;
    let pen = |s: &ThermalSolid, u: f64| (s.diffusivity() * 2.0 * b / u.abs().max(1e-9)).sqrt();
    let z1 = solid_depths(d, ns, pen(&bodies.body_1, u1));
    let z2 = solid_depths(d, ns, pen(&bodies.body_2, u2));
    let rc1 = bodies.body_1.density * bodies.body_1.specific_heat;
    let rc2 = bodies.body_2.density * bodies.body_2.specific_heat;
    let compressive = lub.density_model == DensityModel::DowsonHigginson;
    let eyring = input.rheology.eyring_stress.filter(|t| *t > 0.0);
    let ln_eta0 = lub.viscosity.ln();
    let dpdx: Vec<f64> = (0..n)
        .map(|i| {
            let (a, c) = (i.saturating_sub(1), (i + 1).min(n - 1));
            (p[c] - p[a]) / (x[c] - x[a])
        })
        .collect();
    // Trapezoidal x weights.
    let wx: Vec<f64> = (0..n).map(|i| 0.5 * (x[(i + 1).min(n - 1)] - x[i.saturating_sub(1)])).collect();

    let mut field = match input.warm {
        Some(w) if w.film_points == nz && w.solid_points == ns => w.resampled(x),
        _ => TemperatureField::uniform(x, t0, nz, ns),
    };
    let old = input.previous.filter(|(f, dt)| f.film_points == nz && f.solid_points == ns && *dt > 0.0).map(|(f, dt)| (f.resampled(x), dt));
    // Column layout: body 1 from the depth (index 0) to its surface (ns − 1), the film levels
    // (ns − 1 .. ns − 2 + nz), body 2 from its surface to the depth (N − 1).
    let nn = 2 * ns + nz - 2;
    let i_film0 = ns - 1;
    let i_film1 = ns + nz - 3 + 1;
    let mut columns: Vec<Column> = (0..n).map(|_| Column { eta: vec![1.0; nz], eta_n: vec![1.0; nz], rho: vec![1.0; nz], u: vec![0.0; nz], tau: vec![0.0; nz], beta: vec![0.0; nz] }).collect();
    let mut eta_ref = vec![1.0; n];
    let relax_cell = std::cell::Cell::new(1.0f64);
    // Columns below `HOLD_FLOW_PRESSURE` of the peak pressure (the inlet and the exit) hold their
    // mass flow at its value when this solve first evaluates them (Anderson iteration only): at
    // a fixed pressure gradient a heated layer at the exit would draw an unbounded Poiseuille flow
    // (a runaway to 4× the surface speeds was measured at w' = 2e5 N/m, u_m = 5 m/s, S = 0.3),
    // which the coupled Reynolds solution would not carry, and the inlet's backflow kept the
    // mixing from settling. The gradient then follows the viscosity, never beyond the pressure's
    // own (same sign, at most its size).
    let p_peak = p.iter().fold(0.0f64, |m, &v| m.max(v));
    let hold_flow = |i: usize| {
        options.iteration == EnergyIteration::Anderson && p[i] < HOLD_FLOW_PRESSURE * p_peak
    };
    let flow_target: Vec<std::cell::Cell<f64>> = (0..n).map(|_| std::cell::Cell::new(f64::NAN)).collect();

    // Film properties of column i at its current temperatures (and the previous stresses for
    // the Eyring viscosity).
    let update_column = |i: usize, temps: &[f64], col: &mut Column, eta_ref: &mut f64| {
        let hi = h[i];
        let dz = hi / (nz - 1) as f64;
        let pi = p[i].max(0.0);
        let law = lub.pressure_law(pi);
        // Reference viscosity: the lubricant at the inlet temperature and this pressure.
        let ln_ref = (ln_eta0 + law.ln_ratio_and_temperature_slope(t0).0).min(600.0 + ln_eta0);
        *eta_ref = ln_ref.exp();
        for k in 0..nz {
            let (ln_ratio, ln_slope) = law.ln_ratio_and_temperature_slope(temps[k]);
            let ln_e = (ln_eta0 + ln_ratio).min(600.0 + ln_eta0);
            let w = relax_cell.get();
            let ln_new = ln_e - ln_ref;
            let ln_rel = if w < 1.0 && col.eta_n[k] > 0.0 && col.u.iter().any(|&u| u != 0.0) { (1.0 - w) * col.eta_n[k].ln() + w * ln_new } else { ln_new };
            col.eta_n[k] = ln_rel.exp().max(1e-300);
            col.eta[k] = col.eta_n[k];
            col.beta[k] = -ln_slope;
            col.rho[k] = lub.density_ratio(pi, temps[k]);
        }
        if let Some(te) = eyring {
            // The column's Eyring stress solved exactly at these viscosities: the lagged form
            // (η* from the previous sweep's stress) is unstable wherever τ > 1.9 τ_E — its
            // fixed-point map s ← A s/sinh s has the slope 1 − s coth s at s = asinh A — and ran
            // away in the first sweep at the seed 001 nose (1.4 GPa, τ_E = 5 MPa).
            eyring_column(&col.eta_n, *eta_ref, dz, u2 - u1, dpdx[i], te, &mut col.eta);
        }
        // F0, F1 in units of dz/η_ref.
        let mut f0 = vec![0.0; nz];
        let mut f1 = vec![0.0; nz];
        for k in 1..nz {
            f0[k] = f0[k - 1] + 0.5 * dz * (1.0 / col.eta[k - 1] + 1.0 / col.eta[k]);
            f1[k] = f1[k - 1] + 0.5 * dz * (dz * (k - 1) as f64 / col.eta[k - 1] + dz * k as f64 / col.eta[k]);
        }
        let mut px = dpdx[i];
        if hold_flow(i) {
            // Mass flow per unit width (trapezoidal over the levels, units ρ0·m²/s) as
            // `A + px·B`: u_k = u1 + (u2 − u1) f0_k/f0_h + px (f1_k − f1_h f0_k/f0_h)/η_ref.
            let (f0h, f1h) = (f0[nz - 1], f1[nz - 1]);
            let (mut a, mut bcoef) = (0.0, 0.0);
            for k in 0..nz {
                let w = if k == 0 || k == nz - 1 { 0.5 * dz } else { dz };
                a += w * col.rho[k] * (u1 + (u2 - u1) * f0[k] / f0h);
                bcoef += w * col.rho[k] * (f1[k] - f1h * f0[k] / f0h) / *eta_ref;
            }
            let target = flow_target[i].get();
            if target.is_nan() {
                flow_target[i].set(a + px * bcoef);
            } else if bcoef.abs() > 0.0 {
                let want = (target - a) / bcoef;
                px = if px > 0.0 { want.clamp(0.0, px) } else { want.clamp(px, 0.0) };
            }
        }
        // Dimensional: F0 = f0/η_ref, F1 = f1/η_ref.
        let tau1 = ((u2 - u1) * *eta_ref - px * f1[nz - 1]) / f0[nz - 1];
        for k in 0..nz {
            col.u[k] = u1 + (tau1 * f0[k] + px * f1[k]) / *eta_ref;
            col.tau[k] = tau1 + px * dz * k as f64;
        }
    };

    let mut sweeps = 0;
    let mut converged = false;
    let mut last_change = f64::INFINITY;
    let mut relax: f64 = 1.0;
    let mut same_direction = f64::INFINITY;
    // Anderson iteration state: the outer iterate x_k the current linear sweeps started from (its
    // temperatures linearise the shear heating), the sweeps of the current outer step and their
    // tolerance, the mixing history.
    let anderson = options.iteration == EnergyIteration::Anderson;
    let mut outer_start: Option<TemperatureField> = None;
    let mut inner_sweeps = 0u32;
    let mut inner_tolerance = 0.1;
    let mut mixer = AndersonMixer::new(ANDERSON_DEPTH);
    let mut best_residual = f64::INFINITY;
    let scale_rise = |f: &TemperatureField| (f.film_max() - t0).abs().max(1e-3);
    // Tridiagonal work arrays.
    let mut za = vec![0.0; nn];
    let mut zb = vec![0.0; nn];
    let mut zc = vec![0.0; nn];
    let mut zr = vec![0.0; nn];
    let mut pos = vec![0.0; nn];
    let mut temps = vec![0.0; nn];
    // Convection in conservative donor-cell form. `q[i·N + j]`: the heat-capacity flux
    // `Σ ρ c u ℓ` of column node j (its two half cells ℓ; the film's on the stretched levels
    // ζ = z/h), W/(m·K); face fluxes are the means of neighbouring nodes, the boundary faces the
    // end nodes'. The film's flow across the levels follows from continuity: the flux through the
    // face above film node j is `V = −Σ_{m ≤ j} (G_{i+½,m} − G_{i−½,m})/Δx_i` (seed 000 eq. 7's
    // `q ∂T/∂z`). Every node then convects `Σ_inflow |G| (T − T_upwind)`: exactly conservative.
    let mut q = vec![0.0; n * nn];
    let mut v_up = vec![0.0; n * nn];
    let mut leak = vec![0.0; n];
    for i in 0..n {
        let temps: Vec<f64> = field.film_column(i).to_vec();
        update_column(i, &temps, &mut columns[i], &mut eta_ref[i]);
    }
    let cap_of = |columns: &[Column], i: usize, j: usize| -> f64 {
        // Heat capacity per unit area ρ c ℓ of node j's half cells at column i, J/(m²·K).
        let dzf = h[i] / (nz - 1) as f64;
        let film_half = |k: usize| 0.5 * dzf * lub.density * columns[i].rho[k] * cf;
        let mut c = 0.0;
        if j > 0 && j <= i_film0 {
            c += 0.5 * (z1[ns - j] - z1[ns - 1 - j]) * rc1;
        }
        if j < i_film0 {
            c += 0.5 * (z1[ns - 1 - j] - z1[ns - 2 - j]) * rc1;
        }
        if j >= i_film0 && j < i_film1 {
            c += film_half(j - i_film0);
        }
        if j > i_film0 && j <= i_film1 {
            c += film_half(j - i_film0);
        }
        if j >= i_film1 && j + 1 < nn {
            c += 0.5 * (z2[j + 1 - i_film1] - z2[j - i_film1]) * rc2;
        }
        if j > i_film1 {
            c += 0.5 * (z2[j - i_film1] - z2[j - 1 - i_film1]) * rc2;
        }
        c
    };
    let velocity_of = |columns: &[Column], i: usize, j: usize| -> f64 {
        if j < i_film0 {
            u1
        } else if j > i_film1 {
            u2
        } else {
            columns[i].u[j - i_film0]
        }
    };
    while sweeps < options.max_sweeps {
        let forward = sweeps % 2 == 0;
        sweeps += 1;
        if anderson && outer_start.is_none() {
            // A new outer step: the film's properties once at the current field, then frozen.
            for i in 0..n {
                let temps: Vec<f64> = field.film_column(i).to_vec();
                update_column(i, &temps, &mut columns[i], &mut eta_ref[i]);
            }
            outer_start = Some(field.clone());
            inner_sweeps = 0;
        }
        for i in 0..n {
            if anderson && inner_sweeps > 0 {
                break;
            }
            for j in 0..nn {
                q[i * nn + j] = cap_of(&columns, i, j) * velocity_of(&columns, i, j);
            }
        }
        for i in 0..n {
            if anderson && inner_sweeps > 0 {
                break;
            }
            let mut acc = 0.0;
            for j in i_film0..=i_film1 {
                let gl = if i == 0 { q[j] } else { 0.5 * (q[(i - 1) * nn + j] + q[i * nn + j]) };
                let gr = if i == n - 1 { q[i * nn + j] } else { 0.5 * (q[i * nn + j] + q[(i + 1) * nn + j]) };
                acc += (gr - gl) / wx[i];
                v_up[i * nn + j] = -acc;
            }
            // The film's net outflow (the pressure solution's discrete mass defect).
            leak[i] = acc;
            v_up[i * nn + i_film1] = 0.0;
        }
        let mut change: f64 = 0.0;
        for step in 0..n {
            let i = if forward { step } else { n - 1 - step };
            // Gather the current column.
            for k in 0..ns {
                temps[ns - 1 - k] = field.body_1[i * ns + k];
                temps[i_film1 + k] = field.body_2[i * ns + k];
            }
            for k in 0..nz {
                temps[i_film0 + k] = field.film[i * nz + k];
            }
            // After FREEZE_AFTER sweeps the film's properties and velocities stay as they are:
            // the remaining problem is linear and the sweeps converge (a limit cycle of the
            // upwind directions in the inlet's recirculation can otherwise persist).
            if !anderson && sweeps <= FREEZE_AFTER {
                update_column(i, &temps[i_film0..i_film0 + nz], &mut columns[i], &mut eta_ref[i]);
            }
            let col = &columns[i];
            let hi = h[i];
            let dz = hi / (nz - 1) as f64;
            for k in 0..ns {
                pos[ns - 1 - k] = -z1[k];
                pos[i_film1 + k] = hi + z2[k];
            }
            for k in 0..nz {
                pos[i_film0 + k] = dz * k as f64;
            }
            // Node properties: velocity and ρc of each half cell, sources.
            let prop = |j: usize, upper: bool| -> (f64, f64, f64, f64) {
                // (k, ρc, source density at the current temperature, its temperature slope) of
                // the half cell above (upper) or below node j. The shear heating is linearised
                // with the slope of a film heating uniformly (τ ∝ η, heat ∝ η: −β·heat), which
                // keeps the sweeps stable where the heating is strongly self-limiting.
                let seg = if upper { j } else { j - 1 };
                if seg < i_film0 {
                    (bodies.body_1.conductivity, rc1, 0.0, 0.0)
                } else if seg >= i_film1 {
                    (bodies.body_2.conductivity, rc2, 0.0, 0.0)
                } else {
                    let k = j - i_film0;
                    let rho = lub.density * col.rho[k];
                    let eta = col.eta[k] * eta_ref[i];
                    let shear = col.tau[k] * col.tau[k] / eta;
                    // Compressive heating a·T: cooling (a < 0) implicit, heating lagged.
                    let a_comp = if compressive { lub.density * DH_C3 / rho * col.u[k] * dpdx[i] } else { 0.0 };
                    (kf, rho * cf, shear + a_comp * temps[j], -col.beta[k].max(0.0) * shear + a_comp.min(0.0))
                }
            };
            for j in 0..nn {
                if j == 0 || j == nn - 1 {
                    za[j] = 0.0;
                    zc[j] = 0.0;
                    zb[j] = 1.0;
                    zr[j] = t0;
                    continue;
                }
                let (kl, rcl, sl, dsl) = prop(j, false);
                let (ku, rcu, su, dsu) = prop(j, true);
                let (a, c) = (pos[j] - pos[j - 1], pos[j + 1] - pos[j]);
                let (gl, gu) = (kl / a, ku / c);
                let cap = rcl * 0.5 * a + rcu * 0.5 * c;
                za[j] = -gl;
                zc[j] = -gu;
                zb[j] = gl + gu;
                // Linearised source S* + S'(T − T*), S' ≤ 0, over the half cells.
                let slope = dsl * 0.5 * a + dsu * 0.5 * c;
                zb[j] -= slope;
                // Sweeps: about the current temperature (a stabiliser; the fixed point has the
                // frozen source). Anderson: about the outer iterate (a Newton-like linearisation).
                let t_lin = match &outer_start {
                    Some(x) => node_temperature(x, i, j, ns, nz, i_film0, i_film1),
                    None => temps[j],
                };
                zr[j] = sl * 0.5 * a + su * 0.5 * c - slope * t_lin;
                // Horizontal inflows (donor cell).
                let qj = q[i * nn + j];
                let g_left = if i == 0 { qj } else { 0.5 * (q[(i - 1) * nn + j] + qj) };
                let g_right = if i == n - 1 { qj } else { 0.5 * (qj + q[(i + 1) * nn + j]) };
                if g_left > 0.0 {
                    let t_up = if i == 0 { t0 } else { node_temperature(&field, i - 1, j, ns, nz, i_film0, i_film1) };
                    zb[j] += g_left / wx[i];
                    zr[j] += g_left / wx[i] * t_up;
                }
                if g_right < 0.0 {
                    let t_up = if i == n - 1 { t0 } else { node_temperature(&field, i + 1, j, ns, nz, i_film0, i_film1) };
                    zb[j] -= g_right / wx[i];
                    zr[j] -= g_right / wx[i] * t_up;
                }
                // Flow across the film levels (implicit, upwind).
                if j > i_film0 && j <= i_film1 {
                    let below = v_up[i * nn + j - 1];
                    if below > 0.0 {
                        za[j] -= below;
                        zb[j] += below;
                    }
                }
                if j >= i_film0 && j < i_film1 {
                    let above = v_up[i * nn + j];
                    if above < 0.0 {
                        zc[j] += above;
                        zb[j] -= above;
                    }
                }
                if j == i_film1 && leak[i] > 0.0 {
                    zb[j] += leak[i];
                    zr[j] += leak[i] * t0;
                }
                if let Some((of, dt)) = &old {
                    let told = node_temperature(of, i, j, ns, nz, i_film0, i_film1);
                    zb[j] += cap / dt;
                    zr[j] += cap / dt * told;
                }
            }
            thomas(&za, &mut zb, &zc, &mut zr);
            let rise = scale_rise(&field);
            for j in 0..nn {
                let v = zr[j];
                if !v.is_finite() || v > t0 + MAX_TEMPERATURE_RISE {
                    // Runaway shear heating (a Newtonian film sheared far beyond its traction
                    // maximum, or a hot layer drawing an unbounded Poiseuille flow at the fixed
                    // pressure gradient): a typed failure, not a NaN or a film at thousands of
                    // kelvin where eq. 4–5 mean nothing (measured: 45 000 K, then 1e24 K, with
                    // negative densities, at the seed 001 nose with S = 1 before this bound).
                    return Err(SolveError::NotConverged {
                        solver: "thermal ehl energy equation (temperature runaway)",
                        iterations: sweeps,
                        residual: f64::INFINITY,
                        tolerance: options.sweep_tolerance,
                        history: Vec::new(),
                    });
                }
                change = change.max((v - temps[j]).abs() / rise);
            }
            for k in 0..ns {
                field.body_1[i * ns + k] = zr[ns - 1 - k];
                field.body_2[i * ns + k] = zr[i_film1 + k];
            }
            for k in 0..nz {
                field.film[i * nz + k] = zr[i_film0 + k];
            }
        }
        if anderson {
            inner_sweeps += 1;
            if change >= inner_tolerance && inner_sweeps < ANDERSON_INNER_SWEEPS {
                continue;
            }
            // The outer step ends: G(x_k) = the field now; residual relative to the rise.
            let start = outer_start.take().expect("set at the outer step's start");
            let x = start.flat();
            let g = field.flat();
            let rise = scale_rise(&field);
            let residual = x.iter().zip(&g).fold(0.0f64, |m, (a, b)| m.max((b - a).abs())) / rise;
            last_change = residual;
            if residual < options.sweep_tolerance {
                converged = true;
                break;
            }
            // A step that grows the residual well past the best restarts the mixing from G.
            // (The reference then restarts at this residual.)
            if residual > 4.0 * best_residual {
                mixer.clear();
                best_residual = residual;
            }
            best_residual = best_residual.min(residual);
            let mut next = mixer.next(&x, &g);
            // Keep the mixed field within the range G spans (with a margin): an extrapolating
            // mix must not leave the physical range.
            let (lo, hi) = g.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(l, u), &v| (l.min(v), u.max(v)));
            let margin = 0.25 * (hi - lo).max(1e-3);
            for v in next.iter_mut() {
                *v = v.clamp(lo - margin, hi + margin);
            }
            field.set_flat(&next);
            inner_tolerance = (0.01 * residual).max(0.01 * options.sweep_tolerance);
            continue;
        }
        // Adaptive under-relaxation of the viscosity: a sweep that changes more than the last
        // one reduces the step (strong shear heating localises in the hot mid-film and can
        // oscillate).
        // (Compared with the sweep in the same direction: alternating sweeps change by different
        // amounts.)
        if change > same_direction {
            relax = (relax * 0.7).max(0.2);
        } else {
            relax = (relax * 1.1).min(1.0);
        }
        relax_cell.set(relax);
        same_direction = last_change;
        last_change = change;
        if change < options.sweep_tolerance {
            converged = true;
            break;
        }
    }
    // A stall within 500× the tolerance is accepted (reported in the summary): the inlet's
    // recirculating backflow can keep a sweep-to-sweep wobble of a fraction of a kelvin far
    // upstream, where it does not move the films.
    // (Anderson: within 10× the tolerance; beyond, `energy` falls back to the sweeps.)
    let stall_factor = if anderson { 10.0 } else { 500.0 };
    let stalled = !converged && last_change < stall_factor * options.sweep_tolerance;
    if !converged && !stalled {
        return Err(SolveError::NotConverged {
            solver: "thermal ehl energy equation (Gauss–Seidel)",
            iterations: sweeps,
            residual: last_change,
            tolerance: options.sweep_tolerance,
            history: Vec::new(),
        });
    }
    // Final column quantities at the converged temperatures.
    for i in 0..n {
        let temps: Vec<f64> = field.film_column(i).to_vec();
        update_column(i, &temps, &mut columns[i], &mut eta_ref[i]);
    }

    // Generalized Reynolds factors (normalized column integrals) and traction.
    let mut factors = ThermalFactors { x: x.to_vec(), poiseuille: vec![1.0; n], wedge: vec![1.0; n], mass: vec![1.0; n] };
    let (mut f1, mut f2, mut roll) = (0.0, 0.0, 0.0);
    let mut generated = 0.0;
    let um = 0.5 * (u1 + u2);
    for i in 0..n {
        let col = &columns[i];
        let dz = 1.0 / (nz - 1) as f64;
        let pi = p[i].max(0.0);
        let rho_iso = lub.density_ratio(pi, t0);
        // The effective integrals of the column and of the isothermal column (η̂ = 1, ρ = ρ_iso)
        // by the same quadrature: their ratios are exactly 1 at uniform temperature.
        let th = effective_integrals(&col.eta, &col.rho);
        let iso = effective_integrals(&vec![1.0; nz], &vec![rho_iso; nz]);
        let (rho_over_eta, rs1, rs2, re) = (th.0 / iso.0 * rho_iso, th.1 / iso.1 * rho_iso, th.2 / iso.2 * rho_iso, th.3 / iso.3 * rho_iso);
        factors.poiseuille[i] = (rho_over_eta / rho_iso).max(1e-12);
        factors.wedge[i] = if um.abs() > 1e-9 * (u1.abs() + u2.abs()) { (u1 * rs1 + u2 * rs2) / (2.0 * um * rho_iso) } else { re / rho_iso };
        factors.mass[i] = re / rho_iso;
        // eq. 9: shear on body 1 (τ at z = 0) and on body 2 (−τ at z = h).
        let tau1 = col.tau[0];
        let tau2 = col.tau[nz - 1];
        f1 += wx[i] * tau1;
        f2 -= wx[i] * tau2;
        roll -= wx[i] * 0.5 * h[i] * dpdx[i];
        // Heat generated in the column.
        let dzd = h[i] * dz;
        let temps = field.film_column(i);
        for k in 0..nz {
            let wz = if k == 0 || k == nz - 1 { 0.5 * dzd } else { dzd };
            let rho = lub.density * col.rho[k];
            let shear = col.tau[k] * col.tau[k] / (col.eta[k] * eta_ref[i]);
            let comp = if compressive { temps[k] * lub.density * DH_C3 / rho * col.u[k] * dpdx[i] } else { 0.0 };
            generated += wx[i] * wz * (shear + comp);
        }
    }
    // Heat leaving: convected out through the domain ends (where each node's flow leaves), through
    // the depth boundaries, and stored (transient).
    let out_flux = |i: usize, sign: f64| -> (f64, f64, f64) {
        // (body 1, film, body 2) of ρ c u (T − T0) through the end column i, counted where the
        // velocity points out (sign: +1 at the downstream end x_max, −1 at x_min).
        let col = &columns[i];
        let solid = |z: &[f64], rc: f64, u: f64, v: &[f64]| {
            if u * sign <= 0.0 {
                return 0.0;
            }
            let mut s = 0.0;
            for k in 1..ns {
                s += 0.5 * (z[k] - z[k - 1]) * ((v[i * ns + k - 1] - t0) + (v[i * ns + k] - t0));
            }
            rc * u.abs() * s
        };
        let b1 = solid(&z1, rc1, u1, &field.body_1);
        let b2 = solid(&z2, rc2, u2, &field.body_2);
        let dzd = h[i] / (nz - 1) as f64;
        let temps = field.film_column(i);
        let mut fl = 0.0;
        for k in 0..nz {
            if col.u[k] * sign > 0.0 {
                let wz = if k == 0 || k == nz - 1 { 0.5 * dzd } else { dzd };
                fl += wz * lub.density * col.rho[k] * cf * col.u[k].abs() * (temps[k] - t0);
            }
        }
        (b1, fl, b2)
    };
    let (a1, af, a2) = out_flux(n - 1, 1.0);
    let (c1, cf_, c2) = out_flux(0, -1.0);
    let mut deep_1 = 0.0;
    let mut deep_2 = 0.0;
    let mut store_1 = 0.0;
    let mut store_2 = 0.0;
    let mut store_f = 0.0;
    for i in 0..n {
        deep_1 += wx[i] * bodies.body_1.conductivity * (field.body_1[i * ns + ns - 2] - t0) / (z1[ns - 1] - z1[ns - 2]);
        deep_2 += wx[i] * bodies.body_2.conductivity * (field.body_2[i * ns + ns - 2] - t0) / (z2[ns - 1] - z2[ns - 2]);
        if let Some((of, dt)) = &old {
            for k in 0..ns {
                let w = 0.5 * (z1[(k + 1).min(ns - 1)] - z1[k.saturating_sub(1)]);
                store_1 += wx[i] * w * rc1 * (field.body_1[i * ns + k] - of.body_1[i * ns + k]) / dt;
                let w = 0.5 * (z2[(k + 1).min(ns - 1)] - z2[k.saturating_sub(1)]);
                store_2 += wx[i] * w * rc2 * (field.body_2[i * ns + k] - of.body_2[i * ns + k]) / dt;
            }
            let dzd = h[i] / (nz - 1) as f64;
            for k in 0..nz {
                let wz = if k == 0 || k == nz - 1 { 0.5 * dzd } else { dzd };
                store_f += wx[i] * wz * lub.density * columns[i].rho[k] * cf * (field.film[i * nz + k] - of.film[i * nz + k]) / dt;
            }
        }
    }
    let heat_to_body_1 = a1 + c1 + deep_1 + store_1;
    let heat_to_body_2 = a2 + c2 + deep_2 + store_2;
    let heat_convected = af + cf_ + store_f;
    let total_out = heat_to_body_1 + heat_to_body_2 + heat_convected;
    let energy_balance_error = if generated.abs() > 0.0 { ((generated - total_out) / generated).abs() } else { 0.0 };
    let (s1, s2) = field.surface_max();
    let (mut pw, mut pt) = (0.0, 0.0);
    for i in 0..n {
        let tm = field.film_column(i).iter().sum::<f64>() / nz as f64;
        pw += wx[i] * p[i].max(0.0);
        pt += wx[i] * p[i].max(0.0) * tm;
    }
    let film_temperature_mean = if pw > 0.0 { pt / pw } else { t0 };
    let summary = ThermalSummary {
        film_temperature_max: field.film_max(),
        surface_temperature_max_1: s1,
        surface_temperature_max_2: s2,
        film_temperature_mean,
        heat_generated: generated,
        heat_to_body_1,
        heat_to_body_2,
        heat_convected,
        energy_balance_error,
        sweeps,
        sweep_change: last_change,
    };
    let traction = TractionResult {
        force_body_1: f1,
        force_body_2: f2,
        friction_coefficient: (f2 - f1) / (2.0 * input.load_per_length),
        rolling_force: roll,
    };
    crate::ensure_finite("thermal ehl", [&traction.force_body_1, &traction.force_body_2, &summary.film_temperature_max, &summary.heat_generated])?;
    Ok(EnergySolution { field, factors, traction, summary })
}

/// The generalized Reynolds integrals of one column (seed 000 eq. 2) at uniform levels
/// `ζ = z/h` with viscosity `η̂` (relative) and density ratio `ρ̄`, trapezoidal:
/// `((ρ/η)_e, ρ*_1, ρ*_2, ρ_e)` in units of `ρ̄/η̂`.
fn effective_integrals(eta: &[f64], rho: &[f64]) -> (f64, f64, f64, f64) {
    let nz = eta.len();
    let dz = 1.0 / (nz - 1) as f64;
    let (mut f0, mut f1) = (0.0, 0.0);
    let (mut re, mut re1, mut re2) = (0.0, 0.0, 0.0);
    let mut prev = (rho[0], 0.0, 0.0);
    for k in 1..nz {
        let zk = k as f64 * dz;
        f0 += 0.5 * dz * (1.0 / eta[k - 1] + 1.0 / eta[k]);
        f1 += 0.5 * dz * ((zk - dz) / eta[k - 1] + zk / eta[k]);
        let cur = (rho[k], rho[k] * f0, rho[k] * f1);
        re += 0.5 * dz * (prev.0 + cur.0);
        re1 += 0.5 * dz * (prev.1 + cur.1);
        re2 += 0.5 * dz * (prev.2 + cur.2);
        prev = cur;
    }
    let eta_e = 1.0 / f0;
    let eta_e1 = 1.0 / f1;
    (12.0 * (eta_e * re1 / eta_e1 - re2), 2.0 * (re - re1 * eta_e), 2.0 * re1 * eta_e, re)
}

/// Temperature of column node `j` (column layout of [`energy`]) at column `i` of `f`.
fn node_temperature(f: &TemperatureField, i: usize, j: usize, ns: usize, nz: usize, i_film0: usize, i_film1: usize) -> f64 {
    if j < i_film0 {
        f.body_1[i * ns + (ns - 1 - j)]
    } else if j >= i_film1 {
        f.body_2[i * ns + (j - i_film1)]
    } else {
        f.film[i * nz + (j - i_film0)]
    }
}

/// A thermal EHL problem: the isothermal problem's input (its `temperature` is the inlet
/// temperature `T0`) and the thermal properties.
#[derive(Debug, Clone, Copy)]
pub struct ThermalInput<'a> {
    pub ehl: EhlInput<'a>,
    pub bodies: ThermalBodies,
    /// The previous time step's temperature field (with `ehl.transient`); `None`: steady
    /// temperatures.
    pub previous_temperature: Option<&'a TemperatureField>,
}

/// The solution of a thermal EHL problem.
#[derive(Debug, Clone)]
pub struct ThermalSolution {
    /// Films, pressures and state of the thermal solution; its `traction` is the thermal one.
    pub ehl: EhlSolution,
    pub temperature: TemperatureField,
    pub summary: ThermalSummary,
    /// The generalized Reynolds factors of the converged temperature field.
    pub factors: ThermalFactors,
    /// Coupling iterations; `residual` is the last relative change.
    pub convergence: Convergence,
}

/// The contiguous columns around the minimum film where the film is at most `extent` times it
/// (at least three).
fn thermal_range(film: &[f64], extent: f64) -> (usize, usize) {
    let n = film.len();
    let imin = (0..n).fold(0, |j, i| if film[i] < film[j] { i } else { j });
    let limit = extent * film[imin];
    let mut a = imin;
    while a > 0 && film[a - 1] <= limit {
        a -= 1;
    }
    let mut e = imin;
    while e + 1 < n && film[e + 1] <= limit {
        e += 1;
    }
    while e - a < 2 {
        if a > 0 {
            a -= 1;
        }
        if e - a < 2 && e + 1 < n {
            e += 1;
        }
    }
    (a, e)
}

/// `old` (on its positions) blended towards `new` by `w`: the Poiseuille factor geometrically,
/// the densities linearly, on `new`'s positions.
/// Largest temperature rise over the inlet temperature an energy solve may reach, K: beyond it
/// the oil has long decomposed and the Roelands/Dowson–Higginson laws (seed 000 eq. 4–5) are far
/// outside their range; the solve ends as a runaway (typed error). (400 K was too tight: the
/// sweeps of a Newtonian film at w' = 2e5 N/m, u_m = 5 m/s, S = 0.3 pass it on their way to a
/// converged 122 K rise.)
pub const MAX_TEMPERATURE_RISE: f64 = 1000.0;

/// Development trace of one coupling iteration (`TRIBOD_THERMAL_TRACE`): where the film is
/// hottest and the range of the new generalized-Reynolds factors.
fn trace_coupling(iteration: u32, relax: f64, sol: &EhlSolution, en: &EnergySolution) {
    let mm = |v: &[f64]| v.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| (a.min(x), b.max(x)));
    let nzp = en.field.film.len() / en.field.x.len();
    let kmax = (0..en.field.film.len()).max_by(|&a, &b| en.field.film[a].total_cmp(&en.field.film[b])).unwrap_or(0);
    let (ix, iz) = (kmax / nzp, kmax % nzp);
    let ip = sol.state.x.partition_point(|&v| v < en.field.x[ix]).min(sol.state.x.len() - 1);
    eprintln!("   Tmax at x/b {:.3} level {iz}/{nzp} p {:.3e} h {:.3e}", en.field.x[ix] / sol.hertz_half_width, sol.state.pressure[ip], sol.state.film[ip]);
    eprintln!("thermal coupling {iteration}: relax {relax:.3} Tmax {:.1} poiseuille {:?} wedge {:?} mass {:?}", en.summary.film_temperature_max, mm(&en.factors.poiseuille), mm(&en.factors.wedge), mm(&en.factors.mass));
}

/// Smallest step towards new generalized Reynolds factors after a failed Reynolds solve.
const MIN_FACTOR_STEP: f64 = 1.0 / 32.0;

fn blend(old: &ThermalFactors, new: &ThermalFactors, w: f64) -> ThermalFactors {
    if w >= 1.0 {
        return new.clone();
    }
    let at = |v: &[f64], x: f64| {
        let m = old.x.len();
        let i = old.x.partition_point(|&a| a <= x).clamp(1, m - 1);
        let t = ((x - old.x[i - 1]) / (old.x[i] - old.x[i - 1])).clamp(0.0, 1.0);
        v[i - 1] * (1.0 - t) + v[i] * t
    };
    let mut out = new.clone();
    for (k, &x) in new.x.iter().enumerate() {
        out.poiseuille[k] = (at(&old.poiseuille, x).max(1e-300).ln() * (1.0 - w) + new.poiseuille[k].ln() * w).exp();
        out.wedge[k] = at(&old.wedge, x) * (1.0 - w) + new.wedge[k] * w;
        out.mass[k] = at(&old.mass, x) * (1.0 - w) + new.mass[k] * w;
    }
    out
}

/// Surface velocities `(u1, u2)` of an input: `u_m ± u_s/2`.
fn surface_velocities(input: &EhlInput) -> (f64, f64) {
    let (um, us) = (input.entrainment_velocity, input.sliding_velocity);
    (um + 0.5 * us, um - 0.5 * us)
}

/// Solve one thermal line-contact EHL problem.
pub fn solve(input: &ThermalInput, options: &EhlOptions, thermal: &ThermalOptions, observer: &dyn Observer) -> Result<ThermalSolution, SolveError> {
    ThermalEngine::new().solve(input, options, thermal, None, None, observer)
}

/// A reusable thermal solver (grids, factorisations and the last temperature field survive between
/// solves): a cam cycle keeps one.
pub struct ThermalEngine {
    engine: Engine,
}

impl Default for ThermalEngine {
    fn default() -> Self {
        Self::new()
    }
}

impl std::fmt::Debug for ThermalEngine {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("ThermalEngine")
    }
}

impl ThermalEngine {
    pub fn new() -> Self {
        ThermalEngine { engine: Engine::new() }
    }

    /// Solve one problem. `warm_field` (a temperature field of a nearby problem, any grid) starts
    /// the energy sweeps; `warm_factors` (that problem's generalized Reynolds factors) the first
    /// pressure solve, which is otherwise isothermal; `input.ehl.warm_start`/`transient` the
    /// Newton solver.
    pub fn solve(
        &mut self,
        input: &ThermalInput,
        options: &EhlOptions,
        thermal: &ThermalOptions,
        warm_field: Option<&TemperatureField>,
        warm_factors: Option<&ThermalFactors>,
        observer: &dyn Observer,
    ) -> Result<ThermalSolution, SolveError> {
        if !(thermal.film_points >= 3 && thermal.solid_points >= 4 && thermal.solid_depth > 0.0 && thermal.tolerance > 0.0) {
            return Err(SolveError::invalid("ThermalOptions", "film_points ≥ 3, solid_points ≥ 4, solid_depth > 0, tolerance > 0"));
        }
        let ehl = &input.ehl;
        let (u1, u2) = surface_velocities(ehl);
        let (h_est, dir) = super::newton::film_estimate(ehl);
        let layout = super::grid::Layout::for_film(h_est, dir, options.inlet, options.outlet, options.grading);
        let previous = match (input.previous_temperature, ehl.transient) {
            (Some(f), Some(t)) => Some((f, t.time_step)),
            _ => None,
        };
        let energy_at = |sol: &EhlSolution, warm: Option<&TemperatureField>| {
            let ein = EnergyInput {
                velocity_1: u1,
                velocity_2: u2,
                lubricant: &ehl.lubricant,
                inlet_temperature: ehl.temperature,
                bodies: &input.bodies,
                half_width: sol.hertz_half_width,
                load_per_length: ehl.load_per_length,
                rheology: &ehl.rheology,
                previous,
                warm,
            };
            let (a, e) = thermal_range(&sol.state.film, thermal.film_extent);
            let st = &sol.state;
            energy(&st.x[a..=e], &st.pressure[a..=e], &st.film[a..=e], &ein, thermal)
        };
        let mut sol = self.engine.solve_with(ehl, options, Some(layout), None, warm_factors, observer)?;
        let mut field: Option<TemperatureField> = warm_field.cloned();
        let mut iterations = 0;
        let mut history = Vec::new();
        let mut last: Option<EnergySolution> = None;
        let mut used: Option<ThermalFactors> = warm_factors.cloned();
        let mut termination = Termination::Converged;
        let mut relax: f64 = 1.0;
        loop {
            observer.check()?;
            let mut en = energy_at(&sol, field.as_ref())?;
            iterations += 1;
            // Under-relaxed factors (the last ones used, interpolated onto this grid, blended
            // with the new): the energy ↔ Reynolds fixed point can oscillate where the heating
            // is strong; the step shrinks when the change grows.
            let raw = en.factors.clone();
            let unit = || ThermalFactors { x: raw.x.clone(), poiseuille: vec![1.0; raw.x.len()], wedge: vec![1.0; raw.x.len()], mass: vec![1.0; raw.x.len()] };
            en.factors = match &used {
                Some(old) => blend(old, &raw, relax),
                None => raw.clone(),
            };
            if std::env::var_os("TRIBOD_THERMAL_TRACE").is_some() {
                trace_coupling(iterations, relax, &sol, &en);
            }
            let ph = sol.hertz_pressure;
            let pred: Vec<f64> = sol.state.pressure.iter().map(|p| p / ph).collect();
            let prediction = Prediction { pressure: &pred, centre_film: sol.central_film };
            // Where the Reynolds solve fails on the new factors (strong heating: the film's
            // Poiseuille coefficient moves by orders of magnitude between iterations), the step
            // towards them is halved (from the isothermal factors on the first iteration).
            let next = loop {
                match self.engine.solve_with(ehl, options, Some(layout), Some(prediction), Some(&en.factors), observer) {
                    Ok(next) => break next,
                    Err(SolveError::NotConverged { .. }) if relax > MIN_FACTOR_STEP => {
                        relax *= 0.5;
                        en.factors = match &used {
                            Some(old) => blend(old, &raw, relax),
                            None => blend(&unit(), &raw, relax),
                        };
                    }
                    Err(e) => return Err(e),
                }
            };
            used = Some(en.factors.clone());
            let rel = |a: f64, b: f64| ((a - b) / b.abs().max(1e-30)).abs();
            // Change of the largest temperature rise, relative to the rise (at least 0.1 K).
            let rise = en.summary.film_temperature_max - ehl.temperature;
            let t_change = match (&last, warm_field) {
                (Some(l), _) => (rise - (l.summary.film_temperature_max - ehl.temperature)).abs() / rise.abs().max(0.1),
                (None, Some(w)) => (rise - (w.film_max() - ehl.temperature)).abs() / rise.abs().max(0.1),
                (None, None) => f64::INFINITY,
            };
            // Films to the tolerance; the temperature rise to 100× it (the energy sweeps themselves
            // stop at `sweep_tolerance`, or stall above it, so the rise carries that noise).
            let change = rel(next.central_film, sol.central_film).max(rel(next.min_film, sol.min_film)).max(0.01 * t_change);
            if let Some(&before) = history.last() {
                relax = if change > before { (relax * 0.6).max(0.15) } else { (relax * 1.2).min(1.0) };
            }
            history.push(change);
            sol = next;
            field = Some(en.field.clone());
            last = Some(en);
            if change < thermal.tolerance {
                break;
            }
            if iterations >= thermal.max_iterations {
                // Within 10× the tolerance the coupling has stalled on the energy sweeps' noise:
                // the result is usable and reported as stalled.
                if change < 10.0 * thermal.tolerance {
                    termination = Termination::Stalled;
                    break;
                }
                return Err(SolveError::NotConverged {
                    solver: "thermal ehl coupling (energy ↔ Reynolds)",
                    iterations,
                    residual: change,
                    tolerance: thermal.tolerance,
                    history,
                });
            }
        }
        let en = last.expect("one iteration ran");
        // The final temperatures on the final pressure and film.
        let fin = energy_at(&sol, Some(&en.field))?;
        sol.traction = fin.traction;
        let residual = history.last().copied().unwrap_or(0.0);
        Ok(ThermalSolution {
            ehl: sol,
            temperature: fin.field,
            summary: fin.summary,
            factors: fin.factors,
            convergence: Convergence { iterations, residual, tolerance: thermal.tolerance, termination },
        })
    }
}

#[cfg(test)]
mod tests {
    use super::eyring_column;

    /// Couette flow of a uniform film (no pressure gradient): the Eyring stress is the closed
    /// form `τ = τ_E asinh(η Δu/(h τ_E))`, far beyond τ_E where the lagged iteration diverged.
    #[test]
    fn eyring_column_is_the_couette_closed_form() {
        let (nz, h, te, eta) = (7, 2.8e-7, 5e6, 4.0e3);
        let dz = h / (nz - 1) as f64;
        for du in [1e-4, 0.04, 0.4, 4.0] {
            let mut out = vec![0.0; nz];
            eyring_column(&vec![1.0; nz], eta, dz, du, 0.0, te, &mut out);
            let tau = te * (eta * du / (h * te)).asinh();
            // η* = τ/γ̇ with γ̇ = Δu/h.
            let expect = tau / (du / h) / eta;
            println!("Δu {du}: τ/τ_E {:.3}, η*/η {:.4e} (closed form {:.4e})", tau / te, out[3], expect);
            for v in &out {
                assert!((v - expect).abs() <= 1e-9 * expect, "{v} vs {expect}");
            }
        }
    }

    /// With a pressure gradient and viscosity varying across the film, the shear rates of the
    /// solved stress integrate to the surface speed difference (the constraint it solves).
    #[test]
    fn eyring_column_meets_the_speed_difference() {
        let (nz, h, te) = (9, 3e-7, 5e6);
        let dz = h / (nz - 1) as f64;
        let eta_ref = 1e4;
        let eta_n: Vec<f64> = (0..nz).map(|k| (-(0.5 * (k as f64 - 4.0)).powi(2)).exp() * 0.2 + 0.01).collect();
        for (du, px) in [(2.0, 3e12), (-1.0, -5e13), (0.0, 1e13)] {
            let mut out = vec![0.0; nz];
            eyring_column(&eta_n, eta_ref, dz, du, px, te, &mut out);
            // τ_k = η*_k γ̇_k with γ̇_k = (τ_E/η_k) sinh(τ_k/τ_E): recover τ_1 from level 0 and check
            // the trapezoidal ∫ γ̇ dz.
            let gam = |tau: f64, k: usize| te / (eta_n[k] * eta_ref) * (tau / te).sinh();
            // τ_k from η*_k: solve η*/η = s/sinh s at level 0 by bisection on s ≥ 0 with the sign
            // of the integral's τ_1 (found as the one meeting the constraint below).
            let ratio = out[0] / eta_n[0];
            let (mut lo, mut hi) = (0.0f64, 700.0f64);
            for _ in 0..200 {
                let mid = 0.5 * (lo + hi);
                let r = if mid > 1e-8 { mid / mid.sinh() } else { 1.0 };
                if r > ratio { lo = mid } else { hi = mid }
            }
            let s0 = 0.5 * (lo + hi);
            let best = [s0, -s0].into_iter().map(|s| {
                let t1 = s * te;
                let integral: f64 = (0..nz).map(|k| { let w = if k == 0 || k == nz - 1 { 0.5 * dz } else { dz }; w * gam(t1 + px * dz * k as f64, k) }).sum();
                (integral - du).abs()
            }).fold(f64::INFINITY, f64::min);
            println!("Δu {du} px {px:e}: τ_1/τ_E = ±{s0:.4}, constraint error {best:.3e} m/s");
            assert!(best < 1e-6 * du.abs().max(1e-3), "constraint error {best}");
        }
    }
}
