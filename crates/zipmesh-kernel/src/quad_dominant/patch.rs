//! The exact undo of a triangle move: the entries it wrote, old and new.
//!
//! A move touches a handful of array entries (the `next`, origin and face of some darts, the
//! records of some vertices and faces) and allocates or frees a few slots. Its [`Patch`]
//! saves the old value of every touched entry before the move and the new one after; the
//! undo checks that each entry still holds what the move wrote and that the slots are where
//! it left them, then puts the slots back and the old values in place. Written by hand
//! rather than as the inverse move because the inverse of a move is not always the same
//! kind of move with the same arguments (an EV after a VE merges the two halves back, but
//! which dart records the vertex is the patch's to know), and because one mechanism then
//! serves all four moves and the merge.

use crate::map::{Dart, Face, Map, Vert, NONE};
use crate::ops::guard::Guard;
use crate::ops::slots::Slots;
use crate::ops::Refusal;
use alloc::vec::Vec;

/// One dart's three fields.
type DartFields = [u32; 3];

/// The touched entries of one move, before and after, and the slots it allocated or freed.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct Patch {
    darts: Vec<(u32, DartFields, DartFields)>,
    verts: Vec<(u32, u32, u32)>,
    faces: Vec<(u32, u32, u32)>,
    slots: SlotChange,
}

/// What a move did to slots.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum SlotChange {
    /// No slot allocated or freed.
    None,
    /// These slots were allocated (their entries are not in the patch).
    Allocated(Slots),
    /// These slots were freed (their entries are in the patch, new values `NONE`).
    Freed(Slots),
    /// One edge and one face were allocated (no vertex): the edge's even dart and the face,
    /// each with whether it was appended rather than taken from its free list.
    EdgeFace(Dart, bool, Face, bool),
    /// One edge and one face were freed (their entries are in the patch).
    FreedEdgeFace(Dart, Face),
}

impl SlotChange {
    /// Allocates one edge and one face (no vertex), as [`Slots::alloc`] would.
    pub(crate) fn alloc_edge_face(map: &mut Map) -> SlotChange {
        let edge_appended = map.free_edges.is_empty();
        let e = map.alloc_edge();
        let face_appended = map.free_faces.is_empty();
        let f = map.alloc_face();
        SlotChange::EdgeFace(e, edge_appended, f, face_appended)
    }
}

fn fields(map: &Map, d: u32) -> DartFields {
    let i = d as usize;
    [map.next[i], map.vert[i], map.face[i]]
}

impl Patch {
    /// Saves the old values of the given entries (live ones: the caller planned the move on
    /// this map). Repeated entries are saved once.
    pub(crate) fn before(map: &Map, darts: &[Dart], verts: &[Vert], faces: &[Face]) -> Patch {
        let mut d: Vec<u32> = darts.iter().map(|d| d.0).collect();
        let mut v: Vec<u32> = verts.iter().map(|v| v.0).collect();
        let mut f: Vec<u32> = faces.iter().map(|f| f.0).collect();
        for x in [&mut d, &mut v, &mut f] {
            x.sort_unstable();
            x.dedup();
        }
        Patch {
            darts: d
                .into_iter()
                .map(|d| (d, fields(map, d), [NONE; 3]))
                .collect(),
            verts: v
                .into_iter()
                .map(|v| (v, map.vdart[v as usize], NONE))
                .collect(),
            faces: f
                .into_iter()
                .map(|f| (f, map.fdart[f as usize], NONE))
                .collect(),
            slots: SlotChange::None,
        }
    }

    /// Records the new values, after the move, and what it did to slots.
    pub(crate) fn seal(mut self, map: &Map, slots: SlotChange) -> Patch {
        for (d, _, new) in &mut self.darts {
            *new = fields(map, *d);
        }
        for (v, _, new) in &mut self.verts {
            *new = map.vdart[*v as usize];
        }
        for (f, _, new) in &mut self.faces {
            *new = map.fdart[*f as usize];
        }
        self.slots = slots;
        self
    }

    /// The staleness checks, in order.
    pub(crate) fn guard(&self, map: &Map) -> Guard {
        let get = |a: &Vec<u32>, i: u32| a.get(i as usize).copied();
        Guard::new()
            .check("touched darts as the move left them", || {
                self.darts.iter().all(|&(d, _, new)| {
                    [get(&map.next, d), get(&map.vert, d), get(&map.face, d)] == new.map(Some)
                })
            })
            .check("touched vertex records as the move left them", || {
                self.verts
                    .iter()
                    .all(|&(v, _, new)| get(&map.vdart, v) == Some(new))
            })
            .check("touched face records as the move left them", || {
                self.faces
                    .iter()
                    .all(|&(f, _, new)| get(&map.fdart, f) == Some(new))
            })
            .check("slots where the move left them", || match self.slots {
                SlotChange::None => true,
                SlotChange::Allocated(s) => s.releasable(map),
                SlotChange::Freed(s) => s.on_free_lists(map),
                SlotChange::EdgeFace(e, ea, f, fa) => {
                    let top = |list: &Vec<u32>, x: u32, appended: bool, len: usize| {
                        if appended {
                            x as usize + 1 == len
                        } else {
                            (x as usize) < len && !list.contains(&x)
                        }
                    };
                    top(&map.free_edges, e.0 / 2, ea, map.edge_slots())
                        && top(&map.free_faces, f.0, fa, map.face_slots())
                }
                SlotChange::FreedEdgeFace(e, f) => {
                    map.free_edges.last() == Some(&(e.0 / 2)) && map.free_faces.last() == Some(&f.0)
                }
            })
    }

    /// Restores the map as it was before the move; [`Refusal::StaleRecord`] and no change
    /// if a check of [`Patch::guard`] fails.
    ///
    /// The guard shows the touched entries are as the move left them, not that the rest of
    /// the map is the one the move ran on: on a foreign map that passes it, the old values
    /// could leave an invalid map. So the undo is made on a copy that replaces the map only if
    /// it passes [`Map::check`]: O(size of the map) per undo, the price of the kernel's
    /// contract until a local check of the restored orbits replaces it.
    pub(crate) fn undo(&self, map: &mut Map) -> Result<(), Refusal> {
        self.guard(map).result()?;
        let mut trial = map.clone();
        self.restore(&mut trial)?;
        if trial.check().is_err() {
            return Err(Refusal::StaleRecord);
        }
        *map = trial;
        Ok(())
    }

    /// [`Patch::undo`] in place, without the copy and the full check: O(entries touched).
    /// Only for a probe that made the move on this very map and changed nothing since, so
    /// that the record cannot be stale; the guard still runs.
    pub(crate) fn undo_fresh(&self, map: &mut Map) -> Result<(), Refusal> {
        self.guard(map).result()?;
        self.restore(map)
    }

    /// Puts the slots back and the old values in place (the guard has passed).
    fn restore(&self, map: &mut Map) -> Result<(), Refusal> {
        match self.slots {
            SlotChange::None => {}
            SlotChange::Allocated(s) => s.release(map),
            SlotChange::Freed(s) => s.reclaim(map)?,
            SlotChange::EdgeFace(e, ea, f, fa) => {
                if fa {
                    map.fdart.pop();
                } else {
                    map.free_face(f);
                }
                if ea {
                    let n = map.next.len().saturating_sub(2);
                    map.next.truncate(n);
                    map.vert.truncate(n);
                    map.face.truncate(n);
                } else {
                    map.free_edge(e);
                }
            }
            SlotChange::FreedEdgeFace(..) => {
                map.free_edges.pop();
                map.free_faces.pop();
            }
        }
        for &(d, old, _) in &self.darts {
            let i = d as usize;
            [map.next[i], map.vert[i], map.face[i]] = old;
        }
        for &(v, old, _) in &self.verts {
            map.vdart[v as usize] = old;
        }
        for &(f, old, _) in &self.faces {
            map.fdart[f as usize] = old;
        }
        Ok(())
    }
}
