//! The view (azimuth and elevation, in degrees) and the orthographic camera that fits a mesh
//! into the picture.
//!
//! Conventions: `+Y` is up. The azimuth turns the eye about `+Y`, from `+Z` (azimuth 0)
//! toward `+X` (azimuth 90); the elevation raises it from the `XZ` plane toward `+Y`
//! (90: seen from straight above). Picture coordinates are pixels, `x` to the right, `y`
//! down (as in SVG); depth grows away from the eye, in the same pixel units.

use super::RenderError;
use glam::DVec3;

/// Where the eye is, seen from the centre of the mesh: azimuth and elevation in degrees.
///
/// ```
/// use zipmesh::render::View;
/// let v = View::new(0.0, 0.0).unwrap();
/// assert!((v.toward_eye() - glam::DVec3::Z).length() < 1e-12);
/// assert!(View::new(0.0, 91.0).is_err());
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct View {
    /// Degrees about `+Y`, from `+Z` toward `+X`.
    pub azimuth: f64,
    /// Degrees above the `XZ` plane, in `[-90, 90]`.
    pub elevation: f64,
}

impl View {
    /// A view, refused ([`RenderError::View`]) unless both angles are finite and the
    /// elevation is within `[-90, 90]`.
    ///
    /// ```
    /// assert!(zipmesh::render::View::new(f64::NAN, 0.0).is_err());
    /// ```
    pub fn new(azimuth: f64, elevation: f64) -> Result<View, RenderError> {
        if !azimuth.is_finite() || !elevation.is_finite() || elevation.abs() > 90.0 {
            return Err(RenderError::View { azimuth, elevation });
        }
        Ok(View { azimuth, elevation })
    }

    /// The default view of a bounding box `lo..hi`: a three-quarter view (30 degrees to the
    /// side, 20 degrees above) of the box's two largest extents, so the thinnest axis points
    /// roughly at the eye. Thinnest `Z` (or a tie): azimuth 30, elevation 20; thinnest `X`:
    /// azimuth 60, elevation 20; thinnest `Y`: azimuth 30, elevation 70 (seen from above).
    ///
    /// ```
    /// use glam::DVec3;
    /// use zipmesh::render::View;
    /// let flat_on_xz = View::fitting(DVec3::ZERO, DVec3::new(4.0, 0.1, 3.0));
    /// assert_eq!((flat_on_xz.azimuth, flat_on_xz.elevation), (30.0, 70.0));
    /// let cube = View::fitting(DVec3::ZERO, DVec3::ONE);
    /// assert_eq!((cube.azimuth, cube.elevation), (30.0, 20.0));
    /// ```
    pub fn fitting(lo: DVec3, hi: DVec3) -> View {
        let e = hi - lo;
        let (azimuth, elevation) = if e.z <= e.x && e.z <= e.y {
            (30.0, 20.0)
        } else if e.x <= e.y {
            (60.0, 20.0)
        } else {
            (30.0, 70.0)
        };
        View { azimuth, elevation }
    }

    /// The unit vector from the mesh toward the eye.
    ///
    /// ```
    /// let up = zipmesh::render::View::new(10.0, 90.0).unwrap().toward_eye();
    /// assert!((up - glam::DVec3::Y).length() < 1e-12);
    /// ```
    pub fn toward_eye(&self) -> DVec3 {
        let (az, el) = (self.azimuth.to_radians(), self.elevation.to_radians());
        DVec3::new(el.cos() * az.sin(), el.sin(), el.cos() * az.cos())
    }

    /// The picture's right direction: horizontal, and defined at every elevation (also
    /// straight above or below, where the eye's up would be undefined).
    fn right(&self) -> DVec3 {
        let az = self.azimuth.to_radians();
        DVec3::new(az.cos(), 0.0, -az.sin())
    }
}

/// An orthographic camera: the view, and the scale and offset that fit the mesh into the
/// picture with a margin.
///
/// ```
/// use glam::DVec3;
/// use zipmesh::render::{Camera, View};
/// let view = View::new(0.0, 0.0).unwrap();
/// let points = [DVec3::new(-1.0, -1.0, 0.0), DVec3::new(1.0, 1.0, 0.0)];
/// let cam = Camera::fit(view, points.iter().copied(), 200, 100, 10.0);
/// let top_right = cam.project(DVec3::new(1.0, 1.0, 0.0));
/// assert!((top_right.x - 140.0).abs() < 1e-9 && (top_right.y - 10.0).abs() < 1e-9);
/// // Nearer the eye (+Z here) is a smaller depth.
/// assert!(cam.project(DVec3::Z).z < cam.project(DVec3::ZERO).z);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    view: View,
    right: DVec3,
    up: DVec3,
    toward_eye: DVec3,
    /// Pixels per model unit.
    scale: f64,
    /// The model point drawn at the centre of the picture.
    centre: DVec3,
    half: (f64, f64),
}

impl Camera {
    /// The camera of `view` that fits `points` into a `width` x `height` picture, leaving
    /// `margin` pixels on every side. No points, or points all in one spot, give scale 1
    /// about that spot.
    ///
    /// ```
    /// use glam::DVec3;
    /// use zipmesh::render::{Camera, View};
    /// let v = View::new(0.0, 0.0).unwrap();
    /// let cam = Camera::fit(v, [DVec3::ZERO, DVec3::ONE].into_iter(), 100, 100, 10.0);
    /// assert_eq!(cam.scale(), 80.0);
    /// assert_eq!(Camera::fit(v, [DVec3::ONE].into_iter(), 100, 100, 10.0).scale(), 1.0);
    /// ```
    pub fn fit(
        view: View,
        points: impl Iterator<Item = DVec3>,
        width: u32,
        height: u32,
        margin: f64,
    ) -> Camera {
        let toward_eye = view.toward_eye();
        let right = view.right();
        let up = toward_eye.cross(right);
        let mut lo = (f64::INFINITY, f64::INFINITY);
        let mut hi = (f64::NEG_INFINITY, f64::NEG_INFINITY);
        let mut depth = (f64::INFINITY, f64::NEG_INFINITY);
        for p in points {
            let (x, y) = (p.dot(right), p.dot(up));
            lo = (lo.0.min(x), lo.1.min(y));
            hi = (hi.0.max(x), hi.1.max(y));
            let d = p.dot(toward_eye);
            depth = (depth.0.min(d), depth.1.max(d));
        }
        let (w, h) = (f64::from(width), f64::from(height));
        let extent = (hi.0 - lo.0, hi.1 - lo.1);
        let room = ((w - 2.0 * margin).max(1.0), (h - 2.0 * margin).max(1.0));
        let scale = (room.0 / extent.0).min(room.1 / extent.1);
        let scale = if scale.is_finite() && scale > 0.0 {
            scale
        } else {
            1.0
        };
        let mid = |a: f64, b: f64| if a <= b { (a + b) / 2.0 } else { 0.0 };
        let centre =
            right * mid(lo.0, hi.0) + up * mid(lo.1, hi.1) + toward_eye * mid(depth.0, depth.1);
        Camera {
            view,
            right,
            up,
            toward_eye,
            scale,
            centre,
            half: (w / 2.0, h / 2.0),
        }
    }

    /// The view this camera looks from.
    ///
    /// ```
    /// use zipmesh::render::{Camera, View};
    /// let v = View::new(45.0, 10.0).unwrap();
    /// assert_eq!(Camera::fit(v, std::iter::empty(), 10, 10, 1.0).view(), v);
    /// ```
    pub fn view(&self) -> View {
        self.view
    }

    /// Pixels per model unit.
    ///
    /// ```
    /// use glam::DVec3;
    /// use zipmesh::render::{Camera, View};
    /// let v = View::new(0.0, 0.0).unwrap();
    /// let cam = Camera::fit(v, [DVec3::ZERO, DVec3::X].into_iter(), 120, 100, 10.0);
    /// assert_eq!(cam.scale(), 100.0);
    /// ```
    pub fn scale(&self) -> f64 {
        self.scale
    }

    /// The unit vector from the mesh toward the eye.
    ///
    /// ```
    /// use zipmesh::render::{Camera, View};
    /// let cam = Camera::fit(View::new(90.0, 0.0).unwrap(), std::iter::empty(), 8, 8, 0.0);
    /// assert!((cam.toward_eye() - glam::DVec3::X).length() < 1e-12);
    /// ```
    pub fn toward_eye(&self) -> DVec3 {
        self.toward_eye
    }

    /// The direction of the light, in model space: from the eye's upper left.
    ///
    /// ```
    /// use zipmesh::render::{Camera, View};
    /// let cam = Camera::fit(View::new(0.0, 0.0).unwrap(), std::iter::empty(), 8, 8, 0.0);
    /// let l = cam.light();
    /// assert!((l.length() - 1.0).abs() < 1e-12 && l.z > 0.0 && l.y > 0.0 && l.x < 0.0);
    /// ```
    pub fn light(&self) -> DVec3 {
        (self.toward_eye + 0.6 * self.up - 0.4 * self.right).normalize()
    }

    /// A model point in picture coordinates: `x` and `y` in pixels (y down), `z` the depth
    /// in pixels, growing away from the eye.
    ///
    /// ```
    /// use glam::DVec3;
    /// use zipmesh::render::{Camera, View};
    /// let cam = Camera::fit(View::new(0.0, 0.0).unwrap(), std::iter::empty(), 100, 50, 0.0);
    /// assert_eq!(cam.project(DVec3::ZERO), DVec3::new(50.0, 25.0, 0.0)); // the centre
    /// assert!(cam.project(DVec3::Y).y < 25.0); // up is toward the top
    /// ```
    pub fn project(&self, p: DVec3) -> DVec3 {
        let q = p - self.centre;
        DVec3::new(
            self.half.0 + q.dot(self.right) * self.scale,
            self.half.1 - q.dot(self.up) * self.scale,
            -q.dot(self.toward_eye) * self.scale,
        )
    }
}
