use super::*;
use crate::ehl::twod::Geometry2d;
use crate::geometry::Crown;
use crate::lubricant::Lubricant;
use crate::Silent;

/// Seed 000's roller at the cam nose (`tests/it/ehl_2d.rs::seed000_nose`) with sliding `srr·u_m`.
pub(super) fn nose(srr: f64) -> ThermalFiniteInput {
    let ehl = Ehl2dInput { load: 954.0, geometry: Geometry2d::Finite { rx: 0.01037, crown: Crown::SEED000 }, effective_modulus: 2.1e11, entrainment_velocity: 2.77, lubricant: Lubricant::SEED000, temperature: 313.0 };
    ThermalFiniteInput { ehl, sliding_velocity: srr * 2.77, rheology: Rheology::default(), bodies: ThermalBodies::SEED000 }
}

#[test]
#[ignore]
fn explore_nose() {
    for (nx, ny) in [(65, 129)] {
        let t = std::time::Instant::now();
        let s = solve(&nose(0.02), &Ehl2dOptions { nx, ny, ..Default::default() }, &ThermalOptions::default(), &Silent).unwrap();
        println!("{nx}x{ny}: {:.2} s hc {:.4e} (iso {:?}) hmin {:.4e} pmax {:.4e} edge {:?} Tmax {:?} mu {:.4e} heat {:?} conv {:?}", t.elapsed().as_secs_f64(), s.ehl.central_film, s.isothermal_central_film, s.ehl.min_film.value, s.ehl.max_pressure.value, s.ehl.edge_pressure_peak, s.film_temperature_max, s.traction.friction_coefficient, s.heat, s.convergence);
    }
}

#[test]
#[ignore]
fn explore_symmetry() {
    let inp = nose(0.02);
    let s = crate::ehl::twod::solve(&inp.ehl, &Ehl2dOptions { nx: 33, ny: 65, fields: true, ..Default::default() }, &Silent).unwrap();
    let f = s.fields.unwrap();
    let nx = 33;
    for j in [29usize, 31, 33, 35] {
        let hmin = (0..nx).map(|i| f.film[j * nx + i]).fold(f64::INFINITY, f64::min);
        println!("iso row {j} y {:.4e} hmin {hmin:.6e}", f.y[j]);
    }
}

#[test]
#[ignore]
fn explore_symmetry_pass() {
    let inp = nose(0.02);
    let o = Ehl2dOptions { nx: 33, ny: 65, fields: true, ..Default::default() };
    let s = crate::ehl::twod::solve(&inp.ehl, &o, &Silent).unwrap();
    let pass = energy_pass(&inp, &s, &ThermalOptions::default(), &[]).unwrap();
    let nx = 33;
    let f = &pass.factors;
    let asym = (0..65 * nx).map(|k| (f.poiseuille[k] - f.poiseuille[(64 - k / nx) * nx + k % nx]).abs()).fold(0.0, f64::max);
    println!("factor asymmetry {asym:.3e}");
    let (s2, _) = solve_factored(&inp.ehl, &o, Some(f), None, &mut Kept2d::default(), &Silent).unwrap();
    let g = s2.fields.unwrap();
    let asym = (0..65 * nx).map(|k| (g.film[k] - g.film[(64 - k / nx) * nx + k % nx]).abs()).fold(0.0, f64::max);
    println!("film asymmetry {asym:.3e} conv {:?}", s2.convergence);
    let ones = Factors2d { poiseuille: vec![1.0; f.poiseuille.len()], wedge: vec![1.0; f.poiseuille.len()], ..f.clone() };
    let (s3, _) = solve_factored(&inp.ehl, &o, Some(&ones), None, &mut Kept2d::default(), &Silent).unwrap();
    println!("ones: {:e} vs {:e}; {:e} vs {:e}", s3.central_film, s.central_film, s3.min_film.value, s.min_film.value);
}

#[test]
#[ignore]
fn explore_symmetry_warm() {
    let inp = nose(0.02);
    let o = Ehl2dOptions { nx: 33, ny: 65, fields: true, grid_check: false, ..Default::default() };
    let mut kept = Kept2d::default();
    let (s, w) = solve_factored(&inp.ehl, &o, None, None, &mut kept, &Silent).unwrap();
    let pass = energy_pass(&inp, &s, &ThermalOptions::default(), &[]).unwrap();
    let nx = 33;
    let f = &pass.factors;
    let asym = |g: &crate::ehl::twod::Fields2d| (0..65 * nx).map(|k| (g.film[k] - g.film[(64 - k / nx) * nx + k % nx]).abs()).fold(0.0, f64::max);
    let (s2, _) = solve_factored(&inp.ehl, &o, Some(f), Some(&w), &mut kept.clone(), &Silent).unwrap();
    println!("warm+kept film asymmetry {:.3e} conv {:?} warm {}", asym(s2.fields.as_ref().unwrap()), s2.convergence, s2.warm_started);
    let (s3, _) = solve_factored(&inp.ehl, &o, Some(f), Some(&w), &mut Kept2d::default(), &Silent).unwrap();
    println!("warm film asymmetry {:.3e} conv {:?}", asym(s3.fields.as_ref().unwrap()), s3.convergence);
}
