//! Random quad, triangle and quad-dominant meshes of a requested size, genus and number of
//! boundary loops.
//!
//! How they are made is documented on [`random_quad`].

use super::catmull_clark::catmull_clark;
use super::{torus_positions, torus_quads};
use crate::invariants::Counts;
use crate::mesh::Mesh;
use crate::rng::Rng;
use alloc::vec;
use alloc::vec::Vec;
use glam::DVec3;
use hashbrown::HashMap;

/// The largest face count the random generators aim for; larger requests are clamped.
///
/// ```
/// assert!(zipmesh_kernel::gen::MAX_RANDOM_FACES >= 1_000_000);
/// ```
pub const MAX_RANDOM_FACES: usize = 1 << 22;

/// The largest genus, and the largest number of holes, the random generators accept;
/// larger requests are clamped to it.
///
/// ```
/// assert!(zipmesh_kernel::gen::MAX_RANDOM_GENUS >= 1000);
/// ```
pub const MAX_RANDOM_GENUS: usize = 1 << 14;

/// A random connected quad mesh of exactly the given genus with exactly `holes` boundary
/// loops and about `faces` faces.
///
/// # Construction
/// 1. **Pieces.** Genus 0: the surface of an `a x b x c` box grid with random side counts.
///    Genus `g >= 1`: `g` torus grids of random sizes (at least 4 x 4).
/// 2. **Sites.** Each piece offers *sites*: quads whose 4 x 4 block of vertices (the quad and
///    its one-ring) lies inside the piece (strictly inside a box side) and is disjoint from
///    every other site's block. Sites sit on a lattice of period 4 with a random offset, so
///    they are disjoint by construction; pieces are enlarged until they have enough of them.
/// 3. **Connected sum.** Torus `t` and torus `t + 1` each lose one site quad, and the two
///    square holes are glued by merging their corners (reversing orientation), which adds a
///    handle: four vertices of valence 6 appear per gluing.
/// 4. **Holes.** Each requested boundary loop removes one site quad. Its corners are interior
///    and belong to no other hole, so the result stays a manifold with one more loop.
/// 5. **Singularities.** A few more sites are collapsed: the quad is removed and two opposite
///    corners are merged, leaving a vertex of valence 6 and two of valence 3. The site's
///    one-ring being regular and untouched is what makes this valid (the two corners share
///    exactly the two other corners as neighbours).
///
/// The polygon list is then built with [`Mesh::from_polygons`]. For requests of at least
/// about eight times the minimum size, one seed in three instead builds a mesh like
/// [`random_mixed`]'s (one quad in sixteen split) a quarter of the size and applies [`catmull_clark`], which turns each triangle and
/// pentagon into a vertex of valence 3 or 5.
/// [`random_triangle`] splits each quad of a quad mesh along a random diagonal; [`random_mixed`]
/// splits some quads into two triangles and merges some of those triangles with a neighbouring
/// quad into a pentagon (only across an edge whose ends keep valence at least 3).
///
/// Every result is checked (it builds, has the requested genus and loops and is connected);
/// if a random variant ever failed that check, the plain construction (steps 1-4 only) is
/// used instead, and if that failed too an empty mesh is returned. Neither happens for any
/// seed tried by the tests.
///
/// **Size.** Let `T = 64 (genus + holes) + 256`. For `faces >= T` the face count `F`
/// satisfies `|F - faces| <= faces / 8 + 64`. Smaller requests get the pieces' minimum
/// sizes (a torus has at least 16 quads, a box with holes at least 5 x 5 x 5, and every
/// gluing and hole needs a site of its own), with `F <= T + T / 8 + 64`. `faces` is clamped
/// to [`MAX_RANDOM_FACES`], `genus` and `holes` to [`MAX_RANDOM_GENUS`]. The same arguments
/// always give the same mesh.
///
/// ```
/// use zipmesh_kernel::{gen, invariants::Counts};
/// let m = gen::random_quad(500, 2, 1, 7);
/// let c = Counts::of(&m.map);
/// assert_eq!((c.genus, c.boundary_loops, c.components), (2, 1, 1));
/// assert!(m.map.faces().all(|f| m.map.degree(f) == 4));
/// assert!((c.faces as i64 - 500).abs() <= 500 / 8 + 64);
/// ```
pub fn random_quad(faces: usize, genus: usize, holes: usize, seed: u64) -> Mesh {
    random(Family::Quad, faces, genus, holes, seed)
}

/// A random connected triangle mesh of exactly the given genus with exactly `holes` boundary
/// loops and about `faces` faces: a [`random_quad`] mesh of `faces / 2` quads with every quad
/// split along a random diagonal. The face count `F` is even; with `T` as in [`random_quad`],
/// `|F - faces| <= faces / 8 + 130` when `faces >= 2 T`, and `F <= 2 (T + T / 8 + 64)`
/// otherwise. Clamping and determinism as for [`random_quad`].
///
/// ```
/// use zipmesh_kernel::{gen, invariants::Counts};
/// let m = gen::random_triangle(800, 0, 2, 3);
/// let c = Counts::of(&m.map);
/// assert_eq!((c.genus, c.boundary_loops), (0, 2));
/// assert!(m.map.faces().all(|f| m.map.degree(f) == 3));
/// ```
pub fn random_triangle(faces: usize, genus: usize, holes: usize, seed: u64) -> Mesh {
    random(Family::Triangle, faces, genus, holes, seed)
}

/// A random connected quad-dominant mesh of exactly the given genus with exactly `holes`
/// boundary loops and about `faces` faces: mostly quads, with triangles (about one quad in
/// eight is split in two, at least one) and pentagons (one triangle of some of those pairs
/// merged with a neighbouring quad); at least one triangle is always left. Size tolerance, clamping and determinism as for [`random_quad`].
///
/// ```
/// use zipmesh_kernel::{gen, invariants::Counts};
/// let m = gen::random_mixed(1000, 1, 0, 11);
/// let c = Counts::of(&m.map);
/// assert_eq!((c.genus, c.boundary_loops), (1, 0));
/// assert!(m.map.faces().all(|f| (3..=5).contains(&m.map.degree(f))));
/// assert!(m.map.faces().any(|f| m.map.degree(f) == 3));
/// ```
pub fn random_mixed(faces: usize, genus: usize, holes: usize, seed: u64) -> Mesh {
    random(Family::Mixed, faces, genus, holes, seed)
}

fn clamp(faces: usize, genus: usize, holes: usize) -> (usize, usize, usize) {
    (
        faces.min(MAX_RANDOM_FACES),
        genus.min(MAX_RANDOM_GENUS),
        holes.min(MAX_RANDOM_GENUS),
    )
}

/// The three generators.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Family {
    Quad,
    Triangle,
    Mixed,
}

impl Family {
    #[cfg(test)]
    pub(crate) const ALL: [Family; 3] = [Family::Quad, Family::Triangle, Family::Mixed];

    /// A stream per generator, so that equal seeds do not give related meshes.
    fn stream(self) -> u64 {
        match self {
            Family::Quad => 0x51AD_0000_0000_0001,
            Family::Triangle => 0x7121_0000_0000_0002,
            Family::Mixed => 0x313E_0000_0000_0003,
        }
    }
}

/// The generator's mesh: a try with singularities and the Catmull-Clark variant, then a
/// plain one; the empty mesh if neither fits (never seen: see the tests).
fn random(family: Family, faces: usize, genus: usize, holes: usize, seed: u64) -> Mesh {
    let (faces, genus, holes) = clamp(faces, genus, holes);
    attempt(family, faces, genus, holes, seed, true)
        .or_else(|| attempt(family, faces, genus, holes, seed, false))
        .unwrap_or_default()
}

/// One try at a generator; `fancy` enables singularities and the Catmull-Clark variant.
pub(crate) fn attempt(
    family: Family,
    faces: usize,
    genus: usize,
    holes: usize,
    seed: u64,
    fancy: bool,
) -> Option<Mesh> {
    let mut rng = Rng::new(seed ^ family.stream());
    let mesh = match family {
        Family::Quad => {
            let (pos, quads) = quad_polygons(faces, genus, holes, &mut rng, fancy)?;
            Mesh::from_polygons(pos, &quads).ok()?.0
        }
        Family::Triangle => {
            let (pos, quads) = quad_polygons(faces / 2, genus, holes, &mut rng, fancy)?;
            let mut tris = Vec::with_capacity(2 * quads.len());
            for [a, b, c, d] in quads {
                if rng.chance(1, 2) {
                    tris.extend([[a, b, c], [a, c, d]]);
                } else {
                    tris.extend([[a, b, d], [b, c, d]]);
                }
            }
            Mesh::from_polygons(pos, &tris).ok()?.0
        }
        Family::Mixed => {
            // Splits add about faces / 8 and merges remove up to as many: aim a little low.
            let (pos, quads) = base_quads(faces * 16 / 17, genus, holes, &mut rng, fancy);
            let polys = mixify(&quads, pos.len(), 8, &mut rng);
            Mesh::from_polygons(pos, &polys).ok()?.0
        }
    };
    validated(mesh, genus, holes)
}

fn validated(mesh: Mesh, genus: usize, holes: usize) -> Option<Mesh> {
    let c = Counts::of(&mesh.map);
    (c.faces > 0 && c.genus == genus as i64 && c.boundary_loops == holes && c.components == 1)
        .then_some(mesh)
}

/// A rough lower bound on the base mesh for a genus and number of holes, used to decide
/// whether a request is large enough for the Catmull-Clark variant.
fn min_base(genus: usize, holes: usize) -> usize {
    if genus == 0 {
        150 * (1 + holes)
    } else {
        32 * (genus + holes)
    }
}

type Polygons<const N: usize> = (Vec<DVec3>, Vec<[u32; N]>);

/// The quads of a random quad mesh: usually [`base_quads`], for large enough requests
/// sometimes the Catmull-Clark refinement of a mixed mesh a quarter of the size.
fn quad_polygons(
    faces: usize,
    genus: usize,
    holes: usize,
    rng: &mut Rng,
    fancy: bool,
) -> Option<Polygons<4>> {
    if fancy && faces / 4 >= 2 * min_base(genus, holes) && rng.chance(1, 3) {
        // Each split adds 2 to the sum of degrees and each merge removes 2: one quad in
        // sixteen split, so aim the base at faces / 4 less about 1.5 %.
        let (pos, quads) = base_quads(faces * 8 / 33, genus, holes, rng, true);
        let polys = mixify(&quads, pos.len(), 16, rng);
        let mixed = Mesh::from_polygons(pos, &polys).ok()?.0;
        let sub = catmull_clark(&mixed);
        let quads = sub
            .polygons()
            .into_iter()
            .map(|p| <[u32; 4]>::try_from(p.as_slice()).ok())
            .collect::<Option<Vec<_>>>()?;
        Some((sub.positions, quads))
    } else {
        Some(base_quads(faces, genus, holes, rng, fancy))
    }
}

/// Vertices and quads under construction; merged vertices point to their survivor.
struct Soup {
    pos: Vec<DVec3>,
    quads: Vec<[u32; 4]>,
    alive: Vec<bool>,
    alias: Vec<u32>,
}

impl Soup {
    fn vertex(&mut self, p: DVec3) -> u32 {
        self.alias.push(self.pos.len() as u32);
        self.pos.push(p);
        self.pos.len() as u32 - 1
    }

    fn quad(&mut self, q: [u32; 4]) {
        self.quads.push(q);
        self.alive.push(true);
    }

    fn find(&self, mut v: u32) -> u32 {
        // Aliases are one level deep by construction; the bound keeps this total anyway.
        for _ in 0..self.alias.len() {
            let a = self.alias[v as usize];
            if a == v {
                break;
            }
            v = a;
        }
        v
    }

    /// Merges `b` into `a` (both survivors so far).
    fn merge(&mut self, a: u32, b: u32) {
        let (a, b) = (self.find(a), self.find(b));
        if a != b {
            self.alias[b as usize] = a;
        }
    }

    /// The live quads with merged corners, vertices renumbered densely in creation order.
    fn finish(self) -> Polygons<4> {
        let mut new_id = vec![u32::MAX; self.pos.len()];
        let mut quads = Vec::with_capacity(self.quads.len());
        for (q, _) in self.quads.iter().zip(&self.alive).filter(|(_, &a)| a) {
            let q = q.map(|v| self.find(v));
            for v in q {
                new_id[v as usize] = 0;
            }
            quads.push(q);
        }
        let mut pos = Vec::new();
        for (v, id) in new_id.iter_mut().enumerate() {
            if *id == 0 {
                *id = pos.len() as u32;
                pos.push(self.pos[v]);
            }
        }
        for q in &mut quads {
            *q = q.map(|v| new_id[v as usize]);
        }
        (pos, quads)
    }
}

fn shuffle<T>(v: &mut [T], rng: &mut Rng) {
    for i in (1..v.len()).rev() {
        v.swap(i, rng.below(i + 1));
    }
}

fn isqrt(n: usize) -> usize {
    libm::sqrt(n as f64) as usize
}

/// An `nx` x `ny` torus grid (both at least 4) placed at `offset`; returns its sites,
/// shuffled: quads `(ox + 4a + 1, oy + 4b + 1)`, whose blocks `ox + 4a .. ox + 4a + 3`
/// (mod `nx`, likewise in y) are disjoint because `4 * (nx / 4) <= nx`.
fn add_torus(s: &mut Soup, nx: usize, ny: usize, offset: DVec3, rng: &mut Rng) -> Vec<usize> {
    let v0 = s.pos.len() as u32;
    let f0 = s.quads.len();
    for p in torus_positions(nx, ny) {
        s.vertex(p + offset);
    }
    for q in torus_quads(nx, ny) {
        s.quad(q.map(|v| v + v0));
    }
    let (ox, oy) = (rng.below(nx), rng.below(ny));
    let mut sites = Vec::with_capacity((nx / 4) * (ny / 4));
    for b in 0..ny / 4 {
        for a in 0..nx / 4 {
            let (i, j) = ((ox + 4 * a + 1) % nx, (oy + 4 * b + 1) % ny);
            sites.push(f0 + j * nx + i);
        }
    }
    shuffle(&mut sites, rng);
    sites
}

/// Sites along one side of `n` quads, strictly inside it: block starts `1 + o + 4k`.
fn side_sites(n: usize, rng: &mut Rng) -> (usize, usize) {
    let count = n.saturating_sub(1) / 4;
    (count, rng.range(0, n.saturating_sub(1 + 4 * count)))
}

fn box_sites(d: [usize; 3]) -> usize {
    let s = d.map(|n| n.saturating_sub(1) / 4);
    2 * (s[0] * s[1] + s[1] * s[2] + s[0] * s[2])
}

/// The surface of an `a x b x c` box grid; returns its sites, shuffled.
fn add_box(s: &mut Soup, dims: [usize; 3], rng: &mut Rng) -> Vec<usize> {
    let scale = 1.0 / dims.iter().copied().max().unwrap_or(1).max(1) as f64;
    let mut ids: HashMap<[usize; 3], u32> = HashMap::new();
    let mut sites = Vec::new();
    for axis in 0..3 {
        let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
        for side in [0, dims[axis]] {
            let f0 = s.quads.len();
            for j in 0..dims[v] {
                for i in 0..dims[u] {
                    let mut corner = |di: usize, dj: usize| {
                        let mut c = [0; 3];
                        c[axis] = side;
                        c[u] = i + di;
                        c[v] = j + dj;
                        *ids.entry(c).or_insert_with(|| {
                            s.vertex(DVec3::new(c[0] as f64, c[1] as f64, c[2] as f64) * scale)
                        })
                    };
                    // (u, v, axis) is right-handed: counter-clockwise in (u, v) faces +axis.
                    let q = [corner(0, 0), corner(1, 0), corner(1, 1), corner(0, 1)];
                    s.quad(if side == dims[axis] {
                        q
                    } else {
                        [q[0], q[3], q[2], q[1]]
                    });
                }
            }
            let (cu, ou) = side_sites(dims[u], rng);
            let (cv, ov) = side_sites(dims[v], rng);
            for l in 0..cv {
                for k in 0..cu {
                    let (i, j) = (2 + ou + 4 * k, 2 + ov + 4 * l);
                    sites.push(f0 + j * dims[u] + i);
                }
            }
        }
    }
    shuffle(&mut sites, rng);
    sites
}

/// A random quad mesh (steps 1-5 of the module documentation) as a polygon list.
fn base_quads(
    faces: usize,
    genus: usize,
    holes: usize,
    rng: &mut Rng,
    collapses: bool,
) -> Polygons<4> {
    let mut s = Soup {
        pos: Vec::new(),
        quads: Vec::new(),
        alive: Vec::new(),
        alias: Vec::new(),
    };
    let n_collapse = if collapses {
        rng.below(faces / 256 + 2)
    } else {
        0
    };
    let (hole_sites, pool) = if genus == 0 {
        sphere_box(&mut s, faces + holes + n_collapse, holes, rng)
    } else {
        chained_tori(&mut s, faces + holes + n_collapse, genus, holes, rng)
    };
    for &f in &hole_sites {
        s.alive[f] = false;
    }
    for &f in pool.iter().take(n_collapse) {
        let [a, b, c, d] = s.quads[f];
        let (keep, gone) = if rng.chance(1, 2) { (a, c) } else { (b, d) };
        s.alive[f] = false;
        s.pos[keep as usize] = (s.pos[keep as usize] + s.pos[gone as usize]) / 2.0;
        s.merge(keep, gone);
    }
    s.finish()
}

/// Genus 0: the surface of a box of about `quads` quads (the faces asked for plus those
/// the holes and collapses remove) with room for `holes` hole sites; returns the hole
/// sites and the other sites (for the collapses).
fn sphere_box(s: &mut Soup, quads: usize, holes: usize, rng: &mut Rng) -> (Vec<usize>, Vec<usize>) {
    // 2 (ab + bc + ca) = faces + the quads removed later.
    let target = quads / 2;
    let lo = if holes > 0 { 5 } else { 1 };
    let hi = (isqrt(target / 3) * 3 / 2).max(lo);
    let (mut a, mut b) = (rng.range(lo, hi), rng.range(lo, hi));
    if a * b + (a + b) * lo > target {
        // Too small a request for random sides: the smallest box that fits.
        (a, b) = (lo, lo);
    }
    let c = (target.saturating_sub(a * b) + (a + b) / 2) / (a + b);
    let mut dims = [a, b, c.max(lo)];
    while box_sites(dims) < holes {
        let k = (0..3).min_by_key(|&k| dims[k]).unwrap_or(0);
        dims[k] += 4;
    }
    let mut sites = add_box(s, dims, rng);
    let hole_sites = sites.drain(sites.len().saturating_sub(holes)..).collect();
    (hole_sites, sites)
}

/// Genus `genus` (at least 1): a chain of tori glued end to end, about `quads` quads in
/// all before the gluings, the holes spread over them at random; returns the hole sites
/// and the other sites, shuffled (for the collapses).
fn chained_tori(
    s: &mut Soup,
    quads: usize,
    genus: usize,
    holes: usize,
    rng: &mut Rng,
) -> (Vec<usize>, Vec<usize>) {
    let mut holes_on = vec![0usize; genus];
    for _ in 0..holes {
        holes_on[rng.below(genus)] += 1;
    }
    // Every gluing removes two quads.
    let mut remaining = quads + 2 * (genus - 1);
    let (mut hole_sites, mut pool) = (Vec::with_capacity(holes), Vec::new());
    let mut glue_prev = Vec::with_capacity(genus);
    let mut glue_next = Vec::with_capacity(genus);
    for (t, &h) in holes_on.iter().enumerate() {
        let left = genus - t;
        let share = if left == 1 {
            remaining
        } else {
            remaining / left * rng.range(50, 150) / 100
        };
        let hi = isqrt(share).saturating_mul(2).min(share / 4).max(4);
        let nx = rng.range(4, hi);
        let mut ny = ((share + nx / 2) / nx).max(4);
        let mut nx = nx;
        let need = usize::from(t > 0) + usize::from(t + 1 < genus) + h;
        while (nx / 4) * (ny / 4) < need {
            if nx <= ny {
                nx += 4;
            } else {
                ny += 4;
            }
        }
        remaining = remaining.saturating_sub(nx * ny);
        let offset = DVec3::new(6.0 * t as f64, 0.0, 0.0);
        let mut sites = add_torus(s, nx, ny, offset, rng);
        // `need` sites exist, so these pops succeed; `unwrap_or` keeps the code total.
        glue_prev.push(if t > 0 { sites.pop() } else { None });
        glue_next.push(if t + 1 < genus { sites.pop() } else { None });
        hole_sites.extend(sites.drain(sites.len().saturating_sub(h)..));
        pool.extend(sites);
    }
    for t in 1..genus {
        if let (Some(f), Some(g)) = (glue_next[t - 1], glue_prev[t]) {
            glue(s, f, g, rng.below(4));
        }
    }
    shuffle(&mut pool, rng);
    (hole_sites, pool)
}

/// Removes quads `f` and `g` and glues their holes: corner `i` of `f` meets corner
/// `shift - i` of `g`, which runs the second hole the other way round, as an oriented
/// gluing must.
fn glue(s: &mut Soup, f: usize, g: usize, shift: usize) {
    let (p, q) = (s.quads[f], s.quads[g]);
    s.alive[f] = false;
    s.alive[g] = false;
    for (i, &pi) in p.iter().enumerate() {
        let qi = q[(shift + 4 - i) % 4];
        s.pos[pi as usize] = (s.pos[pi as usize] + s.pos[qi as usize]) / 2.0;
        s.merge(pi, qi);
    }
}

/// Splits about one quad in `den` (at least one) into two triangles along a random diagonal,
/// then merges the first triangle of some pairs with an untouched neighbouring quad into a
/// pentagon, only across an edge both of whose ends have valence at least 4 (so no vertex
/// drops below 3). Every split leaves at least one triangle.
fn mixify(quads: &[[u32; 4]], n_vertices: usize, den: usize, rng: &mut Rng) -> Vec<Vec<u32>> {
    const QUAD: u8 = 0;
    const TRI: u8 = 1;
    const DONE: u8 = 2;
    let mut polys: Vec<Vec<u32>> = quads.iter().map(|q| q.to_vec()).collect();
    let mut kind = vec![QUAD; polys.len()];
    let mut tris = Vec::new();
    for _ in 0..(quads.len() / den).max(1) {
        let f = rng.below(quads.len());
        if kind.get(f) != Some(&QUAD) {
            continue;
        }
        let [a, b, c, d] = quads[f];
        let (t1, t2) = if rng.chance(1, 2) {
            ([a, b, c], [a, c, d])
        } else {
            ([a, b, d], [b, c, d])
        };
        polys[f] = t1.to_vec();
        kind[f] = TRI;
        // Only the first triangle of a pair may become a pentagon: every split keeps one.
        tris.push(f);
        polys.push(t2.to_vec());
        kind.push(TRI);
    }
    // Directed edge -> face, and valences (distinct edges per vertex).
    let mut owner: HashMap<(u32, u32), usize> = HashMap::new();
    for (f, p) in polys.iter().enumerate() {
        for k in 0..p.len() {
            owner.insert((p[k], p[(k + 1) % p.len()]), f);
        }
    }
    let mut valence = vec![0usize; n_vertices];
    for &(a, b) in owner.keys() {
        if a < b || !owner.contains_key(&(b, a)) {
            valence[a as usize] += 1;
            valence[b as usize] += 1;
        }
    }
    for &t in &tris {
        if kind[t] != TRI || !rng.chance(1, 2) {
            continue;
        }
        let tri = [polys[t][0], polys[t][1], polys[t][2]];
        let k = rng.below(3);
        let (x, y, z) = (tri[k], tri[(k + 1) % 3], tri[(k + 2) % 3]);
        let Some(&q) = owner.get(&(y, x)) else {
            continue;
        };
        if kind[q] != QUAD
            || valence[x as usize] < 4
            || valence[y as usize] < 4
            || polys[q].contains(&z)
        {
            continue;
        }
        // The quad from x round to y, then the triangle's far corner: y, z, x, q1, q2.
        let Some(at) = polys[q].iter().position(|&v| v == x) else {
            continue;
        };
        let quad = &polys[q];
        let pent = vec![y, z, x, quad[(at + 1) % 4], quad[(at + 2) % 4]];
        polys[t] = pent;
        polys[q].clear();
        kind[t] = DONE;
        kind[q] = DONE;
        valence[x as usize] -= 1;
        valence[y as usize] -= 1;
    }
    polys.retain(|p| !p.is_empty());
    polys
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The random variants never need the fallback on a spread of sizes and seeds.
    #[test]
    fn random_variants_never_fall_back() {
        for seed in 0..40u64 {
            for genus in 0..=3 {
                for holes in 0..=2 {
                    let faces = [0, 10, 100, 700, 2000][(seed % 5) as usize];
                    for family in Family::ALL {
                        assert!(
                            attempt(family, faces, genus, holes, seed, true).is_some(),
                            "{family:?} {faces} {genus} {holes} {seed}"
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn random_variants_never_fall_back_on_many_handles_and_holes() {
        for seed in 0..4u64 {
            for (genus, holes) in [(9, 0), (0, 13), (5, 7), (20, 30), (1, 40)] {
                let t = 64 * (genus + holes) + 256;
                for faces in [0, t / 2, t, 3 * t] {
                    for family in Family::ALL {
                        assert!(attempt(family, faces, genus, holes, seed, true).is_some());
                    }
                }
            }
        }
    }

    #[test]
    fn plain_variants_build() {
        for seed in 0..10u64 {
            for genus in 0..=4 {
                for holes in 0..=3 {
                    for family in Family::ALL {
                        assert!(attempt(family, 300, genus, holes, seed, false).is_some());
                    }
                }
            }
        }
    }
}
