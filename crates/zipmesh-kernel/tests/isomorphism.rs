//! `is_isomorphic`, `is_isomorphic_mirror` and `CanonicalCode` against brute-force oracles.
//!
//! * Every map with at most 6 darts (every `next` permutation, every boundary marking that
//!   is constant on `next` cycles and accepted by `Map::from_permutation`), all pairs.
//! * A deterministic sample of the maps with 8 darts, with relabelled copies.
//! * Tori with some quads cut into triangles, small and 300 x 300, against an oracle that
//!   searches the symmetries of the torus grid.

use zipmesh_kernel::invariants::canonical::CanonicalCode;
use zipmesh_kernel::rng::Rng;
use zipmesh_kernel::{gen, is_isomorphic, is_isomorphic_mirror, Map};

/// A map as the permutation data it was built from, with the built map and its code.
struct Raw {
    next: Vec<u32>,
    boundary: Vec<bool>,
    map: Map,
    code: CanonicalCode,
}

impl Raw {
    fn new(next: Vec<u32>, boundary: Vec<bool>) -> Option<Raw> {
        let map = Map::from_permutation(&next, &boundary).ok()?;
        let code = CanonicalCode::of(&map);
        Some(Raw {
            next,
            boundary,
            map,
            code,
        })
    }

    /// The mirror image from its definition: the same darts and twins with every vertex
    /// rotation reversed. Rotation is `rot(d) = next(twin d)`, so the mirror's `next` is
    /// `rot⁻¹ ∘ twin = twin ∘ prev ∘ twin`, and the face left of a dart in the mirror is the
    /// face that was on its right, so its boundary mark is its twin's.
    fn mirror(&self) -> (Vec<u32>, Vec<bool>) {
        let n = self.next.len();
        let mut prev = vec![0u32; n];
        for (d, &x) in self.next.iter().enumerate() {
            prev[x as usize] = d as u32;
        }
        let next = (0..n).map(|d| prev[d ^ 1] ^ 1).collect();
        let boundary = (0..n).map(|d| self.boundary[d ^ 1]).collect();
        (next, boundary)
    }
}

/// All permutations of `0..n`, in lexicographic order.
fn permutations(n: usize) -> Vec<Vec<u32>> {
    let mut out = Vec::new();
    let mut p: Vec<u32> = (0..n as u32).collect();
    loop {
        out.push(p.clone());
        // Next lexicographic permutation.
        let Some(i) = (1..n).rev().find(|&i| p[i - 1] < p[i]) else {
            return out;
        };
        let j = (i..n).rev().find(|&j| p[j] > p[i - 1]).unwrap();
        p.swap(i - 1, j);
        p[i..].reverse();
    }
}

/// Every valid map on `n` darts: each `next` permutation with each boundary marking that
/// is constant on its cycles (invalid ones are rejected by `from_permutation`).
fn maps_with(n: usize) -> Vec<Raw> {
    let mut out = Vec::new();
    for next in permutations(n) {
        let mut cycle = vec![usize::MAX; n];
        let mut count = 0;
        for d0 in 0..n {
            let mut d = d0;
            while cycle[d] == usize::MAX {
                cycle[d] = count;
                d = next[d] as usize;
            }
            if cycle[d0] == count {
                count += 1;
            }
        }
        for mask in 0u32..1 << count {
            let boundary = (0..n).map(|d| (mask >> cycle[d]) & 1 == 1).collect();
            if let Some(raw) = Raw::new(next.clone(), boundary) {
                out.push(raw);
            }
        }
    }
    out
}

/// Brute force: some bijection `f` of the darts with `f(twin d) = twin f(d)`,
/// `f(next d) = next f(d)` and equal boundary marks. Such an `f` is fixed by a permutation of
/// the edges and a choice of direction per edge; every one is tried.
fn oracle(a: (&[u32], &[bool]), b: (&[u32], &[bool]), edge_perms: &[Vec<u32>]) -> bool {
    let n = a.0.len();
    if n != b.0.len() {
        return false;
    }
    let ne = n / 2;
    edge_perms.iter().filter(|p| p.len() == ne).any(|p| {
        (0u32..1 << ne).any(|flip| {
            let f = |d: usize| 2 * p[d / 2] as usize + ((d & 1) ^ ((flip >> (d / 2)) & 1) as usize);
            (0..n).all(|d| f(a.0[d] as usize) == b.0[f(d)] as usize && a.1[d] == b.1[f(d)])
        })
    })
}

fn edge_perms(max_edges: usize) -> Vec<Vec<u32>> {
    (0..=max_edges).flat_map(permutations).collect()
}

fn compare(a: &Raw, b: &Raw, perms: &[Vec<u32>], stats: &mut [usize; 3]) {
    let am = a.mirror();
    let iso = oracle((&a.next, &a.boundary), (&b.next, &b.boundary), perms);
    let iso_m = iso || oracle((&am.0, &am.1), (&b.next, &b.boundary), perms);
    let ctx = || {
        format!(
            "a = {:?} {:?}, b = {:?} {:?}",
            a.next, a.boundary, b.next, b.boundary
        )
    };
    assert_eq!(is_isomorphic(&a.map, &b.map), iso, "{}", ctx());
    assert_eq!(is_isomorphic(&b.map, &a.map), iso, "{}", ctx());
    assert_eq!(a.code == b.code, iso, "{}", ctx());
    assert_eq!(is_isomorphic_mirror(&a.map, &b.map), iso_m, "{}", ctx());
    assert_eq!(is_isomorphic_mirror(&b.map, &a.map), iso_m, "{}", ctx());
    stats[0] += 1;
    stats[1] += usize::from(iso);
    stats[2] += usize::from(iso_m);
}

/// All pairs of maps with at most 6 darts (maps with different dart counts are never
/// isomorphic; those pairs are covered by sampling one map per count against the rest).
#[test]
fn all_pairs_up_to_six_darts() {
    let perms = edge_perms(3);
    let by_size: Vec<Vec<Raw>> = [0, 2, 4, 6].iter().map(|&n| maps_with(n)).collect();
    let sizes: Vec<usize> = by_size.iter().map(Vec::len).collect();
    let mut stats = [0usize; 3];
    for maps in &by_size {
        for i in 0..maps.len() {
            // The mirror built by the library matches the one built from the definition.
            let (mn, mb) = maps[i].mirror();
            let mirror = Raw::new(mn, mb).expect("the mirror of a valid map is valid");
            assert!(is_isomorphic(&maps[i].map.mirror(), &mirror.map));
            for j in i..maps.len() {
                compare(&maps[i], &maps[j], &perms, &mut stats);
            }
        }
    }
    for (s, maps) in by_size.iter().enumerate() {
        for other in by_size.iter().skip(s + 1) {
            for b in other {
                compare(&maps[0], b, &perms, &mut stats);
            }
        }
    }
    println!(
        "maps by dart count 0/2/4/6: {sizes:?}; pairs {}, isomorphic {}, mirror-isomorphic {}",
        stats[0], stats[1], stats[2]
    );
    // Both answers occur, so the comparison is not one-sided.
    assert!(stats[1] > 0 && stats[1] < stats[0] && stats[2] > stats[1]);
}

/// Maps with 8 darts: a deterministic sample (every 97th valid map), each with a randomly
/// relabelled copy, all pairs of that set against the oracle.
#[test]
fn sampled_pairs_with_eight_darts() {
    let perms = edge_perms(4);
    let mut rng = Rng::new(8);
    let mut set = Vec::new();
    for (k, raw) in maps_with(8).into_iter().enumerate() {
        if k % 97 != 0 {
            continue;
        }
        // Relabel: a random permutation of the edges and a random direction per edge.
        let mut p: Vec<usize> = (0..4).collect();
        for i in (1..4).rev() {
            p.swap(i, rng.below(i + 1));
        }
        let flip = rng.below(16);
        let f = |d: usize| 2 * p[d / 2] + ((d & 1) ^ ((flip >> (d / 2)) & 1));
        let mut next = vec![0u32; 8];
        let mut boundary = vec![false; 8];
        for d in 0..8 {
            next[f(d)] = f(raw.next[d] as usize) as u32;
            boundary[f(d)] = raw.boundary[d];
        }
        let copy = Raw::new(next, boundary).expect("a relabelled valid map is valid");
        assert!(is_isomorphic(&raw.map, &copy.map));
        set.push(raw);
        set.push(copy);
    }
    let mut stats = [0usize; 3];
    for i in 0..set.len() {
        for j in i..set.len() {
            compare(&set[i], &set[j], &perms, &mut stats);
        }
    }
    println!(
        "8 darts: {} maps sampled with copies; pairs {}, isomorphic {}, mirror-isomorphic {}",
        set.len(),
        stats[0],
        stats[1],
        stats[2]
    );
    assert!(stats[2] > stats[1] && stats[1] >= set.len());
}

/// A cut: quad `(i, j)` of an `n x n` torus split along `/` (`false`: from `(i, j)` to
/// `(i+1, j+1)`) or `\` (`true`).
type Cut = (usize, usize, bool);

/// The `n x n` torus grid with the given quads cut into two triangles, its vertex numbers
/// permuted, faces shuffled and corner lists rotated by `rng` (when given).
fn cut_torus(n: usize, cuts: &[Cut], rng: Option<&mut Rng>) -> Map {
    let id = |i: usize, j: usize| ((j % n) * n + i % n) as u32;
    let mut polys: Vec<Vec<u32>> = Vec::new();
    for j in 0..n {
        for i in 0..n {
            let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            match cuts.iter().find(|&&(x, y, _)| (x, y) == (i, j)) {
                Some(&(_, _, false)) => polys.extend([vec![a, b, c], vec![a, c, d]]),
                Some(&(_, _, true)) => polys.extend([vec![a, b, d], vec![b, c, d]]),
                None => polys.push(vec![a, b, c, d]),
            }
        }
    }
    if let Some(rng) = rng {
        let mut label: Vec<u32> = (0..(n * n) as u32).collect();
        for i in (1..label.len()).rev() {
            label.swap(i, rng.below(i + 1));
        }
        for p in &mut polys {
            let r = rng.below(p.len());
            p.rotate_left(r);
            for v in p.iter_mut() {
                *v = label[*v as usize];
            }
        }
        for i in (1..polys.len()).rev() {
            polys.swap(i, rng.below(i + 1));
        }
    }
    Map::from_polygons(n * n, &polys).expect("a cut torus is a valid mesh")
}

/// The 8 symmetries of the square lattice fixing the origin, as integer matrices; the first
/// 4 are the rotations (orientation-preserving).
const POINT_GROUP: [[i64; 4]; 8] = [
    [1, 0, 0, 1],
    [0, -1, 1, 0],
    [-1, 0, 0, -1],
    [0, 1, -1, 0],
    [-1, 0, 0, 1],
    [1, 0, 0, -1],
    [0, 1, 1, 0],
    [0, -1, -1, 0],
];

/// The image of a cut under lattice symmetry `r` followed by translation `(tx, ty)`.
fn move_cut(n: usize, r: [i64; 4], (tx, ty): (usize, usize), (i, j, slash): Cut) -> Cut {
    let m = 2 * n as i64;
    // Work with doubled coordinates of the quad's centre, which stay odd.
    let (x, y) = (2 * i as i64 + 1, 2 * j as i64 + 1);
    let (x2, y2) = (r[0] * x + r[1] * y, r[2] * x + r[3] * y);
    let (i2, j2) = (
        ((x2.rem_euclid(m) - 1) / 2) as usize,
        ((y2.rem_euclid(m) - 1) / 2) as usize,
    );
    let (dx, dy) = if slash { (1, -1) } else { (1, 1) };
    let (ex, ey) = (r[0] * dx + r[1] * dy, r[2] * dx + r[3] * dy);
    ((i2 + tx) % n, (j2 + ty) % n, ex != ey)
}

/// The oracle for cut tori: an isomorphism maps triangles to triangles and, as no two cut
/// quads share an edge, diagonals to diagonals; removing them gives an automorphism of the
/// torus grid, which is a translation after a lattice symmetry (the orientation-preserving
/// automorphisms are exactly the 4 n² translations and rotations, one per dart). So the
/// maps are isomorphic iff such a symmetry maps one cut set onto the other.
fn same_pattern(n: usize, a: &[Cut], b: &[Cut], mirror: bool) -> bool {
    if a.len() != b.len() {
        return false;
    }
    let group = if mirror {
        &POINT_GROUP[..]
    } else {
        &POINT_GROUP[..4]
    };
    group.iter().any(|&r| {
        if a.is_empty() {
            return true;
        }
        let moved: Vec<Cut> = a.iter().map(|&c| move_cut(n, r, (0, 0), c)).collect();
        b.iter().any(|&(bi, bj, _)| {
            let t = ((bi + n - moved[0].0) % n, (bj + n - moved[0].1) % n);
            moved
                .iter()
                .all(|&c| b.contains(&move_cut(n, [1, 0, 0, 1], t, c)))
        })
    })
}

/// Random cuts, no two in quads that share an edge.
fn random_cuts(n: usize, count: usize, rng: &mut Rng) -> Vec<Cut> {
    let mut cuts: Vec<Cut> = Vec::new();
    while cuts.len() < count {
        let c = (rng.below(n), rng.below(n), rng.chance(1, 2));
        let near = |&(i, j, _): &Cut| {
            let (di, dj) = ((c.0 + n - i) % n, (c.1 + n - j) % n);
            let (di, dj) = (di.min(n - di), dj.min(n - dj));
            di + dj <= 1
        };
        if !cuts.iter().any(near) {
            cuts.push(c);
        }
    }
    cuts
}

/// Small cut tori: pairs that are random, or a random symmetry image, or a symmetry image
/// with one cut moved, compared with the lattice oracle.
#[test]
fn small_cut_tori_against_the_lattice_oracle() {
    let mut rng = Rng::new(2024);
    let mut stats = [0usize; 3];
    for round in 0..600 {
        let n = 5 + round % 4;
        let count = 1 + rng.below(3);
        let a = random_cuts(n, count, &mut rng);
        let b = match round % 3 {
            0 => random_cuts(n, count, &mut rng),
            _ => {
                let r = POINT_GROUP[rng.below(8)];
                let t = (rng.below(n), rng.below(n));
                let mut b: Vec<Cut> = a.iter().map(|&c| move_cut(n, r, t, c)).collect();
                if round % 3 == 2 {
                    // Move one cut to a random free place.
                    let other = random_cuts(n, count + 1, &mut rng);
                    let k = rng.below(count);
                    let spare = other.iter().find(|c| {
                        !b.iter().enumerate().any(|(x, d)| {
                            x != k && {
                                let (di, dj) = ((c.0 + n - d.0) % n, (c.1 + n - d.1) % n);
                                di.min(n - di) + dj.min(n - dj) <= 1
                            }
                        })
                    });
                    if let Some(&s) = spare {
                        b[k] = s;
                    }
                }
                b
            }
        };
        let ma = cut_torus(n, &a, Some(&mut rng));
        let mb = cut_torus(n, &b, Some(&mut rng));
        let iso = same_pattern(n, &a, &b, false);
        let iso_m = same_pattern(n, &a, &b, true);
        assert_eq!(is_isomorphic(&ma, &mb), iso, "n {n}: {a:?} vs {b:?}");
        assert_eq!(
            is_isomorphic_mirror(&ma, &mb),
            iso_m,
            "n {n}: {a:?} vs {b:?}"
        );
        stats[0] += 1;
        stats[1] += usize::from(iso);
        stats[2] += usize::from(iso_m);
    }
    println!(
        "cut tori: {} pairs, isomorphic {}, mirror-isomorphic {}",
        stats[0], stats[1], stats[2]
    );
    assert!(stats[1] > 0 && stats[1] < stats[0] && stats[2] > stats[1]);
}

/// A 300 x 300 torus, regular and with three quads cut, against relabelled, moved and
/// mirrored versions.
#[test]
fn large_torus() {
    let n = 300;
    let mut rng = Rng::new(300);
    let regular = gen::torus_grid(n, n).map;
    let regular_relabelled = cut_torus(n, &[], Some(&mut rng));
    assert!(is_isomorphic(&regular, &regular_relabelled));
    assert!(is_isomorphic(&regular, &regular.mirror()));

    let a: Vec<Cut> = vec![(10, 20, false), (100, 37, false), (200, 250, true)];
    let ma = cut_torus(n, &a, None);
    assert!(!is_isomorphic(&regular, &ma));
    assert!(!is_isomorphic_mirror(&ma, &regular));

    // Rotated by a quarter turn and translated, then relabelled: isomorphic.
    let b: Vec<Cut> = a
        .iter()
        .map(|&c| move_cut(n, POINT_GROUP[1], (37, 91), c))
        .collect();
    assert!(same_pattern(n, &a, &b, false));
    assert!(is_isomorphic(&ma, &cut_torus(n, &b, Some(&mut rng))));

    // One cut moved by one quad: not isomorphic, even allowing mirrors.
    let mut c = a.clone();
    c[1].1 += 1;
    assert!(!same_pattern(n, &a, &c, true));
    let mc = cut_torus(n, &c, Some(&mut rng));
    assert!(!is_isomorphic(&ma, &mc));
    assert!(!is_isomorphic_mirror(&ma, &mc));

    // One diagonal turned the other way: not isomorphic either.
    let mut d = a.clone();
    d[0].2 = true;
    assert!(!same_pattern(n, &a, &d, true));
    assert!(!is_isomorphic_mirror(
        &ma,
        &cut_torus(n, &d, Some(&mut rng))
    ));

    // Reflected: a mirror image, and the pattern has no reflection symmetry.
    let e: Vec<Cut> = a
        .iter()
        .map(|&c| move_cut(n, POINT_GROUP[4], (5, 0), c))
        .collect();
    assert!(!same_pattern(n, &a, &e, false) && same_pattern(n, &a, &e, true));
    let me = cut_torus(n, &e, Some(&mut rng));
    assert!(!is_isomorphic(&ma, &me));
    assert!(is_isomorphic_mirror(&ma, &me));
    assert!(is_isomorphic(&ma.mirror(), &me));
}
