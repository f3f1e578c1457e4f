//! 5-5-7-7 generation with the two pairs apart (Sec. 7.3), and the sides of a quadruple.
//!
//! The paper connects the four vertices `v1 .. v4` of a generated quadruple by the shortest
//! paths `p_i` from `v_i` to `v_(i+1)` made of two straight lines of `x_i` and `y_i` edges,
//! bending clockwise, and states that they form a convex polygon whose opposite sides are
//! equal, `x_i = x_(i+2)`, `y_i = y_(i+2)`: otherwise removing one 5-7 pair would leave a
//! single 5-7 pair made from a regular triangulation, which Theorem 5.5 rules out.
//!
//! [`generate_quadruple_apart`] makes such a quadruple: the atomic generation of
//! [`Quadruple::Flip`] or [`Quadruple::Split`] at `v = origin(d)` (`d = v -> a`, `b` the
//! apex left of `d`, `e` the one right, `f` opposite `a`), then the moving pair walks
//! `steps` atomic 5-7 moves ([`super::move_pair`]) in one [`Direction`]; the staying pair
//! keeps its place. A walk in one direction is a translation, so the polygon is a
//! parallelogram. [`quadruple_sides`] measures the four sides.
//!
//! ```text
//!  Flip:  stay (v, e), move (a, b)         Split: stay (v, f), move (v', a)
//!          b(7) ....... b'(7)                  a(7) ....... a'(7)
//!         /  \           \                    /   \           \
//!     v(5)    a(5) ....... a'(5)          v(5)---v'(5) ....... v''(5)
//!         \  /                                \   /
//!          e(7)       polygon v, e, a', b'     f(7)       polygon v, f, v'', a'
//! ```

use super::pair::{plan, Direction};
use super::quadruple::{check_start, first, Quadruple, QuadrupleEdit};
use super::record::turn;
use super::types::run_with;
use super::{apex, regular, TriEditError};
use crate::map::{Dart, Map, Vert};
use crate::mesh::{EditTarget, Edited};
use crate::ops::tri::TriRecord;
use crate::ops::Refusal;

/// The vertices round `v = origin(d)` that the pairs are made of, read before the
/// generation: `a`, `b` (apex left of `d`), `e` (apex right), `f` (opposite `a`).
#[derive(Clone, Copy)]
struct Around {
    v: Vert,
    a: Vert,
    b: Vert,
    e: Vert,
    f: Vert,
}

impl Around {
    fn of(map: &Map, d: Dart) -> Result<Around, TriEditError> {
        let bad = TriEditError::Refused(Refusal::WrongDegree);
        Ok(Around {
            v: map.origin(d),
            a: map.dest(d),
            b: apex(map, d).ok_or(bad)?,
            e: apex(map, d.twin()).ok_or(bad)?,
            f: map.dest(turn(map, d, 3)),
        })
    }

    /// The staying and the moving pair `[(v5, v7), (v5, v7)]` right after the atomic
    /// generation `done` (see the module diagram).
    fn pairs(self, done: &[TriRecord]) -> Option<[(Vert, Vert); 2]> {
        match done.first() {
            Some(TriRecord::Flip(_)) => Some([(self.v, self.e), (self.a, self.b)]),
            Some(TriRecord::SplitVertex(s)) => Some([(self.v, self.f), (s.created(), self.a)]),
            _ => None,
        }
    }
}

/// Checks whether [`generate_quadruple_apart`] applies, by running it on a copy of the map
/// (O(map) time and memory).
///
/// See [`generate_quadruple_apart`] for an example.
pub fn can_generate_quadruple_apart(
    map: &Map,
    d: Dart,
    how: Quadruple,
    dir: Direction,
    steps: usize,
) -> Result<(), TriEditError> {
    generate_quadruple_apart(&mut map.clone(), d, how, dir, steps).map(|_| ())
}

/// Generates a 5-5-7-7 quadruple at the regular vertex `origin(d)` with its two 5-7 pairs
/// `steps` atomic moves apart (Sec. 7.3; the module documentation says which pair moves),
/// or refuses with the map unchanged: `how` must be [`Quadruple::Flip`] or
/// [`Quadruple::Split`] (the other gives a chain, not two pairs:
/// [`TriEditError::WrongValence`]); `steps` at most [`Map::vertex_slots`]
/// ([`Refusal::BadArguments`]); the refusals of [`super::generate_quadruple`], then of each
/// [`super::move_pair`] ([`TriEditError::Irregular`] when the walk meets an irregular
/// vertex). [`QuadrupleEdit::vertices`] lists the four in polygon order: the staying v5
/// and v7, the moving v5 and v7. Opposite sides are equal ([`quadruple_sides`]).
///
/// ```
/// use zipmesh::gen::geodesic_sphere;
/// use zipmesh::tri_edit::{generate_quadruple_apart, quadruple_sides, Direction, Quadruple};
/// use zipmesh::Vert;
/// let mut map = geodesic_sphere(4);
/// let before = map.clone();
/// let d = map.vertex_dart(Vert::new(400));
/// let g = generate_quadruple_apart(&mut map, d, Quadruple::Flip, Direction::FlipRight, 3)
///     .unwrap();
/// let four: [Vert; 4] = g.vertices().try_into().unwrap();
/// assert_eq!(four.map(|v| map.valence(v)), [5, 7, 5, 7]);
/// let s = quadruple_sides(&map, four, 20).unwrap();
/// assert_eq!(s, [(1, 0), (4, 0), (1, 0), (4, 0)]); // opposite sides equal
/// assert!(!g.in_two_triangles(&map));
/// g.undo(&mut map).unwrap();
/// assert_eq!(map, before);
/// ```
///
/// On any [`EditTarget`]: the [module docs](crate::tri_edit) say how values are placed.
///
/// ```
/// use zipmesh::gen::geodesic_sphere;
/// use zipmesh::tri_edit::{generate_quadruple_apart, Direction, Quadruple};
/// use zipmesh::Vert;
/// let mut map = geodesic_sphere(4);
/// let mut marks = vec![1.0f64; map.vertex_slots()];
/// let before = (map.clone(), marks.clone());
/// let d = map.vertex_dart(Vert::new(400));
/// let g = generate_quadruple_apart(&mut (&mut map, &mut marks), d, Quadruple::Split,
///     Direction::SplitLeft, 2).unwrap();
/// assert_eq!(marks.len(), map.vertex_slots());
/// g.undo(&mut (&mut map, &mut marks)).unwrap();
/// assert_eq!((map, marks), before);
/// ```
pub fn generate_quadruple_apart<T: EditTarget>(
    target: &mut T,
    d: Dart,
    how: Quadruple,
    dir: Direction,
    steps: usize,
) -> Result<Edited<QuadrupleEdit, T::Values>, TriEditError> {
    let (map, attrs) = target.parts();
    check_start(map, d)?;
    if how == Quadruple::CollapseFlip {
        return Err(TriEditError::WrongValence);
    }
    if steps > map.vertex_slots() {
        return Err(TriEditError::Refused(Refusal::BadArguments));
    }
    let (op, need) = first(map, d, how)?;
    need.iter().try_for_each(|&w| regular(map, w))?;
    let around = Around::of(map, d)?;
    let mut four = None;
    let ((steps_done, _), journal) = run_with(map, attrs, |m, done| {
        if done.is_empty() {
            return Ok(Some(op));
        }
        let [stay, (p, q)] = match four {
            Some(f) => f,
            None => around.pairs(done).ok_or(TriEditError::NotAPair)?,
        };
        if done.len() > steps {
            four = Some([stay, (p, q)]);
            return Ok(None);
        }
        let (op, np, nq) = plan(m, p, q, dir)?;
        four = Some([stay, (np, nq)]);
        Ok(Some(op))
    })?;
    let [(s5, s7), (m5, m7)] = four.ok_or(TriEditError::NotAPair)?;
    let edit = QuadrupleEdit::new(alloc::vec![s5, s7, m5, m7], steps_done);
    Ok(Edited::new(edit, journal))
}

/// The four sides of the polygon `four` (see the module documentation): for each `i`, the
/// shortest path from `four[i]` to `four[(i + 1) % 4]` made of a straight line of `x >= 1`
/// edges and, after a bend of one sector clockwise, one of `y >= 0` edges, through regular
/// interior vertices only (straight: the opposite dart of a regular vertex), as `(x, y)`;
/// ties go to the smaller `x`. `None` when a side has no such path of at most `max` edges,
/// or a vertex is not live. Cost: O(valence x max^2) per side, `max` taken at most
/// [`Map::dart_slots`] (a longer straight line repeats an edge).
///
/// See [`generate_quadruple_apart`] for an example.
pub fn quadruple_sides(map: &Map, four: [Vert; 4], max: usize) -> Option<[(usize, usize); 4]> {
    if !four.iter().all(|&v| map.is_live_vertex(v)) {
        return None;
    }
    let max = max.min(map.dart_slots());
    let mut out = [(0, 0); 4];
    for (i, side) in out.iter_mut().enumerate() {
        *side = side_path(map, four[i], four[(i + 1) % 4], max)?;
    }
    Some(out)
}

/// The dart straight on after `d` (the opposite dart at its regular end), if that end is
/// a regular interior vertex.
fn straight(map: &Map, d: Dart) -> Option<Dart> {
    regular(map, map.dest(d)).ok()?;
    Some(turn(map, d.twin(), 3))
}

/// The shortest two-line path of [`quadruple_sides`] from `from` to `to`.
fn side_path(map: &Map, from: Vert, to: Vert, max: usize) -> Option<(usize, usize)> {
    let mut best: Option<(usize, usize)> = None;
    let better = |best: Option<(usize, usize)>, x: usize, y: usize| match best {
        Some((bx, by)) => x + y < bx + by || (x + y == bx + by && x < bx),
        None => true,
    };
    for start in map.vertex_darts(from) {
        let mut d = Some(start);
        for x in 1..=max {
            let Some(h) = d else { break };
            if map.dest(h) == to {
                if better(best, x, 0) {
                    best = Some((x, 0));
                }
                break;
            }
            // The bend: one sector clockwise from straight on, at a regular vertex.
            let mut e = straight(map, h).map(|s| map.rotate_cw(s));
            for y in 1..=max - x {
                let Some(g) = e else { break };
                if map.dest(g) == to {
                    if better(best, x, y) {
                        best = Some((x, y));
                    }
                    break;
                }
                e = straight(map, g);
            }
            d = straight(map, h);
        }
    }
    best
}
