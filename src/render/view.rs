//! Interactive views of meshes: one self-contained HTML page (WebGL 1, the viewer's script
//! inline, no network access) showing the faces, their edges and the interior singularities
//! as balls coloured as in [`Scene`](super::Scene)'s pictures ([`ball_colour`]), with a
//! legend, orbit and zoom, picking, and the view in the URL (`#view=AZ,EL&zoom=Z&pick=A,B`).
//!
//! The script is hand-written (`view.js`, about 400 lines, no library): the page may load
//! nothing from outside, and a minimal WebGL viewer is small.
//!
//! ```
//! use zipmesh::{gen, render::view::{Page, PageOptions}};
//! let page = Page::new(&gen::cube(2), &PageOptions::new("cube.obj")).unwrap();
//! assert_eq!(page.balls().len(), 8); // the cube's corners, valence 3
//! let html = page.html();
//! assert!(html.starts_with("<!DOCTYPE html>") && html.contains("id=\"zipmesh-data\""));
//! assert!(!html.contains("src=\"http") && !html.contains("<link"));
//! ```

use super::{ball_colour, check_paths, live_positions, scaled_points, singularities};
use super::{BallColour, RenderError, View};
use crate::invariants::MeshKind;
use crate::map::{Map, Vert};
use crate::mesh::Mesh;
use alloc::string::{String, ToString};
use alloc::vec::Vec;
use core::fmt::Write;
use glam::DVec3;

/// The page's frame: `@@TITLE@@`, `@@DATA@@` and `@@SCRIPT@@` are filled in.
const TEMPLATE: &str = include_str!("view.html");
/// The viewer.
const SCRIPT: &str = include_str!("view.js");
/// Valences up to this one are named in the legend; above it every valence has the colour
/// of this one (`ball_colour`'s catch-all), written `vK+`.
const LEGEND_VALENCES: usize = 12;

/// What a page shows besides the mesh.
///
/// ```
/// let o = zipmesh::render::view::PageOptions::new("spot.obj");
/// assert_eq!(o.file, "spot.obj");
/// assert!(o.title.is_none() && o.paths.is_empty() && o.point_paths.is_empty());
/// ```
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PageOptions {
    /// The mesh file's name as the user gave it: the commands the page shows name it.
    pub file: String,
    /// The page's title (default: the file's name).
    pub title: Option<String>,
    /// Surgery paths to draw, as vertex numbers (slots) of the mesh.
    pub paths: Vec<Vec<u64>>,
    /// Surgery paths to draw, as points in the mesh's coordinates.
    pub point_paths: Vec<Vec<[f64; 3]>>,
}

impl PageOptions {
    /// Options for the mesh file `file`, with nothing else.
    ///
    /// ```
    /// let o = zipmesh::render::view::PageOptions::new("a b.obj");
    /// assert_eq!(o.file, "a b.obj");
    /// ```
    pub fn new(file: &str) -> PageOptions {
        PageOptions {
            file: file.to_string(),
            ..PageOptions::default()
        }
    }
}

/// One singularity on the page.
///
/// ```
/// use zipmesh::{gen, render::{view::{Page, PageOptions}, BallColour}};
/// let page = Page::new(&gen::icosahedron(), &PageOptions::new("ico.obj")).unwrap();
/// assert!(page.balls().iter().all(|b| b.valence == 5 && b.colour == BallColour::Blue));
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PageBall {
    /// The vertex (its number is the one every command takes).
    pub vertex: Vert,
    /// Its valence.
    pub valence: usize,
    /// Its colour, as [`ball_colour`] gives it.
    pub colour: BallColour,
}

/// One line of the legend: a colour, the valences it stands for in this kind of mesh, and
/// how many singularities of the mesh have it.
///
/// ```
/// use zipmesh::{gen, render::{view::{Page, PageOptions}, BallColour}};
/// let page = Page::new(&gen::cube(2), &PageOptions::new("cube.obj")).unwrap();
/// let blue = &page.legend()[0];
/// assert_eq!((blue.colour, blue.valences.as_str(), blue.count), (BallColour::Blue, "v3", 8));
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct LegendEntry {
    /// The colour.
    pub colour: BallColour,
    /// The valences it stands for, as `v3` or `v1, v6+` (`+`: and every larger one).
    pub valences: String,
    /// How many singularities of the mesh have this colour.
    pub count: usize,
}

/// The legend of a mesh kind: every colour that [`ball_colour`] gives some valence in
/// `kind`, in [`BallColour::ALL`]'s order, with the valences it stands for (counts 0).
///
/// ```
/// use zipmesh::{invariants::MeshKind, render::view::legend};
/// let quad: Vec<String> = legend(MeshKind::Quad).into_iter().map(|e| e.valences).collect();
/// assert_eq!(quad, ["v3", "v5", "v1, v6+", "v2"]);
/// let tri: Vec<String> = legend(MeshKind::Triangle).into_iter().map(|e| e.valences).collect();
/// assert_eq!(tri, ["v5", "v7", "v1-v4, v8+"]);
/// ```
pub fn legend(kind: MeshKind) -> Vec<LegendEntry> {
    BallColour::ALL
        .iter()
        .filter_map(|&colour| {
            let has = |k: usize| ball_colour(kind, k) == Some(colour);
            let mut runs: Vec<String> = Vec::new();
            let mut k = 1;
            while k <= LEGEND_VALENCES {
                if !has(k) {
                    k += 1;
                    continue;
                }
                let start = k;
                while k < LEGEND_VALENCES && has(k + 1) {
                    k += 1;
                }
                runs.push(match (start, k) {
                    (a, LEGEND_VALENCES) => alloc::format!("v{a}+"),
                    (a, b) if a == b => alloc::format!("v{a}"),
                    (a, b) => alloc::format!("v{a}-v{b}"),
                });
                k += 1;
            }
            (!runs.is_empty()).then(|| LegendEntry {
                colour,
                valences: runs.join(", "),
                count: 0,
            })
        })
        .collect()
}

/// An interactive view of a mesh, as one HTML page.
#[derive(Clone, Debug, PartialEq)]
pub struct Page {
    kind: MeshKind,
    view: View,
    balls: Vec<PageBall>,
    legend: Vec<LegendEntry>,
    html: String,
}

impl Page {
    /// The page of `mesh`: checks the positions and the paths as [`Scene::new`] does
    /// (the same errors), and writes the mesh, its singularities and the viewer into one
    /// HTML text. The first view is [`View::fitting`] the bounding box, as `render`'s.
    ///
    /// [`Scene::new`]: super::Scene::new
    ///
    /// ```
    /// use zipmesh::{gen, render::{view::{Page, PageOptions}, RenderError}};
    /// let bad = PageOptions { paths: vec![vec![0, 99]], ..PageOptions::new("cube.obj") };
    /// let e = Page::new(&gen::cube(1), &bad).unwrap_err();
    /// assert!(matches!(e, RenderError::PathVertex { path: 0, entry: 1, vertex: 99, .. }));
    /// ```
    pub fn new(mesh: &Mesh, options: &PageOptions) -> Result<Page, RenderError> {
        let map = &mesh.map;
        let (positions, scale) = live_positions(mesh)?;
        check_paths(map, &options.paths)?;
        let points = scaled_points(&options.point_paths, scale)?;
        let (lo, hi) = map.vertices().map(|v| positions[v.index()]).fold(
            (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
            |(lo, hi), p| (lo.min(p), hi.max(p)),
        );
        let view = View::fitting(lo, hi);
        // Into the unit ball about the bounding box's centre (the viewer orbits it).
        let (centre, radius) = if lo.x <= hi.x {
            (0.5 * (lo + hi), 0.5 * (hi - lo).length())
        } else {
            (DVec3::ZERO, 1.0)
        };
        let radius = if radius > 0.0 { radius } else { 1.0 };
        let unit = |p: DVec3| (p - centre) / radius;
        let kind = MeshKind::of(map);
        let balls: Vec<PageBall> = singularities(map)
            .into_iter()
            .filter_map(|(vertex, valence)| {
                Some(PageBall {
                    vertex,
                    valence,
                    colour: ball_colour(kind, valence)?,
                })
            })
            .collect();
        let mut legend = legend(kind);
        for e in &mut legend {
            e.count = balls.iter().filter(|b| b.colour == e.colour).count();
        }
        let mut paths: Vec<Vec<DVec3>> = options
            .paths
            .iter()
            // Every entry was checked to be a live vertex (below u32::MAX).
            .map(|p| p.iter().map(|&v| unit(positions[v as usize])).collect())
            .collect();
        paths.extend(points.iter().map(|p| p.iter().map(|&q| unit(q)).collect()));
        let unit_positions: Vec<DVec3> = positions.iter().map(|&p| unit(p)).collect();
        let mut page = Page {
            kind,
            view,
            balls,
            legend,
            html: String::new(),
        };
        let data = page.data(map, &unit_positions, &paths, options);
        let title = options.title.as_deref().unwrap_or(&options.file);
        page.html = fill(&html_escape(title), &data);
        Ok(page)
    }

    /// The HTML text.
    ///
    /// ```
    /// use zipmesh::{gen, render::view::{Page, PageOptions}};
    /// let page = Page::new(&gen::cube(1), &PageOptions::new("<cube>.obj")).unwrap();
    /// assert!(page.html().contains("<title>&lt;cube&gt;.obj</title>"));
    /// ```
    pub fn html(&self) -> &str {
        &self.html
    }

    /// The interior singularities, in vertex order: the balls the page draws.
    ///
    /// ```
    /// use zipmesh::{gen, render::view::{Page, PageOptions}};
    /// let page = Page::new(&gen::grid(3, 3), &PageOptions::new("grid.obj")).unwrap();
    /// assert!(page.balls().is_empty()); // a grid's corners are on the boundary
    /// ```
    pub fn balls(&self) -> &[PageBall] {
        &self.balls
    }

    /// The legend: [`legend`] of the mesh's kind, with the mesh's counts.
    ///
    /// ```
    /// use zipmesh::{gen, render::view::{Page, PageOptions}};
    /// let page = Page::new(&gen::icosahedron(), &PageOptions::new("ico.obj")).unwrap();
    /// assert_eq!(page.legend()[0].valences, "v5"); // a triangle mesh's blue
    /// assert_eq!(page.legend()[0].count, 12);
    /// ```
    pub fn legend(&self) -> &[LegendEntry] {
        &self.legend
    }

    /// The first view (the page's URL can set another).
    ///
    /// ```
    /// use zipmesh::{gen, render::view::{Page, PageOptions}};
    /// let page = Page::new(&gen::cube(1), &PageOptions::new("cube.obj")).unwrap();
    /// assert_eq!((page.view().azimuth, page.view().elevation), (30.0, 20.0));
    /// ```
    pub fn view(&self) -> View {
        self.view
    }

    /// The mesh's kind.
    ///
    /// ```
    /// use zipmesh::{gen, invariants::MeshKind, render::view::{Page, PageOptions}};
    /// let page = Page::new(&gen::cube(1), &PageOptions::new("cube.obj")).unwrap();
    /// assert_eq!(page.kind(), MeshKind::Quad);
    /// ```
    pub fn kind(&self) -> MeshKind {
        self.kind
    }

    /// The page's data as one JSON object (positions in the unit ball, every vertex slot;
    /// faces as polygons of vertex numbers; balls as `[vertex, valence, colour index]`).
    fn data(
        &self,
        map: &Map,
        positions: &[DVec3],
        paths: &[Vec<DVec3>],
        options: &PageOptions,
    ) -> String {
        let mut s = String::new();
        // Writing into a String cannot fail.
        let _ = write!(
            s,
            "{{\"file\":{},\"command_file\":{},\"kind\":\"{}\",\"view\":[{},{}],\
             \"vertices\":{},\"radius\":{:.6},\"positions\":[",
            json_string(&options.file),
            json_string(&shell_word(&options.file)),
            kind_name(self.kind),
            self.view.azimuth,
            self.view.elevation,
            map.num_vertices(),
            0.4 * median_edge(map, positions),
        );
        let xyz = |s: &mut String, p: DVec3| {
            let _ = write!(s, "{},{},{}", num(p.x), num(p.y), num(p.z));
        };
        for (i, &p) in positions.iter().enumerate() {
            if i > 0 {
                s.push(',');
            }
            xyz(&mut s, p);
        }
        s.push_str("],\"faces\":[");
        for (i, f) in map.faces().enumerate() {
            s.push_str(if i > 0 { ",[" } else { "[" });
            for (j, d) in map.face_darts(f).enumerate() {
                let _ = write!(
                    s,
                    "{}{}",
                    if j > 0 { "," } else { "" },
                    map.origin(d).index()
                );
            }
            s.push(']');
        }
        s.push_str("],\"paths\":[");
        for (i, path) in paths.iter().enumerate() {
            s.push_str(if i > 0 { ",[" } else { "[" });
            for (j, &p) in path.iter().enumerate() {
                if j > 0 {
                    s.push(',');
                }
                xyz(&mut s, p);
            }
            s.push(']');
        }
        self.write_balls(&mut s);
        s.push('}');
        s
    }

    /// The colours, the legend and the balls, as the data's last members.
    fn write_balls(&self, s: &mut String) {
        s.push_str("],\"colours\":[");
        for (i, c) in BallColour::ALL.iter().enumerate() {
            let [r, g, b] = c.rgb();
            let sep = if i > 0 { "," } else { "" };
            let _ = write!(
                s,
                "{sep}{{\"name\":\"{}\",\"rgb\":[{r},{g},{b}]}}",
                c.name()
            );
        }
        s.push_str("],\"legend\":[");
        for (i, e) in self.legend.iter().enumerate() {
            let _ = write!(
                s,
                "{}{{\"colour\":{},\"valences\":{},\"count\":{}}}",
                if i > 0 { "," } else { "" },
                colour_index(e.colour),
                json_string(&e.valences),
                e.count
            );
        }
        s.push_str("],\"balls\":[");
        for (i, b) in self.balls.iter().enumerate() {
            let _ = write!(
                s,
                "{}[{},{},{}]",
                if i > 0 { "," } else { "" },
                b.vertex.index(),
                b.valence,
                colour_index(b.colour)
            );
        }
        s.push(']');
    }
}

fn colour_index(c: BallColour) -> usize {
    BallColour::ALL.iter().position(|&a| a == c).unwrap_or(0)
}

fn kind_name(kind: MeshKind) -> &'static str {
    match kind {
        MeshKind::Triangle => "triangle",
        MeshKind::Quad => "quad",
        MeshKind::Mixed => "mixed",
    }
}

/// A coordinate in the unit ball, to 1e-6 (finite: the positions were checked).
fn num(x: f64) -> String {
    let s = alloc::format!("{x:.6}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    match s {
        "" | "-" | "-0" => "0".to_string(),
        s => s.to_string(),
    }
}

/// The median length of the mesh's edges (each counted from both sides; 0.05 without edges).
fn median_edge(map: &Map, positions: &[DVec3]) -> f64 {
    let mut lengths: Vec<f64> = map
        .faces()
        .flat_map(|f| map.face_darts(f))
        .map(|d| (positions[map.origin(d).index()] - positions[map.dest(d).index()]).length())
        .collect();
    if lengths.is_empty() {
        return 0.05;
    }
    let mid = lengths.len() / 2;
    *lengths.select_nth_unstable_by(mid, f64::total_cmp).1
}

/// `s` as a JSON string that is also safe inside an HTML `<script>` element (`<`, `>`,
/// `&` and the line separators escaped).
fn json_string(s: &str) -> String {
    let mut out = String::from("\"");
    for c in s.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            c if (c as u32) < 0x20 || matches!(c, '<' | '>' | '&' | '\u{2028}' | '\u{2029}') => {
                let _ = write!(out, "\\u{:04x}", c as u32);
            }
            c => out.push(c),
        }
    }
    out.push('"');
    out
}

/// `s` for HTML text.
fn html_escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// `s` as one word of a POSIX shell command: as it is when it has only safe characters,
/// else in single quotes.
fn shell_word(s: &str) -> String {
    let safe = |c: char| c.is_ascii_alphanumeric() || "-_./+,:=@%".contains(c);
    if !s.is_empty() && s.chars().all(safe) {
        s.to_string()
    } else {
        alloc::format!("'{}'", s.replace('\'', "'\\''"))
    }
}

/// The template with its three markers filled in, each once, in one pass (a title that
/// contains a marker stays as it is).
fn fill(title: &str, data: &str) -> String {
    let mut out = String::with_capacity(TEMPLATE.len() + SCRIPT.len() + data.len());
    for (i, part) in TEMPLATE.split("@@").enumerate() {
        if i % 2 == 0 {
            out.push_str(part);
            continue;
        }
        match part {
            "TITLE" => out.push_str(title),
            "DATA" => out.push_str(data),
            "SCRIPT" => out.push_str(SCRIPT),
            other => {
                out.push_str("@@");
                out.push_str(other);
                out.push_str("@@");
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn words_and_strings_are_escaped() {
        assert_eq!(shell_word("tests/a.obj"), "tests/a.obj");
        assert_eq!(shell_word("a b.obj"), "'a b.obj'");
        assert_eq!(shell_word("it's.obj"), "'it'\\''s.obj'");
        assert_eq!(shell_word(""), "''");
        assert_eq!(
            json_string("</script>\"\n"),
            "\"\\u003c/script\\u003e\\\"\\u000a\""
        );
        assert_eq!(num(-0.0000001), "0");
        assert_eq!(num(0.5), "0.5");
        assert_eq!(num(-1.0), "-1");
    }

    #[test]
    fn a_title_with_a_marker_is_left_alone() {
        let page = Page::new(
            &crate::gen::cube(1),
            &PageOptions {
                title: Some("@@DATA@@".into()),
                ..PageOptions::new("x.obj")
            },
        )
        .unwrap();
        assert!(page.html().contains("<title>@@DATA@@</title>"));
        assert_eq!(page.html().matches("id=\"zipmesh-data\"").count(), 1);
    }
}
