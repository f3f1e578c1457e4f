//! Reading back the JSON that `zipmesh check --json` prints (`Report::to_json`), for
//! `--merge`. The library writes JSON by hand and does not depend on serde; the command-line
//! tool has serde_json, so the parsing lives here.

use serde_json::Value;
use std::collections::BTreeMap;
use std::path::PathBuf;
use std::time::Duration;
use zipmesh::campaign::{Campaign, Failure, Report, Row, Shard, Shrunk};
use zipmesh::{io, Vert};

/// Parses one report; the error names the field that is missing or wrong.
pub fn parse(text: &str) -> Result<Report, String> {
    let v: Value = serde_json::from_str(text).map_err(|e| format!("not JSON ({e})"))?;
    let shard: Shard = string(&v, "shard")?
        .parse()
        .map_err(|e| format!("field shard: {e}"))?;
    let rows = array(&v, "properties")?
        .iter()
        .map(row)
        .collect::<Result<_, _>>()?;
    let failures = array(&v, "failures")?
        .iter()
        .map(failure)
        .collect::<Result<_, _>>()?;
    let inputs = array(&v, "inputs")?
        .iter()
        .map(|i| {
            i.as_str()
                .map(String::from)
                .ok_or("field inputs: not a string")
        })
        .collect::<Result<_, _>>()?;
    let settings = v
        .get("settings")
        .and_then(Value::as_object)
        .ok_or("field settings missing or not an object")?
        .iter()
        .map(|(k, x)| {
            Ok((
                k.clone(),
                x.as_str().ok_or("field settings: not a string")?.into(),
            ))
        })
        .collect::<Result<BTreeMap<_, _>, &str>>()?;
    Ok(Report {
        seed: number(&v, "seed")?,
        shard,
        planned: number(&v, "planned")?,
        run: number(&v, "run")?,
        timed_out: v
            .get("timed_out")
            .and_then(Value::as_bool)
            .ok_or("field timed_out missing or not true/false")?,
        elapsed: seconds(&v),
        rows,
        failures,
        campaign: Campaign {
            cases: number(&v, "cases")?,
            max_faces: usize::try_from(number(&v, "max_faces")?).map_err(|e| e.to_string())?,
            inputs,
            settings,
        },
    })
}

fn row(v: &Value) -> Result<Row, String> {
    Ok(Row {
        property: string(v, "name")?.to_string(),
        cases: number(v, "cases")?,
        passed: number(v, "passed")?,
        failed: number(v, "failed")?,
        skipped: number(v, "skipped")?,
        checks: number(v, "checks")?,
        cut: number(v, "cut")?,
        unchecked: number(v, "unchecked")?,
        // Absent in reports written before the field existed.
        searched: v.get("searched").and_then(Value::as_u64).unwrap_or(0),
        time: seconds(v),
    })
}

fn failure(v: &Value) -> Result<Failure, String> {
    let shrunk = match v.get("counterexample_obj").and_then(Value::as_str) {
        None => None,
        Some(obj) => {
            let (mesh, _) = io::obj::parse(obj)
                .map_err(|e| format!("field counterexample_obj: not an OBJ mesh ({e})"))?;
            if Some(mesh.map.num_faces() as u64) != v.get("shrunk_faces").and_then(Value::as_u64) {
                return Err("field shrunk_faces: not the counterexample's face count".into());
            }
            let focus = match v.get("shrunk_focus").and_then(Value::as_u64) {
                Some(f) => Some(Vert::new(
                    u32::try_from(f).map_err(|_| "field shrunk_focus: too large")?,
                )),
                None => None,
            };
            Some(Shrunk {
                mesh,
                focus,
                message: string(v, "shrunk_message")?.to_string(),
                evaluations: 0,
            })
        }
    };
    Ok(Failure {
        property: string(v, "property")?.to_string(),
        case: number(v, "case")?,
        position: number(v, "position")?,
        description: string(v, "description")?.to_string(),
        message: string(v, "message")?.to_string(),
        original_faces: usize::try_from(number(v, "original_faces")?).map_err(|e| e.to_string())?,
        shrunk,
        path: v
            .get("counterexample")
            .and_then(Value::as_str)
            .map(PathBuf::from),
        replay: string(v, "replay")?.to_string(),
        case_replay: string(v, "case_replay")?.to_string(),
    })
}

fn number(v: &Value, key: &str) -> Result<u64, String> {
    v.get(key)
        .and_then(Value::as_u64)
        .ok_or_else(|| format!("field {key} missing or not a whole number"))
}

fn string<'a>(v: &'a Value, key: &str) -> Result<&'a str, String> {
    v.get(key)
        .and_then(Value::as_str)
        .ok_or_else(|| format!("field {key} missing or not a string"))
}

fn array<'a>(v: &'a Value, key: &str) -> Result<&'a Vec<Value>, String> {
    v.get(key)
        .and_then(Value::as_array)
        .ok_or_else(|| format!("field {key} missing or not a list"))
}

/// A `seconds` field as a duration (0 when absent: reports printed without times).
fn seconds(v: &Value) -> Duration {
    v.get("seconds")
        .and_then(Value::as_f64)
        .filter(|s| s.is_finite() && *s >= 0.0)
        .map(|s| Duration::from_secs_f64(s.min(1e15)))
        .unwrap_or_default()
}
