//! Stability of the `wear` kind (issue 6 item 8): over wear coefficients, loads, speeds and
//! durations the run completes, reaches its wear limit, or ends on a typed reason with the history
//! up to the last valid profile — never a NaN, never an untyped failure. Fidelity accurate and
//! auto (the numerical EHL film at every angle) on coarse grids: the same, or a typed solver error.
//! Run: `cargo test --test wear_stability` (CI fixes `PROPTEST_RNG_SEED`).

use crate::common::wear_spec;
use proptest::prelude::*;
use serde_json::{json, Value};
use tribod::jobs::{registry, Limits};
use tribod::physics::{Silent, SolveError};

fn run(spec: &Value) -> Result<Value, SolveError> {
    let k = registry::find("wear").unwrap();
    let prepared = k.prepare(spec, &Limits::default()).unwrap_or_else(|p| panic!("spec refused: {p:?}\n{spec}"));
    prepared.run(&Silent)
}

#[allow(clippy::too_many_arguments)]
fn spec(roller: bool, k: f64, preload: f64, stiffness: f64, mass: f64, rpm: f64, hours: f64, updates: f64, full: bool, limit: Option<f64>) -> Value {
    let follower = if roller {
        json!({"type": "roller", "radius": 0.012, "length": 0.012, "pin_radius": 0.005, "pin": {"model": "coefficient", "coefficient": 0.05}, "roughness_rq": 2e-7})
    } else {
        json!({"type": "flat_faced", "roughness_rq": 2e-7})
    };
    let mut s = wear_spec(json!({
        "cam": {"profile": {"type": "rise_return", "base_radius": 0.018, "lift": 0.008, "rise_start_deg": 90.0,
                            "rise_deg": 100.0, "return_deg": 100.0, "law": "polynomial_345"},
                "width": 0.012, "roughness_rq": 3e-7},
        "follower": follower,
        "operation": {"speed_rpm": rpm},
        "load": {"type": "valve_train", "spring_preload": preload, "spring_stiffness": stiffness, "moving_mass": mass},
        "lubricant": {"viscosity": 0.008, "pressure_viscosity": 2e-8},
        "load_share": if full { "full" } else { "asperity" },
        "wear_coefficient": {"dimensionless": k, "hardness": 7e9},
        "hours": hours,
        "update_interval_hours": hours / updates,
        "angles": 180,
        "snapshots": 3
    }));
    if let Some(l) = limit {
        s["wear_limit"] = json!(l);
    }
    s
}

fn nums(v: &Value) -> Vec<f64> {
    v.as_array().unwrap().iter().map(|x| x.as_f64().unwrap()).collect()
}

/// Checks one run; returns its output when it ran.
fn check(spec: &Value, hours: f64, limit: Option<f64>) -> Result<Option<Value>, TestCaseError> {
    let result = run(spec);
    if std::env::var_os("WEAR_STABILITY_VERBOSE").is_some() {
        eprintln!("{}", match &result { Ok(o) => format!("{} {} h, {} updates", o["termination"]["reason"], o["hours"], o["updates"]), Err(e) => format!("error {e}") });
    }
    match result {
        // The unworn pair may be unable to run (separation at this speed): a typed error.
        Err(SolveError::Physical { code, .. }) => {
            prop_assert!(["follower_separation", "cam_undercut", "no_contact_load", "film_collapse"].contains(&code.code()), "{code}");
        }
        Err(SolveError::NotConverged { solver, .. }) => {
            prop_assert!(["periodic roller speed", "ehl line contact (Newton)"].contains(&solver), "{solver}")
        }
        Err(e) => prop_assert!(false, "untyped failure {e:?}"),
        Ok(out) => {
            let copy = out.clone();
            let reason = out["termination"]["reason"].as_str().unwrap().to_string();
            let reached = out["hours"].as_f64().unwrap();
            let depth = nums(&out["series"]["wear_depth"]);
            prop_assert!(depth.iter().all(|d| d.is_finite() && *d >= 0.0));
            let history = out["history"].as_array().unwrap();
            let times: Vec<f64> = history.iter().map(|h| h["hours"].as_f64().unwrap()).collect();
            prop_assert!(times.windows(2).all(|w| w[1] > w[0]), "{times:?}");
            prop_assert!((times.last().unwrap() - reached).abs() <= 1e-9 * hours.max(1.0));
            let vol: Vec<f64> = history.iter().map(|h| h["worn_volume"].as_f64().unwrap()).collect();
            prop_assert!(vol.windows(2).all(|w| w[1] >= w[0]));
            let max_depth = out["summary"]["max_wear_depth"].as_f64().unwrap();
            match reason.as_str() {
                "completed" => prop_assert!((reached - hours).abs() <= 1e-9 * hours),
                "wear_limit" => {
                    prop_assert!((max_depth - limit.unwrap()).abs() <= 1e-9 * limit.unwrap());
                    prop_assert!((out["summary"]["hours_to_limit"].as_f64().unwrap() - reached).abs() < 1e-9 * hours);
                }
                "cam_undercut" | "follower_separation" | "contact_off_face" | "profile_failure" | "update_limit" => {
                    let at = out["termination"]["at_hours"].as_f64().unwrap();
                    prop_assert!(at > reached && reached < hours, "{at} {reached}");
                    prop_assert!(out["termination"]["message"].as_str().is_some_and(|m| !m.is_empty()));
                }
                other => prop_assert!(false, "unknown reason {other}"),
            }
            if let Some(l) = limit {
                prop_assert!(max_depth <= l * (1.0 + 1e-9));
            }
            return Ok(Some(copy));
        }
    }
    Ok(None)
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 24, ..ProptestConfig::default() })]

    #[test]
    fn flat_follower_wear_is_stable(
        log_k in -10.0f64..-6.0,
        preload in 150.0f64..1500.0,
        stiffness in 1e4f64..8e4,
        mass in 0.0f64..0.4,
        rpm in 500.0f64..4000.0,
        log_hours in 0.0f64..3.3,
        updates in 1.0f64..40.0,
        full in any::<bool>(),
        limit in prop::option::of(1e-7f64..5e-5),
    ) {
        let hours = 10f64.powf(log_hours);
        let s = spec(false, 10f64.powf(log_k), preload, stiffness, mass, rpm, hours, updates.floor(), full, limit);
        check(&s, hours, limit)?;
    }

    #[test]
    fn roller_follower_wear_is_stable(
        log_k in -9.0f64..-5.0,
        preload in 200.0f64..1500.0,
        mass in 0.0f64..0.3,
        rpm in 500.0f64..3000.0,
        log_hours in 0.0f64..3.0,
        updates in 1.0f64..20.0,
        full in any::<bool>(),
        limit in prop::option::of(1e-7f64..5e-5),
    ) {
        let hours = 10f64.powf(log_hours);
        let s = spec(true, 10f64.powf(log_k), preload, 3e4, mass, rpm, hours, updates.floor(), full, limit);
        check(&s, hours, limit)?;
    }

    /// Heavy wear near separation: most runs end on a typed reason (separation, the update
    /// limit) with their partial history.
    #[test]
    fn heavy_wear_ends_cleanly(
        log_k in -6.0f64..-4.0,
        preload in 150.0f64..400.0,
        rpm in 2000.0f64..4000.0,
        log_hours in 1.0f64..3.0,
    ) {
        let hours = 10f64.powf(log_hours);
        let s = spec(false, 10f64.powf(log_k), preload, 38000.0, 0.25, rpm, hours, 10.0, true, None);
        check(&s, hours, None)?;
    }

    /// Fidelity accurate/auto on coarse EHL grids (48–96 nodes, 72 angles, 1–3 updates): the
    /// run completes or ends on a typed reason, every film-model count adds up to the cycles run,
    /// nothing is NaN.
    #[test]
    fn accurate_and_auto_wear_is_stable(
        roller in any::<bool>(),
        auto in any::<bool>(),
        log_k in -9.0f64..-5.0,
        preload in 200.0f64..1500.0,
        rpm in 500.0f64..4000.0,
        log_hours in 0.0f64..3.0,
        updates in 1.0f64..3.99,
        nodes in 48usize..96,
        full in any::<bool>(),
        limit in prop::option::of(1e-7f64..5e-5),
    ) {
        let hours = 10f64.powf(log_hours);
        let mut s = spec(roller, 10f64.powf(log_k), preload, 3e4, 0.1, rpm, hours, updates.floor(), full, limit);
        s["cycle"]["fidelity"] = json!(if auto { "auto" } else { "accurate" });
        s["cycle"]["ehl"] = json!({"nodes": nodes});
        s["cycle"]["angles"] = json!(72);
        if let Some(out) = check(&s, hours, limit)? {
            let counted: u64 = out["summary"]["fidelity_used"].as_object().unwrap().values().map(|v| v.as_u64().unwrap()).sum();
            prop_assert_eq!(counted, 72 * (out["updates"].as_u64().unwrap() + 1));
        }
    }
}
