//! Stability of the cam kinds over wide inputs (issue 4 item 14): every case converges to a
//! finite result or fails with a typed error — never a panic, never NaN.
//! Run: `cargo test --test cam_stability`.

use proptest::prelude::*;
use serde_json::{json, Value};
use tribod::jobs::{registry, Limits};
use tribod::physics::ehl::EhlOptions;
use tribod::physics::film::{Auto, ClosedForm, ContactInput, ContactShape, FilmFormula, FilmModel, FilmSolution, Numerical};
use tribod::physics::friction::{AsperityFriction, AsperityModel, Rheology, Roughness, TractionLaw};
use tribod::physics::lubricant::{DensityModel, Lubricant, ViscosityModel};
use tribod::physics::{Silent, SolveError};

/// Run a spec; `Ok(true)` on success, `Ok(false)` on a typed refusal; `Err` on anything that
/// must never happen (non-finite numbers, unexpected error kinds).
fn outcome(kind: &str, spec: &Value) -> Result<bool, String> {
    let r = outcome_inner(kind, spec);
    if std::env::var("CAM_STABILITY_VERBOSE").is_ok() {
        eprintln!("{kind}: {r:?}");
    }
    r
}

fn outcome_inner(kind: &str, spec: &Value) -> Result<bool, String> {
    let k = registry::find(kind).unwrap();
    let prepared = match k.prepare(spec, &Limits::default()) {
        Ok(p) => p,
        Err(p) => {
            if std::env::var("CAM_STABILITY_VERBOSE").is_ok() {
                eprintln!("  spec refused: {p}");
            }
            return if p.code == "invalid_spec" || p.code == "limit_exceeded" { Ok(false) } else { Err(format!("{p}")) };
        }
    };
    match prepared.run(&Silent) {
        Ok(v) => {
            check_finite(&v)?;
            Ok(true)
        }
        Err(e @ (SolveError::Physical { .. } | SolveError::InvalidInput { .. } | SolveError::NotConverged { .. })) => {
            if std::env::var("CAM_STABILITY_VERBOSE").is_ok() {
                eprintln!("  refused: {e}");
            }
            Ok(false)
        }
        Err(e) => Err(format!("{e}")),
    }
}

fn check_finite(v: &Value) -> Result<(), String> {
    match v {
        Value::Null => Err("null (non-finite) in result".into()),
        Value::Number(n) if !n.as_f64().is_some_and(f64::is_finite) => Err("non-finite number".into()),
        // A numeric column may hold `null` where the quantity was not computed at that index
        // (the pressure spike of a step solved in closed form); every number must be finite.
        Value::Array(a) if a.iter().all(|x| x.is_null() || x.is_number()) => {
            a.iter().filter(|x| !x.is_null()).try_for_each(check_finite)
        }
        Value::Array(a) => a.iter().try_for_each(check_finite),
        Value::Object(m) => m.values().try_for_each(check_finite),
        _ => Ok(()),
    }
}

fn law() -> impl Strategy<Value = &'static str> {
    prop_oneof![Just("cycloidal"), Just("polynomial_345"), Just("polynomial_4567"), Just("simple_harmonic")]
}

fn follower() -> impl Strategy<Value = Value> {
    prop_oneof![
        (0.0f64..0.01).prop_map(|off| json!({"type": "flat_faced", "offset": off})),
        (0.003f64..0.05, 0.005f64..0.03, 0.0f64..0.3, prop::bool::ANY, 0.0f64..0.02).prop_map(|(r, len, pin_frac, hydro, mu)| json!({
            "type": "roller", "radius": r, "length": len, "pin_radius": r * (0.2 + pin_frac),
            "pin": if hydro { json!({"model": "hydrodynamic"}) } else { json!({"model": "coefficient", "coefficient": mu}) },
            "offset": 0.0,
        })),
        (0.005f64..0.2).prop_map(|r| json!({"type": "spherical", "radius": r})),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, .. ProptestConfig::default() })]

    /// Laws, tiny to large base circles, lifts, speeds up to separation, loads, viscosities,
    /// roughness, startup or steady: a finite result or a typed error.
    #[test]
    fn cycles_converge_or_fail_cleanly(
        law in law(),
        base in 0.002f64..0.06,
        lift in 0.0005f64..0.02,
        rise in 20.0f64..170.0,
        dwell in 0.0f64..40.0,
        fall in 20.0f64..170.0,
        follower in follower(),
        rpm in 10.0f64..12000.0,
        preload in 10.0f64..3000.0,
        stiffness in 1e3f64..2e5,
        mass in 0.0f64..1.0,
        eta in 1e-4f64..1.0,
        alpha in 0.0f64..4e-8,
        rq in 0.0f64..1e-6,
        startup in prop::bool::ANY,
        formula in prop_oneof![Just("pan_hamrock"), Just("dowson_higginson"), Just("seed003")],
        angles in 64usize..400,
    ) {
        let spec = json!({
            "cam": {"profile": {"type": "rise_return", "base_radius": base, "lift": lift, "rise_deg": rise,
                                "top_dwell_deg": dwell, "return_deg": fall, "law": law},
                    "width": 0.01, "roughness_rq": rq},
            "follower": follower,
            "operation": if startup { json!({"speed_rpm": rpm, "startup": {"rated_angle_deg": 180.0}}) } else { json!({"speed_rpm": rpm}) },
            "load": {"type": "valve_train", "spring_preload": preload, "spring_stiffness": stiffness, "moving_mass": mass},
            "lubricant": {"viscosity": eta, "pressure_viscosity": alpha},
            "film": {"formula": formula, "squeeze": formula == "seed003"},
            "angles": angles,
        });
        if let Err(e) = outcome("cam_cycle", &spec) {
            return Err(TestCaseError::fail(format!("{e}\n{spec}")));
        }
    }

    /// Load spectra from tiny to extreme (1 N – 1 MN) on a roller: finite or typed.
    #[test]
    fn extreme_spectra(scale in 1.0f64..1e6, eta in 1e-3f64..0.5, barus in prop::bool::ANY) {
        let angles: Vec<f64> = (0..36).map(|i| 10.0 * i as f64).collect();
        let load: Vec<f64> = angles.iter().map(|a| scale * (1.2 + (a.to_radians()).sin())).collect();
        let spec = json!({
            "cam": {"profile": {"type": "rise_return", "base_radius": 0.02, "lift": 0.008, "rise_deg": 80.0, "return_deg": 80.0, "law": "polynomial_4567"}},
            "follower": {"type": "roller", "radius": 0.012, "length": 0.012, "pin_radius": 0.005, "pin": {"model": "hydrodynamic"},
                         "crown": {"middle_length": 0.01, "crown_height": 5e-6, "end_radius": 0.01}},
            "operation": {"speed_rpm": 1500.0},
            "load": {"type": "spectrum", "angle_deg": angles, "load": load},
            "lubricant": {"viscosity": eta, "pressure_viscosity": 2.2e-8, "viscosity_model": if barus { "barus" } else { "roelands" }},
            "angles": 180,
        });
        if let Err(e) = outcome("cam_cycle", &spec) {
            return Err(TestCaseError::fail(format!("{e}\n{spec}")));
        }
    }

    /// Point analyses across loads, speeds (down to near zero), viscosities and pin friction.
    #[test]
    fn point_analyses(load in 10.0f64..1e5, uc in 1e-4f64..20.0, eta in 1e-4f64..1.0, mu in 0.0f64..0.3, rq in 0.0f64..1e-6, law in 0usize..3, dx_gs in 1e-9f64..1e-6) {
        let asperities = match law {
            0 => json!({"model": "coulomb"}),
            1 => json!({"model": "carter"}),
            _ => json!({"model": "micro_slip", "gross_sliding_displacement": dx_gs}),
        };
        let spec = json!({
            "load": load, "reduced_radius": 0.01, "cam_surface_velocity": uc, "contact_length": 0.02,
            "roller": {"radius": 0.018, "pin_radius": 0.009, "inertia": 2.5e-5, "angular_acceleration": 500.0},
            "pin_friction": [mu, 0.5 * mu],
            "cam": {"roughness_rq": rq}, "follower": {"roughness_rq": rq},
            "lubricant": {"viscosity": eta, "pressure_viscosity": 2e-8},
            "asperities": asperities,
        });
        if let Err(e) = outcome("cam_point", &spec) {
            return Err(TestCaseError::fail(format!("{e}\n{spec}")));
        }
    }

    /// The closed-form film model itself: p0 from 0.01 to 5 GPa, entrainment down to zero and
    /// reversed, any formula: finite film, traction and slope.
    #[test]
    fn closed_form_film_is_finite(
        w in 1e2f64..1e8,
        r in 1e-4f64..0.5,
        ue in -20.0f64..20.0,
        us in -20.0f64..20.0,
        eta in 1e-4f64..2.0,
        alpha in 0.0f64..5e-8,
        sigma in 0.0f64..2e-6,
        formula in prop_oneof![Just(FilmFormula::PanHamrock), Just(FilmFormula::DowsonHigginson), Just(FilmFormula::Seed003)],
        newtonian in prop::bool::ANY,
    ) {
        let lub = Lubricant { viscosity: eta, pressure_viscosity: alpha, temperature_viscosity: 0.0, reference_temperature: 313.0,
                              density: 870.0, viscosity_model: ViscosityModel::Roelands, density_model: DensityModel::DowsonHigginson };
        let rough = Roughness { sigma, eta_beta_sigma: 0.05, sigma_over_beta: 0.001, plastic_limit: f64::INFINITY, curve: None };
        let law = TractionLaw { rheology: if newtonian { Rheology::Newtonian } else { Rheology::Eyring { tau0: 5e6 } }, limiting_shear_coefficient: None };
        let asp = AsperityFriction { coefficient: 0.1, model: AsperityModel::Carter, map: None };
        let input = ContactInput {
            load: w * 0.01, shape: ContactShape::Line { reduced_radius: r, length: 0.01 }, entrainment_velocity: ue,
            sliding_velocity: us, time: 0.0, time_step: 1e-4, contact_modulus: 1.15e11, temperature: 313.0,
            lubricant: &lub, roughness: &rough, traction_law: &law, asperity_friction: &asp, interrupts: tribod::physics::Interrupts::NONE,
        };
        let model = ClosedForm { formula, squeeze: formula == FilmFormula::Seed003 };
        match model.solve(&input, None) {
            Ok(f) => {
                prop_assert!(f.central_film.is_finite() && f.central_film >= 0.0);
                prop_assert!(f.min_film.is_finite() && f.min_film >= 0.0);
                prop_assert!(f.asperity.load <= input.load * (1.0 + 1e-12));
                let again = model.solve(&input, Some(&f)).unwrap();
                prop_assert!(again.central_film.is_finite());
                let t = model.traction(&f, &input, us);
                prop_assert!(t.force.is_finite() && t.slope.is_finite() && t.slope >= 0.0);
                // Sliding adds traction in its own direction on top of the film's rolling
                // (Poiseuille) resistance at zero sliding, which opposes the entrainment.
                let rolling = model.traction(&f, &input, 0.0).force;
                prop_assert!((t.force - rolling) * us >= 0.0);
                prop_assert!(rolling * ue <= 0.0 && rolling.is_finite());
            }
            Err(SolveError::Physical { .. }) | Err(SolveError::NonFinite { .. }) => {
                // NonFinite is a typed refusal at the chokepoint (e.g. Barus-like overflow):
                // allowed here because it names the quantity; the job layer maps it to an error.
            }
            Err(e) => prop_assert!(false, "{e}"),
        }
    }
}

// ------------------------------------------------------------------ accurate and auto (issue 5)

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, .. ProptestConfig::default() })]

    /// Cycles at fidelity `accurate` or `auto` (numerical EHL with squeeze between angles, coarse
    /// grids to bound the run time): a finite result or a typed error (`not_converged` included).
    #[test]
    fn numerical_cycles_converge_or_fail_cleanly(
        law in law(),
        base in 0.005f64..0.04,
        lift in 0.001f64..0.012,
        rise in 40.0f64..150.0,
        fall in 40.0f64..150.0,
        follower in follower(),
        rpm in 50.0f64..8000.0,
        preload in 50.0f64..3000.0,
        eta in 1e-3f64..0.5,
        alpha in 0.0f64..3e-8,
        rq in 0.0f64..5e-7,
        startup in prop::bool::ANY,
        auto in prop::bool::ANY,
        nodes in 48usize..96,
        angles in 32usize..72,
    ) {
        let spec = json!({
            "cam": {"profile": {"type": "rise_return", "base_radius": base, "lift": lift, "rise_deg": rise,
                                "return_deg": fall, "law": law},
                    "width": 0.01, "roughness_rq": rq},
            "follower": follower,
            "operation": if startup { json!({"speed_rpm": rpm, "startup": {"rated_angle_deg": 180.0}}) } else { json!({"speed_rpm": rpm}) },
            "load": {"type": "valve_train", "spring_preload": preload, "spring_stiffness": 3e4, "moving_mass": 0.1},
            "lubricant": {"viscosity": eta, "pressure_viscosity": alpha},
            "fidelity": if auto { "auto" } else { "accurate" },
            "ehl": {"nodes": nodes, "tolerance": 1e-6, "auto_tolerance": 0.1},
            "slip": {"max_cycles": 6},
            "angles": angles,
        });
        if let Err(e) = outcome("cam_cycle", &spec) {
            return Err(TestCaseError::fail(format!("{e}\n{spec}")));
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, .. ProptestConfig::default() })]

    /// The numerical and auto film models over p0 ≈ 0.1–3 GPa, entrainment down to near zero and
    /// reversing within a four-step transient, viscosities and radii over their ranges: each step
    /// converges (positive film, non-negative pressure, finite traction nodes and traction) or
    /// fails with a typed error; never NaN.
    #[test]
    fn numerical_film_steps_are_finite_or_typed(
        p0 in 0.1e9f64..3e9,
        r in 2e-3f64..0.05,
        u0 in -10.0f64..10.0,
        du in -12.0f64..12.0,
        eta in 1e-3f64..1.0,
        alpha in 0.0f64..3e-8,
        sigma in 0.0f64..5e-7,
        dt in 1e-6f64..1e-3,
        auto in prop::bool::ANY,
        barus in prop::bool::ANY,
    ) {
        let es = 1.15e11;
        // Load per length for p0: w = π R p0² / E*.
        let w = std::f64::consts::PI * r * p0 * p0 / es;
        let lub = Lubricant { viscosity: eta, pressure_viscosity: alpha, temperature_viscosity: 0.0, reference_temperature: 313.0,
                              density: 870.0, viscosity_model: if barus { ViscosityModel::Barus } else { ViscosityModel::Roelands },
                              density_model: DensityModel::DowsonHigginson };
        let rough = Roughness { sigma, eta_beta_sigma: 0.05, sigma_over_beta: 0.001, plastic_limit: f64::INFINITY, curve: None };
        let law = TractionLaw { rheology: Rheology::Eyring { tau0: 5e6 }, limiting_shear_coefficient: None };
        let asp = AsperityFriction { coefficient: 0.1, model: AsperityModel::Coulomb, map: None };
        let fast = ClosedForm { formula: FilmFormula::PanHamrock, squeeze: false };
        let numerical = Numerical::new(EhlOptions { nodes: 64, tolerance: 1e-6, ..EhlOptions::default() }, fast);
        let model: Box<dyn FilmModel> = if auto { Box::new(Auto { fast, numerical, tolerance: 0.05, thermal: None }) } else { Box::new(numerical) };
        let mut prev: Option<FilmSolution> = None;
        for k in 0..4 {
            // Entrainment sweeps linearly from u0 to u0 + du: crosses zero for many cases.
            let u = u0 + du * k as f64 / 3.0;
            let input = ContactInput {
                load: w * 0.01, shape: ContactShape::Line { reduced_radius: r, length: 0.01 }, entrainment_velocity: u,
                sliding_velocity: 0.1 * u, time: k as f64 * dt, time_step: if k == 0 { 0.0 } else { dt }, contact_modulus: es,
                temperature: 313.0, lubricant: &lub, roughness: &rough, traction_law: &law, asperity_friction: &asp, interrupts: tribod::physics::Interrupts::NONE,
            };
            match model.solve(&input, prev.as_ref()) {
                Ok(f) => {
                    prop_assert!(f.central_film.is_finite() && f.central_film >= 0.0, "{f:?}");
                    prop_assert!(f.min_film.is_finite() && f.min_film >= 0.0);
                    if let Some(p) = &f.profile {
                        prop_assert!(p.film.iter().all(|h| h.is_finite() && *h > 0.0));
                        prop_assert!(p.pressure.iter().all(|p| p.is_finite() && *p >= 0.0));
                        prop_assert!(f.nodes.iter().all(|n| n.area >= 0.0 && n.film > 0.0 && n.viscosity.is_finite()));
                    }
                    let t = model.traction(&f, &input, 0.1 * u);
                    prop_assert!(t.force.is_finite() && t.slope.is_finite() && t.slope >= 0.0);
                    prev = Some(f);
                }
                Err(SolveError::Physical { .. } | SolveError::NotConverged { .. } | SolveError::NonFinite { .. } | SolveError::InvalidInput { .. }) => break,
                Err(e) => prop_assert!(false, "{e}"),
            }
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 24, .. ProptestConfig::default() })]

    /// The mixed `cam_point` at fidelity `accurate` (issue 15 item 7): λ = h_min/σ from 0.1 to
    /// 10 (σ set from the smooth film of the same point), p0 ≈ 0.5–2 GPa, cam speeds 0.2–10 m/s,
    /// the three asperity laws (micro-slip with a two-row map along the contact): a finite result
    /// whose SRR grows with the pin friction, or a typed error.
    #[test]
    fn accurate_mixed_point_analyses(
        p0 in 0.5e9f64..2e9,
        uc in 0.2f64..10.0,
        lambda in (0.1f64).ln()..(10f64).ln(),
        law in 0usize..3,
        d0 in 10e-9f64..200e-9,
        n0 in 2.0f64..6.0,
    ) {
        let (r, len, es) = (0.0105, 0.02, 200e9 / (2.0 * 0.91));
        let load = std::f64::consts::PI * r * p0 * p0 / es * len;
        let base = json!({
            "load": load, "reduced_radius": r, "cam_surface_velocity": uc, "contact_length": len,
            "roller": {"radius": 0.018, "pin_radius": 0.009},
            "pin_friction": [0.002, 0.02],
            "cam": {"material": {"youngs_modulus": 200e9}}, "follower": {"material": {"youngs_modulus": 200e9}},
            "lubricant": {"viscosity": 0.013, "pressure_viscosity": 1.84e-8},
            "fidelity": "accurate", "ehl": {"nodes": 96},
        });
        let smooth = registry::find("cam_point").unwrap().prepare(&base, &Limits::default()).unwrap().run(&Silent);
        let Ok(smooth) = smooth else { return Ok(()) };
        let hmin = smooth["summary"]["film_min"].as_f64().unwrap();
        let rq = hmin / lambda.exp() / 2f64.sqrt();
        let mut spec = base.clone();
        spec["cam"]["roughness_rq"] = json!(rq);
        spec["follower"]["roughness_rq"] = json!(rq);
        spec["asperities"] = match law {
            0 => json!({"model": "coulomb", "plastic_limit": 6e9}),
            1 => json!({"model": "carter", "plastic_limit": 6e9}),
            _ => json!({"model": "micro_slip", "plastic_limit": 6e9, "micro_slip_map": {
                "film": [0.5 * hmin, 2.0 * hmin], "gross_sliding_displacement": [d0, 0.5 * d0], "exponent": [n0, 2.0]}}),
        };
        let prepared = registry::find("cam_point").unwrap().prepare(&spec, &Limits::default());
        let prepared = match prepared {
            Ok(p) => p,
            Err(p) => return Err(TestCaseError::fail(format!("refused: {p}\n{spec}"))),
        };
        match prepared.run(&Silent) {
            Ok(out) => {
                check_finite(&out).map_err(|e| TestCaseError::fail(format!("{e}\n{spec}")))?;
                let srr: Vec<f64> = out["rows"].as_array().unwrap().iter().map(|r| r["slide_roll_ratio"].as_f64().unwrap()).collect();
                prop_assert!(srr[1] >= srr[0], "{srr:?}\n{spec}");
                let fa = out["summary"]["asperity_load_fraction"].as_f64().unwrap();
                prop_assert!((0.0..1.0).contains(&fa), "{fa}");
            }
            Err(SolveError::Physical { .. } | SolveError::InvalidInput { .. } | SolveError::NotConverged { .. }) => {}
            Err(e) => return Err(TestCaseError::fail(format!("{e}\n{spec}"))),
        }
    }
}
