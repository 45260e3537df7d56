//! One energy pass: the energy equations of every loaded row of the 2-D grid at the current
//! pressure and film (the 1-D solver per row, rows in parallel), the generalized Reynolds factors
//! they give over the plane, and the contact's temperatures, heat balance and traction.

use super::*;
use rayon::prelude::*;

/// The result of one energy pass over the rows.
pub(super) struct Pass {
    pub(super) rows: Vec<RowThermal>,
    /// Each grid row's temperature field (`None`: not solved), by row index.
    pub(super) fields: Vec<Option<TemperatureField>>,
    pub(super) factors: Factors2d,
    pub(super) film_temperature_max: Located,
    pub(super) surface_max: (f64, f64),
    pub(super) heat: HeatBalance,
    pub(super) traction: ContactTraction,
}

/// One row's energy solution: the row index, its first column and the solution.
struct RowSolve {
    j: usize,
    first: usize,
    row: RowThermal,
    factors: super::super::thermal::ThermalFactors,
    field: TemperatureField,
}

/// Surface velocities `(u1, u2)` = `u_m ± u_s/2`.
pub(super) fn surface_velocities(input: &ThermalFiniteInput) -> (f64, f64) {
    let (um, us) = (input.ehl.entrainment_velocity, input.sliding_velocity);
    (um + 0.5 * us, um - 0.5 * us)
}

/// The energy pass at the solution `sol` (whose `fields` must be present); `warm[j]` starts row
/// `j`'s sweeps.
pub(super) fn energy_pass(input: &ThermalFiniteInput, sol: &Ehl2dSolution, thermal: &ThermalOptions, warm: &[Option<TemperatureField>]) -> Result<Pass, SolveError> {
    let f = sol.fields.as_ref().ok_or_else(|| SolveError::invalid("Ehl2dOptions.fields", "the thermal model needs the pressure and film fields"))?;
    let (nx, ny) = (f.x.len(), f.y.len());
    // Columns in ascending x (the solver's frame is mirrored for a negative entrainment).
    let order: Vec<usize> = if f.x[0] <= f.x[nx - 1] { (0..nx).collect() } else { (0..nx).rev().collect() };
    let x: Vec<f64> = order.iter().map(|&i| f.x[i]).collect();
    let p_peak = f.pressure.iter().fold(0.0f64, |m, &v| m.max(v));
    let (u1, u2) = surface_velocities(input);
    let solved: Vec<Option<RowSolve>> = (0..ny)
        .into_par_iter()
        .map(|j| -> Result<Option<RowSolve>, SolveError> {
            let p: Vec<f64> = order.iter().map(|&i| f.pressure[j * nx + i].max(0.0)).collect();
            let h: Vec<f64> = order.iter().map(|&i| f.film[j * nx + i]).collect();
            let row_peak = p.iter().fold(0.0f64, |m, &v| m.max(v));
            if !(row_peak > ROW_PRESSURE * p_peak) {
                return Ok(None);
            }
            let (a, e) = thermal_range(&h, thermal.film_extent);
            let load: f64 = (1..nx).map(|i| 0.5 * (p[i] + p[i - 1]) * (x[i] - x[i - 1])).sum();
            let ein = EnergyInput {
                limited_gradient: true,
                velocity_1: u1,
                velocity_2: u2,
                lubricant: &input.ehl.lubricant,
                inlet_temperature: input.ehl.temperature,
                bodies: &input.bodies,
                half_width: sol.hertz_half_width,
                load_per_length: load.max(1e-30),
                rheology: &input.rheology,
                previous: None,
                warm: warm.get(j).and_then(|w| w.as_ref()),
            };
            let mut en = energy(&x[a..=e], &p[a..=e], &h[a..=e], &ein, thermal);
            // A row whose sweeps fail from the last pass's field (a runaway where the exit's
            // pressure drops within a cell) is solved again from the inlet temperature, then by
            // the Anderson iteration, whose low-pressure columns hold their mass flow.
            if matches!(en, Err(SolveError::NotConverged { .. })) && ein.warm.is_some() {
                en = energy(&x[a..=e], &p[a..=e], &h[a..=e], &EnergyInput { warm: None, ..ein }, thermal);
            }
            if matches!(en, Err(SolveError::NotConverged { .. })) && thermal.iteration != EnergyIteration::Anderson {
                en = energy(&x[a..=e], &p[a..=e], &h[a..=e], &ein, &ThermalOptions { iteration: EnergyIteration::Anderson, ..*thermal });
            }
            let en = en?;
            let ic = x.partition_point(|&v| v < 0.0).min(nx - 1);
            let row = RowThermal {
                y: f.y[j],
                summary: en.summary,
                traction: en.traction,
                central_film: h[ic],
                min_film: h.iter().cloned().fold(f64::INFINITY, f64::min),
                max_pressure: row_peak,
            };
            Ok(Some(RowSolve { j, first: a, row, factors: en.factors, field: en.field }))
        })
        .collect::<Result<_, _>>()?;
    let mut factors = Factors2d { x: x.clone(), y: f.y.clone(), poiseuille: vec![1.0; nx * ny], wedge: vec![1.0; nx * ny] };
    let mut fields: Vec<Option<TemperatureField>> = vec![None; ny];
    let mut rows = Vec::new();
    let mut t_max = Located { value: input.ehl.temperature, x: 0.0, y: 0.0 };
    let mut surface_max = (input.ehl.temperature, input.ehl.temperature);
    let (mut heat, mut traction) = (HeatBalance::default(), ContactTraction::default());
    for r in solved.into_iter().flatten() {
        let j = r.j;
        for (k, (&cp, &cw)) in r.factors.poiseuille.iter().zip(&r.factors.wedge).enumerate() {
            factors.poiseuille[j * nx + r.first + k] = cp;
            factors.wedge[j * nx + r.first + k] = cw;
        }
        // Trapezoidal weight of the row along y, m.
        let wy = 0.5 * (f.y[(j + 1).min(ny - 1)] - f.y[j.saturating_sub(1)]);
        let s = &r.row.summary;
        heat.generated += wy * s.heat_generated;
        heat.to_body_1 += wy * s.heat_to_body_1;
        heat.to_body_2 += wy * s.heat_to_body_2;
        heat.convected += wy * s.heat_convected;
        heat.side += wy * s.heat_side;
        traction.force_body_1 += wy * r.row.traction.force_body_1;
        traction.force_body_2 += wy * r.row.traction.force_body_2;
        traction.rolling_force += wy * r.row.traction.rolling_force;
        surface_max.0 = surface_max.0.max(s.surface_temperature_max_1);
        surface_max.1 = surface_max.1.max(s.surface_temperature_max_2);
        if s.film_temperature_max > t_max.value {
            let nz = r.field.film_points;
            let k = (0..r.field.film.len()).max_by(|&a, &b| r.field.film[a].total_cmp(&r.field.film[b])).unwrap_or(0);
            t_max = Located { value: s.film_temperature_max, x: r.field.x[k / nz], y: r.row.y };
        }
        fields[j] = Some(r.field);
        rows.push(r.row);
    }
    crate::work::add(&crate::work::THERMAL_2D_PASSES, 1);
    crate::work::add(&crate::work::THERMAL_2D_ROW_SOLVES, rows.len() as u64);
    crate::work::add(&crate::work::THERMAL_2D_SWEEPS, rows.iter().map(|r| r.summary.sweeps as u64).sum());
    let removed = heat.to_body_1 + heat.to_body_2 + heat.convected + heat.side;
    heat.error = if heat.generated.abs() > 0.0 { ((heat.generated - removed) / heat.generated).abs() } else { 0.0 };
    traction.friction_coefficient = (traction.force_body_2 - traction.force_body_1) / (2.0 * input.ehl.load);
    crate::ensure_finite("thermal finite ehl", [&heat.generated, &traction.force_body_1, &traction.force_body_2, &t_max.value])?;
    Ok(Pass { rows, fields, factors, film_temperature_max: t_max, surface_max, heat, traction })
}

/// `old` (any grid, interpolated) blended towards `new` by `w` on `new`'s nodes: the Poiseuille
/// factor geometrically, the wedge factor linearly (as the line contact's coupling does).
pub(super) fn blend(old: Option<&Factors2d>, new: &Factors2d, w: f64) -> Factors2d {
    if w >= 1.0 {
        return new.clone();
    }
    let mut out = new.clone();
    let nx = new.x.len();
    for k in 0..new.poiseuille.len() {
        let (op, ow) = old.map_or((1.0, 1.0), |o| o.at(new.x[k % nx], new.y[k / nx]));
        out.poiseuille[k] = (op.max(1e-300).ln() * (1.0 - w) + new.poiseuille[k].max(1e-300).ln() * w).exp();
        out.wedge[k] = ow * (1.0 - w) + new.wedge[k] * w;
    }
    out
}
