use tribod::jobs::{registry, Limits};
use tribod::physics::Silent;

fn run(path: &str) -> serde_json::Value {
    let text = std::fs::read_to_string(path).unwrap();
    let v: serde_json::Value = serde_json::from_str(&text).unwrap();
    let k = registry::find(v["kind"].as_str().unwrap()).unwrap();
    let t = std::time::Instant::now();
    let out = k.prepare(&v["spec"], &Limits::default()).unwrap().run(&Silent).unwrap();
    println!("{path}: {:?}", t.elapsed());
    out
}

#[test]
fn debug_seed000() {
    for p in ["examples/seed000_roller_steady.json", "examples/seed000_roller_startup.json"] {
        let out = run(p);
        println!("{}", serde_json::to_string_pretty(&out["summary"]).unwrap());
        println!("{}", serde_json::to_string(&out["convergence"]).unwrap());
        let s = &out["series"];
        for i in (0..40).chain((40..720).step_by(20)) {
            println!("{:6.1} F={:7.1} uc={:6.3} srr={:9.5} mu={:8.5} hc={:8.3e} om={:8.3} pin={:8.4}",
                s["angle_deg"][i], s["contact_load"][i], s["cam_surface_velocity"][i].as_f64().unwrap(),
                s["slide_roll_ratio"][i].as_f64().unwrap(), s["friction_coefficient"][i].as_f64().unwrap(),
                s["film_central"][i].as_f64().unwrap(), s["roller_speed"][i].as_f64().unwrap(), s["pin_torque"][i].as_f64().unwrap());
        }
    }
}
