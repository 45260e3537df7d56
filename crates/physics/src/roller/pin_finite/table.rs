use super::*;

impl PinTable {
    /// Grid and tolerances of the table's Reynolds solutions at `length_to_diameter`: 361
    /// circumferential nodes (seed 002's), axial nodes in proportion to L/D (`90 L/D`, odd,
    /// 21–121), pressure and load tolerances 1e-8. At L/D = 0.4375 (41 axial nodes) halving the
    /// circumferential spacing from 181 nodes moved W̄ and F̄ by ≤ 0.13 % up to ε = 0.98 and W̄ by
    /// 0.3 % at ε = 0.99 (the pressure peak narrows); 2–6 ms per analysis.
    pub fn settings(length_to_diameter: f64) -> Settings {
        let axial = ((90.0 * length_to_diameter).ceil() as usize).clamp(21, 121) | 1;
        Settings { circumferential: 361, axial, pressure_tolerance: 1e-8, load_tolerance: 1e-8, ..Settings::default() }
    }

    /// The node eccentricities: uniform in `ln(ε/(1 − ε))` over [`TABLE_EPS_MIN`, `TABLE_EPS_MAX`].
    pub fn node_eccentricities(nodes: usize) -> Vec<f64> {
        let logit = |e: f64| (e / (1.0 - e)).ln();
        let (a, b) = (logit(TABLE_EPS_MIN), logit(TABLE_EPS_MAX));
        (0..nodes)
            .map(|i| {
                let v = a + (b - a) * i as f64 / (nodes - 1) as f64;
                1.0 / (1.0 + (-v).exp())
            })
            .collect()
    }

    /// Build the table of a plain aligned bearing of `length_to_diameter` from [`TABLE_NODES`]
    /// journal analyses at fixed eccentricity (grid: [`Self::settings`]).
    pub fn build(length_to_diameter: f64, observer: &dyn Observer) -> Result<PinTable, SolveError> {
        Self::build_with(length_to_diameter, &Self::node_eccentricities(TABLE_NODES), &Self::settings(length_to_diameter), observer)
    }

    /// [`Self::build`] at given node eccentricities (increasing, in (0, 1)) and grid.
    pub fn build_with(length_to_diameter: f64, eccentricities: &[f64], settings: &Settings, observer: &dyn Observer) -> Result<PinTable, SolveError> {
        if !(length_to_diameter.is_finite() && length_to_diameter > 0.0) {
            return Err(SolveError::invalid("length_to_diameter", "must be > 0"));
        }
        if eccentricities.len() < 4 || !eccentricities.windows(2).all(|w| w[1] > w[0]) || !(eccentricities[0] > 0.0) || !(eccentricities[eccentricities.len() - 1] < 1.0) {
            return Err(SolveError::invalid("eccentricities", "at least 4, increasing, in (0, 1)"));
        }
        let bearing = Bearing::plain(length_to_diameter);
        let mut ws = Workspace::new(&bearing, settings);
        let mut guess: Option<Guess> = None;
        let mut x = Vec::with_capacity(eccentricities.len());
        let mut values = Vec::with_capacity(eccentricities.len());
        let mut worst = Convergence { iterations: 0, residual: 0.0, tolerance: settings.load_tolerance, termination: Termination::Converged };
        let mut worst_ratio = -1.0;
        let mut steps = 0u32;
        for &e in eccentricities {
            observer.check()?;
            let a = analyse(&bearing, &Operating::Eccentricity(e), settings, Some(&mut ws), guess, false, observer)?;
            guess = Some(Guess { eccentricity: e, attitude: a.attitude });
            steps += a.convergence.iterations;
            let ratio = if a.convergence.tolerance > 0.0 { a.convergence.residual / a.convergence.tolerance } else { 0.0 };
            if ratio > worst_ratio || a.convergence.termination != Termination::Converged {
                worst_ratio = ratio;
                worst = a.convergence.clone();
            }
            if !(a.load > 0.0 && a.friction_force > 0.0 && a.side_flow_variable > 0.0) {
                return Err(SolveError::physical(
                    crate::PhysicalFailure::FilmClosed,
                    format!("the pin bearing's Reynolds solution at ε = {e} carries no load or shear (W̄ {}, F̄ {}, Q̄s {})", a.load, a.friction_force, a.side_flow_variable),
                ));
            }
            x.push(a.load.ln());
            values.push([e, a.friction_force.ln(), a.side_flow_variable.ln(), a.attitude]);
        }
        if !x.windows(2).all(|w| w[1] > w[0]) {
            return Err(SolveError::physical(
                crate::PhysicalFailure::NoEquilibriumAttitude,
                "the pin bearing's load does not rise monotonically with eccentricity over the table",
            ));
        }
        worst.iterations = steps;
        let slopes = steffen_slopes(&x, &values);
        let table = PinTable { length_to_diameter, x, values, slopes, convergence: worst };
        ensure_finite("pin bearing table", table.values.iter().flatten().chain(table.slopes.iter().flatten()).chain(table.x.iter()))?;
        Ok(table)
    }

    /// Number of nodes.
    pub fn len(&self) -> usize {
        self.x.len()
    }
    pub fn is_empty(&self) -> bool {
        self.x.is_empty()
    }
    /// `(ε, W̄)` at node `i`.
    pub fn node(&self, i: usize) -> (f64, f64) {
        (self.values[i][EPS], self.x[i].exp())
    }

    /// The interpolated solution at `x = ln W̄` (any value, `−∞` included: the light-load and
    /// heavy-load continuations of the module docs outside the nodes).
    pub fn at(&self, x: f64) -> TablePoint {
        let n = self.x.len();
        let (x0, xn) = (self.x[0], self.x[n - 1]);
        if x <= x0 {
            // light load: ε ∝ W̄, Q̄s ∝ W̄, F̄ − 2π ∝ W̄² (Petroff at ε = 0)
            let v = &self.values[0];
            let r = (x - x0).exp();
            let f0 = v[LN_F].exp();
            let excess = (f0 - TAU) * r * r;
            let f = TAU + excess;
            return TablePoint {
                eccentricity: v[EPS] * r,
                d_eccentricity: v[EPS] * r,
                friction_force: f,
                d_ln_friction: 2.0 * excess / f,
                side_flow: v[LN_QS].exp() * r,
                d_ln_side_flow: 1.0,
                attitude: v[ATT],
            };
        }
        if x >= xn {
            // heavy load: power laws with the end slopes
            let v = &self.values[n - 1];
            let s = &self.slopes[n - 1];
            let gap0 = 1.0 - v[EPS];
            let k = (s[EPS] / gap0).max(0.0);
            let gap = gap0 * (-k * (x - xn)).exp();
            let sf = s[LN_F].min(HEAVY_SLOPE_CAP);
            return TablePoint {
                eccentricity: 1.0 - gap,
                d_eccentricity: k * gap,
                friction_force: (v[LN_F] + sf * (x - xn)).exp(),
                d_ln_friction: sf,
                side_flow: (v[LN_QS] + s[LN_QS] * (x - xn)).exp(),
                d_ln_side_flow: s[LN_QS],
                attitude: v[ATT] * (gap / gap0).sqrt(),
            };
        }
        let i = self.x.partition_point(|&xi| xi <= x).clamp(1, n - 1) - 1;
        let h = self.x[i + 1] - self.x[i];
        let t = (x - self.x[i]) / h;
        let (v0, v1, d0, d1) = (&self.values[i], &self.values[i + 1], &self.slopes[i], &self.slopes[i + 1]);
        // cubic Hermite basis and its derivative (d/dt)
        let t2 = t * t;
        let t3 = t2 * t;
        let (h00, h10, h01, h11) = (2.0 * t3 - 3.0 * t2 + 1.0, t3 - 2.0 * t2 + t, -2.0 * t3 + 3.0 * t2, t3 - t2);
        let (g00, g10, g01, g11) = (6.0 * t2 - 6.0 * t, 3.0 * t2 - 4.0 * t + 1.0, -6.0 * t2 + 6.0 * t, 3.0 * t2 - 2.0 * t);
        let val = |c: usize| h00 * v0[c] + h10 * h * d0[c] + h01 * v1[c] + h11 * h * d1[c];
        let der = |c: usize| (g00 * v0[c] + g01 * v1[c]) / h + g10 * d0[c] + g11 * d1[c];
        TablePoint {
            eccentricity: val(EPS),
            d_eccentricity: der(EPS),
            friction_force: val(LN_F).exp(),
            d_ln_friction: der(LN_F),
            side_flow: val(LN_QS).exp(),
            d_ln_side_flow: der(LN_QS),
            attitude: val(ATT),
        }
    }
}

/// Steffen's (1990) monotone slopes of each column against `x`: at an interior node the
/// three-point (parabola) slope, limited to twice the smaller neighbouring secant and zeroed at a
/// local extremum; at the ends the one-sided parabola slope, limited the same way.
pub(super) fn steffen_slopes(x: &[f64], v: &[[f64; COLS]]) -> Vec<[f64; COLS]> {
    let n = x.len();
    let mut out = vec![[0.0; COLS]; n];
    for c in 0..COLS {
        let sec = |i: usize| (v[i + 1][c] - v[i][c]) / (x[i + 1] - x[i]);
        let hh = |i: usize| x[i + 1] - x[i];
        for i in 1..n - 1 {
            let (s0, s1, h0, h1) = (sec(i - 1), sec(i), hh(i - 1), hh(i));
            let p = (s0 * h1 + s1 * h0) / (h0 + h1);
            out[i][c] = if s0 * s1 <= 0.0 { 0.0 } else { s0.signum() * s0.abs().min(s1.abs()).min(0.5 * p.abs()) * 2.0 };
        }
        let end = |s0: f64, s1: f64, h0: f64, h1: f64| {
            let p = s0 * (1.0 + h0 / (h0 + h1)) - s1 * h0 / (h0 + h1);
            if p * s0 <= 0.0 { 0.0 } else if p.abs() > 2.0 * s0.abs() { 2.0 * s0 } else { p }
        };
        out[0][c] = end(sec(0), sec(1), hh(0), hh(1));
        out[n - 1][c] = end(sec(n - 2), sec(n - 3), hh(n - 2), hh(n - 3));
    }
    out
}
