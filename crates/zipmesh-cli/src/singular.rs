//! `zipmesh singularities`: every irregular vertex with its number, valence, place, defect and
//! position, as a table or JSON.

use crate::kind_name;
use crate::out::outln;
use clap::Args;
use serde_json::{json, Value};
use std::path::PathBuf;
use zipmesh::invariants::{irregular_vertices, regular_valence, MeshKind};
use zipmesh::io::{self, MeshFileError};
use zipmesh::{optimize, Mesh, Vert};

#[derive(Args)]
pub struct SingularitiesArgs {
    /// An .obj, .off or .ply file.
    file: PathBuf,
    /// Print one JSON object instead of a table.
    #[arg(long)]
    json: bool,
}

/// One irregular vertex as the command reports it.
struct Row {
    vertex: Vert,
    valence: usize,
    boundary: bool,
    defect: i64,
    position: [f64; 3],
}

/// The irregular vertices of `mesh`, in vertex order. Quad and quad-dominant meshes use the
/// optimizer's defect (4 inside; on the boundary the ideal valence of the vertex's angle),
/// triangle meshes the regular valence (6 inside, 4 on the boundary).
fn rows(mesh: &Mesh, kind: MeshKind) -> Vec<Row> {
    let map = &mesh.map;
    let at = |v: Vert| {
        let p = mesh.positions.get(v.index()).copied().unwrap_or_default();
        [p.x, p.y, p.z]
    };
    let found: Vec<(Vert, i64)> = match kind {
        MeshKind::Triangle => irregular_vertices(map, kind)
            .into_iter()
            .map(|v| {
                let regular = regular_valence(kind, map.is_boundary_vertex(v));
                (v, map.valence(v) as i64 - regular as i64)
            })
            .collect(),
        MeshKind::Quad | MeshKind::Mixed => optimize::singularities(mesh)
            .into_iter()
            .map(|s| (s.vertex, s.defect))
            .collect(),
    };
    found
        .into_iter()
        .map(|(v, defect)| Row {
            vertex: v,
            valence: map.valence(v),
            boundary: map.is_boundary_vertex(v),
            defect,
            position: at(v),
        })
        .collect()
}

pub fn run(args: SingularitiesArgs) -> Result<(), MeshFileError> {
    let (mesh, _) = io::read_mesh(&args.file)?;
    let kind = MeshKind::of(&mesh.map);
    let rows = rows(&mesh, kind);
    let name = args.file.display();
    if args.json {
        let list: Vec<Value> = rows
            .iter()
            .map(|r| {
                json!({
                    "vertex": r.vertex.index(),
                    "valence": r.valence,
                    "boundary": r.boundary,
                    "defect": r.defect,
                    "position": r.position,
                })
            })
            .collect();
        let report =
            json!({"file": name.to_string(), "kind": kind_name(kind), "singularities": list});
        outln!("{report}");
        return Ok(());
    }
    outln!(
        "{name}: {} singularities ({} mesh; vertices numbered from 0)",
        rows.len(),
        kind_name(kind)
    );
    outln!(
        "{:>8} {:>7} {:<8} {:>6}  position",
        "vertex",
        "valence",
        "place",
        "defect"
    );
    for r in &rows {
        let [x, y, z] = r.position;
        let place = if r.boundary { "boundary" } else { "interior" };
        outln!(
            "{:>8} {:>7} {:<8} {:>+6}  {x} {y} {z}",
            r.vertex.index(),
            r.valence,
            place,
            r.defect
        );
    }
    Ok(())
}
