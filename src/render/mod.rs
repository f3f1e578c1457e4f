//! Pictures of meshes like the Q-zip paper's figures (feature `render`): flat-shaded faces
//! with their edges, hidden surfaces removed, the interior singularities as coloured balls,
//! and optionally surgery paths as thick polylines; as SVG, or as PNG through resvg.
//!
//! * [`camera`](Camera): an orthographic [`View`] (azimuth, elevation; `+Y` up) fitted to the
//!   picture; the default view ([`View::fitting`]) follows the bounding box.
//! * [`depth`](DepthBuffer): a depth buffer of the faces decides what is seen: a face is drawn
//!   when it is nearest at some pixel, a ball or a path vertex when no face is nearer at its
//!   position (by more than [`TOLERANCE`] pixels). Faces are drawn far to near on top of that
//!   choice, so an SVG viewer's painting order only matters where two seen faces overlap.
//! * [`balls`](ball_colour): which vertices get a ball, in which colour.
//! * `svg` and `png`: the writers ([`Scene::svg`], [`Scene::png`]).
//! * [`view`]: an interactive view (one self-contained HTML page, WebGL) with the same
//!   balls, a legend, orbit, zoom and picking.
//!
//! ```
//! use zipmesh::{gen, render::{self, Options}};
//! let cube = gen::cube(3);
//! let scene = render::Scene::new(&cube, &Options::default()).unwrap();
//! // The default view sees 7 of the cube's 8 corners (valence 3, blue).
//! assert_eq!(scene.balls().iter().filter(|b| b.visible).count(), 7);
//! let svg = scene.svg();
//! assert_eq!(svg.matches("<circle class=\"v3\"").count(), 7);
//! let png = scene.png().unwrap();
//! assert_eq!(&png[1..4], b"PNG");
//! ```

mod balls;
mod camera;
mod depth;
mod legend;
mod png;
mod svg;
pub mod view;

pub use balls::{ball_colour, singularities, BallColour};
pub use camera::{Camera, View};
pub use depth::DepthBuffer;

use crate::map::{Face, Map, Vert};
use crate::mesh::Mesh;
use alloc::string::String;
use alloc::vec;
use alloc::vec::Vec;
use core::fmt;
use glam::DVec3;

/// The default picture size, in pixels.
pub const DEFAULT_SIZE: (u32, u32) = (800, 600);
/// The largest width or height accepted.
pub const MAX_SIDE: u32 = 16384;
/// The largest number of pixels of a PNG (8192 x 8192: 256 MiB of RGBA).
pub const MAX_PNG_PIXELS: u64 = 1 << 26;
/// The depth buffer's longest side: larger pictures decide visibility at this resolution.
pub const MAX_DEPTH_SIDE: u32 = 2048;
/// How much nearer (in pixels of depth) a face must be than a point to hide it.
pub const TOLERANCE: f64 = 1.0;

/// What to draw and how.
///
/// ```
/// let o = zipmesh::render::Options::default();
/// assert_eq!((o.width, o.height), (800, 600));
/// assert!(o.view.is_none() && o.paths.is_empty());
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Options {
    /// The view; `None`: [`View::fitting`] the mesh's bounding box.
    pub view: Option<View>,
    /// The picture's width in pixels (1 to [`MAX_SIDE`]).
    pub width: u32,
    /// The picture's height in pixels (1 to [`MAX_SIDE`]).
    pub height: u32,
    /// Surgery paths to draw, as vertex numbers (slots) of the mesh.
    pub paths: Vec<Vec<u64>>,
    /// Surgery paths to draw, as points in the mesh's coordinates (as `zipmesh optimize
    /// --paths` writes them: vertices are renumbered from batch to batch, positions are
    /// not). A point is seen unless a face is more than [`TOLERANCE`] pixels nearer there.
    pub point_paths: Vec<Vec<[f64; 3]>>,
    /// Draw the legend: per valence of the singularities, its colour and `vK: N` (the count
    /// of interior singularities of valence K, seen or not), in the top-left corner.
    pub legend: bool,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            view: None,
            width: DEFAULT_SIZE.0,
            height: DEFAULT_SIZE.1,
            paths: Vec::new(),
            point_paths: Vec::new(),
            legend: true,
        }
    }
}

/// Why a picture cannot be made.
///
/// ```
/// use zipmesh::{gen, render::{Options, RenderError, Scene}};
/// let o = Options { width: 0, ..Options::default() };
/// let e = Scene::new(&gen::cube(1), &o).unwrap_err();
/// assert!(matches!(e, RenderError::Size { width: 0, .. }));
/// assert!(e.to_string().contains("16384"));
/// ```
#[derive(Clone, Debug, PartialEq)]
pub enum RenderError {
    /// A width or height of 0 or above [`MAX_SIDE`].
    Size {
        /// The width asked for.
        width: u32,
        /// The height asked for.
        height: u32,
    },
    /// A PNG of more than [`MAX_PNG_PIXELS`] pixels.
    PngSize {
        /// The width asked for.
        width: u32,
        /// The height asked for.
        height: u32,
    },
    /// A view angle that is not finite, or an elevation outside `[-90, 90]`.
    View {
        /// The azimuth given.
        azimuth: f64,
        /// The elevation given.
        elevation: f64,
    },
    /// A live vertex without a finite position.
    Position {
        /// Its slot.
        vertex: usize,
    },
    /// A path entry that is not a live vertex of the mesh.
    PathVertex {
        /// Which path (0-based, in the order given).
        path: usize,
        /// Which entry of that path (0-based).
        entry: usize,
        /// The number found there.
        vertex: u64,
        /// The mesh's vertex slots (valid numbers are below this and not unreferenced).
        slots: usize,
    },
    /// A point of a point path that is not finite.
    PathPoint {
        /// Which point path (0-based, in the order given).
        path: usize,
        /// Which entry of that path (0-based).
        entry: usize,
    },
    /// The rasteriser failed (not expected for the SVG this module writes).
    Png(String),
}

impl fmt::Display for RenderError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            RenderError::Size { width, height } => write!(
                f,
                "picture size {width}x{height}: each side must be 1 to {MAX_SIDE} pixels"
            ),
            RenderError::PngSize { width, height } => write!(
                f,
                "picture size {width}x{height}: a PNG may have at most {MAX_PNG_PIXELS} pixels \
                 (8192x8192); write an SVG for larger pictures"
            ),
            RenderError::View { azimuth, elevation } => write!(
                f,
                "view {azimuth},{elevation}: the angles must be finite and the elevation \
                 within -90..90 degrees"
            ),
            RenderError::Position { vertex } => {
                write!(f, "vertex {vertex} has no finite position")
            }
            RenderError::PathVertex {
                path,
                entry,
                vertex,
                slots,
            } => write!(
                f,
                "path {path}, entry {entry}: {vertex} is not a vertex of the mesh (vertex \
                 numbers are 0-based, below {slots}, and unreferenced ones do not count)"
            ),
            RenderError::PathPoint { path, entry } => {
                write!(f, "point path {path}, entry {entry}: not a finite point")
            }
            RenderError::Png(e) => write!(f, "cannot rasterise the picture: {e}"),
        }
    }
}

impl std::error::Error for RenderError {}

/// One interior singularity: where it is and whether it is seen.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ball {
    /// The vertex.
    pub vertex: Vert,
    /// Its valence.
    pub valence: usize,
    /// Its colour.
    pub colour: BallColour,
    /// Picture coordinates (pixels, `y` down) and depth (pixels, away from the eye).
    pub centre: DVec3,
    /// Whether no face hides it (only seen balls are drawn).
    pub visible: bool,
}

/// A face as drawn: its corners on the picture and its shade.
#[derive(Clone, Debug, PartialEq)]
pub struct DrawnFace {
    /// The face.
    pub face: Face,
    /// Its corners in picture coordinates, in the face's order.
    pub corners: Vec<[f64; 2]>,
    /// Its flat Lambert shade (sRGB).
    pub fill: [u8; 3],
    /// The mean depth of its corners (drawing order: far first).
    pub depth: f64,
    /// Whether its outline on the picture is not convex (a folded or concave face): then
    /// the picture fills the triangles the depth buffer used, so that what is drawn is what
    /// decided visibility.
    pub folded: bool,
}

/// Everything a picture shows, decided once; [`Scene::svg`] and [`Scene::png`] write it.
#[derive(Clone, Debug, PartialEq)]
pub struct Scene {
    width: u32,
    height: u32,
    camera: Camera,
    faces: Vec<DrawnFace>,
    total_faces: usize,
    balls: Vec<Ball>,
    polylines: Vec<Vec<[f64; 2]>>,
    radius: f64,
    stroke: f64,
    legend: bool,
}

impl Scene {
    /// Decides what a picture of `mesh` shows under `options`: checks the size, the
    /// positions and the paths, fits the camera, fills the depth buffer and from it decides
    /// which faces, balls and path segments are seen.
    ///
    /// ```
    /// use zipmesh::{gen, render::{Options, RenderError, Scene}};
    /// let bad = Options { paths: vec![vec![0, 99]], ..Options::default() };
    /// let e = Scene::new(&gen::cube(1), &bad).unwrap_err();
    /// assert!(matches!(e, RenderError::PathVertex { path: 0, entry: 1, vertex: 99, .. }));
    /// ```
    pub fn new(mesh: &Mesh, options: &Options) -> Result<Scene, RenderError> {
        let (width, height) = (options.width, options.height);
        if width == 0 || height == 0 || width > MAX_SIDE || height > MAX_SIDE {
            return Err(RenderError::Size { width, height });
        }
        let map = &mesh.map;
        let (positions, scale) = live_positions(mesh)?;
        check_paths(map, &options.paths)?;
        let points = scaled_points(&options.point_paths, scale)?;
        let live = || map.vertices().map(|v| positions[v.index()]);
        let (lo, hi) = live().fold(
            (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
            |(lo, hi), p| (lo.min(p), hi.max(p)),
        );
        let view = options.view.unwrap_or_else(|| View::fitting(lo, hi));
        let margin = 0.05 * f64::from(width.min(height));
        let camera = Camera::fit(view, live(), width, height, margin);
        let projected: Vec<DVec3> = positions.iter().map(|&p| camera.project(p)).collect();
        let edge = median_edge(map, &projected);
        let short = f64::from(width.min(height));
        let radius = (0.4 * edge).clamp(2.0, (0.016 * short).max(2.0));
        let stroke = (0.06 * edge).clamp(0.2, 1.0);
        let resolution = (f64::from(MAX_DEPTH_SIDE) / f64::from(width.max(height))).min(1.0);
        let mut buffer = DepthBuffer::new(width, height, resolution);
        for f in map.faces() {
            let c = corners(map, f);
            for i in 1..c.len().saturating_sub(1) {
                let tri = [c[0], c[i], c[i + 1]].map(|v| projected[v.index()]);
                buffer.add_triangle(tri, f.index() as u32);
            }
        }
        let faces = seen_faces(map, &positions, &projected, &camera, &buffer);
        let sees = |v: Vert| {
            let around: Vec<u32> = map
                .vertex_darts(v)
                .filter_map(|d| map.face(d))
                .map(|f| f.index() as u32)
                .collect();
            buffer.sees(projected[v.index()], TOLERANCE, |f| around.contains(&f))
        };
        let kind = crate::invariants::MeshKind::of(map);
        let mut balls: Vec<Ball> = singularities(map)
            .into_iter()
            .filter_map(|(vertex, valence)| {
                Some(Ball {
                    vertex,
                    valence,
                    colour: ball_colour(kind, valence)?,
                    centre: projected[vertex.index()],
                    visible: sees(vertex),
                })
            })
            .collect();
        balls.sort_by(|a, b| b.centre.z.total_cmp(&a.centre.z));
        let mut polylines = seen_runs(options.paths.iter().map(|path| {
            // Every entry was checked to be a live vertex (below u32::MAX).
            path.iter()
                .map(|&v| Vert::new(v as u32))
                .map(|v| (projected[v.index()], sees(v)))
                .collect()
        }));
        polylines.extend(seen_runs(points.iter().map(|path| {
            path.iter()
                .map(|&p| camera.project(p))
                .map(|q| (q, buffer.sees(q, TOLERANCE, |_| false)))
                .collect()
        })));
        Ok(Scene {
            width,
            height,
            camera,
            faces,
            total_faces: map.num_faces(),
            balls,
            polylines,
            radius,
            stroke,
            legend: options.legend,
        })
    }

    /// The picture's size in pixels.
    ///
    /// ```
    /// use zipmesh::{gen, render::{Options, Scene}};
    /// let o = Options { width: 300, height: 200, ..Options::default() };
    /// assert_eq!(Scene::new(&gen::cube(1), &o).unwrap().size(), (300, 200));
    /// ```
    pub fn size(&self) -> (u32, u32) {
        (self.width, self.height)
    }

    /// The camera (its view, scale and projection).
    ///
    /// ```
    /// use zipmesh::{gen, render::{Options, Scene}};
    /// let scene = Scene::new(&gen::cube(1), &Options::default()).unwrap();
    /// assert_eq!(scene.camera().view().azimuth, 30.0); // the default view of a cube
    /// ```
    pub fn camera(&self) -> &Camera {
        &self.camera
    }

    /// The faces drawn (those seen somewhere), far to near.
    ///
    /// ```
    /// use zipmesh::{gen, render::{Options, Scene}};
    /// let scene = Scene::new(&gen::cube(1), &Options::default()).unwrap();
    /// assert!(scene.faces().len() >= 3); // three sides of a cube face a generic eye
    /// assert!(scene.faces().windows(2).all(|w| w[0].depth >= w[1].depth));
    /// ```
    pub fn faces(&self) -> &[DrawnFace] {
        &self.faces
    }

    /// The number of faces of the mesh, drawn or not.
    ///
    /// ```
    /// use zipmesh::{gen, render::{Options, Scene}};
    /// let scene = Scene::new(&gen::cube(2), &Options::default()).unwrap();
    /// assert_eq!(scene.total_faces(), 24);
    /// ```
    pub fn total_faces(&self) -> usize {
        self.total_faces
    }

    /// Every interior singularity, far to near; those with `visible` are drawn.
    ///
    /// ```
    /// use zipmesh::{gen, render::{Options, Scene}};
    /// let scene = Scene::new(&gen::icosahedron(), &Options::default()).unwrap();
    /// assert_eq!(scene.balls().len(), 12); // triangle mesh: twelve v5s
    /// assert!(scene.balls().iter().all(|b| b.valence == 5));
    /// ```
    pub fn balls(&self) -> &[Ball] {
        &self.balls
    }

    /// The seen stretches of the paths (runs of consecutive seen vertices, at least two),
    /// in picture coordinates.
    ///
    /// ```
    /// use zipmesh::{gen, render::{Options, Scene}};
    /// // Vertex 0, the corner (0, 0, 0), is hidden from the default view: no seen stretch.
    /// let o = Options { paths: vec![vec![0, 1]], ..Options::default() };
    /// assert!(Scene::new(&gen::cube(1), &o).unwrap().polylines().is_empty());
    /// ```
    pub fn polylines(&self) -> &[Vec<[f64; 2]>] {
        &self.polylines
    }

    /// The balls' radius in pixels (from the median edge length on the picture).
    ///
    /// ```
    /// use zipmesh::{gen, render::{Options, Scene}};
    /// let r = Scene::new(&gen::cube(8), &Options::default()).unwrap().radius();
    /// assert!((2.0..=9.6).contains(&r));
    /// ```
    pub fn radius(&self) -> f64 {
        self.radius
    }

    /// The picture as SVG text: one `<circle class="vK" data-vertex="N">` per seen ball,
    /// one `<polyline class="path">` per seen path stretch, and the legend (a `<circle
    /// class="legend">` per row) unless [`Options::legend`] is off.
    ///
    /// ```
    /// use zipmesh::{gen, render::{Options, Scene}};
    /// let svg = Scene::new(&gen::cube(1), &Options::default()).unwrap().svg();
    /// assert!(svg.starts_with("<?xml") && svg.trim_end().ends_with("</svg>"));
    /// assert_eq!(svg.matches("<circle class=\"v3\"").count(), 7); // the cube's seen corners
    /// assert_eq!(svg.matches("<circle class=\"legend\"").count(), 1); // v3: 8
    /// ```
    pub fn svg(&self) -> String {
        svg::write(self)
    }

    /// The picture as PNG bytes: the SVG of [`Scene::svg`] rasterised by resvg.
    ///
    /// ```
    /// use zipmesh::{gen, render::{Options, RenderError, Scene}};
    /// let big = Options { width: 16384, height: 16384, ..Options::default() };
    /// let scene = Scene::new(&gen::cube(1), &big).unwrap(); // fine as SVG
    /// assert!(matches!(scene.png(), Err(RenderError::PngSize { .. })));
    /// ```
    pub fn png(&self) -> Result<Vec<u8>, RenderError> {
        png::rasterise(&self.svg(), self.width, self.height)
    }
}

/// The positions of the vertex slots, checked finite for every live vertex (dead slots
/// are set to the origin: nothing draws them), scaled by one common factor.
/// The live vertices' positions, scaled, and the factor they were divided by.
fn live_positions(mesh: &Mesh) -> Result<(Vec<DVec3>, f64), RenderError> {
    let map = &mesh.map;
    let mut p = vec![DVec3::ZERO; map.vertex_slots()];
    for v in map.vertices() {
        let i = v.index();
        match mesh.positions.get(i) {
            Some(q) if q.is_finite() => p[i] = *q,
            _ => return Err(RenderError::Position { vertex: i }),
        }
    }
    // Scaled into [-1, 1]^3 (the picture is fitted anyway), so that no difference or sum
    // of coordinates overflows, whatever finite positions the mesh has.
    let largest = p.iter().map(|q| q.abs().max_element()).fold(0.0, f64::max);
    let scale = if largest > 0.0 { largest } else { 1.0 };
    p.iter_mut().for_each(|q| *q /= scale);
    Ok((p, scale))
}

/// The point paths divided by the positions' `scale`; a point that is not finite (before or
/// after scaling) is an error.
fn scaled_points(paths: &[Vec<[f64; 3]>], scale: f64) -> Result<Vec<Vec<DVec3>>, RenderError> {
    paths
        .iter()
        .enumerate()
        .map(|(path, points)| {
            points
                .iter()
                .enumerate()
                .map(|(entry, &q)| {
                    let p = DVec3::from_array(q) / scale;
                    p.is_finite()
                        .then_some(p)
                        .ok_or(RenderError::PathPoint { path, entry })
                })
                .collect()
        })
        .collect()
}

fn check_paths(map: &Map, paths: &[Vec<u64>]) -> Result<(), RenderError> {
    for (path, vs) in paths.iter().enumerate() {
        for (entry, &vertex) in vs.iter().enumerate() {
            let live = u32::try_from(vertex)
                .ok()
                .is_some_and(|v| map.is_live_vertex(Vert::new(v)));
            if !live {
                return Err(RenderError::PathVertex {
                    path,
                    entry,
                    vertex,
                    slots: map.vertex_slots(),
                });
            }
        }
    }
    Ok(())
}

fn corners(map: &Map, f: Face) -> Vec<Vert> {
    map.face_darts(f).map(|d| map.origin(d)).collect()
}

/// The median length of the edges on the picture (1 pixel for a mesh without edges).
fn median_edge(map: &Map, projected: &[DVec3]) -> f64 {
    let mut lengths: Vec<f64> = map
        .faces()
        .flat_map(|f| map.face_darts(f))
        .map(|d| {
            let (a, b) = (
                projected[map.origin(d).index()],
                projected[map.dest(d).index()],
            );
            (a.truncate() - b.truncate()).length()
        })
        .collect();
    if lengths.is_empty() {
        return 1.0;
    }
    let mid = lengths.len() / 2;
    *lengths.select_nth_unstable_by(mid, f64::total_cmp).1
}

/// The faces to draw, far to near, with their shades: those nearest at some buffer pixel,
/// and those too small to own one whose centre is seen.
fn seen_faces(
    map: &Map,
    positions: &[DVec3],
    projected: &[DVec3],
    camera: &Camera,
    buffer: &DepthBuffer,
) -> Vec<DrawnFace> {
    let owned = buffer.pixels_per_face(map.face_slots());
    let light = camera.light();
    let mut faces: Vec<DrawnFace> = map
        .faces()
        .filter_map(|f| {
            let c = corners(map, f);
            let n = c.len().max(1) as f64;
            let centre = c.iter().map(|v| projected[v.index()]).sum::<DVec3>() / n;
            let seen =
                owned[f.index()] > 0 || buffer.sees(centre, TOLERANCE, |g| g == f.index() as u32);
            seen.then(|| DrawnFace {
                face: f,
                corners: c
                    .iter()
                    .map(|v| projected[v.index()].truncate().to_array())
                    .collect(),
                fill: shade(&c, positions, camera.toward_eye(), light),
                depth: centre.z,
                folded: !convex(c.iter().map(|v| projected[v.index()])),
            })
        })
        .collect();
    faces.sort_by(|a, b| b.depth.total_cmp(&a.depth));
    faces
}

/// Whether the polygon turns the same way at every corner on the picture (a triangle always
/// does, unless degenerate, which is drawn as it is anyway).
fn convex(corners: impl Iterator<Item = DVec3>) -> bool {
    let p: Vec<DVec3> = corners.collect();
    let n = p.len();
    if n <= 3 {
        return true;
    }
    let turn = |i: usize| {
        let (a, b, c) = (p[i], p[(i + 1) % n], p[(i + 2) % n]);
        (b.x - a.x) * (c.y - b.y) - (b.y - a.y) * (c.x - b.x)
    };
    let turns: Vec<f64> = (0..n).map(turn).collect();
    turns.iter().all(|&t| t >= 0.0) || turns.iter().all(|&t| t <= 0.0)
}

/// Flat Lambert shading, two-sided: front faces light grey, back faces (seen through a
/// hole or an open boundary) light blue-grey.
fn shade(corners: &[Vert], positions: &[DVec3], toward_eye: DVec3, light: DVec3) -> [u8; 3] {
    // Newell's normal: the polygon's area vector, also for non-planar quads.
    let mut n = DVec3::ZERO;
    for (i, a) in corners.iter().enumerate() {
        let (p, q) = (
            positions[a.index()],
            positions[corners[(i + 1) % corners.len()].index()],
        );
        n += p.cross(q);
    }
    let n = n.normalize_or_zero();
    let lambert = if n == DVec3::ZERO {
        0.5
    } else {
        n.dot(light).abs()
    };
    let base = if n.dot(toward_eye) < 0.0 {
        [0.72, 0.76, 0.86]
    } else {
        [0.88, 0.88, 0.86]
    };
    let k = 0.3 + 0.7 * lambert;
    base.map(|b| (b * k * 255.0).round().clamp(0.0, 255.0) as u8)
}

/// The stretches of the paths (projected points, each with whether it is seen) whose
/// consecutive points are both seen, two points at least.
fn seen_runs(paths: impl Iterator<Item = Vec<(DVec3, bool)>>) -> Vec<Vec<[f64; 2]>> {
    let mut runs = Vec::new();
    for path in paths {
        let mut run: Vec<[f64; 2]> = Vec::new();
        for (p, seen) in path {
            if seen {
                run.push(p.truncate().to_array());
            } else if run.len() >= 2 {
                runs.push(core::mem::take(&mut run));
            } else {
                run.clear();
            }
        }
        if run.len() >= 2 {
            runs.push(run);
        }
    }
    runs
}
