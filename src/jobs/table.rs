//! Tabular results as CSV. A table is a result field holding either an object of equal-length
//! arrays (columnar, e.g. a per-angle `series`) or an array of flat objects (rows, e.g. `runs`).

use serde_json::Value;

/// Render the table `value` as CSV (header line first), each dimensional column's header with
/// its unit (`film_min [m]`, from `unit(column)`). `Err` names what is not tabular.
pub fn to_csv(value: &Value, unit: &dyn Fn(&str) -> Option<String>) -> Result<String, String> {
    let head = |k: &str| match unit(k) {
        Some(u) => format!("{k} [{u}]"),
        None => k.to_string(),
    };
    let mut w = csv::WriterBuilder::new().from_writer(Vec::new());
    match value {
        Value::Object(columns) => {
            let cols: Vec<(&String, &Vec<Value>)> = columns
                .iter()
                .filter_map(|(k, v)| v.as_array().map(|a| (k, a)))
                .collect();
            if cols.is_empty() {
                return Err("the field has no array columns".into());
            }
            let rows = cols.iter().map(|(_, a)| a.len()).max().unwrap_or(0);
            if cols.iter().any(|(_, a)| a.len() != rows) {
                return Err("the columns have different lengths".into());
            }
            w.write_record(cols.iter().map(|(k, _)| head(k))).map_err(|e| e.to_string())?;
            for i in 0..rows {
                w.write_record(cols.iter().map(|(_, a)| cell(&a[i]))).map_err(|e| e.to_string())?;
            }
        }
        Value::Array(rows) => {
            let mut header: Vec<&String> = Vec::new();
            for row in rows {
                let obj = row.as_object().ok_or("the rows are not objects")?;
                for k in obj.keys() {
                    if !header.contains(&k) {
                        header.push(k);
                    }
                }
            }
            w.write_record(header.iter().map(|k| head(k))).map_err(|e| e.to_string())?;
            for row in rows {
                let obj = row.as_object().ok_or("the rows are not objects")?;
                w.write_record(header.iter().map(|k| obj.get(*k).map(cell).unwrap_or_default()))
                    .map_err(|e| e.to_string())?;
            }
        }
        _ => return Err("the field is neither columns nor rows".into()),
    }
    let bytes = w.into_inner().map_err(|e| e.to_string())?;
    String::from_utf8(bytes).map_err(|e| e.to_string())
}

fn cell(v: &Value) -> String {
    match v {
        Value::Null => String::new(),
        Value::String(s) => s.clone(),
        Value::Number(n) => n.to_string(),
        Value::Bool(b) => b.to_string(),
        other => other.to_string(),
    }
}

/// The unit lookup of table `table` of a `result` of kind `k` (for [`to_csv`]): the result's
/// own `units` by column name where it has them (a sweep's columns), else the kind's
/// `result_units`. Pure numbers (`1`) get no unit in the header.
pub fn units_of(k: Option<&dyn crate::jobs::kind::DynKind>, result: &Value, table: &str) -> Box<dyn Fn(&str) -> Option<String>> {
    if let Some(own) = result.get("units").and_then(Value::as_object) {
        let own = own.clone();
        return Box::new(move |column: &str| own.get(column).and_then(Value::as_str).filter(|u| *u != "1").map(str::to_string));
    }
    let Some(k) = k else { return Box::new(|_: &str| None) };
    let units = k.result_units();
    let table = table.to_string();
    Box::new(move |column: &str| crate::jobs::units::column_unit(units, &table, column).map(str::to_string))
}
