//! The triangle paper's semantic edits as campaign properties (`tri_edit`): at sites around
//! the case's irregular vertices, `can_*` and the edit agree, a refusal leaves the map as it
//! was, and an application leaves a valid map whose graph operation changed valences as
//! Sec. 6.1's rules say ([`TriOp::effect`], computed before), whose irregular multiset
//! changed as the edit promises, and whose undo restores the map exactly (`==`).

use super::case::Case;
use super::property::{at_darts, settle, Outcome, Property, SITES};
use crate::invariants::{irregular_valences, MeshKind};
use crate::map::{Dart, Map, Vert};
use crate::ops::tri::{TriOp, TriRecord};
use crate::rng::Rng;
use crate::tri_edit::{
    aggregate_type, can_aggregate_type, can_generate_quadruple_apart, generate_quadruple_apart,
};
use crate::tri_edit::{
    can_cancel_triple, can_generate_pair, can_generate_pair_v7, can_generate_quadruple,
    can_move_pair, can_split_type, cancel_triple, generate_pair, generate_pair_v7,
    generate_quadruple, move_pair, split_type, Direction, Moved, Quadruple, TripleEdit, Via, Via7,
};
use crate::tri_edit::{can_move_far_pair, move_far_pair, Start};
use alloc::format;
use alloc::string::String;
use alloc::vec::Vec;

/// The semantic triangle edits' properties: `tri-pair-move` (atomic 5-7 movement in a
/// random direction), `tri-pair-generate` (v5 and v7 movement with 5-7 generation),
/// `tri-triple-cancel` (5-5-7 and 5-7-7 triples), `tri-quadruple` (5-5-7-7 generation),
/// `tri-far-pair-move` (composite movement of a pair that need not be adjacent) and
/// `tri-type` (type splitting).
///
/// ```
/// use zipmesh::campaign::{self, tri_edit_properties, Config};
/// let props = tri_edit_properties();
/// assert_eq!(props.len(), 6);
/// let report = campaign::run(&Config { cases: 6, max_faces: 300, ..Config::default() }, &props);
/// assert!(report.passed());
/// ```
pub fn tri_edit_properties() -> Vec<Property> {
    alloc::vec![
        Property::new(
            "tri-pair-move",
            "5-7 movement: the op's valence changes (Sec. 6.1), a v5 and a v7 adjacent after, irregular multiset unchanged; exact undo",
            pair_move
        ),
        Property::new(
            "tri-pair-generate",
            "v5 / v7 movement with 5-7 generation: the op's valence changes, multiset + {5, 7}; exact undo",
            pair_generate
        ),
        Property::new(
            "tri-triple-cancel",
            "5-5-7 / 5-7-7 cancellation: the op's valence changes, multiset - {5, 7}, one v5 / v7 left; exact undo",
            triple_cancel
        ),
        Property::new(
            "tri-quadruple",
            "5-5-7-7 generation at a regular vertex, the pairs together or apart (Sec. 7.3): multiset + {5, 5, 7, 7}; exact undo",
            quadruple
        ),
        Property::new(
            "tri-far-pair-move",
            "composite move of a 5-7, 5-5 or 7-7 pair (Sec. 7.1 pipeline): the pair's valences at its new vertices, multiset unchanged; exact undo",
            far_pair_move
        ),
        Property::new(
            "tri-type",
            "type splitting: vk into k-6 v7, v4 into two v5, v3 into three v5; aggregation of those back into one vk (or a refusal, map unchanged); exact undo",
            type_split
        ),
    ]
}

fn interior(map: &Map, v: Vert) -> Option<usize> {
    (!map.is_boundary_vertex(v)).then(|| map.valence(v))
}

/// Up to [`SITES`] darts out of interior vertices whose valence `want` accepts (the focus
/// vertex's first), drawn from the case.
fn vertex_sites(case: &Case, salt: u64, want: impl Fn(usize) -> bool) -> Vec<Dart> {
    let map = &case.mesh.map;
    let mut out: Vec<Dart> = case
        .focus
        .filter(|&v| map.is_live_vertex(v))
        .map(|v| map.vertex_darts(v).take(SITES / 2).collect())
        .unwrap_or_default();
    let pool: Vec<Vert> = map
        .vertices()
        .filter(|&v| interior(map, v).is_some_and(&want))
        .collect();
    let mut rng = case.rng(salt);
    while out.len() < SITES && !pool.is_empty() {
        let v = pool[rng.below(pool.len())];
        let k = rng.below(map.valence(v));
        out.push(cw(map, map.vertex_dart(v), k));
    }
    out
}

fn cw(map: &Map, d: Dart, k: usize) -> Dart {
    (0..k).fold(d, |x, _| map.rotate_cw(x))
}

/// Runs `attempt` at the sites on a triangle-bearing case (others are skipped).
fn run(
    case: &Case,
    salt: u64,
    sites: Vec<Dart>,
    mut attempt: impl FnMut(&Map, &mut Map, Dart, &mut Rng) -> Result<bool, String>,
) -> Outcome {
    at_darts(case, salt, 3, sites, &mut attempt)
}

/// `before`'s irregular multiset with `add` added and `remove` taken out (interior).
fn multiset(before: &Map, add: &[usize], remove: &[usize]) -> Option<Vec<(usize, bool)>> {
    let mut v = irregular_valences(before, MeshKind::Triangle);
    v.extend(add.iter().map(|&k| (k, false)));
    for &k in remove {
        let i = v.iter().position(|&x| x == (k, false))?;
        v.remove(i);
    }
    v.sort_unstable();
    Some(v)
}

fn same_multiset(before: &Map, after: &Map, add: &[usize], remove: &[usize]) -> Result<(), String> {
    let want = multiset(before, add, remove).ok_or("nothing to remove")?;
    let got = irregular_valences(after, MeshKind::Triangle);
    if got == want {
        Ok(())
    } else {
        Err(format!(
            "irregular multiset {got:?}, expected {want:?} (+{add:?} -{remove:?})"
        ))
    }
}

/// The graph operation `op` (planned on `before`) changed counts and valences as its
/// effect (Sec. 6.1's rules) says.
fn op_effect(before: &Map, after: &Map, op: TriOp, record: &TriRecord) -> Result<(), String> {
    let effect = op
        .effect(before)
        .map_err(|r| format!("no effect for {op:?}: {r}"))?;
    effect
        .check(before, after, record)
        .map_err(|e| format!("{}: {e}", op.name()))
}

fn vals(map: &Map, vs: &[Vert]) -> Vec<usize> {
    vs.iter().map(|&v| map.valence(v)).collect()
}

fn pair_move(case: &Case) -> Outcome {
    let map = &case.mesh.map;
    // Darts from an interior v5 to an interior v7, and a few other darts out of v5 (refusals).
    let pairs: Vec<Dart> = map
        .vertices()
        .filter(|&v| interior(map, v) == Some(5))
        .flat_map(|v| map.vertex_darts(v))
        .filter(|&d| interior(map, map.dest(d)) == Some(7))
        .collect();
    let mut sites = vertex_sites(case, 21, |k| k == 5);
    sites.truncate(SITES / 4);
    let mut rng = case.rng(0x7061_6972);
    while sites.len() < SITES && !pairs.is_empty() {
        sites.push(pairs[rng.below(pairs.len())]);
    }
    run(case, 21, sites, |before, work, d, rng| {
        let (p, q) = (before.origin(d), before.dest(d));
        let dir = Direction::ALL[rng.below(6)];
        let can = can_move_pair(before, p, q, dir);
        let result = move_pair(work, p, q, dir).map(|e| e.into_record());
        settle(before, work, can, result, |after, m| {
            op_effect(before, after, m.op(), m.record())?;
            if vals(after, &[m.p(), m.q()]) != [5, 7] || after.dart_between(m.p(), m.q()).is_none()
            {
                return Err(format!(
                    "{dir:?}: the new pair is not an adjacent v5 and v7"
                ));
            }
            same_multiset(before, after, &[], &[])
        })
    })
}

fn pair_generate(case: &Case) -> Outcome {
    let sites = vertex_sites(case, 22, |k| k == 5 || k == 7);
    run(case, 22, sites, |before, work, d, rng| {
        let moved = if rng.below(2) == 0 {
            Moved::First
        } else {
            Moved::Second
        };
        let five = before.valence(before.origin(d)) == 5;
        let check = |after: &Map, op: TriOp, rec: &TriRecord, m: Vert, pq: Option<(Vert, Vert)>| {
            op_effect(before, after, op, rec)?;
            let (p, q) = pq.ok_or("no pair")?;
            let want = if five { [5, 5, 7] } else { [7, 5, 7] };
            if vals(after, &[m, p, q]) != want || after.dart_between(p, q).is_none() {
                return Err("the moved vertex and the new pair have the wrong valences".into());
            }
            same_multiset(before, after, &[5, 7], &[])
        };
        if five {
            let via = [Via::Flip, Via::Collapse, Via::Split][rng.below(3)];
            let can = can_generate_pair(before, d, via);
            let result = generate_pair(work, d, via, moved).map(|e| e.into_record());
            settle(before, work, can, result, |after, g| {
                check(after, g.op(), g.record(), g.moved(), g.pair())
            })
        } else {
            let via = Via7::ALL[rng.below(2)];
            let can = can_generate_pair_v7(before, d, via);
            let result = generate_pair_v7(work, d, via, moved).map(|e| e.into_record());
            settle(before, work, can, result, |after, g| {
                check(after, g.op(), g.record(), g.moved(), g.pair())
            })
        }
    })
}

fn triple_cancel(case: &Case) -> Outcome {
    let sites = vertex_sites(case, 23, |k| k == 5 || k == 7);
    run(case, 23, sites, |before, work, d, rng| {
        let x = before.origin(d);
        let other = cw(before, d, 1 + rng.below(before.valence(x).max(2) - 1));
        let three = [before.dest(d), x, before.dest(other)];
        let can = can_cancel_triple(before, &three);
        let result = cancel_triple(work, &three).map(|e| e.into_record());
        settle(before, work, can, result, |after, t| {
            let rec = match t {
                TripleEdit::Five(m) => *m.record(),
                TripleEdit::Seven(m) => *m.record(),
            };
            op_effect(before, after, t.op(), &rec)?;
            let k = after.valence(t.remaining());
            if k != 5 && k != 7 {
                return Err(format!("the vertex left has valence {k}"));
            }
            same_multiset(before, after, &[], &[5, 7])
        })
    })
}

fn quadruple(case: &Case) -> Outcome {
    let sites = vertex_sites(case, 24, |k| k == 6);
    run(case, 24, sites, |before, work, d, rng| {
        let how = Quadruple::ALL[rng.below(3)];
        if how != Quadruple::CollapseFlip && rng.below(2) == 1 {
            return quadruple_apart(before, work, d, how, rng);
        }
        let can = can_generate_quadruple(before, d, how);
        let result = generate_quadruple(work, d, how).map(|e| e.into_record());
        settle(before, work, can, result, |after, g| {
            let mut v = vals(after, g.vertices());
            v.sort_unstable();
            if v != [5, 5, 7, 7] {
                return Err(format!("{how:?}: the four have valences {v:?}"));
            }
            same_multiset(before, after, &[5, 5, 7, 7], &[])
        })
    })
}

/// The pairs `1..=4` atomic moves apart in a random direction: v5, v7, v5, v7 in polygon
/// order, the multiset + {5, 5, 7, 7}.
fn quadruple_apart(
    before: &Map,
    work: &mut Map,
    d: Dart,
    how: Quadruple,
    rng: &mut Rng,
) -> Result<bool, String> {
    let dir = Direction::ALL[rng.below(6)];
    let k = 1 + rng.below(4);
    let can = can_generate_quadruple_apart(before, d, how, dir, k);
    let result = generate_quadruple_apart(work, d, how, dir, k).map(|e| e.into_record());
    settle(before, work, can, result, |after, g| {
        let v = vals(after, g.vertices());
        if v != [5, 7, 5, 7] {
            return Err(format!(
                "{how:?} apart {k} {dir:?}: the four have valences {v:?}"
            ));
        }
        same_multiset(before, after, &[5, 5, 7, 7], &[])
    })
}

/// Aggregation of what a split of a vk left (`split` the split's vertices): one vertex of
/// valence `k` and `before`'s multiset, or a refusal equal to `can_aggregate_type`'s with
/// the map unchanged.
fn aggregate_back(before: &Map, after: &Map, split: &[Vert], k: usize) -> Result<(), String> {
    let mut back = after.clone();
    let can = can_aggregate_type(after, split);
    match aggregate_type(&mut back, split) {
        Ok(a) => {
            if vals(&back, a.vertices()) != [k] {
                return Err(format!(
                    "v{k}: aggregated into {:?}",
                    vals(&back, a.vertices())
                ));
            }
            back.check()
                .map_err(|v| format!("the aggregation fails check(): {v:?}"))?;
            same_multiset(before, &back, &[], &[])
        }
        Err(e) if can == Err(e) && back == *after => Ok(()),
        Err(e) => Err(format!(
            "aggregation refused ({e}) but can_* said {can:?} or the map changed"
        )),
    }
}

fn type_split(case: &Case) -> Outcome {
    let sites = vertex_sites(case, 25, |k| k == 3 || k == 4 || k > 7);
    run(case, 25, sites, |before, work, d, _| {
        let v = before.origin(d);
        let k = before.valence(v);
        let can = can_split_type(before, v);
        let result = split_type(work, v).map(|e| e.into_record());
        settle(before, work, can, result, |after, s| {
            let (kind, n) = if k > 7 { (7, k - 6) } else { (5, 6 - k) };
            let want: Vec<usize> = (0..n).map(|_| kind).collect();
            if vals(after, s.vertices()) != want {
                return Err(format!("v{k}: left {:?}", vals(after, s.vertices())));
            }
            same_multiset(before, after, &want, &[k])?;
            aggregate_back(before, after, s.vertices(), k)
        })
    })
}

/// The walk's bound in `tri-far-pair-move` (each step clones the map to pick a direction).
const FAR_STEPS: usize = 12;

/// The interior v5 and v7 nearest `s` (breadth-first, at most `radius` edges away, `s`
/// itself left out), nearest first.
fn odd_near(map: &Map, s: Vert, radius: usize) -> Vec<Vert> {
    super::near(map, s, radius, |w| matches!(interior(map, w), Some(5 | 7)))
}

fn far_pair_move(case: &Case) -> Outcome {
    let sites = vertex_sites(case, 26, |k| k == 5 || k == 7);
    run(case, 26, sites, |before, work, d, rng| {
        let s = before.origin(d);
        // The other vertex: one of the three v5 / v7 nearest s.
        let near = odd_near(before, s, 6);
        if near.is_empty() {
            return Ok(false);
        }
        let o = near[rng.below(near.len().min(3))];
        let starts = Start::all(before.valence(s));
        if starts.is_empty() {
            return Ok(false);
        }
        let start = starts[rng.below(starts.len())];
        let moved = if rng.below(2) == 0 {
            Moved::First
        } else {
            Moved::Second
        };
        let want = vals(before, &[s, o]);
        let can = can_move_far_pair(before, d, start, moved, o, FAR_STEPS);
        let result = move_far_pair(work, d, start, moved, o, FAR_STEPS).map(|e| e.into_record());
        settle(before, work, can, result, |after, m| {
            let (a, b) = m.pair();
            if vals(after, &[a, b]) != want {
                return Err(format!(
                    "{start:?}: the pair has valences {:?}, expected {want:?}",
                    vals(after, &[a, b])
                ));
            }
            same_multiset(before, after, &[], &[])
        })
    })
}
