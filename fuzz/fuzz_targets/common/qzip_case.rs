//! The input shared by the Q-zip fuzz targets: a small generated quad mesh with isolated or
//! clustered singularities, closed or with boundary, or a patch given face by face (the seeds
//! `fuzz/corpus/TARGET/patch-*` are patches of the real meshes round singularity pairs,
//! written by `cargo run --example fuzz_patches`), two fuzzer-chosen vertices, an initial
//! tag, and a shortest or fuzzer-bent path between the vertices.
#![allow(dead_code)]

use zipmesh::invariants::{irregular_vertices, MeshKind};
use zipmesh::ops::quad;
use zipmesh::qzip::{sketch, validate_path, Path, SketchOptions, Tag};
use zipmesh::{gen, Dart, Map, Vert};

/// Reads the input a byte at a time; zeros once it runs out, so every input is usable.
pub struct Bytes<'a>(&'a [u8]);

impl Bytes<'_> {
    pub fn u8(&mut self) -> u8 {
        match self.0.split_first() {
            Some((&b, rest)) => {
                self.0 = rest;
                b
            }
            None => 0,
        }
    }

    pub fn u16(&mut self) -> u16 {
        u16::from_le_bytes([self.u8(), self.u8()])
    }
}

/// Vertex splits along opposite edges at fuzzer-chosen darts: each split of a regular vertex
/// makes a cluster of two v3s and two v5s. Refused splits are skipped.
fn with_splits(mut map: Map, k: u8, bytes: &mut Bytes) -> Map {
    for _ in 0..k {
        let d = Dart::new(u32::from(bytes.u16()) % map.dart_slots().max(1) as u32);
        if map.is_live_dart(d) {
            let d2 = map.rotate_cw(map.rotate_cw(d));
            let _ = quad::split_vertex(&mut map, d, d2);
        }
    }
    map
}

/// The first byte that asks for a patch given face by face ([`patch`]).
pub const PATCH: u8 = 0xff;

/// The most vertices and faces a patch may have (a few rings round a pair).
pub const PATCH_LIMIT: u16 = 2048;

/// A patch given face by face: vertex and face counts (`u16`, at most [`PATCH_LIMIT`]), then
/// per face its degree (`3 + byte % 2`) and its corners (`u16`, taken modulo the vertex
/// count). `None` if the faces do not make a valid map.
fn patch(bytes: &mut Bytes) -> Option<Map> {
    let nv = bytes.u16().min(PATCH_LIMIT);
    let nf = bytes.u16().min(PATCH_LIMIT);
    if nv == 0 {
        return None;
    }
    let faces: Vec<Vec<u32>> = (0..nf)
        .map(|_| {
            let degree = 3 + usize::from(bytes.u8() % 2);
            (0..degree).map(|_| u32::from(bytes.u16() % nv)).collect()
        })
        .collect();
    Map::from_polygons(usize::from(nv), &faces).ok()
}

/// The bytes of a patch for [`case`]: [`PATCH`], the counts, the faces (triangles and quads
/// only, corners below `nv`). What `cargo run --example fuzz_patches` writes.
pub fn encode_patch(nv: u16, faces: &[Vec<u16>]) -> Vec<u8> {
    let mut out = vec![PATCH];
    out.extend(nv.to_le_bytes());
    out.extend((faces.len() as u16).to_le_bytes());
    for f in faces {
        out.push(u8::from(f.len() == 4));
        for &v in f {
            out.extend(v.to_le_bytes());
        }
    }
    out
}

/// The mesh the bytes ask for: a patch given face by face, or small and generated, with
/// isolated or clustered singularities, closed or with boundary.
fn mesh(bytes: &mut Bytes) -> Option<Map> {
    if bytes.0.first() == Some(&PATCH) {
        bytes.u8();
        return patch(bytes);
    }
    Some(generated(bytes))
}

/// A small generated mesh, with isolated or clustered singularities, closed or with boundary.
fn generated(bytes: &mut Bytes) -> Map {
    let (pick, a, b) = (bytes.u8(), bytes.u8(), bytes.u8());
    let (na, nb) = (3 + usize::from(a % 8), 3 + usize::from(b % 8));
    match pick % 6 {
        0 => gen::subdivided_icosahedron(1).map,
        1 => gen::subdivided_icosahedron(2).map,
        2 => gen::cube(1 + usize::from(a % 5)).map,
        3 => with_splits(gen::torus_grid(na, nb).map, 1 + b % 3, bytes),
        4 => with_splits(gen::grid(na, nb).map, a % 3, bytes),
        _ => {
            let seed = u64::from(bytes.u16());
            gen::random_quad(
                40 + 8 * usize::from(a % 20),
                usize::from(b % 3),
                usize::from(a % 2),
                seed,
            )
            .map
        }
    }
}

/// A vertex: with the low bit set one of the irregular ones, else any slot (dead slots
/// give `None`).
fn vertex(map: &Map, irregular: &[Vert], bytes: &mut Bytes) -> Option<Vert> {
    let x = bytes.u16();
    if x & 1 == 1 && !irregular.is_empty() {
        return Some(irregular[usize::from(x >> 1) % irregular.len()]);
    }
    let v = Vert::new(u32::from(x >> 1) % map.vertex_slots().max(1) as u32);
    map.is_live_vertex(v).then_some(v)
}

/// A path from `from` to `to`: the shortest one, or a fuzzer-driven walk from `from` followed
/// by the shortest path from the walk's end that avoids the walk (its edges are forbidden),
/// validated as a caller's path.
fn path(map: &Map, from: Vert, to: Vert, bytes: &mut Bytes) -> Option<Path> {
    let mode = bytes.u8();
    let mut opts = SketchOptions::default().avoid_boundary(mode & 2 != 0);
    let walk_len = usize::from(mode >> 4);
    if mode & 1 == 0 || walk_len == 0 {
        return sketch(map, from, to, &opts).ok();
    }
    let mut walk = vec![from];
    let mut v = from;
    for _ in 0..walk_len {
        if v == to {
            break;
        }
        let spokes: Vec<Dart> = map.vertex_darts(v).collect();
        if spokes.is_empty() {
            return None;
        }
        v = map.dest(spokes[usize::from(bytes.u8()) % spokes.len()]);
        walk.push(v);
    }
    let last = *walk.last()?;
    if last != to {
        // The rest of the path may not come back to a walk vertex before the last.
        for &w in &walk[..walk.len() - 1] {
            opts.forbidden_edges
                .extend(map.vertex_darts(w).map(|d| d.edge()));
        }
        let tail = sketch(map, last, to, &opts).ok()?;
        walk.extend_from_slice(&tail.vertices()[1..]);
    }
    // The walk may repeat vertices: then validation refuses it, which is fine (no panic).
    validate_path(map, from, to, &walk, &SketchOptions::default()).ok()
}

/// One Q-zip input: the map, the path and the initial tag, and the bytes left.
pub struct Case<'a> {
    pub original: Map,
    pub path: Path,
    pub tag: Tag,
    pub rest: Bytes<'a>,
}

/// The case the bytes ask for, or `None` when they name no usable mesh, vertex or path.
pub fn case(data: &[u8]) -> Option<Case<'_>> {
    let mut bytes = Bytes(data);
    let original = mesh(&mut bytes)?;
    if original.check().is_err() || original.num_vertices() == 0 {
        return None;
    }
    let irregular = irregular_vertices(&original, MeshKind::Quad);
    let tag = Tag::CCW[usize::from(bytes.u8() % 4)];
    let from = vertex(&original, &irregular, &mut bytes)?;
    let to = vertex(&original, &irregular, &mut bytes)?;
    let path = path(&original, from, to, &mut bytes)?;
    Some(Case {
        original,
        path,
        tag,
        rest: bytes,
    })
}
