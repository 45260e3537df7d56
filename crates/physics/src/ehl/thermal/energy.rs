use super::*;

/// Thomas algorithm for `a_i x_{i−1} + b_i x_i + c_i x_{i+1} = r_i` (in place into `r`).
pub(super) fn thomas(a: &[f64], b: &mut [f64], c: &[f64], r: &mut [f64]) {
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

pub(super) fn energy_iterated(x: &[f64], p: &[f64], h: &[f64], input: &EnergyInput, options: &ThermalOptions) -> Result<EnergySolution, SolveError> {
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
pub(super) fn effective_integrals(eta: &[f64], rho: &[f64]) -> (f64, f64, f64, f64) {
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
pub(super) fn node_temperature(f: &TemperatureField, i: usize, j: usize, ns: usize, nz: usize, i_film0: usize, i_film1: usize) -> f64 {
    if j < i_film0 {
        f.body_1[i * ns + (ns - 1 - j)]
    } else if j >= i_film1 {
        f.body_2[i * ns + (j - i_film1)]
    } else {
        f.film[i * nz + (j - i_film0)]
    }
}
