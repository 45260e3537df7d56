//! The result document of a search: the baseline and best reports, the designs table with its
//! columns and units, and the Pareto front.

use super::evaluate::{self as ev, constraint_label, label_of, Judged, Measured, Outcome};
use super::result::{CamOptimisationResult, ConstraintOutcome, Pareto, Report};
use super::search::{judge_all, rank, Record, Searched};
use super::spec::{CamOptimisationSpec, Goal};
use crate::jobs::units::unit_at;
use crate::physics::SolveError;
use serde_json::{json, Map, Value};
use std::collections::BTreeMap;

/// The report of design `i` (0-based), measured as `m` and judged `j`.
fn report(spec: &CamOptimisationSpec, i: usize, m: &Measured, j: &Judged) -> Report {
    let mut variables = Map::new();
    for (v, x) in spec.variables.iter().zip(&m.values) {
        if !x.is_null() {
            variables.insert(v.path.clone(), x.clone());
        }
    }
    let mut objectives = Map::new();
    for (o, x) in spec.objectives.iter().zip(&m.objectives) {
        if let Some(x) = x {
            objectives.insert(label_of(&o.quantity), json!(x));
        }
    }
    let constraints = spec
        .constraints
        .iter()
        .zip(&m.constraints)
        .zip(&j.margins)
        .map(|((c, value), (limit, sense, margin, ok))| {
            let pointer = ev::pointer_of(&c.quantity);
            ConstraintOutcome {
                name: constraint_label(c),
                unit: unit_at(ev::units_of(&c.quantity), &pointer).unwrap_or("1").to_string(),
                pointer,
                value: *value,
                limit: *limit,
                bound: if *sense > 0.0 { "min".into() } else { "max".into() },
                margin: *margin,
                satisfied: *ok,
            }
        })
        .collect();
    Report {
        design: i + 1,
        feasible: j.feasible,
        score: j.score,
        variables,
        friction_power: m.friction_power,
        objectives,
        constraints,
        spec: m.spec.clone(),
        cycle: m.summary.clone(),
    }
}

/// The designs table's columns and their units.
fn columns(spec: &CamOptimisationSpec) -> (Vec<String>, BTreeMap<String, String>) {
    let spec_units = ev::cycle_kind().spec_units();
    let mut cols: Vec<String> = ["design", "phase", "status", "feasible", "score"].map(String::from).to_vec();
    let mut out = BTreeMap::new();
    out.insert("score".to_string(), "1".to_string());
    for v in &spec.variables {
        let name = label_of(&v.path);
        if let Some(u) = unit_at(spec_units, &v.path) {
            out.insert(name.clone(), u.to_string());
        }
        cols.push(name);
    }
    for o in &spec.objectives {
        let name = label_of(&o.quantity);
        if let Some(u) = unit_at(ev::units_of(&o.quantity), &ev::pointer_of(&o.quantity)) {
            out.insert(name.clone(), u.to_string());
        }
        if !cols.contains(&name) {
            cols.push(name);
        }
    }
    for c in &spec.constraints {
        let name = constraint_label(c);
        if let Some(u) = unit_at(ev::units_of(&c.quantity), &ev::pointer_of(&c.quantity)) {
            out.insert(name.clone(), u.to_string());
            out.insert(format!("{name}.margin"), u.to_string());
        }
        if !cols.contains(&name) {
            cols.push(name.clone());
        }
        cols.push(format!("{name}.margin"));
    }
    cols.push("error_code".into());
    (cols, out)
}

/// One row of the designs table.
fn row(spec: &CamOptimisationSpec, i: usize, r: &Record, j: Option<&Judged>) -> Map<String, Value> {
    let mut row = Map::new();
    row.insert("design".into(), json!(i + 1));
    row.insert("phase".into(), json!(r.phase.name()));
    let values = match &r.outcome {
        Outcome::Measured(m) => &m.values,
        Outcome::Failed { values, .. } => values,
    };
    for (v, x) in spec.variables.iter().zip(values) {
        if !x.is_null() {
            row.insert(label_of(&v.path), x.clone());
        }
    }
    match (&r.outcome, j) {
        (Outcome::Measured(m), Some(j)) => {
            // A cam that undercuts: its cycle refused, the design measured from its profile.
            let undercut = m.summary["undercut"] == true;
            row.insert("status".into(), json!(if undercut { "undercut" } else { "succeeded" }));
            if undercut {
                row.insert("error_code".into(), json!("cam_undercut"));
            }
            row.insert("feasible".into(), json!(j.feasible));
            row.insert("score".into(), json!(j.score));
            for (o, x) in spec.objectives.iter().zip(&m.objectives) {
                if let Some(x) = x {
                    row.insert(label_of(&o.quantity), json!(x));
                }
            }
            for ((c, x), (_, _, margin, _)) in spec.constraints.iter().zip(&m.constraints).zip(&j.margins) {
                let name = constraint_label(c);
                if let Some(x) = x {
                    row.insert(name.clone(), json!(x));
                }
                if let Some(g) = margin {
                    row.insert(format!("{name}.margin"), json!(g));
                }
            }
        }
        (Outcome::Failed { code, detail, .. }, _) => {
            row.insert("status".into(), json!("failed"));
            row.insert("feasible".into(), json!(false));
            row.insert("error_code".into(), json!(code));
            row.insert("error".into(), json!(detail));
        }
        _ => {}
    }
    row
}

/// The non-dominated feasible designs of the first two objectives, by the first.
fn pareto(spec: &CamOptimisationSpec, records: &[Record], judged: &[Option<Judged>]) -> Option<Pareto> {
    if spec.objectives.len() < 2 {
        return None;
    }
    let sign = |k: usize| if spec.objectives[k].goal == Goal::Maximise { -1.0 } else { 1.0 };
    let mut pts: Vec<(usize, f64, f64)> = Vec::new();
    for (i, (r, j)) in records.iter().zip(judged).enumerate() {
        let (Outcome::Measured(m), Some(j)) = (&r.outcome, j) else { continue };
        if let (true, Some(a), Some(b)) = (j.feasible, m.objectives[0], m.objectives[1]) {
            pts.push((i, a, b));
        }
    }
    let dominated = |p: &(usize, f64, f64)| {
        pts.iter().any(|q| {
            let (qa, qb, pa, pb) = (sign(0) * q.1, sign(1) * q.2, sign(0) * p.1, sign(1) * p.2);
            qa <= pa && qb <= pb && (qa < pa || qb < pb)
        })
    };
    let mut front: Vec<(usize, f64, f64)> = pts.iter().copied().filter(|p| !dominated(p)).collect();
    front.sort_by(|a, b| a.1.total_cmp(&b.1).then(a.0.cmp(&b.0)));
    // Equal designs (a repeated point) once.
    front.dedup_by(|a, b| a.1 == b.1 && a.2 == b.2);
    Some(Pareto {
        objectives: spec.objectives[..2].iter().map(|o| label_of(&o.quantity)).collect(),
        designs: front.iter().map(|p| p.0 + 1).collect(),
        first: front.iter().map(|p| json!(p.1)).collect(),
        second: front.iter().map(|p| json!(p.2)).collect(),
    })
}

/// The result document of a search.
pub fn result(spec: &CamOptimisationSpec, searched: Searched) -> Result<CamOptimisationResult, SolveError> {
    let Searched { records, limits } = searched;
    let Outcome::Measured(base) = &records[0].outcome else {
        return Err(SolveError::invalid("/base", "the baseline design failed"));
    };
    let judged = judge_all(spec, &records, base, &limits);
    let measured = |i: usize| match &records[i].outcome {
        Outcome::Measured(m) => Some(m.as_ref()),
        Outcome::Failed { .. } => None,
    };
    let failed = || SolveError::invalid("/base", "the baseline design failed");
    let base_j = judged[0].as_ref().ok_or_else(failed)?;
    // The first of the ranking; a failed design is never first unless every design failed.
    let best_i = rank(&judged).into_iter().next().filter(|&i| judged[i].is_some()).unwrap_or(0);
    let best_j = judged[best_i].as_ref().ok_or_else(failed)?;
    let baseline = report(spec, 0, base, base_j);
    let best = report(spec, best_i, measured(best_i).ok_or_else(failed)?, best_j);
    let friction_power_change = match (best.friction_power, baseline.friction_power) {
        (Some(b), Some(a)) if a != 0.0 => Some(100.0 * (b - a) / a),
        _ => None,
    };
    let score_change = if base_j.score != 0.0 { 100.0 * (best_j.score - base_j.score) / base_j.score.abs() } else { 0.0 };
    let (mut columns, units) = columns(spec);
    let designs: Vec<Map<String, Value>> = records.iter().enumerate().map(|(i, r)| row(spec, i, r, judged[i].as_ref())).collect();
    let failed_count = designs.iter().filter(|r| r["status"] == "failed").count();
    if failed_count > 0 {
        columns.push("error".into());
    }
    Ok(CamOptimisationResult {
        pareto: pareto(spec, &records, &judged),
        baseline,
        best,
        friction_power_change,
        score_change,
        columns,
        units,
        evaluations: records.len(),
        feasible_count: judged.iter().flatten().filter(|j| j.feasible).count(),
        failed_count,
        designs,
    })
}
