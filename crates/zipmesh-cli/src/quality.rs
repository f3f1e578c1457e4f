//! The library's `quality::Summary` as the commands print it: the `"quality"` object of
//! `stats --json` and its table rows, and the one-line comparison of an input and an output
//! that the edits and `optimize` print.

use serde_json::{json, Value};
use zipmesh::quality::{Summary, THIN_TRIANGLE_DEGREES};

/// The summary as the `"quality"` object of `stats --json`; `distance` is null without a
/// reference.
pub fn to_json(s: &Summary) -> Value {
    json!({
        "faces": s.faces,
        "quads": s.quads,
        "triangles": s.triangles,
        "folded_quads": s.folded_quads,
        "folded_by": {
            "diagonal": s.folded_by.diagonal,
            "corner": s.folded_by.corner,
            "neighbours": s.folded_by.neighbours,
        },
        "negative_scaled_jacobian": s.negative_jacobian,
        "scaled_jacobian": s.jacobian.map(|j| json!({
            "min": j.min, "p1": j.p1, "p5": j.p5, "median": j.median,
        })),
        "min_angle_degrees": s.min_angle,
        "thin_triangles": s.thin_triangles,
        "thin_triangle_degrees": THIN_TRIANGLE_DEGREES,
        "flipped_triangles": s.flipped_triangles,
        "max_edge_ratio": s.max_edge_ratio,
        "degenerate_faces": s.degenerate_faces,
        "distance": s.distance.map(|d| json!({
            "vertices": d.vertices, "mean": d.mean, "p99": d.p99, "max": d.max,
        })),
    })
}

/// The table rows of the `"quality"` object ([`to_json`]), as label and text.
pub fn rows(q: &Value) -> Vec<(String, String)> {
    let num = |v: &Value, digits: usize| {
        v.as_f64()
            .map_or("-".to_string(), |x| format!("{x:.digits$}"))
    };
    let by = &q["folded_by"];
    let mut rows = vec![
        (
            "folded quads".to_string(),
            format!(
                "{} (diagonal {}, corner {}, neighbours {})",
                q["folded_quads"], by["diagonal"], by["corner"], by["neighbours"]
            ),
        ),
        (
            "scaled jacobian < 0".into(),
            q["negative_scaled_jacobian"].to_string(),
        ),
        (
            "scaled jacobian 1st %".into(),
            num(&q["scaled_jacobian"]["p1"], 3),
        ),
        ("min angle".into(), {
            let a = num(&q["min_angle_degrees"], 1);
            if a == "-" {
                a
            } else {
                format!("{a} degrees")
            }
        }),
        (
            format!("triangles < {THIN_TRIANGLE_DEGREES} deg"),
            q["thin_triangles"].to_string(),
        ),
        (
            "flipped triangles".into(),
            q["flipped_triangles"].to_string(),
        ),
        ("max edge ratio".into(), num(&q["max_edge_ratio"], 2)),
        ("degenerate faces".into(), q["degenerate_faces"].to_string()),
    ];
    let d = &q["distance"];
    if !d.is_null() {
        rows.push((
            "distance to reference".into(),
            format!(
                "mean {}, 99th % {}, max {} (of its diagonal)",
                num(&d["mean"], 6),
                num(&d["p99"], 6),
                num(&d["max"], 6)
            ),
        ));
    }
    rows
}

/// The `"quality"` object of an edit's or `optimize`'s JSON report: `input` and `output`,
/// both measured against the input's surface.
pub fn both_json(q: &[Summary; 2]) -> Value {
    json!({"input": to_json(&q[0]), "output": to_json(&q[1])})
}

/// One line comparing input and output, then the output's largest distance to the input
/// surface: folded quads and negative scaled Jacobians where there are quads, else thin and
/// flipped triangles and the smallest angle.
pub fn line(q: &[Summary; 2]) -> String {
    let far = q[1].distance.map_or(0.0, |d| d.max);
    let angle = |s: &Summary| s.min_angle.unwrap_or(0.0);
    let faces = if q[0].quads > 0 || q[1].quads > 0 {
        format!(
            "folded quads {} -> {}, scaled jacobian < 0 {} -> {}",
            q[0].folded_quads, q[1].folded_quads, q[0].negative_jacobian, q[1].negative_jacobian
        )
    } else {
        format!(
            "triangles under {THIN_TRIANGLE_DEGREES} degrees {} -> {}, flipped {} -> {}, \
             smallest angle {:.1} -> {:.1} degrees",
            q[0].thin_triangles,
            q[1].thin_triangles,
            q[0].flipped_triangles,
            q[1].flipped_triangles,
            angle(&q[0]),
            angle(&q[1]),
        )
    };
    format!("{faces}, max distance to the input {far:.2e} of its diagonal")
}
