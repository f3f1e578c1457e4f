//! The score a batch decreases (Q-zip paper, Sec. 4.1, "Scoring strategy"): a weighted sum of
//! terms, each a [`ScoreTerm`], so that library users can add their own.
//!
//! Every term is a function of the whole mesh; a candidate Q-zip is scored by applying it,
//! scoring, and undoing it exactly. `docs/optimize.md` gives each formula.

use alloc::boxed::Box;
use alloc::vec;
use alloc::vec::Vec;

use glam::DVec3;

use super::defect::{singularities, Singularity};
use super::marks::Marks;
use crate::{Mesh, Vert};

/// A built-in term's `name` and `fork` (a clone for another thread), written once.
macro_rules! builtin_term {
    ($name:literal) => {
        fn name(&self) -> &str {
            $name
        }
        fn fork(&self) -> Option<alloc::boxed::Box<dyn super::ScoreTerm + Send>> {
            Some(alloc::boxed::Box::new(self.clone()))
        }
    };
}

/// The impl of a built-in quad term: the sum of `$value` over the scored quads, and the
/// value the scorer keeps per quad.
macro_rules! quad_term {
    ($term:ty, $name:literal, $value:path) => {
        impl ScoreTerm for $term {
            builtin_term!($name);
            fn score(&mut self, ctx: &Context<'_>) -> f64 {
                ctx.quad_sum($value)
            }
            fn quad_value(&self) -> Option<QuadValue> {
                Some($value)
            }
        }
    };
}

mod bfs;
mod budget;
mod count;
mod electric;
mod isotropy;
mod separatrix;
mod sizing;

pub(crate) use bfs::Bfs;
pub use budget::FaceBudget;
pub use count::Count;
pub use electric::{Electric, Potential};
pub use isotropy::Isotropy;
pub use separatrix::Separatrix;
pub use sizing::Sizing;

/// What a term may read: the mesh, its singularities, and what the run fixed at the start.
///
/// See [`ScoreTerm`] for an example.
#[derive(Debug)]
pub struct Context<'a> {
    /// The mesh being scored.
    pub mesh: &'a Mesh,
    /// Its vertices with a non-zero defect ([`super::singularities`]).
    pub singularities: &'a [Singularity],
    /// Whether a vertex (by index) lies on a sharp feature; shorter than the vertex slots
    /// means "no" for the rest.
    pub features: &'a [bool],
    /// The mean face area of the input: the size the sizing term aims for.
    pub target_area: f64,
    /// The input's face count (before preprocessing): what [`FaceBudget`] keeps.
    pub target_faces: usize,
    /// When set, the faces whose terms are summed (a window around a candidate);
    /// `singularities` is then the window's too.
    pub faces: Option<&'a [crate::Face]>,
    /// Whether the mesh may have boundary or feature vertices; `false` lets [`Electric`]
    /// skip its search for a wall (on a closed mesh without features it never finds one).
    pub walls: bool,
}

impl Context<'_> {
    fn position(&self, v: Vert) -> DVec3 {
        self.mesh
            .positions
            .get(v.index())
            .copied()
            .unwrap_or(DVec3::ZERO)
    }

    fn is_feature(&self, v: Vert) -> bool {
        self.features.get(v.index()).copied().unwrap_or(false)
    }

    /// The faces a face term sums over: the window's, or every face.
    pub fn scored_faces(&self) -> alloc::boxed::Box<dyn Iterator<Item = crate::Face> + '_> {
        match self.faces {
            Some(f) => alloc::boxed::Box::new(f.iter().copied()),
            None => alloc::boxed::Box::new(self.mesh.map.faces()),
        }
    }
    /// The sum of a quad term's `value` over the scored quads.
    fn quad_sum(&self, value: QuadValue) -> f64 {
        let mut total = 0.0;
        for f in self.scored_faces() {
            if let Some(c) = self.corners(f) {
                total += value(&c, self.target_area);
            }
        }
        total
    }

    fn corners(&self, f: crate::Face) -> Option<[DVec3; 4]> {
        let map = &self.mesh.map;
        let d = map.face_dart(f);
        let mut c = [DVec3::ZERO; 4];
        let mut n = 0;
        for x in map.face_cycle(d) {
            *c.get_mut(n)? = self.position(map.origin(x));
            n += 1;
        }
        (n == 4).then_some(c)
    }
}

/// One term of the score: a number for the whole mesh, smaller is better.
///
/// A user term is added with [`super::OptimizeOptions::term`]:
///
/// ```
/// use zipmesh::optimize::{Context, ScoreTerm};
/// /// The number of faces: prefer coarser meshes.
/// #[derive(Debug)]
/// struct Faces;
/// impl ScoreTerm for Faces {
///     fn name(&self) -> &str { "faces" }
///     fn score(&mut self, ctx: &Context<'_>) -> f64 { ctx.mesh.map.num_faces() as f64 }
/// }
/// let options = zipmesh::optimize::OptimizeOptions::default().term(0.001, Box::new(Faces));
/// assert!(options.terms().iter().any(|(_, t)| t.name() == "faces"));
/// ```
pub trait ScoreTerm: core::fmt::Debug {
    /// A short name (used in reports).
    fn name(&self) -> &str;
    /// The term's value on `ctx.mesh`.
    fn score(&mut self, ctx: &Context<'_>) -> f64;
    /// A copy for another thread, or `None` (the default) if the term cannot be copied: the
    /// optimizer's candidate search then runs on one thread. Results are the same either
    /// way; every built-in term can be copied.
    ///
    /// ```
    /// use zipmesh::optimize::{Context, Count, Electric, ScoreTerm};
    /// assert_eq!(Count.fork().unwrap().name(), "count");
    /// assert_eq!(Electric::default().fork().unwrap().name(), "electric");
    /// #[derive(Debug)]
    /// struct Mine;
    /// impl ScoreTerm for Mine {
    ///     fn name(&self) -> &str { "mine" }
    ///     fn score(&mut self, _: &Context<'_>) -> f64 { 0.0 }
    /// }
    /// assert!(Mine.fork().is_none());
    /// ```
    fn fork(&self) -> Option<Box<dyn ScoreTerm + Send>> {
        None
    }
    /// If the term is a sum over the scored quads (in [`Context::scored_faces`] order, from
    /// 0) of a function of each quad's corners (from the face's dart, in cycle order) and
    /// [`Context::target_area`]: that function. The optimizer then reuses the value of a
    /// quad whose corners did not move, with the same score to the last bit. `None` (the
    /// default) for any other term.
    ///
    /// ```
    /// use zipmesh::{gen, optimize::{Context, Count, Isotropy, ScoreTerm, Sizing}};
    /// let m = gen::grid(2, 2);
    /// let ctx = Context { mesh: &m, singularities: &[], features: &[], target_area: 2.0, target_faces: 0, faces: None, walls: true };
    /// let square = [0.0, 1.0].map(|x| [0.0, 1.0].map(|y| glam::DVec3::new(x, y, 0.0)));
    /// let one = Sizing.quad_value().unwrap()(&[square[0][0], square[1][0], square[1][1], square[0][1]], 2.0);
    /// assert_eq!(Sizing.score(&ctx), 4.0 * one); // four unit squares
    /// assert!(Isotropy.quad_value().is_some() && Count.quad_value().is_none());
    /// ```
    fn quad_value(&self) -> Option<QuadValue> {
        None
    }
}

/// A quad term's value of one quad: its corners in cycle order and the target area
/// ([`ScoreTerm::quad_value`]).
pub type QuadValue = fn(&[DVec3; 4], f64) -> f64;

/// The weighted terms and the singularity list they share: scores a mesh.
#[derive(Debug)]
pub(crate) struct Scorer {
    pub(crate) terms: Vec<(f64, Box<dyn ScoreTerm + Send>)>,
    pub(crate) features: Vec<bool>,
    pub(crate) target_area: f64,
    pub(crate) target_faces: usize,
    /// Whether the mesh has a boundary or features ([`Context::walls`]).
    pub(crate) walls: bool,
    /// [`Scorer::local`]'s buffers and quad values, kept between calls.
    pub(crate) scratch: LocalScratch,
}

/// What [`Scorer::local`] keeps between calls: its lists, and per face slot the corners
/// the quad terms ([`ScoreTerm::quad_value`]) last read and their values, so that a quad
/// no candidate moved is not measured again.
#[derive(Clone, Debug, Default)]
pub(crate) struct LocalScratch {
    sing: Vec<Singularity>,
    faces: Vec<crate::Face>,
    /// The faces listed by this call (a face is listed once per call).
    listed: Marks,
    /// Per face slot, the corners its row of `values` was computed from.
    corners: Vec<Option<[DVec3; 4]>>,
    /// Per face slot, one value per term (0 for the terms that are not quad terms).
    values: Vec<f64>,
    /// Per term, its quad function, if any.
    quad: Vec<Option<QuadValue>>,
    totals: Vec<f64>,
    /// The target area and the number of terms `values` were computed with.
    area: f64,
    width: usize,
}

impl LocalScratch {
    /// The window's singularities, in window order, and `faces` sorted, each once: listing
    /// first and sorting the few left is cheaper than sorting every corner's face. One walk
    /// round each vertex gives its faces and its valence, so an interior vertex's defect
    /// ([`super::defect::defect`]: valence - 4) costs no walk of its own.
    fn list(&mut self, mesh: &Mesh, window: &[Vert]) {
        let map = &mesh.map;
        self.sing.clear();
        self.faces.clear();
        self.listed.begin(map.face_slots());
        for &v in window {
            let mut valence = 0;
            for d in map.vertex_darts(v) {
                valence += 1;
                if let Some(f) = map.face(d) {
                    if self.listed.first(f.index()) {
                        self.faces.push(f);
                    }
                }
            }
            let boundary = map.is_boundary_vertex(v);
            let defect = match (map.is_live_vertex(v), boundary) {
                (false, _) => 0,
                (true, true) => super::defect::defect(mesh, v),
                (true, false) => valence - 4,
            };
            if defect != 0 {
                self.sing.push(Singularity {
                    vertex: v,
                    defect,
                    boundary,
                });
            }
        }
        self.faces.sort_unstable();
    }

    /// Each weighted quad term's value of every listed quad added into `totals`, in face
    /// order, measuring only the quads whose corners changed since they were last measured.
    fn quad_totals(
        &mut self,
        terms: &[(f64, Box<dyn ScoreTerm + Send>)],
        mesh: &Mesh,
        target_area: f64,
    ) {
        self.quad.clear();
        self.quad.extend(
            terms
                .iter()
                .map(|(w, t)| t.quad_value().filter(|_| *w != 0.0)),
        );
        let width = self.quad.len();
        self.totals.clear();
        self.totals.resize(width, 0.0);
        if self.quad.iter().all(Option::is_none) {
            return;
        }
        if self.area.to_bits() != target_area.to_bits() || self.width != width {
            self.corners.clear();
            self.values.clear();
            (self.area, self.width) = (target_area, width);
        }
        let slots = mesh.map.face_slots().max(self.corners.len());
        self.corners.resize(slots, None);
        self.values.resize(slots * width, 0.0);
        for &f in &self.faces {
            let Some(c) = quad_corners(mesh, f) else {
                continue;
            };
            let (Some(known), Some(row)) = (
                self.corners.get_mut(f.index()),
                self.values
                    .get_mut(f.index() * width..(f.index() + 1) * width),
            ) else {
                continue;
            };
            if known.is_none_or(|k| !same_bits(&k, &c)) {
                for (x, q) in row.iter_mut().zip(&self.quad) {
                    *x = q.map_or(0.0, |q| q(&c, target_area));
                }
                *known = Some(c);
            }
            for (t, x) in self.totals.iter_mut().zip(row.iter()) {
                *t += *x;
            }
        }
    }
}

/// The corners of `f` if it is a quad ([`Context::corners`]).
fn quad_corners(mesh: &Mesh, f: crate::Face) -> Option<[DVec3; 4]> {
    let map = &mesh.map;
    let mut c = [DVec3::ZERO; 4];
    let mut n = 0;
    for x in map.face_cycle(map.face_dart(f)) {
        *c.get_mut(n)? = mesh
            .positions
            .get(map.origin(x).index())
            .copied()
            .unwrap_or(DVec3::ZERO);
        n += 1;
    }
    (n == 4).then_some(c)
}

fn same_bits(a: &[DVec3; 4], b: &[DVec3; 4]) -> bool {
    a.iter()
        .zip(b)
        .all(|(p, q)| p.to_array().map(f64::to_bits) == q.to_array().map(f64::to_bits))
}

impl Scorer {
    /// A copy for another thread, if every term can be copied ([`ScoreTerm::fork`]).
    pub(crate) fn fork(&self) -> Option<Scorer> {
        let terms = self
            .terms
            .iter()
            .map(|(w, t)| Some((*w, t.fork()?)))
            .collect::<Option<Vec<_>>>()?;
        Some(Scorer {
            terms,
            features: self.features.clone(),
            target_area: self.target_area,
            target_faces: self.target_faces,
            walls: self.walls,
            scratch: LocalScratch::default(),
        })
    }

    /// The weighted total, and each term's unweighted value. The quad terms read the
    /// values [`LocalScratch`] keeps for quads that did not move, summed over every face in
    /// slot order as the terms' own sums are, so the value is the same to the bit; a Q-zip
    /// moves a few dozen quads, and this is called once per executed one.
    pub(crate) fn score(&mut self, mesh: &Mesh) -> (f64, Vec<f64>) {
        let s = singularities(mesh);
        let sc = &mut self.scratch;
        sc.faces.clear();
        sc.faces.extend(mesh.map.faces());
        sc.quad_totals(&self.terms, mesh, self.target_area);
        let ctx = Context {
            mesh,
            singularities: &s,
            features: &self.features,
            target_area: self.target_area,
            target_faces: self.target_faces,
            faces: None,
            walls: self.walls,
        };
        let mut parts = vec![0.0; self.terms.len()];
        let mut total = 0.0;
        let terms = self.terms.iter_mut().zip(&sc.quad).zip(&sc.totals);
        for ((((w, t), quad), sum), p) in terms.zip(&mut parts) {
            if *w != 0.0 {
                *p = match quad {
                    Some(_) => *sum,
                    None => t.score(&ctx),
                };
                total += *w * *p;
            }
        }
        (total, parts)
    }

    /// The weighted sum of the terms over a window (vertices, sorted): its singularities and
    /// the faces at its vertices. The quad terms read the
    /// values [`LocalScratch`] keeps for quads that did not move.
    pub(crate) fn local(&mut self, mesh: &Mesh, window: &[Vert]) -> f64 {
        let sc = &mut self.scratch;
        sc.list(mesh, window);
        sc.quad_totals(&self.terms, mesh, self.target_area);
        let ctx = Context {
            mesh,
            singularities: &sc.sing,
            features: &self.features,
            target_area: self.target_area,
            target_faces: self.target_faces,
            faces: Some(&sc.faces),
            walls: self.walls,
        };
        let (quad, totals) = (&sc.quad, &sc.totals);
        self.terms
            .iter_mut()
            .enumerate()
            .filter(|(_, (w, _))| *w != 0.0)
            .map(|(i, (w, t))| match quad[i] {
                Some(_) => *w * totals[i],
                None => *w * t.score(&ctx),
            })
            .sum()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scorer() -> Scorer {
        Scorer {
            terms: crate::optimize::OptimizeOptions::default().terms,
            features: Vec::new(),
            target_area: 0.7,
            target_faces: 50,
            walls: true,
            scratch: LocalScratch::default(),
        }
    }

    /// A scorer that kept the quad values of earlier calls scores a window as a new one
    /// does, to the bit, after corners moved and after a face changed its corners.
    #[test]
    fn kept_quad_values_give_the_fresh_score() {
        let mut mesh = crate::gen::catmull_clark(&crate::gen::random_triangle(40, 1, 0, 2));
        let window: Vec<Vert> = mesh.map.vertices().take(30).collect();
        let mut kept = scorer();
        let first = kept.local(&mesh, &window);
        assert_eq!(first.to_bits(), scorer().local(&mesh, &window).to_bits());
        for (i, &v) in window.iter().enumerate().step_by(3) {
            mesh.positions[v.index()] += DVec3::splat(0.01 * (i + 1) as f64);
            let again = kept.local(&mesh, &window);
            assert_eq!(again.to_bits(), scorer().local(&mesh, &window).to_bits());
            assert_ne!(again.to_bits(), first.to_bits());
        }
        // A flip of the edge at a window vertex gives two faces new corners.
        let d = mesh.map.vertex_dart(window[0]);
        crate::ops::quad::rotate_edge(&mut mesh.map, d, crate::ops::quad::Rotation::Clockwise)
            .unwrap();
        let flipped = kept.local(&mesh, &window);
        assert_eq!(flipped.to_bits(), scorer().local(&mesh, &window).to_bits());
    }

    /// A window's listed singularities are the mesh's singularities in the window, in
    /// window order, with boundary vertices (defects from their angles) and a dead slot
    /// (none) among them; its faces are those at its vertices, sorted, each once.
    #[test]
    fn window_lists_its_singularities_and_faces() {
        let mut mesh = crate::gen::catmull_clark(&crate::gen::random_triangle(40, 1, 1, 8));
        // A dead vertex slot in the window: a collapse frees one.
        let darts: Vec<_> = mesh.map.darts().collect();
        let gone = darts
            .into_iter()
            .find_map(|d| crate::ops::quad::collapse_quad(&mut mesh.map, d).ok())
            .unwrap()
            .removed();
        assert!(!mesh.map.is_live_vertex(gone));
        let mut window: Vec<Vert> = (0..mesh.map.vertex_slots() as u32)
            .map(Vert::new)
            .rev()
            .step_by(2)
            .collect();
        window.push(gone);
        let mut s = scorer();
        s.local(&mesh, &window);
        let all = singularities(&mesh);
        let want: Vec<Singularity> = window
            .iter()
            .filter_map(|&v| all.iter().find(|x| x.vertex == v).copied())
            .collect();
        assert!(want.iter().any(|x| x.boundary) && want.iter().any(|x| !x.boundary));
        assert_eq!(s.scratch.sing, want);
        let mut faces: Vec<crate::Face> = window
            .iter()
            .flat_map(|&v| mesh.map.vertex_darts(v).filter_map(|d| mesh.map.face(d)))
            .collect();
        faces.sort_unstable();
        faces.dedup();
        assert_eq!(s.scratch.faces, faces);
    }

    /// The counting search visits what [`Bfs::run`] visits, in its order, stopped anywhere,
    /// and counts each vertex's valence.
    #[test]
    fn counting_search_is_the_search_with_valences() {
        let random = crate::gen::catmull_clark(&crate::gen::random_triangle(30, 1, 1, 4));
        for mesh in [crate::gen::grid(4, 3), random] {
            let (mut plain, mut counting) = (Bfs::default(), Bfs::default());
            for from in mesh.map.vertices().step_by(5) {
                for (radius, stop) in [(0, 9), (1, 3), (3, 40), (5, usize::MAX)] {
                    let mut want = Vec::new();
                    plain.run(&mesh, from, radius, |v, d| {
                        want.push((v, d, mesh.map.valence(v)));
                        want.len() < stop
                    });
                    let mut got = Vec::new();
                    counting.run_counting(&mesh, from, radius, |v, d, k| {
                        got.push((v, d, k));
                        got.len() < stop
                    });
                    assert_eq!(got, want, "from {from:?}, radius {radius}, stop {stop}");
                }
            }
        }
    }

    /// The electric term as it was written before its search counted valences: a plain
    /// search, every defect from [`super::super::defect::defect`].
    fn electric_reference(e: &Electric, ctx: &Context<'_>) -> f64 {
        let (map, mut total, mut bfs) = (&ctx.mesh.map, 0.0, Bfs::default());
        for s in ctx.singularities {
            let q = s.charge();
            let (mut found, mut wall) = (0, s.boundary || !ctx.walls);
            bfs.run(ctx.mesh, s.vertex, e.radius, |v, d| {
                if d == 0 {
                    return true;
                }
                let dv = super::super::defect::defect(ctx.mesh, v);
                if dv != 0 && found < 3 {
                    found += 1;
                    total += e.potential.energy(q, -(dv as f64), d, e.radius);
                }
                let b = map.is_boundary_vertex(v) || ctx.is_feature(v);
                if !wall && d <= e.boundary_radius && b {
                    wall = true;
                    total += e.boundary_weight * q.abs() / d as f64;
                }
                found < 3 || (!wall && d < e.boundary_radius)
            });
        }
        total
    }

    /// The electric term, to the bit, is the reference's on meshes with and without
    /// boundary (whose vertices' defects come from their angles), whole and in windows.
    #[test]
    fn electric_is_its_reference() {
        let meshes = [
            crate::gen::catmull_clark(&crate::gen::random_triangle(40, 1, 1, 6)),
            crate::gen::catmull_clark(&crate::gen::random_triangle(30, 0, 0, 7)),
            crate::gen::subdivided_icosahedron(2),
        ];
        for mesh in &meshes {
            let all = singularities(mesh);
            assert!(all.len() > 4);
            for sing in [&all[..], &all[..all.len() / 2]] {
                let ctx = Context {
                    mesh,
                    singularities: sing,
                    features: &[],
                    target_area: 1.0,
                    target_faces: 0,
                    faces: None,
                    walls: true,
                };
                let mut e = Electric::default();
                let want = electric_reference(&e, &ctx);
                assert_eq!(e.score(&ctx).to_bits(), want.to_bits());
                assert_ne!(want, 0.0);
            }
        }
    }

    /// Each term's own sum over the whole mesh, weighted and added in term order: what
    /// [`Scorer::score`] gave before it read kept quad values.
    fn own_sums(s: &mut Scorer, mesh: &Mesh) -> (f64, Vec<f64>) {
        let sing = singularities(mesh);
        let ctx = Context {
            mesh,
            singularities: &sing,
            features: &s.features,
            target_area: s.target_area,
            target_faces: s.target_faces,
            faces: None,
            walls: s.walls,
        };
        let mut parts = vec![0.0; s.terms.len()];
        let mut total = 0.0;
        for ((w, t), p) in s.terms.iter_mut().zip(&mut parts) {
            if *w != 0.0 {
                *p = t.score(&ctx);
                total += *w * *p;
            }
        }
        (total, parts)
    }

    /// The whole-mesh score with kept quad values (warmed by windows and earlier scores)
    /// is each term's own sum, to the bit, as quads move and an edge turns.
    #[test]
    fn whole_score_with_kept_quad_values_is_the_terms_own() {
        let mut mesh = crate::gen::catmull_clark(&crate::gen::random_triangle(40, 1, 0, 3));
        let window: Vec<Vert> = mesh.map.vertices().take(30).collect();
        let mut kept = scorer();
        let bits = |x: &(f64, Vec<f64>)| {
            let mut b = vec![x.0.to_bits()];
            b.extend(x.1.iter().map(|p| p.to_bits()));
            b
        };
        let first = kept.score(&mesh);
        assert_eq!(bits(&first), bits(&own_sums(&mut scorer(), &mesh)));
        for (i, &v) in window.iter().enumerate().step_by(4) {
            mesh.positions[v.index()] += DVec3::splat(0.02 * (i + 1) as f64);
            kept.local(&mesh, &window[..i + 1]);
            let again = kept.score(&mesh);
            assert_eq!(bits(&again), bits(&own_sums(&mut scorer(), &mesh)));
            assert_ne!(again.0.to_bits(), first.0.to_bits());
        }
        let d = mesh.map.vertex_dart(window[1]);
        crate::ops::quad::rotate_edge(&mut mesh.map, d, crate::ops::quad::Rotation::Clockwise)
            .unwrap();
        let turned = kept.score(&mesh);
        assert_eq!(bits(&turned), bits(&own_sums(&mut scorer(), &mesh)));
    }
}
