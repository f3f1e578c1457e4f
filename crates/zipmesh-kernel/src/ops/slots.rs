//! The slots an operator creates or deletes, and how its undo gives them back exactly: the
//! one allocation mechanism of the quad and the triangle operators.
//!
//! An operator that creates elements allocates them with [`Slots::alloc`] (edges, then the
//! vertex, then faces, each from its free list last-in first-out or appended to its arrays)
//! and keeps the [`Slots`] in its record; the undo checks [`Slots::releasable`] and calls
//! [`Slots::release`], which cuts appended slots off the arrays and puts reused ones back on
//! their free lists, in reverse order, so that both are restored exactly (`==`).
//!
//! An operator that deletes elements frees them with [`Slots::free`] in the same order; its
//! undo checks [`Slots::on_free_lists`] and calls [`Slots::reclaim`], which takes them off the
//! tops of the free lists again.

use super::Refusal;
use crate::map::{Dart, Edge, Face, Map, Vert, NONE};

/// Up to three edges, one vertex and up to two faces, in allocation (or freeing) order.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(crate) struct Slots {
    edges: [Edge; 3],
    faces: [Face; 2],
    vert: Vert,
    n_edges: u8,
    n_faces: u8,
    /// Bit `i` (0 to 2): edge `i` was appended rather than reused; bit 3: the vertex; bits 4
    /// and 5: faces 0 and 1.
    appended: u8,
}

const VERT_BIT: u8 = 1 << 3;
const FACE_BIT: u8 = 1 << 4;

impl Slots {
    /// Allocates `n_edges` edges (at most 3), one vertex and `n_faces` faces (at most 2), in
    /// that order, every field of the new slots unset (`NONE`) for the caller to fill.
    pub(crate) fn alloc(map: &mut Map, n_edges: usize, n_faces: usize) -> Slots {
        let mut s = Slots::none();
        for i in 0..n_edges.min(3) {
            if map.free_edges.is_empty() {
                s.appended |= 1 << i;
            }
            s.edges[i] = map.alloc_edge().edge();
        }
        if map.free_verts.is_empty() {
            s.appended |= VERT_BIT;
        }
        s.vert = map.alloc_vert();
        for i in 0..n_faces.min(2) {
            if map.free_faces.is_empty() {
                s.appended |= FACE_BIT << i;
            }
            s.faces[i] = map.alloc_face();
        }
        s.n_edges = n_edges.min(3) as u8;
        s.n_faces = n_faces.min(2) as u8;
        s
    }

    /// The live slots an operator is about to delete, in the order [`Slots::free`] frees
    /// them: the edges of `edges`, `vert`, `faces`.
    pub(crate) fn deleted(edges: &[Dart], vert: Vert, faces: &[Face]) -> Slots {
        let mut s = Slots::none();
        for (slot, d) in s.edges.iter_mut().zip(edges) {
            *slot = d.edge();
        }
        for (slot, &f) in s.faces.iter_mut().zip(faces) {
            *slot = f;
        }
        s.vert = vert;
        s.n_edges = edges.len().min(3) as u8;
        s.n_faces = faces.len().min(2) as u8;
        s
    }

    fn none() -> Slots {
        Slots {
            edges: [Edge(NONE); 3],
            faces: [Face(NONE); 2],
            vert: Vert(NONE),
            n_edges: 0,
            n_faces: 0,
            appended: 0,
        }
    }

    /// The even dart of edge `i`.
    #[inline]
    pub(crate) fn edge(&self, i: usize) -> Dart {
        self.edges[i].dart(0)
    }

    #[inline]
    pub(crate) fn vert(&self) -> Vert {
        self.vert
    }

    #[inline]
    pub(crate) fn face(&self, i: usize) -> Face {
        self.faces[i]
    }

    fn edges(&self) -> &[Edge] {
        &self.edges[..self.n_edges as usize]
    }

    fn faces(&self) -> &[Face] {
        &self.faces[..self.n_faces as usize]
    }

    /// Whether the slots can be given back as [`Slots::release`] will: the appended ones of
    /// each kind are, in allocation order, exactly the last slots of their arrays.
    pub(crate) fn releasable(&self, map: &Map) -> bool {
        let vert = [self.vert];
        tail_fits(self.edges(), self.appended, map.edge_slots(), |e| e.0)
            && tail_fits(&vert, self.appended >> 3, map.vertex_slots(), |v| v.0)
            && tail_fits(self.faces(), self.appended >> 4, map.face_slots(), |f| f.0)
    }

    /// Un-allocates the slots in reverse order: appended slots are cut off the arrays, reused
    /// ones go back on the free lists, which restores both exactly. Call only when
    /// [`Slots::releasable`] holds.
    pub(crate) fn release(&self, map: &mut Map) {
        for (i, &f) in self.faces().iter().enumerate().rev() {
            if self.appended & (FACE_BIT << i) != 0 {
                map.fdart.pop();
            } else {
                map.free_face(f);
            }
        }
        if self.appended & VERT_BIT != 0 {
            map.vdart.pop();
        } else {
            map.free_vert(self.vert);
        }
        for (i, &e) in self.edges().iter().enumerate().rev() {
            if self.appended & (1 << i) != 0 {
                let n = map.next.len().saturating_sub(2);
                map.next.truncate(n);
                map.vert.truncate(n);
                map.face.truncate(n);
            } else {
                map.free_edge(e.dart(0));
            }
        }
    }

    /// Frees the (live) slots in order: edges, the vertex, faces.
    pub(crate) fn free(&self, map: &mut Map) {
        for &e in self.edges() {
            map.free_edge(e.dart(0));
        }
        map.free_vert(self.vert);
        for &f in self.faces() {
            map.free_face(f);
        }
    }

    /// Whether the slots are on top of the free lists as [`Slots::free`] left them.
    pub(crate) fn on_free_lists(&self, map: &Map) -> bool {
        let n = self.edges().len();
        let fe = &map.free_edges;
        fe.len() >= n
            && fe[fe.len() - n..]
                .iter()
                .zip(self.edges())
                .all(|(&x, e)| x == e.0)
            && map.free_verts.last() == Some(&self.vert.0)
            && map.free_faces.len() >= self.faces().len()
            && map.free_faces[map.free_faces.len() - self.faces().len()..]
                .iter()
                .zip(self.faces())
                .all(|(&x, f)| x == f.0)
    }

    /// Takes the slots back off the free lists (dead slots, every field `NONE`, for the
    /// caller to fill); [`Refusal::StaleRecord`] and no change unless
    /// [`Slots::on_free_lists`] holds.
    pub(crate) fn reclaim(&self, map: &mut Map) -> Result<(), Refusal> {
        if !self.on_free_lists(map) {
            return Err(Refusal::StaleRecord);
        }
        let ne = map.free_edges.len() - self.edges().len();
        map.free_edges.truncate(ne);
        map.free_verts.pop();
        let nf = map.free_faces.len() - self.faces().len();
        map.free_faces.truncate(nf);
        Ok(())
    }
}

/// Whether the slots flagged in `appended` (bit `i` for `slots[i]`) are, in order, exactly
/// the last ones of an array of `len` slots.
fn tail_fits<T: Copy>(slots: &[T], appended: u8, len: usize, index: impl Fn(T) -> u32) -> bool {
    let k = (0..slots.len())
        .filter(|i| appended & (1 << i) != 0)
        .count();
    let Some(mut expect) = len.checked_sub(k) else {
        return false;
    };
    for (i, &s) in slots.iter().enumerate() {
        if appended & (1 << i) != 0 {
            if index(s) as usize != expect {
                return false;
            }
            expect += 1;
        }
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::gen;

    /// A torus with two edges, a vertex and a face freed as one record's slots.
    fn freed() -> (Map, Slots) {
        let mut map = gen::torus_grid(4, 4).map;
        let s = Slots::deleted(&[Dart(0), Dart(6)], Vert(2), &[Face(1)]);
        s.free(&mut map);
        (map, s)
    }

    #[test]
    fn freed_slots_are_on_top_until_anything_else_is() {
        let (map, s) = freed();
        assert!(s.on_free_lists(&map));
        // One more slot of any kind on top, or one of the record's taken off, hides them.
        let edits: [fn(&mut Map); 6] = [
            |m| m.free_edges.push(9),
            |m| m.free_verts.push(9),
            |m| m.free_faces.push(9),
            |m| m.free_edges.truncate(1),
            |m| m.free_faces.clear(),
            |m| m.free_edges.swap(0, 1),
        ];
        for (i, edit) in edits.iter().enumerate() {
            let mut m = map.clone();
            edit(&mut m);
            assert!(!s.on_free_lists(&m), "edit {i} went unnoticed");
            let before = m.clone();
            assert_eq!(s.reclaim(&mut m), Err(Refusal::StaleRecord), "edit {i}");
            assert_eq!(m, before, "edit {i}: a refused reclaim changed the map");
        }
    }

    #[test]
    fn reclaim_takes_exactly_the_record_off_the_lists() {
        let (mut map, s) = freed();
        map.free_edges.insert(0, 11);
        let lists = |m: &Map| {
            (
                m.free_edges.clone(),
                m.free_verts.clone(),
                m.free_faces.clone(),
            )
        };
        assert_eq!(s.reclaim(&mut map), Ok(()));
        assert_eq!(lists(&map), (alloc::vec![11], alloc::vec![], alloc::vec![]));
    }

    #[test]
    fn allocated_slots_release_to_the_map_before() {
        for (edges, faces) in [(3, 2), (2, 1), (1, 0)] {
            // Reused slots (a freed record on the lists) and appended ones.
            for reuse in [false, true] {
                let (mut map, _) = freed();
                if !reuse {
                    map = gen::torus_grid(4, 4).map;
                }
                let before = map.clone();
                let s = Slots::alloc(&mut map, edges, faces);
                assert!(s.releasable(&map));
                let mut grown = map.clone();
                grown.alloc_vert();
                // A vertex appended after the record's own appended one hides it.
                assert_eq!(s.releasable(&grown), reuse);
                s.release(&mut map);
                assert_eq!(map, before, "{edges} edges, {faces} faces, reuse {reuse}");
            }
        }
    }
}
