//! The `fast` film model: Hertz contact, a regression film formula and Greenwood–Tripp load
//! sharing.
//!
//! Load sharing (Johnson–Greenwood–Poon, see [`super::mixed`]): the fluid part carries
//! `(1 − f_a) W` with the modulus scaled alike, its film from the formula; the asperities carry
//! `W_a = f_a W = A p_a(h_c)` over the nominal Hertz area `A` (Greenwood–Tripp with the plastic
//! cap); the fluid's traction nodes carry the Hertz pressure profile scaled by `1 − f_a`.
//!
//! Traction nodes: 8 Gauss–Legendre points in `t` on `[0, π/2]` after the substitution
//! `x = b sin t`, which removes the square-root edge of the Hertz profile `p0 cos t` (line:
//! `dA = 2bL cos t dt`; point: `dA = 2πab sin t cos t dt`). The film is taken uniform at the
//! central value, floored at 1 nm so that the shear rate stays finite where the closed form gives
//! no film (zero entrainment); viscosities are capped at 1e20 Pa·s (glassy limit).

use super::formulas::{self, LineGroups};
use super::{ContactInput, ContactShape, FilmModel, FilmModelId, FilmSolution, Regime};
use crate::contact::{hertz_line, hertz_point};
use crate::friction::TractionNode;
use crate::{ensure_finite, SolveError};
use serde::{Deserialize, Serialize};

/// Film formula of a line contact (point contacts always use Hamrock–Dowson).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum FilmFormula {
    /// Pan & Hamrock (1989): central and minimum film.
    #[default]
    PanHamrock,
    /// Dowson & Higginson (1977): minimum film; central = 4/3 minimum.
    DowsonHigginson,
    /// Seed 003 eq. 17 (central) and eq. 18 (side constriction = minimum), with the squeeze term
    /// when `squeeze` is on.
    Seed003,
}

/// The closed-form (`fast`) film model.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ClosedForm {
    pub formula: FilmFormula,
    /// Apply seed 003's squeeze term (only with [`FilmFormula::Seed003`]).
    pub squeeze: bool,
}

/// Smallest film used in the shear rate, m.
pub const FILM_FLOOR: f64 = 1e-9;
/// Largest viscosity used in the traction, Pa·s.
pub const VISCOSITY_CAP: f64 = 1e20;

/// Gauss–Legendre 8-point nodes and weights on [−1, 1] (A&S table 25.4).
const GL8: [(f64, f64); 8] = [
    (-0.960_289_856_497_536_3, 0.101_228_536_290_376_3),
    (-0.796_666_477_413_626_7, 0.222_381_034_453_374_5),
    (-0.525_532_409_916_329_0, 0.313_706_645_877_887_3),
    (-0.183_434_642_495_649_8, 0.362_683_783_378_362_0),
    (0.183_434_642_495_649_8, 0.362_683_783_378_362_0),
    (0.525_532_409_916_329_0, 0.313_706_645_877_887_3),
    (0.796_666_477_413_626_7, 0.222_381_034_453_374_5),
    (0.960_289_856_497_536_3, 0.101_228_536_290_376_3),
];

/// `(sin t, cos t, π/4 · w)` of the [`GL8`] nodes mapped to `t ∈ [0, π/2]`, computed once.
fn gl8_angles() -> &'static [(f64, f64, f64); 8] {
    static TABLE: std::sync::OnceLock<[(f64, f64, f64); 8]> = std::sync::OnceLock::new();
    TABLE.get_or_init(|| {
        GL8.map(|(xi, wi)| {
            let tt = std::f64::consts::FRAC_PI_4 * (1.0 + xi);
            let (s, c) = tt.sin_cos();
            (s, c, std::f64::consts::FRAC_PI_4 * wi)
        })
    })
}

impl ClosedForm {
    /// Central, minimum and steady central film (m) and the formula's id for the fluid part of a
    /// load-sharing contact that carries the fraction `s` of the load with the modulus scaled
    /// alike (Johnson–Greenwood–Poon; `s = 1`: the smooth contact).
    fn films(&self, input: &ContactInput, previous: Option<&FilmSolution>, eta0: f64, s: f64) -> (f64, f64, f64, FilmModelId) {
        let load = s * input.load;
        let e_prime = s * 2.0 * input.contact_modulus;
        let alpha = input.lubricant.pressure_viscosity;
        let u = input.entrainment_velocity;
        match input.shape {
            ContactShape::Line { reduced_radius: r, length } => {
                let w = load / length;
                let g = LineGroups::new(w, r, u, eta0, alpha, e_prime);
                match self.formula {
                    FilmFormula::PanHamrock => {
                        let (c, m) = formulas::pan_hamrock(&g);
                        (c * r, m * r, c * r, FilmModelId::PanHamrock)
                    }
                    FilmFormula::DowsonHigginson => {
                        let (c, m) = formulas::dowson_higginson(&g);
                        (c * r, m * r, c * r, FilmModelId::DowsonHigginson)
                    }
                    FilmFormula::Seed003 => {
                        let w_star = load / (e_prime * r * length);
                        let (c0, _) = formulas::seed003(w_star, g.speed, g.material, 0.0);
                        let steady = c0 * r;
                        let ws = match previous {
                            Some(prev) if self.squeeze && input.time_step > 0.0 && u != 0.0 => {
                                (steady - prev.steady_central_film) / input.time_step / u.abs()
                            }
                            _ => 0.0,
                        };
                        let (c, m) = formulas::seed003(w_star, g.speed, g.material, ws);
                        (c * r, m * r, steady, FilmModelId::Seed003)
                    }
                }
            }
            ContactShape::Point { rx, ry } => {
                let w = load / (e_prime * rx * rx);
                let us = eta0 * u.abs() / (e_prime * rx);
                let k = formulas::ellipticity(rx, ry);
                let (c, m) = formulas::hamrock_dowson_point(w, us, alpha * e_prime, k);
                (c * rx, m * rx, c * rx, FilmModelId::HamrockDowson)
            }
        }
    }
}

impl FilmModel for ClosedForm {
    /// Only seed 003's squeeze term looks at the time step and the previous point.
    fn history_free(&self) -> bool {
        !(self.squeeze && self.formula == FilmFormula::Seed003)
    }

    fn solve(&self, input: &ContactInput, previous: Option<&FilmSolution>) -> Result<FilmSolution, SolveError> {
        let load = input.load;
        if !(load > 0.0 && load.is_finite()) {
            return Err(SolveError::physical(crate::PhysicalFailure::NoContactLoad, format!("contact load {load} N is not positive")));
        }
        let es = input.contact_modulus;
        let lub = input.lubricant;
        let t = input.temperature;
        let law = lub.viscosity_law(t);
        let eta0 = law.at(0.0);
        // Nominal (Hertz) contact of the full load: pressure scale, width, area.
        let (p0, b, area, r_roll, regime, point_ab) = match input.shape {
            ContactShape::Line { reduced_radius: r, length } => {
                let w = load / length;
                let hz = hertz_line(w, r, es);
                let g = LineGroups::new(w, r, input.entrainment_velocity, eta0, lub.pressure_viscosity, 2.0 * es);
                let regime = (g.speed > 0.0).then(|| Regime { viscous: g.viscous_parameter(), elastic: g.elastic_parameter() });
                (hz.max_pressure, hz.half_width, 2.0 * hz.half_width * length, r, regime, None)
            }
            ContactShape::Point { rx, ry } => {
                let hz = hertz_point(load, rx, ry, es)?;
                // Semi-axis along the rolling direction x lies along the smaller reduced radius
                // when rx < ry.
                let (ax, ay) = if rx <= ry { (hz.semi_minor, hz.semi_major) } else { (hz.semi_major, hz.semi_minor) };
                (hz.max_pressure, ax, std::f64::consts::PI * ax * ay, rx, None, Some((ax, ay)))
            }
        };
        // Load sharing (module docs): the fluid part carries the fraction `s` of the load.
        let sigma = input.roughness.sigma;
        let fluid_part = if sigma > 0.0 {
            let fa = super::mixed::share_load(
                load,
                area,
                |s| self.films(input, previous, eta0, s).0,
                |h| input.roughness.load_sharing_pressure(h, es).0,
            )?;
            1.0 - fa
        } else {
            1.0
        };
        let (hc, hm, h_steady, model) = self.films(input, previous, eta0, fluid_part);
        let model = if sigma > 0.0 { model.mixed() } else { model };
        let lambda = (sigma > 0.0).then(|| hm / sigma);
        let w_a = if sigma > 0.0 { ((1.0 - fluid_part) * load).min(load) } else { 0.0 };
        let fluid_share = 1.0 - w_a / load;
        let film = hc.max(FILM_FLOOR);
        let mut nodes = Vec::with_capacity(GL8.len());
        // The previous point's nodes, when their viscosities came from the same law: on a base
        // circle the node pressures repeat exactly and so do the viscosities.
        let reuse = previous.filter(|p| p.viscosity_law == Some(law) && p.nodes.len() == GL8.len()).map(|p| &p.nodes);
        for (k, &(s, c, wt)) in gl8_angles().iter().enumerate() {
            let node_area = match (input.shape, point_ab) {
                (ContactShape::Line { length, .. }, _) => 2.0 * b * length * c * wt,
                (ContactShape::Point { .. }, Some((ax, ay))) => 2.0 * std::f64::consts::PI * ax * ay * s * c * wt,
                _ => 0.0,
            };
            let pressure = fluid_share * p0 * c;
            let viscosity = match reuse {
                Some(prev) if prev[k].pressure == pressure => prev[k].viscosity,
                _ => law.at(pressure).min(VISCOSITY_CAP),
            };
            nodes.push(TractionNode { area: node_area, pressure, viscosity, film, poiseuille: 0.0 });
        }
        // The film's rolling (Poiseuille) resistance, which the Hertzian nodes (uniform film, a
        // symmetric pressure) cannot carry: Goksem–Hargreaves for line contacts at the fluid's
        // load, against the entrainment; point contacts and isoviscous oils leave it out.
        let rolling_force = match input.shape {
            ContactShape::Line { reduced_radius: r, length } if lub.pressure_viscosity > 0.0 && input.entrainment_velocity != 0.0 => {
                let g = LineGroups::new(fluid_share * load / length, r, input.entrainment_velocity, eta0, lub.pressure_viscosity, 2.0 * es);
                -input.entrainment_velocity.signum() * formulas::goksem_hargreaves_rolling(&g) * r * length / lub.pressure_viscosity
            }
            _ => 0.0,
        };
        // The micro-slip map's δx_gs and n at the central film (semi-elliptic asperity pressure).
        let asperity = input.asperity_friction.contact(w_a, b, r_roll, hc);
        ensure_finite("closed-form film", [&hc, &hm, &p0, &b, &area, &w_a, &rolling_force])?;
        ensure_finite("traction nodes", nodes.iter().flat_map(|n| [&n.area, &n.pressure, &n.viscosity]))?;
        Ok(FilmSolution {
            model,
            central_film: hc,
            min_film: hm,
            steady_central_film: h_steady,
            max_pressure: p0,
            pressure_spike: None,
            pressure_spike_position: None,
            exit_film: matches!(input.shape, ContactShape::Line { .. }).then_some(hm),
            half_width: b,
            contact_area: area,
            asperity,
            asperity_nodes: Vec::new(),
            lambda,
            regime,
            nodes,
            rolling_force,
            viscosity_law: Some(law),
            profile: None,
            iterations: None,
            thermal: None,
            finite: None,
        })
    }
}

/// Test inputs shared by the film and roller unit tests: seed 001's nose contact (12.5 kN on a
/// 21 mm line, R = 10.5 mm, u_e = 3.98 m/s, E* = 110 GPa) and its oil.
#[cfg(test)]
pub(crate) mod test_inputs {
    use super::*;
    use crate::friction::{AsperityFriction, Roughness, TractionLaw};
    use crate::lubricant::{DensityModel, Lubricant, ViscosityModel};

    pub(crate) fn seed001_nose<'a>(
        lub: &'a Lubricant,
        rough: &'a Roughness,
        law: &'a TractionLaw,
        asp: &'a AsperityFriction,
    ) -> ContactInput<'a> {
        ContactInput {
            load: 12_500.0,
            shape: ContactShape::Line { reduced_radius: 0.0105, length: 0.021 },
            entrainment_velocity: 3.98,
            sliding_velocity: 0.0,
            time: 0.0,
            time_step: 0.0,
            contact_modulus: 100e9 / 0.91,
            temperature: 313.0,
            lubricant: lub,
            roughness: rough,
            traction_law: law,
            asperity_friction: asp,
            interrupts: crate::Interrupts::NONE,
        }
    }

    pub(crate) fn oil() -> Lubricant {
        Lubricant {
            viscosity: 0.013,
            pressure_viscosity: 1.84e-8,
            temperature_viscosity: 0.0,
            reference_temperature: 313.0,
            density: 870.0,
            viscosity_model: ViscosityModel::Roelands,
            density_model: DensityModel::DowsonHigginson,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::test_inputs::{oil, seed001_nose};
    use super::*;
    use crate::friction::{AsperityFriction, AsperityModel, Rheology, Roughness, TractionLaw};

    #[test]
    fn nodes_integrate_the_hertz_load_and_area() {
        let lub = oil();
        let rough = Roughness { sigma: 0.0, eta_beta_sigma: 0.04, sigma_over_beta: 0.001, plastic_limit: f64::INFINITY, curve: None };
        let law = TractionLaw { rheology: Rheology::Newtonian, limiting_shear_coefficient: None };
        let asp = AsperityFriction { coefficient: 0.12, model: AsperityModel::Coulomb, map: None };
        let input = seed001_nose(&lub, &rough, &law, &asp);
        let f = ClosedForm { formula: FilmFormula::PanHamrock, squeeze: false }.solve(&input, None).unwrap();
        let area: f64 = f.nodes.iter().map(|n| n.area).sum();
        let load: f64 = f.nodes.iter().map(|n| n.area * n.pressure).sum();
        assert!((area / f.contact_area - 1.0).abs() < 1e-3, "{area} vs {}", f.contact_area);
        assert!((load / 12_500.0 - 1.0).abs() < 1e-3, "{load}");
        assert!((f.central_film / 0.2561e-6 - 1.0).abs() < 1e-3);
        assert_eq!(f.asperity.load, 0.0);
        assert!(f.lambda.is_none());
        // Point contact: same node rule integrates the ellipsoidal load.
        let point = ContactInput { shape: ContactShape::Point { rx: 0.0142, ry: 0.042 }, load: 500.0, ..input };
        let f = ClosedForm { formula: FilmFormula::PanHamrock, squeeze: false }.solve(&point, None).unwrap();
        let load: f64 = f.nodes.iter().map(|n| n.area * n.pressure).sum();
        assert!((load / 500.0 - 1.0).abs() < 1e-3, "{load}");
        assert_eq!(f.model, FilmModelId::HamrockDowson);
    }

    #[test]
    fn rough_surfaces_share_the_load_and_add_asperity_friction() {
        let lub = oil();
        let rough = Roughness { sigma: 0.3e-6, eta_beta_sigma: 0.05, sigma_over_beta: 0.001, plastic_limit: f64::INFINITY, curve: None };
        let law = TractionLaw { rheology: Rheology::Eyring { tau0: 5e6 }, limiting_shear_coefficient: None };
        let asp = AsperityFriction { coefficient: 0.12, model: AsperityModel::Coulomb, map: None };
        let input = seed001_nose(&lub, &rough, &law, &asp);
        let model = ClosedForm { formula: FilmFormula::PanHamrock, squeeze: false };
        let f = model.solve(&input, None).unwrap();
        // Johnson–Greenwood–Poon: the asperities carry the load-sharing pressure at the fluid
        // part's central film over the Hertz area (the fixed point, to the bisection's 1e-12).
        let expect = rough.load_sharing_pressure(f.central_film, input.contact_modulus).0 * f.contact_area;
        assert!((f.asperity.load - expect).abs() < 1e-6 * expect && expect > 0.0, "{} vs {expect}", f.asperity.load);
        assert_eq!(f.model, FilmModelId::PanHamrockMixed);
        let tr = model.traction(&f, &input, 0.01);
        assert!((tr.force - tr.viscous - 0.12 * f.asperity.load).abs() < 1e-9);
        assert_eq!(tr.stick_limit, 0.12 * f.asperity.load);
        assert!((f.lambda.unwrap() - f.min_film / 0.3e-6).abs() < 1e-12);
    }

    #[test]
    fn seed003_squeeze_thickens_an_approaching_film() {
        let lub = oil();
        let rough = Roughness { sigma: 0.0, eta_beta_sigma: 0.04, sigma_over_beta: 0.001, plastic_limit: f64::INFINITY, curve: None };
        let law = TractionLaw { rheology: Rheology::Newtonian, limiting_shear_coefficient: None };
        let asp = AsperityFriction { coefficient: 0.1, model: AsperityModel::Coulomb, map: None };
        let mut input = seed001_nose(&lub, &rough, &law, &asp);
        input.load = 2000.0;
        let model = ClosedForm { formula: FilmFormula::Seed003, squeeze: true };
        let first = model.solve(&input, None).unwrap();
        // Next instant: slower entrainment → thinner steady film, i.e. approach (ḣ < 0).
        let next = ContactInput { entrainment_velocity: 3.5, time_step: 1e-4, ..input };
        let with = model.solve(&next, Some(&first)).unwrap();
        let without = ClosedForm { squeeze: false, ..model }.solve(&next, Some(&first)).unwrap();
        assert!(with.central_film > without.central_film);
        assert_eq!(with.steady_central_film, without.central_film);
    }
}
