//! A depth buffer of the mesh's faces: which triangle is nearest the eye at each pixel, and
//! from that whether a point on the surface (a singularity, a path vertex, a face's centre)
//! is seen.
//!
//! Written by hand because the picture's rasteriser (resvg) paints colours, not depths, and
//! all that is needed here is the nearest triangle per pixel centre: edge functions over each
//! triangle's bounding box.

use alloc::vec;
use alloc::vec::Vec;
use glam::DVec3;

/// No triangle covers the pixel.
const EMPTY: u32 = u32::MAX;

/// The nearest triangle at each pixel centre.
///
/// Triangles are given in picture coordinates (see [`Camera::project`](super::Camera::project));
/// the buffer may be coarser than the picture (`resolution` pixels of the buffer per pixel of
/// the picture) so that a huge picture does not need a huge buffer.
///
/// ```
/// use glam::DVec3;
/// use zipmesh::render::DepthBuffer;
/// let mut buf = DepthBuffer::new(10, 10, 1.0);
/// let t = |z| [DVec3::new(0.0, 0.0, z), DVec3::new(10.0, 0.0, z), DVec3::new(0.0, 10.0, z)];
/// buf.add_triangle(t(5.0), 0);
/// buf.add_triangle(t(1.0), 1); // nearer: wins
/// assert_eq!(buf.nearest_face(1.0, 1.0), Some(1));
/// assert!(buf.sees(DVec3::new(1.0, 1.0, 1.0), 0.5, |_| false));
/// assert!(!buf.sees(DVec3::new(1.0, 1.0, 5.0), 0.5, |_| false)); // behind face 1
/// assert!(buf.sees(DVec3::new(1.0, 1.0, 5.0), 0.5, |f| f == 1)); // unless it is on face 1
/// assert!(buf.sees(DVec3::new(9.0, 9.0, 5.0), 0.5, |_| false)); // nothing covers it
/// ```
#[derive(Clone, Debug)]
pub struct DepthBuffer {
    width: usize,
    height: usize,
    resolution: f64,
    depth: Vec<f32>,
    owner: Vec<u32>,
    triangles: Vec<([DVec3; 3], u32)>,
}

impl DepthBuffer {
    /// An empty buffer for a picture of `width` x `height` pixels, with `resolution` buffer
    /// pixels per picture pixel (1 for full resolution; at most 1).
    ///
    /// ```
    /// use zipmesh::render::DepthBuffer;
    /// let buf = DepthBuffer::new(4000, 10, 0.5); // a 2000 x 5 buffer
    /// assert_eq!(buf.nearest_face(3000.0, 5.0), None);
    /// ```
    pub fn new(width: u32, height: u32, resolution: f64) -> DepthBuffer {
        let resolution = if resolution > 0.0 && resolution <= 1.0 {
            resolution
        } else {
            1.0
        };
        let side = |n: u32| ((f64::from(n) * resolution).ceil() as usize).max(1);
        let (w, h) = (side(width), side(height));
        DepthBuffer {
            width: w,
            height: h,
            resolution,
            depth: vec![f32::INFINITY; w * h],
            owner: vec![EMPTY; w * h],
            triangles: Vec::new(),
        }
    }

    /// Draws one triangle of face `face` (any number the caller chooses): at every pixel
    /// centre it covers where it is nearer than what is there, it becomes the owner.
    /// Degenerate triangles (no area on the picture) cover nothing.
    ///
    /// ```
    /// use glam::DVec3;
    /// use zipmesh::render::DepthBuffer;
    /// let mut buf = DepthBuffer::new(8, 8, 1.0);
    /// let t = [DVec3::new(0.0, 0.0, 1.0), DVec3::new(8.0, 0.0, 1.0), DVec3::new(0.0, 8.0, 1.0)];
    /// buf.add_triangle(t, 7);
    /// assert_eq!(buf.nearest_face(1.0, 1.0), Some(7));
    /// assert_eq!(buf.nearest_face(7.0, 7.0), None); // outside the triangle
    /// ```
    pub fn add_triangle(&mut self, tri: [DVec3; 3], face: u32) {
        let id = self.triangles.len() as u32;
        let k = self.resolution;
        let p = tri.map(|q| DVec3::new(q.x * k, q.y * k, q.z));
        self.triangles.push((tri, face));
        let area = edge(p[0], p[1], p[2]);
        if !area.is_finite() || area.abs() < 1e-12 {
            return;
        }
        let (lo, hi) = bounds(&p);
        let clamp = |v: f64, n: usize| v.clamp(0.0, n as f64) as usize;
        let (x0, x1) = (clamp(lo.x - 0.5, self.width), clamp(hi.x + 0.5, self.width));
        let (y0, y1) = (
            clamp(lo.y - 0.5, self.height),
            clamp(hi.y + 0.5, self.height),
        );
        for y in y0..y1 {
            for x in x0..x1 {
                let c = DVec3::new(x as f64 + 0.5, y as f64 + 0.5, 0.0);
                let w = [
                    edge(p[1], p[2], c),
                    edge(p[2], p[0], c),
                    edge(p[0], p[1], c),
                ];
                let inside = if area > 0.0 {
                    w.iter().all(|&a| a >= 0.0)
                } else {
                    w.iter().all(|&a| a <= 0.0)
                };
                if !inside {
                    continue;
                }
                let z = ((w[0] * p[0].z + w[1] * p[1].z + w[2] * p[2].z) / area) as f32;
                let i = y * self.width + x;
                if z < self.depth[i] {
                    self.depth[i] = z;
                    self.owner[i] = id;
                }
            }
        }
    }

    /// The buffer pixel under picture point `(x, y)`, if it is in the buffer.
    fn pixel(&self, x: f64, y: f64) -> Option<usize> {
        let (bx, by) = (x * self.resolution, y * self.resolution);
        if !(bx >= 0.0 && by >= 0.0) {
            return None;
        }
        let (px, py) = (bx as usize, by as usize);
        (px < self.width && py < self.height).then_some(py * self.width + px)
    }

    /// The face of the nearest triangle at the pixel under picture point `(x, y)`.
    ///
    /// ```
    /// let buf = zipmesh::render::DepthBuffer::new(8, 8, 1.0);
    /// assert_eq!(buf.nearest_face(-1.0, 2.0), None); // outside the picture
    /// ```
    pub fn nearest_face(&self, x: f64, y: f64) -> Option<u32> {
        let owner = *self.owner.get(self.pixel(x, y)?)?;
        self.triangles.get(owner as usize).map(|t| t.1)
    }

    /// Whether the surface point `p` (picture coordinates and depth) is seen: nothing covers
    /// its pixel, or the nearest triangle there belongs to a face for which `on(face)` holds
    /// (a face `p` lies on), or that triangle's plane, taken at `p`'s exact position, is not
    /// nearer than `p` by more than `tolerance` pixels.
    ///
    /// ```
    /// use glam::DVec3;
    /// use zipmesh::render::DepthBuffer;
    /// let mut buf = DepthBuffer::new(8, 8, 1.0);
    /// let t = [DVec3::new(0.0, 0.0, 1.0), DVec3::new(8.0, 0.0, 1.0), DVec3::new(0.0, 8.0, 1.0)];
    /// buf.add_triangle(t, 0);
    /// assert!(buf.sees(DVec3::new(2.0, 2.0, 1.5), 1.0, |_| false)); // within the tolerance
    /// assert!(!buf.sees(DVec3::new(2.0, 2.0, 3.0), 1.0, |_| false));
    /// ```
    pub fn sees(&self, p: DVec3, tolerance: f64, on: impl Fn(u32) -> bool) -> bool {
        let Some(i) = self.pixel(p.x, p.y) else {
            return true;
        };
        let Some(&(tri, face)) = self.triangles.get(self.owner[i] as usize) else {
            return true;
        };
        if on(face) {
            return true;
        }
        match plane_depth(tri, p.x, p.y) {
            Some(z) => z >= p.z - tolerance,
            None => true,
        }
    }

    /// For each face number below `faces`, how many buffer pixels it owns.
    ///
    /// ```
    /// use glam::DVec3;
    /// use zipmesh::render::DepthBuffer;
    /// let mut buf = DepthBuffer::new(8, 8, 1.0);
    /// let t = [DVec3::new(0.0, 0.0, 1.0), DVec3::new(8.0, 0.0, 1.0), DVec3::new(0.0, 8.0, 1.0)];
    /// buf.add_triangle(t, 1);
    /// let owned = buf.pixels_per_face(2);
    /// assert_eq!(owned[0], 0);
    /// assert!(owned[1] >= 28 && owned[1] <= 36); // about half of the 64 pixels
    /// ```
    pub fn pixels_per_face(&self, faces: usize) -> Vec<usize> {
        let mut count = vec![0; faces];
        for &o in &self.owner {
            if let Some(&(_, f)) = self.triangles.get(o as usize) {
                if let Some(c) = count.get_mut(f as usize) {
                    *c += 1;
                }
            }
        }
        count
    }
}

/// Twice the signed area of `a, b, c` on the picture.
fn edge(a: DVec3, b: DVec3, c: DVec3) -> f64 {
    (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x)
}

fn bounds(p: &[DVec3; 3]) -> (DVec3, DVec3) {
    (p[0].min(p[1]).min(p[2]), p[0].max(p[1]).max(p[2]))
}

/// The depth of the triangle's plane at picture point `(x, y)`.
fn plane_depth(t: [DVec3; 3], x: f64, y: f64) -> Option<f64> {
    let area = edge(t[0], t[1], t[2]);
    if !area.is_finite() || area.abs() < 1e-12 {
        return None;
    }
    let c = DVec3::new(x, y, 0.0);
    let w = [
        edge(t[1], t[2], c),
        edge(t[2], t[0], c),
        edge(t[0], t[1], c),
    ];
    Some((w[0] * t[0].z + w[1] * t[1].z + w[2] * t[2].z) / area)
}
