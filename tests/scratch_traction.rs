use tribod::physics::ehl::EhlOptions;
use tribod::physics::film::*;
use tribod::physics::friction::*;
use tribod::physics::lubricant::Lubricant;
const ES: f64 = 210e9 / 0.91 / 2.0;
#[test]
fn traction_map() {
    let r = 0.015;
    let alpha = 2.2e-8;
    let len = 0.012;
    let rough = Roughness { sigma: 0.0, eta_beta_sigma: 0.04, sigma_over_beta: 0.001 };
    let asp = AsperityFriction { coefficient: 0.1, model: AsperityModel::Coulomb };
    let fast = ClosedForm { formula: FilmFormula::PanHamrock, squeeze: false };
    let num = Numerical { options: EhlOptions { nodes: 256, tolerance: 1e-8, ..Default::default() }, fallback: fast };
    for tau0 in [5e6, 1e9] {
    let law = TractionLaw { rheology: if tau0 < 1e8 { Rheology::Eyring { tau0 } } else { Rheology::Newtonian }, limiting_shear_coefficient: None };
    for l in [4.0, 10.0, 20.0] {
        for m in [0.5, 1.0, 2.0, 5.0, 10.0, 30.0, 100.0, 300.0] {
            let g = alpha * 2.0 * ES;
            let u_sum = (l / g).powi(4);
            let wd = m * u_sum.sqrt();
            let w = wd * 2.0 * ES * r;
            let eta0 = 0.05;
            let u = 0.5 * u_sum * 2.0 * ES * r / eta0;
            let lub = Lubricant { viscosity: eta0, pressure_viscosity: alpha, ..Lubricant::SEED000 };
            let input = ContactInput { load: w * len, shape: ContactShape::Line { reduced_radius: r, length: len }, entrainment_velocity: u, sliding_velocity: 0.0, time: 0.0, time_step: 0.0, contact_modulus: ES, temperature: lub.reference_temperature, lubricant: &lub, roughness: &rough, traction_law: &law, asperity_friction: &asp };
            let a = fast.solve(&input, None).unwrap();
            let b = match num.solve(&input, None) { Ok(b) => b, Err(e) => { println!("{e}"); continue } };
            let mut line = format!("tau0 {tau0:.0e} L {l:4.1} M {m:6.1} ph {:.2}GPa pmax/ph {:.3}:", a.max_pressure/1e9, b.max_pressure/a.max_pressure);
            for srr in [1e-4, 1e-3, 1e-2, 0.1, 0.5] {
                let us = srr * u;
                let ta = fast.traction(&a, &input, us).viscous;
                let tb = num.traction(&b, &input, us).viscous;
                let x = lub.viscosity_at(a.max_pressure, lub.reference_temperature) * us / (a.central_film * tau0);
                line += &format!(" [srr {srr:.0e} x {x:.1e} mu {:.4} err {:+.0}%]", tb/(w*len), 100.0*(ta/tb-1.0));
            }
            println!("{line}");
        }
    }
    }
}
