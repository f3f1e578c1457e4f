//! The documented effect of an operator as a value: what [`crate::ops::quad::QuadOp::effect`]
//! and [`crate::ops::tri::TriOp::effect`] compute on the map before an application, and the
//! check of an applied operator against it. The tables in the module docs of
//! [`crate::ops::quad`] and [`crate::ops::tri`] state the same rules in prose; this is their
//! executable form, used by the proofs, the tests and the campaign.

use crate::map::{Face, Map, Vert};
use alloc::vec::Vec;
use core::fmt;

/// What one application of an operator does to the counts and valences, computed on the map
/// before it (see [`crate::ops::quad::QuadOp::effect`], [`crate::ops::tri::TriOp::effect`]):
/// the changes of V, E and F, the valence after of each vertex the operator names, the vertex
/// it deletes and the valence of the one it creates, and the degree of every new face. Every
/// other vertex keeps its valence and every surviving face its degree.
///
/// ```
/// use zipmesh_kernel::{gen, ops::quad::QuadOp, Dart};
/// let mut map = gen::torus_grid(5, 5).map;
/// let before = map.clone();
/// let op = QuadOp::InsertDoublet(Dart::new(0));
/// let effect = op.effect(&map).unwrap();
/// assert_eq!(effect.deltas(), [1, 2, 1]);
/// assert_eq!(effect.created_valence(), Some(2));
/// let record = op.apply(&mut map).unwrap();
/// assert_eq!(effect.check(&before, &map, &record), Ok(()));
/// // Against the map before, the new vertex is missing: the check says so.
/// assert!(effect.check(&before, &before, &record).is_err());
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Effect {
    deltas: [i64; 3],
    named: Vec<Named>,
    removed: Option<Vert>,
    created: Option<usize>,
    face_degree: usize,
}

/// A vertex the effect names: its role for messages and its valence after.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Named {
    vertex: Vert,
    role: &'static str,
    before: i64,
    after: i64,
}

impl Effect {
    /// An effect with these V/E/F deltas whose new faces have `face_degree` sides.
    pub(crate) fn new(deltas: [i64; 3], face_degree: usize) -> Effect {
        Effect {
            deltas,
            named: Vec::new(),
            removed: None,
            created: None,
            face_degree,
        }
    }

    /// `v`'s valence changes by `delta` (summed if `v` is named again; the first role stays).
    pub(crate) fn change(mut self, map: &Map, v: Vert, role: &'static str, delta: i64) -> Effect {
        match self.named.iter_mut().find(|n| n.vertex == v) {
            Some(n) => n.after += delta,
            None => {
                let before = map.valence(v) as i64;
                self.named.push(Named {
                    vertex: v,
                    role,
                    before,
                    after: before + delta,
                })
            }
        }
        self
    }

    /// The vertices whose valence the operator states, with their valence before (on the
    /// map the effect was computed on) and after: what a caller scoring valences reads
    /// without walking the vertices again.
    ///
    /// ```
    /// use zipmesh_kernel::{gen, ops::tri::TriOp};
    /// let map = gen::random_triangle(200, 0, 0, 3).map;
    /// let d = map.darts().find(|&d| TriOp::Flip(d).can(&map).is_ok()).unwrap();
    /// let effect = TriOp::Flip(d).effect(&map).unwrap();
    /// for (v, before, after) in effect.changes() {
    ///     assert_eq!(map.valence(v), before);
    ///     assert_eq!(after.abs_diff(before), 1);
    /// }
    /// ```
    pub fn changes(&self) -> impl Iterator<Item = (Vert, usize, usize)> + '_ {
        let k = |x: i64| usize::try_from(x).unwrap_or(0);
        self.named
            .iter()
            .map(move |n| (n.vertex, k(n.before), k(n.after)))
    }

    /// The operator deletes `v`.
    pub(crate) fn removes(mut self, v: Vert) -> Effect {
        self.removed = Some(v);
        self
    }

    /// The operator creates one vertex of valence `k`.
    pub(crate) fn creates(mut self, k: usize) -> Effect {
        self.created = Some(k);
        self
    }

    /// The changes of `[V, E, F]`.
    ///
    /// See [`Effect`] for an example.
    pub fn deltas(&self) -> [i64; 3] {
        self.deltas
    }

    /// The vertices whose valence the operator states, with their valence after (every
    /// other surviving vertex keeps its own).
    ///
    /// ```
    /// use zipmesh_kernel::{gen, ops::quad::QuadOp, Dart};
    /// let map = gen::torus_grid(5, 5).map;
    /// let effect = QuadOp::Collapse(Dart::new(0)).effect(&map).unwrap();
    /// // The merged vertex gets 4 + 4 - 2, the two other corners 3.
    /// let mut after: Vec<usize> = effect.valences().map(|(_, k)| k).collect();
    /// after.sort();
    /// assert_eq!(after, [3, 3, 6]);
    /// ```
    pub fn valences(&self) -> impl Iterator<Item = (Vert, usize)> + '_ {
        self.named
            .iter()
            .map(|n| (n.vertex, usize::try_from(n.after).unwrap_or(0)))
    }

    /// The vertex the operator deletes, if it deletes one.
    ///
    /// ```
    /// use zipmesh_kernel::{gen, ops::quad::QuadOp, Dart};
    /// let map = gen::torus_grid(5, 5).map;
    /// let effect = QuadOp::Collapse(Dart::new(0)).effect(&map).unwrap();
    /// assert_eq!(effect.removed(), Some(map.origin(map.next(map.next(Dart::new(0))))));
    /// ```
    pub fn removed(&self) -> Option<Vert> {
        self.removed
    }

    /// The valence of the vertex the operator creates, if it creates one (its handle is
    /// known only after, from the record: [`VertexChanges::created_vertex`]).
    ///
    /// See [`Effect`] for an example.
    pub fn created_valence(&self) -> Option<usize> {
        self.created
    }

    /// Checks an application: `after` is the map `before` with the operator applied and
    /// `record` its record. `Ok` if V, E, F changed by [`Effect::deltas`], every named vertex
    /// has its stated valence, the deleted vertex is gone and is the record's, exactly one
    /// vertex is new when the effect creates one and it is the record's with the stated
    /// valence, every other vertex kept its valence, every surviving face its degree, and
    /// every new face has the family's degree (4 quad, 3 triangle). Otherwise the first
    /// difference found.
    ///
    /// See [`Effect`] for an example.
    pub fn check(
        &self,
        before: &Map,
        after: &Map,
        record: &impl VertexChanges,
    ) -> Result<(), EffectMismatch> {
        let got = [
            after.num_vertices() as i64 - before.num_vertices() as i64,
            after.num_edges() as i64 - before.num_edges() as i64,
            after.num_faces() as i64 - before.num_faces() as i64,
        ];
        if got != self.deltas {
            return Err(EffectMismatch::Counts {
                got,
                want: self.deltas,
            });
        }
        let (created, removed) = (record.created_vertex(), record.removed_vertex());
        let created_fits = match (created, self.created) {
            (Some(v), Some(_)) => !before.is_live_vertex(v) && after.is_live_vertex(v),
            (None, None) => true,
            _ => false,
        };
        if !created_fits || removed != self.removed {
            return Err(EffectMismatch::Record { created, removed });
        }
        self.check_vertices(before, after, created)?;
        self.check_faces(before, after)
    }

    /// Every vertex slot of either map: named ones as stated, the record's new one as
    /// stated, the deleted one gone, every other one as it was.
    fn check_vertices(
        &self,
        before: &Map,
        after: &Map,
        created: Option<Vert>,
    ) -> Result<(), EffectMismatch> {
        let slots = before.vertex_slots().max(after.vertex_slots());
        for v in (0..slots as u32).map(Vert::new) {
            let (want, role) = match (before.is_live_vertex(v), after.is_live_vertex(v)) {
                (true, false) if Some(v) == self.removed => continue,
                (true, false) => return Err(EffectMismatch::Deleted(v)),
                (true, true) if Some(v) == self.removed => return Err(EffectMismatch::Survived(v)),
                (true, true) => match self.named.iter().find(|n| n.vertex == v) {
                    Some(n) => (usize::try_from(n.after).unwrap_or(0), n.role),
                    None => (before.valence(v), "an uninvolved vertex"),
                },
                (false, true) if Some(v) == created => {
                    (self.created.unwrap_or(0), "the new vertex")
                }
                (false, true) => return Err(EffectMismatch::Appeared(v)),
                (false, false) => continue,
            };
            let got = after.valence(v);
            if got != want {
                return Err(EffectMismatch::Valence {
                    vertex: v,
                    role,
                    got,
                    want,
                });
            }
        }
        Ok(())
    }

    /// Surviving faces keep their degree; new faces have the family's.
    fn check_faces(&self, before: &Map, after: &Map) -> Result<(), EffectMismatch> {
        for face in after.faces() {
            let want = if before.is_live_face(face) {
                before.degree(face)
            } else {
                self.face_degree
            };
            let got = after.degree(face);
            if got != want {
                return Err(EffectMismatch::FaceDegree { face, got, want });
            }
        }
        Ok(())
    }
}

/// What [`Effect::check`] reads from a record: the vertex its operation created (a new
/// vertex takes a free slot, so only the record knows its handle) and the one it deleted.
/// Implemented by [`crate::ops::quad::QuadRecord`] and [`crate::ops::tri::TriRecord`].
///
/// ```
/// use zipmesh_kernel::{gen, ops::{quad::QuadOp, VertexChanges}, Dart};
/// let mut map = gen::torus_grid(5, 5).map;
/// let c = map.origin(map.next(map.next(Dart::new(0))));
/// let record = QuadOp::Collapse(Dart::new(0)).apply(&mut map).unwrap();
/// assert_eq!((record.created_vertex(), record.removed_vertex()), (None, Some(c)));
/// ```
pub trait VertexChanges {
    /// The vertex the operation created, if any.
    fn created_vertex(&self) -> Option<Vert>;
    /// The vertex the operation deleted (its handle before), if any.
    fn removed_vertex(&self) -> Option<Vert>;
}

/// An edit with values changes the vertices its record does.
impl<R: VertexChanges, A: crate::mesh::VertexAttributes> VertexChanges
    for crate::mesh::Edited<R, A>
{
    fn created_vertex(&self) -> Option<Vert> {
        self.record().created_vertex()
    }
    fn removed_vertex(&self) -> Option<Vert> {
        self.record().removed_vertex()
    }
}

/// How an application differs from its [`Effect`]: the first difference
/// [`Effect::check`] finds.
///
/// ```
/// use zipmesh_kernel::{gen, ops::{quad::QuadOp, EffectMismatch}, Dart};
/// let mut map = gen::torus_grid(5, 5).map;
/// let before = map.clone();
/// let effect = QuadOp::Collapse(Dart::new(0)).effect(&map).unwrap();
/// // Checked against another operator's result, the counts differ.
/// let record = QuadOp::InsertDoublet(Dart::new(0)).apply(&mut map).unwrap();
/// let e = effect.check(&before, &map, &record).unwrap_err();
/// assert_eq!(e, EffectMismatch::Counts { got: [1, 2, 1], want: [-1, -2, -1] });
/// assert_eq!(e.to_string(), "(V, E, F) changed by [1, 2, 1], documented [-1, -2, -1]");
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum EffectMismatch {
    /// V, E, F changed by `got`, not by the documented `want`.
    Counts {
        /// The changes of `[V, E, F]` seen.
        got: [i64; 3],
        /// The documented ones.
        want: [i64; 3],
    },
    /// The record's created or deleted vertex does not fit the effect: a created vertex
    /// must be there exactly when the effect creates one, dead before and live after; the
    /// deleted one must be the effect's.
    Record {
        /// The record's created vertex.
        created: Option<Vert>,
        /// The record's deleted vertex.
        removed: Option<Vert>,
    },
    /// A vertex the operator keeps was deleted.
    Deleted(Vert),
    /// The vertex the operator deletes is still live.
    Survived(Vert),
    /// A vertex is new that is not the record's created vertex.
    Appeared(Vert),
    /// A vertex has another valence than documented.
    Valence {
        /// The vertex.
        vertex: Vert,
        /// Its role in the operator's documentation ("an uninvolved vertex" if none).
        role: &'static str,
        /// Its valence after.
        got: usize,
        /// The documented valence.
        want: usize,
    },
    /// A face has another degree than before (or, if new, than the family's).
    FaceDegree {
        /// The face.
        face: Face,
        /// Its degree after.
        got: usize,
        /// The documented degree.
        want: usize,
    },
}

impl fmt::Display for EffectMismatch {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            EffectMismatch::Counts { got, want } => {
                write!(f, "(V, E, F) changed by {got:?}, documented {want:?}")
            }
            EffectMismatch::Record { created, removed } => write!(
                f,
                "the record's vertices (created {created:?}, deleted {removed:?}) do not fit the documented effect"
            ),
            EffectMismatch::Deleted(v) => write!(f, "vertex {} was deleted", v.index()),
            EffectMismatch::Survived(v) => {
                write!(f, "vertex {} should be deleted but is live", v.index())
            }
            EffectMismatch::Appeared(v) => {
                write!(f, "vertex {} is new but not the record's", v.index())
            }
            EffectMismatch::Valence {
                vertex,
                role,
                got,
                want,
            } => write!(
                f,
                "{role} (vertex {}) has valence {got}, documented {want}",
                vertex.index()
            ),
            EffectMismatch::FaceDegree { face, got, want } => write!(
                f,
                "face {} has degree {got}, documented {want}",
                face.index()
            ),
        }
    }
}

#[cfg(feature = "std")]
impl std::error::Error for EffectMismatch {}

/// How many clockwise steps lead from `from` to `to` around their common origin; the whole
/// valence if `to` is not met (callers have checked that it is).
pub(crate) fn cw_steps(map: &Map, from: crate::map::Dart, to: crate::map::Dart) -> usize {
    let mut x = from;
    let k = map.valence(map.origin(from));
    for i in 0..k {
        if x == to {
            return i;
        }
        x = map.rotate_cw(x);
    }
    k
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::gen;
    use crate::map::Dart;
    use crate::ops::quad::QuadOp;
    use alloc::string::ToString;

    /// A record that claims whatever vertices it is given.
    struct Claim(Option<Vert>, Option<Vert>);

    impl VertexChanges for Claim {
        fn created_vertex(&self) -> Option<Vert> {
            self.0
        }
        fn removed_vertex(&self) -> Option<Vert> {
            self.1
        }
    }

    /// The map before and after `op` on a 5 x 5 torus, its effect and its record's claim.
    fn applied(op: QuadOp) -> (Map, Map, Effect, Claim) {
        let mut map = gen::torus_grid(5, 5).map;
        let before = map.clone();
        let effect = op.effect(&map).unwrap();
        let r = op.apply(&mut map).unwrap();
        let claim = Claim(r.created_vertex(), r.removed_vertex());
        (before, map, effect, claim)
    }

    /// `changes` gives each named vertex's valence on the map before and the one stated
    /// after, which the applied map has.
    #[test]
    fn changes_are_the_valences_before_and_after() {
        use crate::ops::quad::Rotation;
        let d = Dart::new(0);
        let ops = [
            QuadOp::Collapse(d),
            QuadOp::InsertDoublet(d),
            QuadOp::Rotate(d, Rotation::Clockwise),
        ];
        for op in ops {
            let (before, after, effect, _) = applied(op);
            let changes: Vec<_> = effect.changes().collect();
            assert!(changes.len() >= 2, "{op:?}");
            assert_eq!(changes.len(), effect.valences().count());
            for (v, b, a) in changes {
                assert_eq!(
                    (b, a),
                    (before.valence(v), after.valence(v)),
                    "{op:?} {v:?}"
                );
            }
        }
    }

    /// A vertex named twice has its changes summed, from its valence before, and keeps
    /// its first role.
    #[test]
    fn a_vertex_named_twice_sums_its_changes() {
        let map = gen::torus_grid(5, 5).map;
        let v = Vert::new(3);
        let e = Effect::new([0, 0, 0], 4)
            .change(&map, v, "first", 1)
            .change(&map, v, "second", 2);
        assert_eq!(e.changes().collect::<Vec<_>>(), [(v, 4, 7)]);
        assert_eq!(e.named[0].role, "first");
    }

    #[test]
    fn the_deleted_vertex_must_be_the_effects() {
        let (before, after, effect, claim) = applied(QuadOp::Collapse(Dart::new(0)));
        assert_eq!(effect.check(&before, &after, &claim), Ok(()));
        let c = claim.1.unwrap();
        let other = Vert::new(if c.index() == 0 { 1 } else { 0 });
        for (created, removed) in [(None, Some(other)), (None, None), (Some(c), Some(c))] {
            assert_eq!(
                effect.check(&before, &after, &Claim(created, removed)),
                Err(EffectMismatch::Record { created, removed })
            );
        }
    }

    #[test]
    fn the_created_vertex_must_be_new_and_the_effects() {
        let (before, after, effect, claim) = applied(QuadOp::InsertDoublet(Dart::new(0)));
        assert_eq!(effect.check(&before, &after, &claim), Ok(()));
        let old = Vert::new(0);
        for (created, removed) in [(None, None), (Some(old), None), (claim.0, Some(old))] {
            assert_eq!(
                effect.check(&before, &after, &Claim(created, removed)),
                Err(EffectMismatch::Record { created, removed })
            );
        }
    }

    #[test]
    fn every_vertex_is_deleted_kept_or_new_as_the_effect_says() {
        let (before, after, effect, claim) = applied(QuadOp::Collapse(Dart::new(0)));
        let c = claim.1.unwrap();
        let none = Claim(None, None);
        let survive = Effect::new([0, 0, 0], 4).removes(c);
        let e = survive.check(&before, &before, &Claim(None, Some(c)));
        assert_eq!(e, Err(EffectMismatch::Survived(c)));
        // The collapse's effect without its deletion: the deleted vertex was one to keep.
        let mut delete = effect.clone();
        delete.removed = None;
        assert_eq!(
            delete.check(&before, &after, &none),
            Err(EffectMismatch::Deleted(c))
        );
        // Compacting moves the vertex above the hole into it: a vertex no record made.
        let mut moved = after.clone();
        moved.compact();
        let same = Effect::new([0, 0, 0], 4);
        assert_eq!(
            same.check(&after, &moved, &none),
            Err(EffectMismatch::Appeared(c))
        );
    }

    #[test]
    fn valences_are_the_named_ones_and_otherwise_kept() {
        let map = gen::torus_grid(5, 5).map;
        let v = Vert::new(7);
        let raised = Effect::new([0, 0, 0], 4).change(&map, v, "the raised vertex", 1);
        let want = EffectMismatch::Valence {
            vertex: v,
            role: "the raised vertex",
            got: 4,
            want: 5,
        };
        assert_eq!(raised.check(&map, &map, &Claim(None, None)), Err(want));
        // The collapse's counts and deletion without its valence changes.
        let (before, after, effect, claim) = applied(QuadOp::Collapse(Dart::new(0)));
        let bare = Effect::new(effect.deltas(), 4).removes(claim.1.unwrap());
        let Err(EffectMismatch::Valence { role, got, .. }) = bare.check(&before, &after, &claim)
        else {
            panic!("the merged vertex's valence went unnoticed");
        };
        assert_eq!((role, got != 4), ("an uninvolved vertex", true));
    }

    #[test]
    fn new_faces_have_the_familys_degree() {
        let (before, after, mut effect, claim) = applied(QuadOp::InsertDoublet(Dart::new(0)));
        effect.face_degree = 3;
        let Err(EffectMismatch::FaceDegree { got, want, face }) =
            effect.check(&before, &after, &claim)
        else {
            panic!("a quad passed as a new triangle");
        };
        assert_eq!((got, want), (4, 3));
        assert!(!before.is_live_face(face) && after.is_live_face(face));
    }

    #[test]
    fn mismatches_name_what_differs() {
        let v = Vert::new(3);
        let cases = [
            (EffectMismatch::Deleted(v), "vertex 3 was deleted"),
            (
                EffectMismatch::Survived(v),
                "vertex 3 should be deleted but is live",
            ),
            (
                EffectMismatch::Appeared(v),
                "vertex 3 is new but not the record's",
            ),
            (
                EffectMismatch::Valence {
                    vertex: v,
                    role: "the kept vertex",
                    got: 5,
                    want: 6,
                },
                "the kept vertex (vertex 3) has valence 5, documented 6",
            ),
            (
                EffectMismatch::FaceDegree {
                    face: Face::new(2),
                    got: 5,
                    want: 4,
                },
                "face 2 has degree 5, documented 4",
            ),
        ];
        for (e, text) in cases {
            assert_eq!(e.to_string(), text);
        }
        let r = EffectMismatch::Record {
            created: Some(v),
            removed: None,
        };
        assert!(r.to_string().contains("created Some(v3)"), "{r}");
    }
}
