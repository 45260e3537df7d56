use tribod::physics::journal::*;
use tribod::physics::Silent;
#[repr(C)]
struct Timespec { tv_sec: i64, tv_nsec: i64 }
unsafe extern "C" { fn clock_gettime(clock: i32, ts: *mut Timespec) -> i32; }
fn cpu() -> f64 { let mut ts = Timespec { tv_sec: 0, tv_nsec: 0 }; unsafe { clock_gettime(3, &mut ts) }; ts.tv_sec as f64 + ts.tv_nsec as f64 * 1e-9 }
#[test]
fn dbg() {
    let b = Bearing { misalignment: Misalignment { vertical: 0.56, horizontal: 0.56 }, profile: Some(Profile { order: 2, height: 0.4, length_fraction: 0.2 }), ..Bearing::plain(1.25) };
    let w = 0.5570256;
    for tol in [1e-8, 1e-7, 1e-6] {
        for sw in [1, 2] {
            let s = Settings { circumferential: 361, axial: 181, pressure_tolerance: tol, ..Settings::default() };
            let mut best = f64::INFINITY; let mut res = None; let mut cyc = vec![];
            for _ in 0..6 {
                let mut ws = Workspace::new(&b, &s);
                ws.set_smoothing_sweeps(sw);
                let c = cpu();
                let a = analyse(&b, &Operating::Load(w), &s, Some(&mut ws), None, false, &Silent).unwrap();
                best = best.min(cpu() - c);
                res = Some(a); cyc = ws.cycles();
            }
            let a = res.unwrap();
            eprintln!("tol {tol:e} sweeps {sw}: {:.1} ms P0 {:.7} H0 {:.7} f {:.7} cycles {cyc:?}", best*1e3, a.max_pressure, a.min_film, a.friction_variable.unwrap());
        }
    }
}
