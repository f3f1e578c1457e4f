//! `zipmesh render`: a picture of a mesh (SVG or PNG), with its seen interior singularities
//! as balls and optionally surgery paths read from a JSON report.

use clap::Args;
use serde_json::Value;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use zipmesh::io;
use zipmesh::render::{Options, Scene, View, MAX_SIDE};

use crate::out::{self, outln};

/// `zipmesh render`.
#[derive(Args)]
pub struct RenderArgs {
    /// A mesh (.obj, .off or .ply).
    file: PathBuf,
    /// The picture: a name ending in .svg or .png.
    #[arg(short, long)]
    pub(crate) output: PathBuf,
    /// The eye's azimuth and elevation in degrees, as AZ,EL: azimuth about +Y from +Z toward
    /// +X, elevation above the XZ plane (default: a three-quarter view chosen from the
    /// bounding box, see docs/render.md).
    #[arg(long, allow_hyphen_values = true, value_parser = parse_view)]
    view: Option<View>,
    /// The picture's width and height in pixels, as W,H (each 1 to 16384; a PNG at most
    /// 8192x8192 pixels in all).
    #[arg(long, value_parser = parse_size, default_value = "800,600")]
    size: (u32, u32),
    /// A JSON file whose arrays of vertex numbers under a key `path` (as `zip --json`
    /// prints), and whose arrays under a key `paths`, at any depth, are drawn as paths
    /// (0-based vertex numbers of FILE).
    #[arg(long)]
    paths: Option<PathBuf>,
    /// No legend (by default the top-left corner shows each valence's colour and how many
    /// interior singularities have it, `vK: N`).
    #[arg(long)]
    no_legend: bool,
}

fn pair(s: &str) -> Result<(&str, &str), String> {
    s.split_once(',')
        .map(|(a, b)| (a.trim(), b.trim()))
        .ok_or_else(|| format!("`{s}`: expected two numbers separated by a comma"))
}

fn parse_view(s: &str) -> Result<View, String> {
    let (a, e) = pair(s)?;
    let num = |t: &str| {
        t.parse::<f64>()
            .map_err(|_| format!("`{t}` is not a number of degrees"))
    };
    View::new(num(a)?, num(e)?).map_err(|e| e.to_string())
}

fn parse_size(s: &str) -> Result<(u32, u32), String> {
    let (w, h) = pair(s)?;
    let side = |t: &str| match t.parse::<u64>() {
        Ok(n) if (1..=u64::from(MAX_SIDE)).contains(&n) => Ok(n as u32),
        _ => Err(format!(
            "`{t}`: each side must be a whole number of pixels from 1 to {MAX_SIDE}"
        )),
    };
    Ok((side(w)?, side(h)?))
}

/// The picture format, from OUT's extension.
#[derive(Clone, Copy, PartialEq)]
enum Picture {
    Svg,
    Png,
}

fn picture(path: &Path) -> Result<Picture, String> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    match ext.as_deref() {
        Some("svg") => Ok(Picture::Svg),
        Some("png") => Ok(Picture::Png),
        _ => Err(format!(
            "{}: the picture's name must end in .svg or .png",
            path.display()
        )),
    }
}

/// Runs `zipmesh render`.
pub fn run(args: RenderArgs) -> Result<ExitCode, String> {
    let format = picture(&args.output)?;
    let (mesh, _) = io::read_mesh(&args.file).map_err(|e| e.to_string())?;
    let Found { paths, points } = match &args.paths {
        Some(p) => read_paths(p)?,
        None => Found::default(),
    };
    let options = Options {
        view: args.view,
        width: args.size.0,
        height: args.size.1,
        paths,
        point_paths: points,
        legend: !args.no_legend,
    };
    let name = args.file.display();
    let scene = Scene::new(&mesh, &options).map_err(|e| format!("{name}: {e}"))?;
    let bytes = match format {
        Picture::Svg => scene.svg().into_bytes(),
        Picture::Png => scene.png().map_err(|e| format!("{name}: {e}"))?,
    };
    let pending =
        io::prepare_atomic(&args.output, |w| w.write_all(&bytes)).map_err(|e| e.to_string())?;
    let view = scene.camera().view();
    let seen = scene.balls().iter().filter(|b| b.visible).count();
    outln!(
        "{name} -> {}: {}x{}, view {},{}; {} of {} faces drawn; {} of {} interior \
         singularities seen; {} path stretches drawn",
        args.output.display(),
        args.size.0,
        args.size.1,
        view.azimuth,
        view.elevation,
        scene.faces().len(),
        scene.total_faces(),
        seen,
        scene.balls().len(),
        scene.polylines().len()
    );
    out::flush().map_err(|e| e.to_string())?;
    pending.commit().map_err(|e| e.to_string())?;
    Ok(ExitCode::SUCCESS)
}

/// The paths of a report: vertex numbers, or points (`[x, y, z]` entries, as `optimize
/// --paths` writes them).
#[derive(Default)]
pub(crate) struct Found {
    pub(crate) paths: Vec<Vec<u64>>,
    pub(crate) points: Vec<Vec<[f64; 3]>>,
}

/// Every path in the JSON file `path`: arrays under a key `path`, and the elements of
/// arrays under a key `paths`, at any depth, in document order; nothing under a key `undo`
/// (a `zip` report's undo path numbers OUT's vertices, not IN's). A path whose first entry
/// is an array is a path of points.
pub(crate) fn read_paths(path: &Path) -> Result<Found, String> {
    let name = path.display();
    let text = std::fs::read(path).map_err(|e| format!("{name}: {e}"))?;
    let value: Value =
        serde_json::from_slice(&text).map_err(|e| format!("{name}: not JSON: {e}"))?;
    let mut found = Found::default();
    collect(&value, &mut found).map_err(|e| format!("{name}: {e}"))?;
    Ok(found)
}

impl Found {
    /// Adds one path: points if its first entry is an array, else vertex numbers.
    fn push(&mut self, a: &[Value]) -> Result<(), String> {
        let which = self.paths.len() + self.points.len();
        if a.first().is_some_and(Value::is_array) {
            self.points.push(points(a, which)?);
        } else {
            self.paths.push(indices(a, which)?);
        }
        Ok(())
    }
}

fn collect(value: &Value, found: &mut Found) -> Result<(), String> {
    match value {
        Value::Object(o) => {
            for (key, v) in o {
                match (key.as_str(), v) {
                    ("path", Value::Array(a)) => found.push(a)?,
                    ("paths", Value::Array(a)) => {
                        for p in a {
                            let Value::Array(p) = p else {
                                return Err(format!(
                                    "an element of `paths` is {p}, not an array of vertex \
                                     numbers"
                                ));
                            };
                            found.push(p)?;
                        }
                    }
                    // A `zip` report's undo path is in OUT's numbering, not IN's.
                    ("undo", _) => {}
                    ("path" | "paths", Value::Null) => {}
                    ("path" | "paths", other) => {
                        return Err(format!(
                            "`{key}` is {other}, not an array of vertex numbers"
                        ))
                    }
                    _ => collect(v, found)?,
                }
            }
        }
        Value::Array(a) => {
            for v in a {
                collect(v, found)?;
            }
        }
        _ => {}
    }
    Ok(())
}

fn points(a: &[Value], which: usize) -> Result<Vec<[f64; 3]>, String> {
    a.iter()
        .enumerate()
        .map(|(i, v)| {
            let xyz: Option<Vec<f64>> = v
                .as_array()
                .filter(|c| c.len() == 3)
                .and_then(|c| c.iter().map(Value::as_f64).collect());
            xyz.map(|c| [c[0], c[1], c[2]])
                .ok_or_else(|| format!("path {which}, entry {i}: {v} is not a point [x, y, z]"))
        })
        .collect()
}

fn indices(a: &[Value], which: usize) -> Result<Vec<u64>, String> {
    a.iter()
        .enumerate()
        .map(|(i, v)| {
            v.as_u64().ok_or_else(|| {
                format!(
                    "path {which}, entry {i}: {v} is not a vertex number (a whole number \
                     from 0)"
                )
            })
        })
        .collect()
}
