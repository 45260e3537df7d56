//! The traction along the rolling direction of a solved line-contact film (seed 001 Fig. 8b):
//! node by node, the fluid and asperity pressures, the film's shear stress (seed 001 eq. 24
//! through the traction law, eq. 25) and the asperity shear stress with its bound `μ_b p_a`
//! (seed 001 eq. 22–23 for the micro-slip law; the other laws share the contact's slip state).
//! What the balance integrates, resolved in x: nothing here changes a traction.

use super::closed_form::{FILM_FLOOR, VISCOSITY_CAP};
use super::{ContactInput, FilmSolution};
use crate::friction::{micro_slip, viscous_traction_local, TractionNode};

/// Shear stresses and pressures along a line contact at one sliding velocity (all per node).
#[derive(Debug, Clone, PartialEq)]
pub struct TractionAlong {
    /// Position along the rolling direction, m (0 at the contact centre, positive downstream).
    pub x: Vec<f64>,
    /// Film thickness, m.
    pub film: Vec<f64>,
    /// Fluid pressure, Pa.
    pub fluid_pressure: Vec<f64>,
    /// Asperity pressure, Pa.
    pub asperity_pressure: Vec<f64>,
    /// Film shear stress on the surfaces, Pa (sign of the sliding; the rolling Poiseuille part
    /// included).
    pub viscous_shear: Vec<f64>,
    /// Asperity shear stress, Pa (sign of the sliding).
    pub asperity_shear: Vec<f64>,
    /// Its bound `μ_b p_a`, Pa: where `|asperity_shear|` reaches it the node slides grossly.
    pub asperity_shear_limit: Vec<f64>,
}

/// The traction along the contact of `film` (solved at `input`) at sliding velocity `sliding`
/// (m/s). `None` when the film model keeps no 1-D profile (closed forms, the 2-D model).
pub fn traction_along(film: &FilmSolution, input: &ContactInput, sliding: f64) -> Option<TractionAlong> {
    let p = film.profile.as_deref()?;
    let n = p.x.len().min(p.pressure.len()).min(p.film.len());
    if n < 2 {
        return None;
    }
    let asperity: Vec<f64> = (0..n).map(|i| p.asperity_pressure.get(i).copied().unwrap_or(0.0).max(0.0)).collect();
    let fluid: Vec<f64> = (0..n).map(|i| (p.pressure[i] - asperity[i]).max(0.0)).collect();
    let t = input.temperature;
    let viscous_shear = (0..n)
        .map(|i| {
            if fluid[i] <= 0.0 {
                return 0.0;
            }
            let (a, b) = (i.saturating_sub(1), (i + 1).min(n - 1));
            let dpdx = (fluid[b] - fluid[a]) / (p.x[b] - p.x[a]);
            let h = p.film[i].max(FILM_FLOOR);
            let node = TractionNode {
                area: 1.0,
                pressure: fluid[i],
                viscosity: input.lubricant.viscosity_at(fluid[i], t).min(VISCOSITY_CAP),
                film: h,
                poiseuille: -0.5 * h * dpdx,
            };
            viscous_traction_local(&[node], input.traction_law, sliding).force
        })
        .collect();
    let law = input.asperity_friction;
    let mu = law.coefficient;
    let ue = input.entrainment_velocity;
    let asperity_shear_limit: Vec<f64> = asperity.iter().map(|pa| mu * pa).collect();
    // Unit cells and length: each node's "load" is its pressure, its traction a stress.
    let nodes = law.asperity_nodes(&p.x[..n], &p.film[..n], &asperity, &vec![1.0; n], 1.0, ue);
    let asperity_shear = if nodes.is_empty() {
        let q = mu * film.asperity.load;
        let share = if q > 0.0 { law.traction(&film.asperity, sliding, ue).0 / q } else { 0.0 };
        asperity_shear_limit.iter().map(|l| l * share).collect()
    } else {
        // the nodes are those with p_a > 0, in grid order
        let mut it = nodes.iter();
        asperity
            .iter()
            .map(|&pa| match (pa > 0.0).then(|| it.next()).flatten() {
                Some(nd) => micro_slip::nodal_traction(std::slice::from_ref(nd), mu, sliding, ue).0,
                None => 0.0,
            })
            .collect()
    };
    Some(TractionAlong { x: p.x[..n].to_vec(), film: p.film[..n].to_vec(), fluid_pressure: fluid, asperity_pressure: asperity, viscous_shear, asperity_shear, asperity_shear_limit })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ehl::EhlOptions;
    use crate::film::closed_form::test_inputs::{oil, seed001_nose};
    use crate::film::{ClosedForm, FilmFormula, FilmModel, Numerical};
    use crate::friction::{AsperityFriction, AsperityModel, Rheology, Roughness, TractionLaw};

    /// Seed 001's smooth nose, Newtonian film at u_s = 0.04 m/s: the film shear along the contact
    /// adds up (trapezoid cells × length) to the model's viscous traction within 0.5 %, is zero
    /// without fluid pressure, and there is no asperity shear on smooth surfaces. A closed form
    /// keeps no profile: `None`.
    #[test]
    fn film_shear_along_the_contact_adds_up_to_the_traction() {
        let lub = oil();
        let rough = Roughness { sigma: 0.0, eta_beta_sigma: 0.04, sigma_over_beta: 0.001, plastic_limit: f64::INFINITY, curve: None };
        let law = TractionLaw { rheology: Rheology::Newtonian, limiting_shear_coefficient: None };
        let asp = AsperityFriction { coefficient: 0.12, model: AsperityModel::Coulomb, map: None };
        let input = seed001_nose(&lub, &rough, &law, &asp);
        let model = Numerical::new(EhlOptions { nodes: 192, tolerance: 1e-8, ..EhlOptions::default() }, ClosedForm { formula: FilmFormula::PanHamrock, squeeze: false });
        let film = model.solve(&input, None).unwrap();
        let t = traction_along(&film, &input, 0.04).expect("a numerical film keeps its profile");
        let n = t.x.len();
        let cell = |i: usize| 0.5 * (t.x[(i + 1).min(n - 1)] - t.x[i.saturating_sub(1)]);
        let sum: f64 = (0..n).map(|i| t.viscous_shear[i] * cell(i) * 0.021).sum();
        let expect = model.traction(&film, &input, 0.04).viscous;
        assert!((sum / expect - 1.0).abs() < 5e-3, "{sum} vs {expect}");
        assert!(t.asperity_shear.iter().chain(&t.asperity_shear_limit).all(|v| *v == 0.0));
        assert!((0..n).all(|i| t.fluid_pressure[i] > 0.0 || t.viscous_shear[i] == 0.0));
        let closed = ClosedForm { formula: FilmFormula::PanHamrock, squeeze: false };
        assert!(traction_along(&closed.solve(&input, None).unwrap(), &input, 0.04).is_none());
    }
}
