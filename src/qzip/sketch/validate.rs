//! Validation of a caller-given vertex list.

use alloc::vec::Vec;

use super::{sorted_darts, Path, Rules, SketchError, SketchOptions};
use crate::{Dart, Map, Vert};

/// Checks a caller-given path (`vertices`) that should run from `from` to `to` and returns it as a [`Path`].
///
/// The checks, in order: at least two vertices; every vertex live; the first is `from` and
/// the last is `to`; no vertex twice; consecutive vertices joined by an edge that is neither
/// forbidden nor on a forbidden face (when several edges join them, the lowest-index allowed
/// one is used). `opts.avoid_boundary` and `opts.weights` play no part.
///
/// ```
/// use zipmesh::{gen, Vert};
/// use zipmesh::qzip::{validate_path, SketchError, SketchOptions};
/// let map = gen::grid(3, 3).map;
/// let v = |i| Vert::new(i);
/// let opts = SketchOptions::default();
/// assert!(validate_path(&map, v(0), v(2), &[v(0), v(1), v(2)], &opts).is_ok());
/// assert!(matches!(
///     validate_path(&map, v(0), v(2), &[v(0), v(2)], &opts),
///     Err(SketchError::NotAdjacent { index: 0, .. })
/// ));
/// ```
pub fn validate_path(
    map: &Map,
    from: Vert,
    to: Vert,
    vertices: &[Vert],
    opts: &SketchOptions<'_>,
) -> Result<Path, SketchError> {
    if vertices.len() < 2 {
        return Err(SketchError::TooShort(vertices.len()));
    }
    for &v in vertices {
        if !map.is_live_vertex(v) {
            return Err(SketchError::DeadVertex(v));
        }
    }
    let ends = [
        (true, from, vertices[0]),
        (false, to, vertices[vertices.len() - 1]),
    ];
    for (start, expected, found) in ends {
        if expected != found {
            return Err(SketchError::WrongEnd {
                start,
                expected,
                found,
            });
        }
    }
    for i in 0..vertices.len() {
        for j in 0..i {
            if vertices[i] == vertices[j] {
                return Err(SketchError::Repeated {
                    vertex: vertices[i],
                    first: j,
                    second: i,
                });
            }
        }
    }
    // Weights play no part in validation, so they are not checked either.
    let unweighted = SketchOptions {
        weights: None,
        ..opts.clone()
    };
    let rules = Rules::new(map, &unweighted, Vec::new())?;
    let forbidden_face = |d: Dart| {
        opts.forbidden_faces
            .iter()
            .copied()
            .find(|&f| map.face(d) == Some(f) || map.face(d.twin()) == Some(f))
    };
    let mut darts = Vec::with_capacity(vertices.len() - 1);
    let mut buf = Vec::new();
    for (i, w) in vertices.windows(2).enumerate() {
        sorted_darts(map, w[0], &mut buf);
        let joining: Vec<Dart> = buf
            .iter()
            .copied()
            .filter(|&d| map.dest(d) == w[1])
            .collect();
        let Some(&first) = joining.first() else {
            return Err(SketchError::NotAdjacent {
                index: i,
                a: w[0],
                b: w[1],
            });
        };
        match joining.iter().copied().find(|&d| rules.usable(d)) {
            Some(d) => darts.push(d),
            None => {
                return Err(match forbidden_face(first) {
                    Some(face) => SketchError::ForbiddenFace { index: i, face },
                    None => SketchError::ForbiddenEdge {
                        index: i,
                        edge: first.edge(),
                    },
                })
            }
        }
    }
    Ok(Path {
        vertices: vertices.to_vec(),
        darts,
    })
}
