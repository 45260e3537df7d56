//! Engineering units for axes: a quantity in its SI unit shown in the multiple that suits its
//! values (a film of 2e-7 m in µm, a pressure of 1.2e9 Pa in GPa), as the cam plots do by hand.

/// Multiples of the SI units the results use: (unit, [(factor, label)] from small to large).
const MULTIPLES: &[(&str, &[(f64, &str)])] = &[
    ("m", &[(1e-9, "nm"), (1e-6, "µm"), (1e-3, "mm"), (1.0, "m")]),
    ("Pa", &[(1.0, "Pa"), (1e3, "kPa"), (1e6, "MPa"), (1e9, "GPa")]),
    ("N", &[(1.0, "N"), (1e3, "kN"), (1e6, "MN")]),
    ("W", &[(1e-3, "mW"), (1.0, "W"), (1e3, "kW")]),
    ("N·m", &[(1e-3, "N·mm"), (1.0, "N·m")]),
    ("Pa·s", &[(1e-3, "mPa·s"), (1.0, "Pa·s")]),
    ("m³/s", &[(1e-9, "mm³/s"), (1e-6, "cm³/s"), (1e-3, "L/s"), (1.0, "m³/s")]),
    ("s", &[(1e-6, "µs"), (1e-3, "ms"), (1.0, "s")]),
];

/// The factor that turns SI values of `unit` with largest magnitude `max_abs` into the shown
/// multiple, and the multiple's name (`1` has none).
pub fn multiple(unit: &str, max_abs: f64) -> (f64, String) {
    let Some((_, steps)) = MULTIPLES.iter().find(|(u, _)| *u == unit) else {
        return (1.0, if unit == "1" { String::new() } else { unit.to_string() });
    };
    // The largest multiple that shows the largest value as 0.1 or more for films and pressures
    // as tribologists quote them (0.3 µm, not 300 nm; 0.5 GPa), as 1 or more for the rest
    // (129.7 W, not 0.1297 kW). The dashboard's `multipleFor` does the same.
    let from = if matches!(unit, "m" | "Pa") { 0.1 } else { 1.0 };
    let mut pick = steps[0];
    for s in steps.iter() {
        if max_abs >= from * s.0 {
            pick = *s;
        }
    }
    (1.0 / pick.0, pick.1.to_string())
}

/// An axis of `name` in `unit` over `values`: the factor to multiply values by, and the label
/// (`min_film, µm`; a pure number keeps its name alone).
pub fn axis(name: &str, unit: &str, values: impl Iterator<Item = f64>) -> (f64, String) {
    let max_abs = values.filter(|v| v.is_finite()).fold(0.0f64, |m, v| m.max(v.abs()));
    let (factor, shown) = multiple(unit, max_abs);
    (factor, if shown.is_empty() { name.to_string() } else { format!("{name}, {shown}") })
}
