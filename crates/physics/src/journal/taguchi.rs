//! Taguchi orthogonal arrays, the weighted-sum score of seed 002 eq. (19) with the per-criterion
//! normalisation of its Table 3, main effects and signal-to-noise ratios, and a bounded
//! Nelder–Mead simplex search for the continuous design step.

/// A standard orthogonal array with three columns assigned to three factors. Levels are 0-based.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Array {
    /// L4(2³): three two-level factors.
    L4,
    /// L9(3⁴), columns 1–3: three three-level factors (seed 002 Table 4 row order).
    L9,
    /// L27(3¹³), columns 1, 2, 5: three three-level factors (here the full factorial).
    L27,
}

impl Array {
    pub fn levels(self) -> usize {
        match self {
            Array::L4 => 2,
            Array::L9 | Array::L27 => 3,
        }
    }

    /// Rows of level indices `[a, b, c]` in the standard order.
    pub fn rows(self) -> Vec<[usize; 3]> {
        match self {
            Array::L4 => vec![[0, 0, 0], [0, 1, 1], [1, 0, 1], [1, 1, 0]],
            Array::L9 => vec![
                [0, 0, 0],
                [0, 1, 1],
                [0, 2, 2],
                [1, 0, 1],
                [1, 1, 2],
                [1, 2, 0],
                [2, 0, 2],
                [2, 1, 0],
                [2, 2, 1],
            ],
            Array::L27 => {
                let mut v = Vec::with_capacity(27);
                for a in 0..3 {
                    for b in 0..3 {
                        for c in 0..3 {
                            v.push([a, b, c]);
                        }
                    }
                }
                v
            }
        }
    }
}

/// The three criteria of one design.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Criteria {
    /// Maximum pressure (smaller is better).
    pub pressure: f64,
    /// Minimum film (larger is better).
    pub film: f64,
    /// Friction (smaller is better).
    pub friction: f64,
}

/// Weights of seed 002 eq. (19) (defaults 0.5 film, 0.25 pressure, 0.25 friction).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Weights {
    pub film: f64,
    pub pressure: f64,
    pub friction: f64,
}

/// Normalisation of seed 002 Table 3: each criterion divided by the best value among the runs,
/// oriented so that 1 is the best run: `H/H_best`, `P_best/P`, `f_best/f`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Reference {
    pub best_pressure: f64,
    pub best_film: f64,
    pub best_friction: f64,
}

impl Reference {
    pub fn of(runs: &[Criteria]) -> Reference {
        Reference {
            best_pressure: runs.iter().map(|c| c.pressure).fold(f64::INFINITY, f64::min),
            best_film: runs.iter().map(|c| c.film).fold(0.0, f64::max),
            best_friction: runs.iter().map(|c| c.friction).fold(f64::INFINITY, f64::min),
        }
    }

    /// Normalised criteria `(film, pressure, friction)`.
    pub fn normalise(&self, c: &Criteria) -> (f64, f64, f64) {
        (c.film / self.best_film, self.best_pressure / c.pressure, self.best_friction / c.friction)
    }

    /// Weighted-sum score, seed 002 eq. (19).
    pub fn score(&self, c: &Criteria, w: &Weights) -> f64 {
        let (h, p, f) = self.normalise(c);
        w.film * h + w.pressure * p + w.friction * f
    }
}

/// Larger-the-better signal-to-noise ratio of one value, dB: `−10 log10(1/y²)`.
pub fn sn_larger_better(y: f64) -> f64 {
    20.0 * y.log10()
}

/// Mean of `values` over the runs at each level of factor `f`.
pub fn level_means(rows: &[[usize; 3]], f: usize, levels: usize, values: &[f64]) -> Vec<f64> {
    (0..levels)
        .map(|l| {
            let (mut s, mut n) = (0.0, 0);
            for (r, v) in rows.iter().zip(values) {
                if r[f] == l {
                    s += v;
                    n += 1;
                }
            }
            if n > 0 { s / n as f64 } else { 0.0 }
        })
        .collect()
}

pub use crate::numerics::nelder_mead::{nelder_mead, Minimum};

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn arrays_are_orthogonal() {
        for a in [Array::L4, Array::L9, Array::L27] {
            let rows = a.rows();
            let l = a.levels();
            for f in 0..3 {
                for g in (f + 1)..3 {
                    // every pair of levels appears equally often in every pair of columns
                    let mut count = vec![0; l * l];
                    for r in &rows {
                        count[r[f] * l + r[g]] += 1;
                    }
                    assert!(count.iter().all(|&c| c == count[0] && c > 0), "{a:?} {f} {g}");
                }
            }
        }
        // seed 002 Table 4 order
        assert_eq!(Array::L9.rows()[5], [1, 2, 0]);
        assert_eq!(Array::L9.rows()[8], [2, 2, 1]);
    }

    #[test]
    fn nelder_mead_finds_a_bounded_minimum() {
        let m = nelder_mead::<()>(
            |x| Ok((x[0] - 0.3).powi(2) + 2.0 * (x[1] - 0.7).powi(2)),
            &[0.9, 0.1],
            &[0.2, 0.2],
            &[0.0, 0.0],
            &[1.0, 1.0],
            200,
            1e-12,
        )
        .unwrap();
        assert!((m.x[0] - 0.3).abs() < 1e-4 && (m.x[1] - 0.7).abs() < 1e-4, "{m:?}");
        // the minimum outside the box lands on its face
        let m = nelder_mead::<()>(|x| Ok((x[0] + 1.0).powi(2) + x[1].powi(2)), &[0.5, 0.5], &[0.2, 0.2], &[0.0, -1.0], &[1.0, 1.0], 200, 1e-12).unwrap();
        assert!(m.x[0].abs() < 1e-6 && m.x[1].abs() < 1e-3, "{m:?}");
    }

    #[test]
    fn score_is_one_for_a_run_best_in_everything() {
        let runs = [
            Criteria { pressure: 1.0, film: 0.2, friction: 2.0 },
            Criteria { pressure: 2.0, film: 0.1, friction: 4.0 },
        ];
        let r = Reference::of(&runs);
        let w = Weights { film: 0.5, pressure: 0.25, friction: 0.25 };
        assert!((r.score(&runs[0], &w) - 1.0).abs() < 1e-15);
        assert!((r.score(&runs[1], &w) - 0.5).abs() < 1e-15);
    }
}
