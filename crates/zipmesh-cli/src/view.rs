//! `zipmesh view`: one self-contained HTML page to look around a mesh (WebGL), with its
//! interior singularities as balls, a legend, picking, and optionally surgery paths read
//! from a JSON report as `render --paths` reads them.

use clap::Args;
use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;
use zipmesh::io;
use zipmesh::render::view::{Page, PageOptions};

use crate::out::{self, outln};
use crate::render::{read_paths, Found};

/// `zipmesh view`.
#[derive(Args)]
#[command(
    after_help = "Open OUT in a browser (it loads nothing from the network). Drag to \
orbit, use the wheel to zoom, click two balls to get the `zipmesh moves` and `zipmesh zip` \
commands for that pair (`tri-move` on triangle meshes). The URL's hash holds the view and the \
picks, e.g. `view.html#view=30,20&zoom=1.5&pick=12,40`: a URL reproduces what it shows."
)]
pub struct ViewArgs {
    /// A mesh (.obj, .off or .ply); the commands the page shows name it as given here.
    file: PathBuf,
    /// The page to write (HTML; written only if the whole run succeeds).
    #[arg(short, long)]
    pub(crate) output: PathBuf,
    /// A JSON file whose paths are drawn, read as `render --paths` reads it: arrays of
    /// vertex numbers under a key `path` (as `zip --json` prints) and arrays of vertex
    /// numbers or of points under a key `paths` (as `optimize --paths` writes), at any depth.
    #[arg(long, value_name = "REPORT")]
    paths: Option<PathBuf>,
    /// The page's title (default: FILE as given).
    #[arg(long)]
    title: Option<String>,
}

/// Runs `zipmesh view`.
pub fn run(args: ViewArgs) -> Result<ExitCode, String> {
    let (mesh, _) = io::read_mesh(&args.file).map_err(|e| e.to_string())?;
    let Found { paths, points } = match &args.paths {
        Some(p) => read_paths(p)?,
        None => Found::default(),
    };
    let name = args.file.display().to_string();
    let options = PageOptions {
        file: name.clone(),
        title: args.title,
        paths,
        point_paths: points,
    };
    let page = Page::new(&mesh, &options).map_err(|e| format!("{name}: {e}"))?;
    let html = page.html();
    let pending = io::prepare_atomic(&args.output, |w| w.write_all(html.as_bytes()))
        .map_err(|e| e.to_string())?;
    let view = page.view();
    outln!(
        "{name} -> {}: {} interior singularities, {} paths; first view {},{} (open it in a \
         browser; its URL's hash holds the view and the picks)",
        args.output.display(),
        page.balls().len(),
        options.paths.len() + options.point_paths.len(),
        view.azimuth,
        view.elevation,
    );
    out::flush().map_err(|e| e.to_string())?;
    pending.commit().map_err(|e| e.to_string())?;
    Ok(ExitCode::SUCCESS)
}
