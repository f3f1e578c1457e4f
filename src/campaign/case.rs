//! Cases: the meshes a campaign checks, made deterministically from a seed and an index.

use crate::gen;
use crate::map::{Dart, Vert};
use crate::mesh::Mesh;
use crate::rng::Rng;
use alloc::format;
use alloc::string::String;
use alloc::vec::Vec;
use glam::DVec3;

/// The face kind a generated case was asked for.
///
/// ```
/// use zipmesh::campaign::{Case, Kind};
/// let kinds: Vec<Kind> = (0..30).map(|i| Case::generate(1, i, 400).kind().unwrap()).collect();
/// assert!(kinds.contains(&Kind::Quad) && kinds.contains(&Kind::Triangle) && kinds.contains(&Kind::Mixed));
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Kind {
    /// Every face a quad.
    Quad,
    /// Every face a triangle.
    Triangle,
    /// Quad-dominant: mostly quads, some triangles (and, from the random generator, pentagons).
    Mixed,
}

impl Kind {
    /// The lower-case name used in descriptions (`quad`, `triangle`, `mixed`).
    ///
    /// ```
    /// assert_eq!(zipmesh::campaign::Kind::Mixed.name(), "mixed");
    /// ```
    pub fn name(self) -> &'static str {
        match self {
            Kind::Quad => "quad",
            Kind::Triangle => "triangle",
            Kind::Mixed => "mixed",
        }
    }
}

/// Where a case's mesh came from.
///
/// ```
/// use zipmesh::campaign::{Case, Origin};
/// let case = Case::generate(3, 0, 300);
/// assert!(matches!(case.origin, Origin::Generated { .. }));
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Origin {
    /// Made by [`Case::generate`]: the generator, the face kind, and the topology it was asked
    /// for (every generator used makes exactly that genus and number of boundary loops, one
    /// component).
    Generated {
        /// `random`, `grid`, `torus` or `cube`.
        shape: &'static str,
        /// The face kind asked for.
        kind: Kind,
        /// The genus asked for.
        genus: usize,
        /// The number of boundary loops asked for.
        holes: usize,
        /// The number of faces asked for (the generators' sizes are approximate).
        faces: usize,
    },
    /// Given by the caller (a file name or any label).
    Given(String),
}

/// One mesh to check, with what a property needs to make its random choices reproducibly.
///
/// A case depends only on its `seed` and `index` (and the face budget it was generated
/// with), never on which thread runs it or when: that is what makes campaigns
/// deterministic for any number of jobs.
///
/// ```
/// use zipmesh::campaign::Case;
/// let a = Case::generate(42, 7, 500);
/// let b = Case::generate(42, 7, 500);
/// assert_eq!(a.mesh.map, b.mesh.map);
/// assert_eq!(a.sites(5), b.sites(5));
/// ```
#[derive(Clone, Debug)]
pub struct Case {
    /// The campaign seed.
    pub seed: u64,
    /// The case number within the campaign (0 for a shrunk counterexample).
    pub index: u64,
    /// The mesh.
    pub mesh: Mesh,
    /// Where the mesh came from.
    pub origin: Origin,
    /// A vertex to look at first: [`Case::sites`] starts with its darts. Set when a
    /// counterexample is shrunk or replayed, so that the property edits the same place.
    pub focus: Option<Vert>,
}

/// SplitMix64's finalizer, to derive independent streams from (seed, index, salt).
fn mix(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

fn stream(seed: u64, index: u64, salt: u64) -> Rng {
    Rng::new(mix(
        mix(seed ^ salt).wrapping_add(index.wrapping_mul(0x9e37_79b9_7f4a_7c15))
    ))
}

/// The largest face count the random generators can exceed for these arguments: the
/// documented bound `T + T / 8 + 64` with `T = 64 (genus + holes) + 256`, doubled for
/// triangles.
fn random_max(kind: Kind, genus: usize, holes: usize) -> usize {
    let t = 64 * (genus + holes) + 256;
    let quads = t + t / 8 + 64;
    match kind {
        Kind::Triangle => 2 * quads,
        _ => quads,
    }
}

impl Case {
    /// Case `index` of the campaign with this `seed`: a quad, triangle or quad-dominant mesh
    /// of at most about `max_faces` faces, with a random genus (0 to 2) and number of
    /// boundary loops (0 to 2).
    ///
    /// Three cases in four use the random generators ([`gen::random_quad`],
    /// [`gen::random_triangle`], [`gen::random_mixed`]) when their minimum size fits in
    /// `max_faces` (lowering genus and holes first); the others, and every case when the
    /// budget is too small, are regular meshes: a grid (disk), a torus grid or a cube, with
    /// random sides, triangulated along random diagonals for triangle cases and partly for
    /// mixed ones. The smallest case is a cube of 6 quads (12 triangles), whatever `max_faces`.
    ///
    /// ```
    /// use zipmesh::campaign::Case;
    /// for i in 0..20 {
    ///     let case = Case::generate(5, i, 64);
    ///     assert!(case.mesh.map.num_faces() <= 64);
    ///     assert_eq!(case.mesh.map.check(), Ok(()));
    /// }
    /// ```
    pub fn generate(seed: u64, index: u64, max_faces: usize) -> Case {
        let mut rng = stream(seed, index, 0x6361_7365);
        let kind = match rng.below(3) {
            0 => Kind::Quad,
            1 => Kind::Triangle,
            _ => Kind::Mixed,
        };
        let mut genus = rng.below(3);
        let mut holes = rng.below(3);
        let random = rng.below(4) != 0;
        while random_max(kind, genus, holes) > max_faces && genus + holes > 0 {
            if genus >= holes {
                genus -= 1;
            } else {
                holes -= 1;
            }
        }
        let (mesh, origin) = if random && random_max(kind, genus, holes) <= max_faces {
            let faces = rng.range(max_faces / 2, max_faces);
            let gen_seed = rng.next_u64();
            let mesh = match kind {
                Kind::Quad => gen::random_quad(faces, genus, holes, gen_seed),
                Kind::Triangle => gen::random_triangle(faces, genus, holes, gen_seed),
                Kind::Mixed => gen::random_mixed(faces, genus, holes, gen_seed),
            };
            let origin = Origin::Generated {
                shape: "random",
                kind,
                genus,
                holes,
                faces,
            };
            (mesh, origin)
        } else {
            regular(kind, max_faces, &mut rng)
        };
        Case {
            seed,
            index,
            mesh,
            origin,
            focus: None,
        }
    }

    /// A case for a mesh the caller provides; `label` names it in reports (a file name).
    ///
    /// ```
    /// use zipmesh::{campaign::Case, gen};
    /// let case = Case::from_mesh(gen::cube(2), 9, 0, "cube");
    /// assert_eq!(case.intended_topology(), None);
    /// assert_eq!(case.describe(), "cube");
    /// ```
    pub fn from_mesh(mesh: Mesh, seed: u64, index: u64, label: impl Into<String>) -> Case {
        Case {
            seed,
            index,
            mesh,
            origin: Origin::Given(label.into()),
            focus: None,
        }
    }

    /// The face kind a generated case was asked for (`None` for given meshes).
    ///
    /// ```
    /// use zipmesh::{campaign::Case, gen};
    /// assert!(Case::generate(1, 1, 300).kind().is_some());
    /// assert!(Case::from_mesh(gen::cube(1), 0, 0, "c").kind().is_none());
    /// ```
    pub fn kind(&self) -> Option<Kind> {
        match self.origin {
            Origin::Generated { kind, .. } => Some(kind),
            Origin::Given(_) => None,
        }
    }

    /// `(genus, boundary loops)` that the generator was asked for, for generated cases.
    ///
    /// ```
    /// use zipmesh::{campaign::Case, invariants::Counts};
    /// let case = Case::generate(2, 3, 800);
    /// let (g, h) = case.intended_topology().unwrap();
    /// let c = Counts::of(&case.mesh.map);
    /// assert_eq!((c.genus, c.boundary_loops), (g as i64, h));
    /// ```
    pub fn intended_topology(&self) -> Option<(usize, usize)> {
        match self.origin {
            Origin::Generated { genus, holes, .. } => Some((genus, holes)),
            Origin::Given(_) => None,
        }
    }

    /// A random generator for this case's choices: the same for the same `seed`, `index`
    /// and `salt`. Properties pass their own salt so that they do not all pick the same darts.
    ///
    /// ```
    /// use zipmesh::campaign::Case;
    /// let case = Case::generate(1, 2, 300);
    /// assert_eq!(case.rng(7).next_u64(), case.rng(7).next_u64());
    /// assert_ne!(case.rng(7).next_u64(), case.rng(8).next_u64());
    /// ```
    pub fn rng(&self, salt: u64) -> Rng {
        stream(self.seed, self.index, salt ^ 0x7369_7465)
    }

    /// Up to `n` live darts to try an edit at: the darts leaving [`Case::focus`] and their
    /// twins first (when set and live), then random live darts (repeats possible), all
    /// reproducible from the case. Empty when the map has no darts.
    ///
    /// ```
    /// use zipmesh::{campaign::Case, gen, Vert};
    /// let mut case = Case::from_mesh(gen::grid(3, 3), 1, 0, "grid");
    /// case.focus = Some(Vert::new(5));
    /// let sites = case.sites(10);
    /// assert_eq!(sites.len(), 10);
    /// assert_eq!(case.mesh.map.origin(sites[0]), Vert::new(5));
    /// ```
    pub fn sites(&self, n: usize) -> Vec<Dart> {
        self.sites_salted(n, 0)
    }

    /// [`Case::sites`] with the random part drawn from [`Case::rng`]`(salt)`.
    ///
    /// ```
    /// use zipmesh::campaign::Case;
    /// let case = Case::generate(4, 4, 300);
    /// assert_eq!(case.sites_salted(6, 3), case.sites_salted(6, 3));
    /// ```
    pub fn sites_salted(&self, n: usize, salt: u64) -> Vec<Dart> {
        let map = &self.mesh.map;
        let mut out = Vec::with_capacity(n);
        if let Some(v) = self.focus.filter(|&v| map.is_live_vertex(v)) {
            let around: Vec<Dart> = map.vertex_darts(v).collect();
            out.extend(around.iter().copied().take(n));
            let room = n - out.len();
            out.extend(around.iter().map(|d| d.twin()).take(room));
        }
        if map.num_darts() == 0 {
            return out;
        }
        let mut rng = self.rng(salt);
        let slots = map.dart_slots();
        // Dead slots are skipped; a bounded number of draws keeps this total on sparse maps.
        let mut draws = 0;
        while out.len() < n && draws < 64 * n + 64 {
            draws += 1;
            let d = Dart::new(rng.below(slots) as u32);
            if map.is_live_dart(d) {
                out.push(d);
            }
        }
        out
    }

    /// A one-line description: the origin, the counts and the seed and index.
    ///
    /// ```
    /// use zipmesh::campaign::Case;
    /// let text = Case::generate(1, 4, 300).describe();
    /// assert!(text.contains("F="));
    /// ```
    pub fn describe(&self) -> String {
        let map = &self.mesh.map;
        let counts = format!(
            "V={} E={} F={}",
            map.num_vertices(),
            map.num_edges(),
            map.num_faces()
        );
        match &self.origin {
            Origin::Generated {
                shape,
                kind,
                genus,
                holes,
                ..
            } => format!(
                "{shape} {} mesh, genus {genus}, {holes} boundary loops, {counts} (seed {}, case {})",
                kind.name(),
                self.seed,
                self.index
            ),
            Origin::Given(label) => label.clone(),
        }
    }
}

/// A regular mesh (grid, torus or cube) of at most `max_faces` faces where possible.
fn regular(kind: Kind, max_faces: usize, rng: &mut Rng) -> (Mesh, Origin) {
    // A split quad is two faces, so triangle and mixed budgets halve.
    let budget = match kind {
        Kind::Quad => max_faces,
        _ => max_faces / 2,
    }
    .max(6);
    // Pick a shape that fits: a grid needs 1 quad, a torus 9, a cube 6.
    let shape = match rng.below(3) {
        1 if budget >= 9 => 1,
        2 => 2,
        0 => 0,
        _ => 2,
    };
    let (quads_mesh, name, genus, holes) = match shape {
        0 => {
            let nx = rng.range(1, isqrt(budget).max(1) * 2).min(budget);
            let ny = rng.range(1, (budget / nx).max(1));
            // A mixed mesh needs two quads: one to split, one to keep.
            let nx = if kind == Kind::Mixed && nx * ny < 2 {
                2
            } else {
                nx
            };
            (gen::grid(nx, ny), "grid", 0, 1)
        }
        1 => {
            let nx = rng.range(3, (budget / 3).clamp(3, 3 * isqrt(budget).max(3)));
            let ny = rng.range(3, (budget / nx).max(3));
            (gen::torus_grid(nx, ny), "torus", 1, 0)
        }
        _ => {
            let n = rng.range(1, isqrt(budget / 6).max(1));
            (gen::cube(n), "cube", 0, 0)
        }
    };
    let mesh = match kind {
        Kind::Quad => quads_mesh,
        Kind::Triangle => split_quads(&quads_mesh, rng, 1, 1),
        Kind::Mixed => split_quads(&quads_mesh, rng, 1, 4),
    };
    let faces = mesh.map.num_faces();
    let origin = Origin::Generated {
        shape: name,
        kind,
        genus,
        holes,
        faces,
    };
    (mesh, origin)
}

fn isqrt(n: usize) -> usize {
    let mut r = 0;
    while (r + 1) * (r + 1) <= n {
        r += 1;
    }
    r
}

/// Splits each quad along a random diagonal with probability `num / den`. At least one quad
/// is split, and when `num < den` at least one other is kept, so that a mixed mesh of two
/// quads or more has both triangles and quads.
fn split_quads(mesh: &Mesh, rng: &mut Rng, num: usize, den: usize) -> Mesh {
    let polys = mesh.polygons();
    let n = polys.len().max(1);
    let forced = rng.below(n);
    let kept = (num < den && n >= 2).then(|| (forced + 1 + rng.below(n - 1)) % n);
    let mut out: Vec<Vec<u32>> = Vec::with_capacity(2 * polys.len());
    for (i, p) in polys.iter().enumerate() {
        let split = i == forced || (Some(i) != kept && rng.chance(num, den));
        if p.len() == 4 && split {
            let r = rng.below(2);
            let q = [p[r], p[r + 1], p[r + 2], p[(r + 3) % 4]];
            out.push(alloc::vec![q[0], q[1], q[2]]);
            out.push(alloc::vec![q[0], q[2], q[3]]);
        } else {
            out.push(p.clone());
        }
    }
    let positions: Vec<DVec3> = mesh.positions.clone();
    match Mesh::from_polygons(positions, &out) {
        Ok((m, _)) => m,
        // Splitting a quad of a valid mesh along a diagonal keeps it valid unless the two
        // ends of the diagonal are already joined (a 3 x n torus can have that); keep quads.
        Err(_) => mesh.clone(),
    }
}
