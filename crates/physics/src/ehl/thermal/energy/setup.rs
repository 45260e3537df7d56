//! The fixed data of one energy solve: the node layout of a column, the solids' node depths and
//! heat capacities, the pressure gradient and the x weights; the start field.

use super::*;

/// The columns of one energy solve on `(x, p, h)` (m, Pa, m) and what stays fixed during it.
///
/// Column layout: body 1 from the depth (index 0) to its surface (`ns − 1`), the film levels
/// (`ns − 1 .. ns − 2 + nz`), body 2 from its surface to the depth (`nn − 1`).
pub(super) struct EnergyGrid<'a> {
    pub(super) x: &'a [f64],
    pub(super) p: &'a [f64],
    pub(super) h: &'a [f64],
    pub(super) input: &'a EnergyInput<'a>,
    pub(super) options: &'a ThermalOptions,
    pub(super) lub: &'a Lubricant,
    pub(super) bodies: &'a ThermalBodies,
    /// Columns.
    pub(super) n: usize,
    /// Film levels of a column.
    pub(super) nz: usize,
    /// Nodes of each solid.
    pub(super) ns: usize,
    /// Nodes of a column.
    pub(super) nn: usize,
    /// The column nodes of the film's surfaces on body 1 and on body 2.
    pub(super) i_film0: usize,
    pub(super) i_film1: usize,
    /// Inlet temperature `T0`, K.
    pub(super) t0: f64,
    /// Surface velocities, m/s.
    pub(super) u1: f64,
    pub(super) u2: f64,
    /// The film's specific heat.
    pub(super) cf: f64,
    /// Node depths of body 1 and body 2 from their surfaces, m.
    pub(super) z1: Vec<f64>,
    pub(super) z2: Vec<f64>,
    /// `ρ c` of body 1 and body 2, J/(m³·K).
    pub(super) rc1: f64,
    pub(super) rc2: f64,
    /// Dowson–Higginson density (compressive heating).
    pub(super) compressive: bool,
    /// The Eyring stress, Pa, when there is one.
    pub(super) eyring: Option<f64>,
    pub(super) ln_eta0: f64,
    /// `∂p/∂x` at the columns (central differences, one-sided at the ends), Pa/m.
    pub(super) dpdx: Vec<f64>,
    /// Trapezoidal x weights, m.
    pub(super) wx: Vec<f64>,
    /// [`EnergyIteration::Anderson`].
    pub(super) anderson: bool,
    /// The largest pressure, Pa.
    pub(super) p_peak: f64,
    /// The previous time step's field on these columns and the time step, s (transient).
    pub(super) old: Option<(TemperatureField, f64)>,
    /// Each column's segment lengths between its nodes, m (`nn − 1` per column), and their
    /// conductances `k / length`, W/(m²·K): fixed while the film's shape is.
    pub(super) lengths: Vec<f64>,
    pub(super) conductances: Vec<f64>,
}

impl<'a> EnergyGrid<'a> {
    pub(super) fn new(x: &'a [f64], p: &'a [f64], h: &'a [f64], input: &'a EnergyInput<'a>, options: &'a ThermalOptions) -> Result<Self, SolveError> {
        let n = x.len();
        let nz = options.film_points;
        let ns = options.solid_points;
        if n < 3 || nz < 3 || ns < 4 {
            return Err(SolveError::invalid("ThermalOptions", "needs ≥ 3 columns, ≥ 3 film points and ≥ 4 solid points"));
        }
        let lub = input.lubricant;
        let (u1, u2) = (input.velocity_1, input.velocity_2);
        let bodies = input.bodies;
        let b = input.half_width;
        let d = options.solid_depth * b;
        let pen = |s: &ThermalSolid, u: f64| (s.diffusivity() * 2.0 * b / u.abs().max(1e-9)).sqrt();
        let dpdx: Vec<f64> = (0..n)
            .map(|i| {
                let (a, c) = (i.saturating_sub(1), (i + 1).min(n - 1));
                if input.limited_gradient && a < i && i < c {
                    // minmod of the one-sided differences
                    let (l, r) = ((p[i] - p[a]) / (x[i] - x[a]), (p[c] - p[i]) / (x[c] - x[i]));
                    if l * r <= 0.0 { 0.0 } else if l.abs() < r.abs() { l } else { r }
                } else {
                    (p[c] - p[a]) / (x[c] - x[a])
                }
            })
            .collect();
        let (z1, z2) = (solid_depths(d, ns, pen(&bodies.body_1, u1)), solid_depths(d, ns, pen(&bodies.body_2, u2)));
        let conductivity = [bodies.body_1.conductivity, bodies.film.conductivity, bodies.body_2.conductivity];
        let (lengths, conductances) = segments(h, &z1, &z2, nz, conductivity);
        let old = input.previous.filter(|(f, dt)| f.film_points == nz && f.solid_points == ns && *dt > 0.0).map(|(f, dt)| (f.resampled(x), dt));
        Ok(EnergyGrid {
            x,
            p,
            h,
            input,
            options,
            lub,
            bodies,
            n,
            nz,
            ns,
            nn: 2 * ns + nz - 2,
            i_film0: ns - 1,
            i_film1: ns + nz - 3 + 1,
            t0: input.inlet_temperature,
            u1,
            u2,
            cf: bodies.film.specific_heat,
            z1,
            z2,
            rc1: bodies.body_1.density * bodies.body_1.specific_heat,
            rc2: bodies.body_2.density * bodies.body_2.specific_heat,
            compressive: lub.density_model == DensityModel::DowsonHigginson,
            eyring: input.rheology.eyring_stress.filter(|t| *t > 0.0),
            ln_eta0: lub.viscosity.ln(),
            dpdx,
            wx: (0..n).map(|i| 0.5 * (x[(i + 1).min(n - 1)] - x[i.saturating_sub(1)])).collect(),
            anderson: options.iteration == EnergyIteration::Anderson,
            p_peak: p.iter().fold(0.0f64, |m, &v| m.max(v)),
            old,
            lengths,
            conductances,
        })
    }

    /// The field the iteration starts from: the warm field on these columns when it has this
    /// resolution, else the inlet temperature.
    pub(super) fn start_field(&self) -> TemperatureField {
        match self.input.warm {
            Some(w) if w.film_points == self.nz && w.solid_points == self.ns => w.resampled(self.x),
            _ => TemperatureField::uniform(self.x, self.t0, self.nz, self.ns),
        }
    }

    /// Whether column `i` holds its mass flow ([`HOLD_FLOW_PRESSURE`], Anderson iteration only).
    pub(super) fn holds_flow(&self, i: usize) -> bool {
        self.options.iteration == EnergyIteration::Anderson && self.p[i] < HOLD_FLOW_PRESSURE * self.p_peak
    }

    /// The largest temperature rise of `f` over the inlet, K (at least 1e-3): the scale of the
    /// sweeps' changes.
    pub(super) fn scale_rise(&self, f: &TemperatureField) -> f64 {
        (f.film_max() - self.t0).abs().max(1e-3)
    }

    /// Temperature of column node `j` at column `i` of `f`.
    pub(super) fn node_temperature(&self, f: &TemperatureField, i: usize, j: usize) -> f64 {
        node_temperature(f, i, j, self.ns, self.nz, self.i_film0, self.i_film1)
    }
}

/// The segment lengths between the nodes of every column (body 1 from its depth, the film's
/// `nz` uniform levels across `h`, body 2 to its depth) and their conductances, with the
/// conductivities of body 1, the film and body 2.
fn segments(h: &[f64], z1: &[f64], z2: &[f64], nz: usize, conductivity: [f64; 3]) -> (Vec<f64>, Vec<f64>) {
    let ns = z1.len();
    let nn = 2 * ns + nz - 2;
    let (i_film0, i_film1) = (ns - 1, ns + nz - 2);
    let mut pos = vec![0.0; nn];
    let mut lengths = Vec::with_capacity(h.len() * (nn - 1));
    let mut conductances = Vec::with_capacity(h.len() * (nn - 1));
    for &hi in h {
        let dz = hi / (nz - 1) as f64;
        for k in 0..ns {
            pos[ns - 1 - k] = -z1[k];
            pos[i_film1 + k] = hi + z2[k];
        }
        for k in 0..nz {
            pos[i_film0 + k] = dz * k as f64;
        }
        for seg in 0..nn - 1 {
            let length = pos[seg + 1] - pos[seg];
            let k = if seg < i_film0 { conductivity[0] } else if seg >= i_film1 { conductivity[2] } else { conductivity[1] };
            lengths.push(length);
            conductances.push(k / length);
        }
    }
    (lengths, conductances)
}
