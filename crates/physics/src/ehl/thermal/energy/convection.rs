//! Convection in conservative donor-cell form: the heat-capacity fluxes of the column nodes along
//! `x` and, from continuity, the film's flows across its levels.

use super::setup::EnergyGrid;
use super::*;

/// The convective fluxes of one sweep. `q[i·N + j]`: the heat-capacity flux `Σ ρ c u ℓ` of column
/// node j (its two half cells ℓ; the film's on the stretched levels ζ = z/h), W/(m·K); face fluxes
/// are the means of neighbouring nodes, the boundary faces the end nodes'. The film's flow across
/// the levels follows from continuity: the flux through the face above film node j is
/// `V = −Σ_{m ≤ j} (G_{i+½,m} − G_{i−½,m})/Δx_i` (seed 000 eq. 7's `q ∂T/∂z`). Every node then
/// convects `Σ_inflow |G| (T − T_upwind)`: exactly conservative.
pub(super) struct Convection {
    pub(super) q: Vec<f64>,
    /// `V` through the face above each film node (`v_up[i·N + j]`).
    pub(super) v_up: Vec<f64>,
    /// The film's net outflow of each column (the pressure solution's discrete mass defect).
    pub(super) leak: Vec<f64>,
}

impl Convection {
    pub(super) fn new(g: &EnergyGrid) -> Self {
        Convection { q: vec![0.0; g.n * g.nn], v_up: vec![0.0; g.n * g.nn], leak: vec![0.0; g.n] }
    }

    /// The fluxes at the film's current velocities and densities.
    pub(super) fn update(&mut self, g: &EnergyGrid, columns: &[Column]) {
        let (n, nn) = (g.n, g.nn);
        let q = &mut self.q;
        for i in 0..n {
            for j in 0..nn {
                q[i * nn + j] = capacity(g, columns, i, j) * velocity(g, columns, i, j);
            }
        }
        for i in 0..n {
            let mut acc = 0.0;
            for j in g.i_film0..=g.i_film1 {
                let gl = if i == 0 { q[j] } else { 0.5 * (q[(i - 1) * nn + j] + q[i * nn + j]) };
                let gr = if i == n - 1 { q[i * nn + j] } else { 0.5 * (q[i * nn + j] + q[(i + 1) * nn + j]) };
                acc += (gr - gl) / g.wx[i];
                self.v_up[i * nn + j] = -acc;
            }
            // The film's net outflow (the pressure solution's discrete mass defect).
            self.leak[i] = acc;
            self.v_up[i * nn + g.i_film1] = 0.0;
        }
    }
}

/// Heat capacity per unit area ρ c ℓ of node j's half cells at column i, J/(m²·K).
fn capacity(g: &EnergyGrid, columns: &[Column], i: usize, j: usize) -> f64 {
    let (ns, nn, i_film0, i_film1) = (g.ns, g.nn, g.i_film0, g.i_film1);
    let (z1, z2) = (&g.z1, &g.z2);
    let dzf = g.h[i] / (g.nz - 1) as f64;
    let film_half = |k: usize| 0.5 * dzf * g.lub.density * columns[i].rho[k] * g.cf;
    let mut c = 0.0;
    if j > 0 && j <= i_film0 {
        c += 0.5 * (z1[ns - j] - z1[ns - 1 - j]) * g.rc1;
    }
    if j < i_film0 {
        c += 0.5 * (z1[ns - 1 - j] - z1[ns - 2 - j]) * g.rc1;
    }
    if j >= i_film0 && j < i_film1 {
        c += film_half(j - i_film0);
    }
    if j > i_film0 && j <= i_film1 {
        c += film_half(j - i_film0);
    }
    if j >= i_film1 && j + 1 < nn {
        c += 0.5 * (z2[j + 1 - i_film1] - z2[j - i_film1]) * g.rc2;
    }
    if j > i_film1 {
        c += 0.5 * (z2[j - i_film1] - z2[j - 1 - i_film1]) * g.rc2;
    }
    c
}

/// Velocity of column node j at column i, m/s.
fn velocity(g: &EnergyGrid, columns: &[Column], i: usize, j: usize) -> f64 {
    if j < g.i_film0 {
        g.u1
    } else if j > g.i_film1 {
        g.u2
    } else {
        columns[i].u[j - g.i_film0]
    }
}
