//! Theorems 5.1 and 5.5 of the triangle paper by exhaustive retriangulation.
//!
//! A region `R` of a triangle mesh is given by its boundary cycle `b_0 .. b_(n-1)` and, for
//! each boundary vertex, the number `t(b_j)` of triangles of `R` at it (the boundary's
//! connectivity: a retriangulation that keeps the valences of the boundary vertices in the
//! whole mesh keeps every `t`). [`enumerate`] lists **every** triangulated disk with that
//! boundary, those `t`, no multi-edge, at most `max_interior` interior vertices and at most
//! `max_irregular` interior vertices of valence other than 6: a depth-first search over an
//! advancing front (fill the triangle on one front edge; its apex is a new interior vertex
//! or a vertex of the same front), with the edge chosen by a fixed rule from the state, so
//! each disk (interior vertices numbered in creation order) is reached on exactly one path.
//! A dedicated search rather than `choice::Exhaustive`: that driver replays every path from
//! the start, and the pruning here (capacities, closed vertices) cuts most paths at depth 2.
//!
//! * **Theorem 5.1** (one irregular vertex `v0`, `l(v0)` not a multiple of 6, convex `R`:
//!   no other configuration with one irregular vertex): on the `r`-disks of lattice cones
//!   with a centre of valence `k` (the convex `k`-gon of side `r`), the disks with at most
//!   one irregular interior vertex and up to `i0 + extra` interior vertices (`i0` the
//!   original's) are exactly one: the original.
//! * **The condition is needed**: for `k = 12` the same search finds more than one disk with
//!   one irregular vertex: the v12 moves.
//! * **Theorem 5.5** (two irregular vertices with valences summing to 12 in a convex `R`:
//!   no retriangulation free of irregular vertices): on convex regions around a 5-7 and a
//!   4-8 pair, the search with `max_irregular = 0` finds no disk at all.
//!
//! Bounds and counts are asserted and printed (`cargo test --test proofs retri -- --nocapture`)
//! and written in docs/VERIFICATION.md.

use std::collections::HashSet;
use zipmesh::map::{Dart, Face, Map, Vert};
use zipmesh::tri_edit::{move_pair, Direction};

/// A region's boundary: the cycle (region on the left) and the triangles at each vertex.
#[derive(Clone, Debug)]
pub struct Boundary {
    /// `t(b_j)`: the triangles of the region at the `j`-th boundary vertex; 0 leaves it
    /// free (any number: used to check the search against Brown's count).
    pub t: Vec<u8>,
}

/// What one enumeration found.
#[derive(Debug, Default)]
pub struct Found {
    /// The complete disks (triangles, vertices `0..n` the boundary, then the interior ones).
    pub disks: Vec<Vec<[u8; 3]>>,
    /// Search nodes visited.
    pub nodes: u64,
}

/// Bounds of a search.
#[derive(Clone, Copy, Debug)]
pub struct Bounds {
    /// Interior vertices at most.
    pub max_interior: usize,
    /// Interior vertices of valence other than 6 at most.
    pub max_irregular: usize,
    /// The largest valence an interior vertex may have.
    pub max_valence: u8,
}

const MAXV: usize = 64;

#[derive(Clone)]
struct State {
    fronts: Vec<Vec<u8>>,
    count: [u8; MAXV],
    adj: [u64; MAXV],
    nv: usize,
    irregular: usize,
    tris: Vec<[u8; 3]>,
}

/// Every disk with the boundary `b` within `bounds` (see the module documentation).
pub fn enumerate(b: &Boundary, bounds: Bounds) -> Found {
    let n = b.t.len();
    assert!(n >= 3 && n + bounds.max_interior <= MAXV);
    let mut s = State {
        fronts: vec![(0..n as u8).collect()],
        count: [0; MAXV],
        adj: [0; MAXV],
        nv: n,
        irregular: 0,
        tris: Vec::new(),
    };
    for j in 0..n {
        let k = (j + 1) % n;
        s.adj[j] |= 1 << k;
        s.adj[k] |= 1 << j;
    }
    let mut found = Found::default();
    search(b, bounds, s, &mut found);
    found
}

/// Brown's number of simplicial triangulations of a disk with `m + 3` labelled boundary
/// vertices and `i` interior ones (W. G. Brown, Enumeration of triangulations of the disk,
/// 1964): `2 (2m+3)! (4i+2m+1)! / ((m+2)! m! i! (3i+2m+3)!)`.
fn brown(i: u128, m: u128) -> u128 {
    let f = |n: u128| (1..=n).product::<u128>();
    2 * f(2 * m + 3) * f(4 * i + 2 * m + 1) / (f(m + 2) * f(m) * f(i) * f(3 * i + 2 * m + 3))
}

/// How many more triangles `v` may take.
fn capacity(b: &Boundary, bounds: Bounds, s: &State, v: usize) -> i32 {
    let cap = if v < b.t.len() {
        if b.t[v] == 0 {
            u8::MAX
        } else {
            b.t[v]
        }
    } else if s.irregular < bounds.max_irregular {
        bounds.max_valence
    } else {
        6
    };
    i32::from(cap) - i32::from(s.count[v])
}

fn on_front(s: &State, v: u8) -> bool {
    s.fronts.iter().any(|f| f.contains(&v))
}

fn search(b: &Boundary, bounds: Bounds, mut s: State, found: &mut Found) {
    found.nodes += 1;
    let Some(front) = s.fronts.pop() else {
        found.disks.push(s.tris);
        return;
    };
    let m = front.len();
    // The front vertex with the least capacity left; fill the edge from it to the next.
    let i = (0..m)
        .min_by_key(|&i| capacity(b, bounds, &s, front[i] as usize))
        .unwrap_or(0);
    let (u, w) = (front[i], front[(i + 1) % m]);
    // The front read from w: w, a_1, ..., a_(m-2), u.
    let from_w: Vec<u8> = (0..m).map(|j| front[(i + 1 + j) % m]).collect();
    // Apex: a vertex of this front.
    for j in 1..m - 1 {
        let x = from_w[j];
        let left: Vec<u8> = from_w[..=j].to_vec(); // w .. x, closed by x -> w
        let right: Vec<u8> = from_w[j..].to_vec(); // x .. u, closed by u -> x
        let mut t = s.clone();
        let new_w = left.len() > 2;
        let new_u = right.len() > 2;
        // A new edge must not exist already (no multi-edge).
        if (new_w && t.adj[w as usize] >> x & 1 == 1) || (new_u && t.adj[u as usize] >> x & 1 == 1)
        {
            continue;
        }
        if new_w {
            t.fronts.push(left);
        }
        if new_u {
            t.fronts.push(right);
        }
        if place(b, bounds, &mut t, [u, w, x]) {
            search(b, bounds, t, found);
        }
    }
    // Apex: a new interior vertex.
    if s.nv - b.t.len() < bounds.max_interior {
        let x = s.nv as u8;
        s.nv += 1;
        let mut f = from_w.clone();
        f.push(x); // w, ..., u, x: the edge u -> w replaced by u -> x -> w
        s.fronts.push(f);
        if place(b, bounds, &mut s, [u, w, x]) {
            search(b, bounds, s, found);
        }
    }
}

/// Adds the triangle `(u, w, x)` and checks its three vertices: none over capacity, none
/// at capacity while still on a front (it would get one more triangle), and a vertex that
/// left every front complete (boundary: `t`; interior: valence 6, or one of the irregular
/// ones allowed, at least 3).
fn place(b: &Boundary, bounds: Bounds, s: &mut State, tri: [u8; 3]) -> bool {
    for k in 0..3 {
        let (a, c) = (tri[k] as usize, tri[(k + 1) % 3] as usize);
        s.adj[a] |= 1 << c;
        s.adj[c] |= 1 << a;
    }
    s.tris.push(tri);
    for &v in &tri {
        let vi = v as usize;
        if capacity(b, bounds, s, vi) < 0 {
            return false;
        }
        s.count[vi] += 1;
        let left = capacity(b, bounds, s, vi);
        let live = on_front(s, v);
        if live && left <= 0 {
            return false;
        }
        if !live {
            if vi < b.t.len() {
                if left != 0 && b.t[vi] != 0 {
                    return false;
                }
            } else if s.count[vi] != 6 {
                if s.count[vi] < 3 || s.irregular >= bounds.max_irregular {
                    return false;
                }
                s.irregular += 1;
            }
        }
    }
    true
}

/// The lattice cone disk of [`zipmesh::gen::cone_disk`].
pub fn cone_disk(k: usize, r: usize) -> Map {
    zipmesh::gen::cone_disk(k, r)
}

/// The boundary of the region `faces` of `map` (a disk: one simple loop), its vertices in
/// order, and the region's interior vertices.
pub fn region_boundary(
    map: &Map,
    faces: &HashSet<Face>,
) -> Option<(Vec<Vert>, Boundary, Vec<Vert>)> {
    let inside = |d: Dart| map.face(d).is_some_and(|f| faces.contains(&f));
    let mut next = std::collections::HashMap::new();
    for &f in faces {
        for d in map.face_darts(f) {
            if !inside(d.twin()) && next.insert(map.origin(d), map.dest(d)).is_some() {
                return None; // a pinched vertex
            }
        }
    }
    let &start = next.keys().min()?;
    let mut cycle = vec![start];
    while let Some(&v) = next.get(cycle.last()?) {
        if v == start {
            break;
        }
        if cycle.len() > next.len() {
            return None;
        }
        cycle.push(v);
    }
    if cycle.len() != next.len() {
        return None; // more than one loop
    }
    let t = cycle
        .iter()
        .map(|&v| map.vertex_darts(v).filter(|&d| inside(d)).count() as u8)
        .collect();
    let on: HashSet<Vert> = cycle.iter().copied().collect();
    let mut interior: Vec<Vert> = faces
        .iter()
        .flat_map(|&f| map.face_darts(f).map(|d| map.origin(d)))
        .filter(|v| !on.contains(v))
        .collect();
    interior.sort();
    interior.dedup();
    Some((cycle, Boundary { t }, interior))
}

/// The faces of `map` with a corner at graph distance below `r` from `seeds`.
pub fn faces_near(map: &Map, seeds: &[Vert], r: usize) -> HashSet<Face> {
    let mut dist = std::collections::HashMap::new();
    let mut frontier: Vec<Vert> = seeds.to_vec();
    for &s in seeds {
        dist.insert(s, 0usize);
    }
    for step in 1..r {
        let mut next = Vec::new();
        for &v in &frontier {
            for d in map.vertex_darts(v) {
                let w = map.dest(d);
                if let std::collections::hash_map::Entry::Vacant(e) = dist.entry(w) {
                    e.insert(step);
                    next.push(w);
                }
            }
        }
        frontier = next;
    }
    map.faces()
        .filter(|&f| map.face_darts(f).any(|d| dist.contains_key(&map.origin(d))))
        .collect()
}

/// The region as a disk of [`enumerate`]'s numbering (boundary `0..n`, interior after), to
/// compare a found disk with it.
fn as_disk(map: &Map, faces: &HashSet<Face>, cycle: &[Vert], interior: &[Vert]) -> Map {
    let index = |v: Vert| -> u32 {
        cycle
            .iter()
            .chain(interior)
            .position(|&x| x == v)
            .expect("a region vertex") as u32
    };
    let tris: Vec<[u32; 3]> = faces
        .iter()
        .map(|&f| {
            let c: Vec<u32> = map.face_darts(f).map(|d| index(map.origin(d))).collect();
            [c[0], c[1], c[2]]
        })
        .collect();
    Map::from_polygons(cycle.len() + interior.len(), &tris).expect("a disk")
}

fn disk_map(n: usize, tris: &[[u8; 3]]) -> Map {
    let nv = 1 + tris.iter().flatten().copied().max().unwrap_or(0) as usize;
    let t: Vec<[u32; 3]> = tris.iter().map(|t| t.map(u32::from)).collect();
    Map::from_polygons(nv.max(n), &t).expect("an enumerated disk is a valid map")
}

/// The interior valences of a found disk other than 6.
fn irregular_of(n: usize, tris: &[[u8; 3]]) -> Vec<usize> {
    let mut count = [0usize; MAXV];
    tris.iter().flatten().for_each(|&v| count[v as usize] += 1);
    let nv = 1 + tris.iter().flatten().copied().max().unwrap_or(0) as usize;
    (n..nv).map(|v| count[v]).filter(|&c| c != 6).collect()
}

/// Runs the search on a region and checks what it found against the region: every disk
/// valid, with the boundary's `t`, and (when `keep` is set) the region itself among them.
fn run(map: &Map, faces: &HashSet<Face>, bounds: Bounds, keep: bool) -> (Found, usize) {
    let (cycle, b, interior) = region_boundary(map, faces).expect("a disk region");
    let found = enumerate(&b, bounds);
    let n = cycle.len();
    let original = as_disk(map, faces, &cycle, &interior);
    let mut same = 0;
    for disk in &found.disks {
        let m = disk_map(n, disk);
        m.check().expect("a valid map");
        assert_eq!(zipmesh::invariants::Counts::of(&m).euler_characteristic, 1);
        assert!(irregular_of(n, disk).len() <= bounds.max_irregular);
        // Same configuration: the same disk with the boundary fixed. Interior vertices are
        // numbered by the search, so compare the canonical codes of the maps with the
        // boundary vertices pinned by distinct marks (a fan of extra triangles would do the
        // same; an equal triangle set after renumbering by the search's order is simpler).
        if same_disk(&m, &original, n) {
            same += 1;
        }
    }
    if keep {
        assert_eq!(same, 1, "the region itself is found exactly once");
    }
    (found, interior.len())
}

/// Whether two disks with the boundary `0..n` in the same order are the same up to
/// renumbering the interior: walk both from the boundary edge `0 -> 1` in the same order
/// and compare the triangles met.
fn same_disk(a: &Map, b: &Map, n: usize) -> bool {
    if a.num_faces() != b.num_faces() || a.num_vertices() != b.num_vertices() {
        return false;
    }
    let (Some(da), Some(db)) = (
        a.dart_between(Vert::new(0), Vert::new(1)),
        b.dart_between(Vert::new(0), Vert::new(1)),
    ) else {
        return false;
    };
    // A breadth-first walk over darts, matching them pairwise.
    let mut map_v: std::collections::HashMap<Vert, Vert> = (0..n as u32)
        .map(|i| (Vert::new(i), Vert::new(i)))
        .collect();
    let mut darts: std::collections::HashMap<Dart, Dart> = std::collections::HashMap::new();
    let mut queue = std::collections::VecDeque::from([(da, db)]);
    while let Some((x, y)) = queue.pop_front() {
        match darts.get(&x) {
            Some(&z) if z != y => return false,
            Some(_) => continue,
            None => {
                darts.insert(x, y);
            }
        }
        let (ox, oy) = (a.origin(x), b.origin(y));
        match map_v.get(&ox) {
            Some(&v) if v != oy => return false,
            Some(_) => {}
            None => {
                map_v.insert(ox, oy);
            }
        }
        if a.face(x).is_some() != b.face(y).is_some() {
            return false;
        }
        queue.push_back((a.next(x), b.next(y)));
        queue.push_back((x.twin(), y.twin()));
    }
    let mut image: Vec<Vert> = map_v.values().copied().collect();
    image.sort();
    image.dedup();
    image.len() == map_v.len()
}

fn verts_of_valence(map: &Map, k: usize) -> Vec<Vert> {
    map.vertices()
        .filter(|&v| !map.is_boundary_vertex(v) && map.valence(v) == k)
        .collect()
}

#[test]
fn retriangulation_theorem_5_1() {
    // (valence, radius, extra interior vertices allowed over the original's)
    let cases = [
        (3, 2, 3),
        (4, 2, 3),
        (5, 2, 3),
        (7, 2, 3),
        (8, 2, 3),
        (9, 2, 2),
        (5, 3, 2),
        (7, 3, 1),
    ];
    for (k, r, extra) in cases {
        let map = cone_disk(k, r);
        assert_eq!(verts_of_valence(&map, k), [Vert::new(0)]);
        assert!(map
            .vertices()
            .all(|v| map.is_boundary_vertex(v) || v.index() == 0 || map.valence(v) == 6));
        let faces: HashSet<Face> = map.faces().collect();
        let i0 = map
            .vertices()
            .filter(|&v| !map.is_boundary_vertex(v))
            .count();
        let bounds = Bounds {
            max_interior: i0 + extra,
            max_irregular: 1,
            // Gauss-Bonnet: the one irregular vertex has valence k.
            max_valence: k.max(6) as u8,
        };
        let (found, _) = run(&map, &faces, bounds, true);
        println!(
            "Theorem 5.1: v{k} in its {r}-disk ({} boundary vertices, {i0} interior, up to {}): {} disk(s) with one irregular vertex, {} search nodes",
            map.vertices().count() - i0,
            i0 + extra,
            found.disks.len(),
            found.nodes
        );
        assert_eq!(found.disks.len(), 1, "v{k}, radius {r}: the vertex moved");
    }
}

#[test]
fn retriangulation_theorem_5_1_needs_its_condition() {
    // A v12 (valence a multiple of 6): its 2-disk has other configurations with one
    // irregular vertex.
    let map = cone_disk(12, 2);
    let faces: HashSet<Face> = map.faces().collect();
    let i0 = map
        .vertices()
        .filter(|&v| !map.is_boundary_vertex(v))
        .count();
    let bounds = Bounds {
        max_interior: i0 + 1,
        max_irregular: 1,
        max_valence: 12,
    };
    let (found, _) = run(&map, &faces, bounds, true);
    println!(
        "Theorem 5.1's condition: v12 in its 2-disk, up to {} interior vertices: {} disks with one irregular vertex, {} nodes",
        i0 + 1,
        found.disks.len(),
        found.nodes
    );
    assert!(found.disks.len() > 1);
}

/// The search is complete and finds each disk once: with the boundary free and no valence
/// bound it finds exactly Brown's number of disks, for every boundary of 3 to 7 vertices
/// and every number of interior vertices up to a bound.
#[test]
fn retriangulation_search_matches_browns_count() {
    let mut total = 0u64;
    for n in 3..=7usize {
        let max_i = match n {
            3 | 4 => 4,
            5 => 3,
            _ => 2,
        };
        let b = Boundary { t: vec![0; n] };
        let bounds = Bounds {
            max_interior: max_i,
            max_irregular: usize::MAX,
            max_valence: 60,
        };
        let found = enumerate(&b, bounds);
        let mut by = vec![0u128; max_i + 1];
        for d in &found.disks {
            let nv = 1 + d.iter().flatten().copied().max().unwrap_or(0) as usize;
            by[nv.max(n) - n] += 1;
            disk_map(n, d).check().expect("a valid disk");
        }
        for (i, &c) in by.iter().enumerate() {
            assert_eq!(
                c,
                brown(i as u128, n as u128 - 3),
                "{n} boundary, {i} interior"
            );
        }
        total += found.disks.len() as u64;
    }
    println!("retriangulation search: {total} disks, as Brown's formula counts them");
}

/// Grows `faces` until it is convex (every boundary vertex with at most 3 triangles of the
/// region) and a disk (no pinched vertex): the faces around a concave or pinched vertex are
/// added. `None` when the region reaches the mesh's boundary.
pub fn convexify(map: &Map, mut faces: HashSet<Face>) -> Option<HashSet<Face>> {
    loop {
        let mut add = Vec::new();
        let verts: HashSet<Vert> = faces
            .iter()
            .flat_map(|&f| map.face_darts(f).map(|d| map.origin(d)))
            .collect();
        for &v in &verts {
            let ds: Vec<Dart> = map.vertex_darts(v).collect();
            let inside = |d: Dart| map.face(d).is_some_and(|f| faces.contains(&f));
            let t = ds.iter().filter(|&&d| inside(d)).count();
            if t == ds.len() && !map.is_boundary_vertex(v) {
                continue; // interior
            }
            // Boundary darts of the region out of v: more than one is a pinch.
            let out = ds
                .iter()
                .filter(|&&d| inside(d) && !inside(d.twin()))
                .count();
            if t >= 4 || out > 1 {
                if map.is_boundary_vertex(v) {
                    return None;
                }
                add.extend(ds.iter().filter_map(|&d| map.face(d)));
            }
        }
        if add.is_empty() {
            return Some(faces);
        }
        faces.extend(add);
    }
}

/// Graph distances from `from` over the whole map.
fn distances(map: &Map, from: Vert) -> std::collections::HashMap<Vert, usize> {
    let mut dist = std::collections::HashMap::from([(from, 0)]);
    let mut queue = std::collections::VecDeque::from([from]);
    while let Some(v) = queue.pop_front() {
        let dv = dist[&v];
        for d in map.vertex_darts(v) {
            let w = map.dest(d);
            if let std::collections::hash_map::Entry::Vacant(e) = dist.entry(w) {
                e.insert(dv + 1);
                queue.push_back(w);
            }
        }
    }
    dist
}

/// The sides of a convex region: for each unit of turning (a vertex with `t` triangles
/// turns by `3 - t`), in order, the side's length `b` (edges) and its distance `d` to `v0`
/// (the least distance of its vertices, corners included). A vertex that turns by 2 is two
/// corners with a side of length 0 between them.
fn sides(
    cycle: &[Vert],
    b: &Boundary,
    dist: &std::collections::HashMap<Vert, usize>,
) -> Vec<(usize, usize)> {
    let n = cycle.len();
    let Some(first) = (0..n).find(|&j| b.t[j] < 3) else {
        return Vec::new();
    };
    let mut out = Vec::new();
    let mut j = first;
    // Walk from corner to corner.
    loop {
        // A corner turning by 2 contributes an empty side first.
        if b.t[j] == 1 {
            out.push((0, dist[&cycle[j]]));
        }
        let mut len = 0;
        let mut d = dist[&cycle[j]];
        let mut k = j;
        loop {
            k = (k + 1) % n;
            len += 1;
            d = d.min(dist[&cycle[k]]);
            if b.t[k] < 3 {
                break;
            }
        }
        out.push((len, d));
        j = k;
        if j == first {
            break;
        }
    }
    out
}

/// A convex region of `map` around the vertex `centre`: the stars of the vertices on
/// shortest paths from it to a few random vertices within `reach`, made convex.
fn random_convex_region(
    map: &Map,
    centre: Vert,
    reach: usize,
    rng: &mut zipmesh::rng::Rng,
) -> Option<HashSet<Face>> {
    let dist = distances(map, centre);
    let mut near: Vec<Vert> = dist
        .iter()
        .filter(|&(_, &d)| d <= reach)
        .map(|(&v, _)| v)
        .collect();
    near.sort();
    let mut seeds = vec![centre];
    for _ in 0..rng.range(0, 4) {
        // Walk back to the centre, each step to a neighbour one closer.
        let mut v = near[rng.below(near.len())];
        while v != centre {
            seeds.push(v);
            v = map
                .vertex_darts(v)
                .map(|d| map.dest(d))
                .find(|w| dist[w] + 1 == dist[&v])?;
        }
    }
    convexify(map, faces_near(map, &seeds, 1))
}

/// Lemma 5.4: for a convex region with one irregular vertex `v0` of valence `k` inside, the
/// boundary has `k` sides (counting turns) and `b_i = d_(i-1) + d_(i+1) - d_i`.
#[test]
fn lemma_5_4_on_random_convex_regions() {
    let mut rng = zipmesh::rng::Rng::new(54);
    let (mut checked, mut skipped) = (0, 0);
    let mut shapes = HashSet::new();
    for k in [3, 4, 5, 7, 8, 9] {
        let map = cone_disk(k, 9);
        let dist = distances(&map, Vert::new(0));
        for _ in 0..40 {
            let Some(faces) = random_convex_region(&map, Vert::new(0), 3, &mut rng) else {
                skipped += 1;
                continue;
            };
            let (cycle, b, _) = region_boundary(&map, &faces).expect("a disk");
            let s = sides(&cycle, &b, &dist);
            assert_eq!(s.len(), k, "v{k}: {s:?}");
            for i in 0..k {
                let (bi, di) = s[i];
                let (dp, dn) = (s[(i + k - 1) % k].1, s[(i + 1) % k].1);
                assert_eq!(bi + di, dp + dn, "v{k}, side {i}: {s:?}");
            }
            shapes.insert(s);
            checked += 1;
        }
    }
    println!(
        "Lemma 5.4: {checked} convex regions checked ({} distinct side lists), {skipped} skipped (reached the cone's rim)",
        shapes.len()
    );
    assert!(checked >= 150 && shapes.len() >= 60);
}

/// Lemma 5.6: a convex region of the regular lattice has six sides (counting turns) with
/// `b1 + b2 = b4 + b5`, `b2 + b3 = b5 + b6`, `b3 + b4 = b6 + b1`.
#[test]
fn lemma_5_6_on_random_convex_regions() {
    let mut rng = zipmesh::rng::Rng::new(56);
    let map = cone_disk(6, 10);
    let dist = distances(&map, Vert::new(0));
    let (mut checked, mut skipped) = (0, 0);
    let mut shapes = HashSet::new();
    for _ in 0..200 {
        let Some(faces) = random_convex_region(&map, Vert::new(0), 4, &mut rng) else {
            skipped += 1;
            continue;
        };
        let (cycle, b, _) = region_boundary(&map, &faces).expect("a disk");
        let s: Vec<usize> = sides(&cycle, &b, &dist).iter().map(|x| x.0).collect();
        assert_eq!(s.len(), 6, "{s:?}");
        for i in 0..3 {
            assert_eq!(s[i] + s[i + 1], s[(i + 3) % 6] + s[(i + 4) % 6], "{s:?}");
        }
        shapes.insert(s);
        checked += 1;
    }
    println!(
        "Lemma 5.6: {checked} convex regions checked ({} distinct side lists), {skipped} skipped",
        shapes.len()
    );
    assert!(checked >= 150 && shapes.len() >= 30);
}

/// A 14 x 14 triangulated torus with one diagonal flipped (two 5-7 pairs) and one pair
/// moved three steps away: an adjacent 5-7 pair `(p, q)` in a regular neighbourhood.
fn torus_lone_pair() -> (Map, Vert, Vert) {
    let n = 14;
    let tris: Vec<[u32; 3]> = zipmesh::gen::torus_quads(n, n)
        .iter()
        .flat_map(|q| [[q[0], q[1], q[2]], [q[0], q[2], q[3]]])
        .collect();
    let mut map = Map::from_polygons(n * n, &tris).expect("a torus");
    let d = map
        .dart_between(Vert::new(0), Vert::new(n as u32 + 1))
        .expect("a diagonal");
    zipmesh::ops::tri::flip_edge(&mut map, d).expect("a flip");
    let (mut p, mut q) = (Vert::new(0), Vert::new(1));
    for _ in 0..3 {
        let m = move_pair(&mut map, p, q, Direction::SplitRight).expect("a regular neighbourhood");
        (p, q) = (m.p(), m.q());
    }
    (map, p, q)
}

/// Theorem 5.5, as stated: convex regions around an adjacent 5-7 pair have no
/// retriangulation free of irregular vertices (up to the stated number of interior
/// vertices).
#[test]
fn retriangulation_theorem_5_5_pair_regions() {
    let (map, p, q) = torus_lone_pair();
    for (r, extra) in [(1, 3), (2, 2)] {
        let faces = convexify(&map, faces_near(&map, &[p, q], r)).expect("inside the torus");
        let (cycle, _, interior) = region_boundary(&map, &faces).expect("a disk");
        let irregular: Vec<usize> = interior
            .iter()
            .map(|&v| map.valence(v))
            .filter(|&l| l != 6)
            .collect();
        assert_eq!(irregular, {
            let mut x = vec![map.valence(p), map.valence(q)];
            x.sort();
            x
        });
        let bounds = Bounds {
            max_interior: interior.len() + extra,
            max_irregular: 0,
            max_valence: 6,
        };
        let (found, i0) = run(&map, &faces, bounds, false);
        println!(
            "Theorem 5.5: 5-7 pair, region of radius {r} ({} boundary, {i0} interior vertices, up to {}): {} regular retriangulations, {} nodes",
            cycle.len(),
            i0 + extra,
            found.disks.len(),
            found.nodes
        );
        assert!(found.disks.is_empty());
        // The control: allowing two irregular vertices, the search finds the region itself
        // (so it does meet pairs), and every disk it finds has a pair summing to 12.
        let two = Bounds {
            max_irregular: 2,
            max_valence: 9,
            ..bounds
        };
        let (with_pair, _) = run(&map, &faces, two, true);
        for d in &with_pair.disks {
            let irr = irregular_of(cycle.len(), d);
            assert!(irr.len() == 2 && irr[0] + irr[1] == 12, "{irr:?}");
        }
        println!(
            "  allowing two irregular vertices: {} disk(s) with a pair, {} nodes",
            with_pair.disks.len(),
            with_pair.nodes
        );
    }
}

/// Theorem 5.5 read from the other side: a convex region of the regular lattice has the
/// same boundary data as any retriangulation of it, and by Gauss-Bonnet two irregular
/// vertices inside have valences summing to 12; so the theorem says no retriangulation
/// has exactly two irregular vertices. The search allows two (valences 3 to 9) and finds
/// only the regular region itself: every pair (5-7, 4-8, 3-9) in every position at once.
#[test]
fn retriangulation_theorem_5_5_flat_regions() {
    let mut rng = zipmesh::rng::Rng::new(55);
    let flat = cone_disk(6, 8);
    let mut regions: Vec<(String, Map, HashSet<Face>)> = Vec::new();
    for r in [1, 2] {
        let m = cone_disk(6, r);
        let f = m.faces().collect();
        regions.push((format!("hexagon of side {r}"), m, f));
    }
    let mut tries = 0;
    while regions.len() < 14 && tries < 600 {
        tries += 1;
        let Some(f) = random_convex_region(&flat, Vert::new(0), 3, &mut rng) else {
            continue;
        };
        let (_, _, interior) = region_boundary(&flat, &f).expect("a disk");
        if (4..=16).contains(&interior.len()) {
            regions.push((
                format!("random convex region {}", regions.len() - 1),
                flat.clone(),
                f,
            ));
        }
    }
    for (name, map, faces) in &regions {
        let (_, _, interior) = region_boundary(map, faces).expect("a disk");
        let extra = if interior.len() <= 8 { 2 } else { 1 };
        let bounds = Bounds {
            max_interior: interior.len() + extra,
            max_irregular: 2,
            max_valence: 9,
        };
        let (found, i0) = run(map, faces, bounds, true);
        println!(
            "Theorem 5.5 (flat side): {name}, {i0} interior vertices, up to {}: {} disk(s), {} nodes",
            i0 + extra,
            found.disks.len(),
            found.nodes
        );
        assert_eq!(found.disks.len(), 1, "{name}: a pair appeared");
    }
}
