use tribod::physics::journal::*;
use tribod::physics::Silent;
#[test]
fn dbg() {
    for (nt, nz) in [(181, 91), (361, 181)] {
    let s = Settings { circumferential: nt, axial: nz, ..Settings::default() };
    let b = Bearing::plain(1.0);
    for e in [0.1, 0.2, 0.4, 0.6, 0.8, 0.9, 0.97] {
        let a = analyse(&b, &Operating::Eccentricity(e), &s, None, None, false, &Silent).unwrap();
        eprintln!("{nt} eps {e}: S {:.5} att {:.2} f {:.4} Q {:.4} Qs/Q {:.4} Pavg/pmax {:.4}", a.sommerfeld.unwrap(), a.attitude.to_degrees(), a.friction_variable.unwrap(), a.flow_variable, a.side_flow_ratio.unwrap(), a.load / 2.0 / a.max_pressure);
    }
    }
}
