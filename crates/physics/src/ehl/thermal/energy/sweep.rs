//! One Gauss–Seidel sweep of the energy equations along `x`: each column's finite-volume
//! conduction balance across cam, film and roller with donor-cell convection, solved by the
//! Thomas algorithm in place into the field.

use super::convection::Convection;
use super::properties::FilmState;
use super::setup::EnergyGrid;
use super::*;

/// The work arrays of one column: its tridiagonal system, node positions and gathered
/// temperatures (column layout of [`EnergyGrid`]).
pub(super) struct ColumnWork {
    za: Vec<f64>,
    zb: Vec<f64>,
    zc: Vec<f64>,
    zr: Vec<f64>,
    temps: Vec<f64>,
}

/// One sweep over the columns (forward in `x` or backward) from `field`, in place; `outer_start`
/// linearises the shear heating (Anderson), else the current temperatures do. Returns the
/// largest temperature change relative to the largest rise; a runaway is a typed failure.
#[allow(clippy::too_many_arguments)]
pub(super) fn sweep(
    g: &EnergyGrid,
    film: &mut FilmState,
    conv: &Convection,
    work: &mut ColumnWork,
    field: &mut TemperatureField,
    outer_start: Option<&TemperatureField>,
    forward: bool,
    sweeps: u32,
) -> Result<f64, SolveError> {
    let n = g.n;
    let mut change: f64 = 0.0;
    let mut film_max = FilmMax::new(field, g.nz);
    for step in 0..n {
        let i = if forward { step } else { n - 1 - step };
        work.gather(g, field, i);
        // After FREEZE_AFTER sweeps the film's properties and velocities stay as they are:
        // the remaining problem is linear and the sweeps converge (a limit cycle of the
        // upwind directions in the inlet's recirculation can otherwise persist).
        if !g.anderson && sweeps <= FREEZE_AFTER {
            film.update(g, i, &work.temps[g.i_film0..g.i_film0 + g.nz]);
        }
        work.assemble(g, film, conv, field, outer_start, i);
        thomas(&work.za, &mut work.zb, &work.zc, &mut work.zr);
        let rise = (film_max.value() - g.t0).abs().max(1e-3);
        change = work.largest_change(g, rise, sweeps, change)?;
        work.scatter(g, field, i);
        film_max.column_changed(i, &field.film[i * g.nz..(i + 1) * g.nz]);
    }
    Ok(change)
}

/// The film's largest temperature over the field as its columns change one at a time: each
/// column's largest kept, the whole recomputed only when the column that held it cools. The
/// same value as [`TemperatureField::film_max`] after every change, at O(1) per column instead
/// of a scan of the field (which was a quarter of the sweeps' time).
struct FilmMax {
    columns: Vec<f64>,
    value: f64,
}

impl FilmMax {
    fn new(field: &TemperatureField, nz: usize) -> Self {
        let columns: Vec<f64> = field.film.chunks(nz).map(column_max).collect();
        let value = column_max(&columns);
        FilmMax { columns, value }
    }

    fn value(&self) -> f64 {
        self.value
    }

    fn column_changed(&mut self, i: usize, column: &[f64]) {
        let old = self.columns[i];
        let new = column_max(column);
        self.columns[i] = new;
        if new >= self.value {
            self.value = new;
        } else if old == self.value {
            self.value = column_max(&self.columns);
        }
    }
}

fn column_max(values: &[f64]) -> f64 {
    values.iter().fold(f64::NEG_INFINITY, |a, &b| a.max(b))
}

impl ColumnWork {
    pub(super) fn new(g: &EnergyGrid) -> Self {
        let nn = g.nn;
        ColumnWork { za: vec![0.0; nn], zb: vec![0.0; nn], zc: vec![0.0; nn], zr: vec![0.0; nn], temps: vec![0.0; nn] }
    }

    /// Gather column `i`'s temperatures from the field.
    fn gather(&mut self, g: &EnergyGrid, field: &TemperatureField, i: usize) {
        let (ns, nz) = (g.ns, g.nz);
        for k in 0..ns {
            self.temps[ns - 1 - k] = field.body_1[i * ns + k];
            self.temps[g.i_film1 + k] = field.body_2[i * ns + k];
        }
        for k in 0..nz {
            self.temps[g.i_film0 + k] = field.film[i * nz + k];
        }
    }

    /// Column `i`'s tridiagonal system: conduction across the half cells, the linearised sources,
    /// the horizontal inflows from the neighbouring columns of `field` (donor cell), the flow
    /// across the film levels, the film's leak and the transient storage.
    fn assemble(&mut self, g: &EnergyGrid, film: &FilmState, conv: &Convection, field: &TemperatureField, outer_start: Option<&TemperatureField>, i: usize) {
        let (n, nn, t0) = (g.n, g.nn, g.t0);
        let col = &film.columns[i];
        let eta_ref = film.eta_ref[i];
        let (za, zb, zc, zr) = (&mut self.za, &mut self.zb, &mut self.zc, &mut self.zr);
        let temps = &self.temps;
        let solid_1 = HalfCell { heat_capacity: g.rc1, ..HalfCell::default() };
        let solid_2 = HalfCell { heat_capacity: g.rc2, ..HalfCell::default() };
        let lengths = &g.lengths[i * (nn - 1)..(i + 1) * (nn - 1)];
        let conductances = &g.conductances[i * (nn - 1)..(i + 1) * (nn - 1)];
        let (q, v_up, leak) = (&conv.q, &conv.v_up, &conv.leak);
        for j in 0..nn {
            if j == 0 || j == nn - 1 {
                za[j] = 0.0;
                zc[j] = 0.0;
                zb[j] = 1.0;
                zr[j] = t0;
                continue;
            }
            // The half cells below and above node j: a solid's, or the film's at the node's level.
            let in_film = if (g.i_film0..=g.i_film1).contains(&j) { film_half_cell(g, col, eta_ref, i, j - g.i_film0) } else { solid_1 };
            let lower = if j - 1 < g.i_film0 { solid_1 } else if j - 1 >= g.i_film1 { solid_2 } else { in_film };
            let upper = if j < g.i_film0 { solid_1 } else if j >= g.i_film1 { solid_2 } else { in_film };
            let (sl, dsl) = (lower.shear + lower.compression * temps[j], lower.slope);
            let (su, dsu) = (upper.shear + upper.compression * temps[j], upper.slope);
            let (rcl, rcu) = (lower.heat_capacity, upper.heat_capacity);
            let (a, c) = (lengths[j - 1], lengths[j]);
            let (gl, gu) = (conductances[j - 1], conductances[j]);
            let cap = rcl * 0.5 * a + rcu * 0.5 * c;
            za[j] = -gl;
            zc[j] = -gu;
            zb[j] = gl + gu;
            // Linearised source S* + S'(T − T*), S' ≤ 0, over the half cells.
            let slope = dsl * 0.5 * a + dsu * 0.5 * c;
            zb[j] -= slope;
            // Sweeps: about the current temperature (a stabiliser; the fixed point has the
            // frozen source). Anderson: about the outer iterate (a Newton-like linearisation).
            let t_lin = match outer_start {
                Some(x) => g.node_temperature(x, i, j),
                None => temps[j],
            };
            zr[j] = sl * 0.5 * a + su * 0.5 * c - slope * t_lin;
            // Horizontal inflows (donor cell).
            let qj = q[i * nn + j];
            let g_left = if i == 0 { qj } else { 0.5 * (q[(i - 1) * nn + j] + qj) };
            let g_right = if i == n - 1 { qj } else { 0.5 * (qj + q[(i + 1) * nn + j]) };
            if g_left > 0.0 {
                let t_up = if i == 0 { t0 } else { g.node_temperature(field, i - 1, j) };
                zb[j] += g_left / g.wx[i];
                zr[j] += g_left / g.wx[i] * t_up;
            }
            if g_right < 0.0 {
                let t_up = if i == n - 1 { t0 } else { g.node_temperature(field, i + 1, j) };
                zb[j] -= g_right / g.wx[i];
                zr[j] -= g_right / g.wx[i] * t_up;
            }
            // Flow across the film levels (implicit, upwind).
            if j > g.i_film0 && j <= g.i_film1 {
                let below = v_up[i * nn + j - 1];
                if below > 0.0 {
                    za[j] -= below;
                    zb[j] += below;
                }
            }
            if j >= g.i_film0 && j < g.i_film1 {
                let above = v_up[i * nn + j];
                if above < 0.0 {
                    zc[j] += above;
                    zb[j] -= above;
                }
            }
            if j == g.i_film1 && leak[i] > 0.0 {
                zb[j] += leak[i];
                zr[j] += leak[i] * t0;
            }
            if let Some((of, dt)) = &g.old {
                let told = g.node_temperature(of, i, j);
                zb[j] += cap / dt;
                zr[j] += cap / dt * told;
            }
        }
    }

    /// `change` and the solved column's largest change relative to the field's largest rise
    /// `rise`, the larger; a temperature that is not finite or beyond [`MAX_TEMPERATURE_RISE`] ends the
    /// solve.
    fn largest_change(&self, g: &EnergyGrid, rise: f64, sweeps: u32, mut change: f64) -> Result<f64, SolveError> {
        for j in 0..g.nn {
            let v = self.zr[j];
            if !v.is_finite() || v > g.t0 + MAX_TEMPERATURE_RISE {
                // Runaway shear heating (a Newtonian film sheared far beyond its traction
                // maximum, or a hot layer drawing an unbounded Poiseuille flow at the fixed
                // pressure gradient): a typed failure, not a NaN or a film at thousands of
                // kelvin where eq. 4–5 mean nothing (measured: 45 000 K, then 1e24 K, with
                // negative densities, at the seed 001 nose with S = 1 before this bound).
                return Err(SolveError::NotConverged {
                    solver: "thermal ehl energy equation (temperature runaway)",
                    iterations: sweeps,
                    residual: f64::INFINITY,
                    tolerance: g.options.sweep_tolerance,
                    history: Vec::new(),
                });
            }
            change = change.max((v - self.temps[j]).abs() / rise);
        }
        Ok(change)
    }

    /// Write the solved column `i` into the field.
    fn scatter(&self, g: &EnergyGrid, field: &mut TemperatureField, i: usize) {
        let (ns, nz) = (g.ns, g.nz);
        for k in 0..ns {
            field.body_1[i * ns + k] = self.zr[ns - 1 - k];
            field.body_2[i * ns + k] = self.zr[g.i_film1 + k];
        }
        for k in 0..nz {
            field.film[i * nz + k] = self.zr[g.i_film0 + k];
        }
    }
}

/// The material of a half cell beside a node, per unit volume: its heat capacity `ρc`,
/// J/(m³·K), and its heat source `shear + compression · T` with the temperature slope `slope`
/// of its linearisation, W/m³ and W/(m³·K). A solid's has no source.
#[derive(Clone, Copy, Default)]
struct HalfCell {
    heat_capacity: f64,
    shear: f64,
    compression: f64,
    slope: f64,
}

/// The film's half cells at level `k` of column `i`. The shear heating is linearised with the
/// slope of a film heating uniformly (τ ∝ η, heat ∝ η: −β·heat), which keeps the sweeps stable
/// where the heating is strongly self-limiting.
fn film_half_cell(g: &EnergyGrid, col: &Column, eta_ref: f64, i: usize, k: usize) -> HalfCell {
    let lub = g.lub;
    let rho = lub.density * col.rho[k];
    let eta = col.eta[k] * eta_ref;
    let shear = col.tau[k] * col.tau[k] / eta;
    // Compressive heating a·T: cooling (a < 0) implicit, heating lagged.
    let a_comp = if g.compressive { lub.density * DH_C3 / rho * col.u[k] * g.dpdx[i] } else { 0.0 };
    HalfCell { heat_capacity: rho * g.cf, shear, compression: a_comp, slope: -col.beta[k].max(0.0) * shear + a_comp.min(0.0) }
}
