//! Triangle walks (Q-zip paper, Sec. 3.2) on fuzzer-chosen quad-dominant meshes: every move
//! of a tracked triangle, and of any dart at all, keeps the contract (a refusal agrees with
//! `can_move_triangle` and leaves the map `==`; an application leaves a valid map with its
//! documented effect), merges of colliding triangles are valid, and undoing everything, last
//! first, gives the start back `==`.
#![no_main]

use libfuzzer_sys::fuzz_target;
use zipmesh::quad_dominant::{self, Move};
use zipmesh::{gen, Dart, Map};

enum Undo {
    Move(quad_dominant::TriangleMove),
    Merge(quad_dominant::TriangleMerge),
}

/// A quad-dominant mesh from the first bytes, with its triangles' tip darts.
fn mesh(data: &[u8]) -> (Map, Vec<Dart>) {
    let b = |i: usize| data.get(i).copied().unwrap_or(0) as usize;
    let seed = u64::from(data.get(4).copied().unwrap_or(0));
    let (mesh, tips) = if b(0) % 2 == 0 {
        gen::quad_dominant(4 + b(1) % 8, 4 + b(2) % 8, 1 + b(3) % 3, seed)
    } else {
        let base = gen::random_quad(100 + 20 * (b(1) % 10), b(2) % 3, b(3) % 2, seed);
        gen::with_triangle_pairs(base, 1 + b(5) % 3, b(6) % 16, seed)
    };
    (mesh.map, tips)
}

fuzz_target!(|data: &[u8]| {
    if data.len() < 8 {
        return;
    }
    let (mut map, mut tips) = mesh(data);
    let start = map.clone();
    let mut done: Vec<Undo> = Vec::new();
    for ch in data[8..].chunks(2).take(64) {
        let (a, k) = (ch[0] as usize, ch.get(1).copied().unwrap_or(0) as usize);
        let mv = Move::ALL[k % 4];
        // Mostly a tracked triangle; sometimes any dart (most are refused).
        let (i, t) = if k & 4 == 0 && !tips.is_empty() {
            (Some(a % tips.len()), tips[a % tips.len()])
        } else {
            (None, Dart::new((a * 7 % map.dart_slots().max(1)) as u32))
        };
        let before = map.clone();
        let can = quad_dominant::can_move_triangle(&map, t, mv);
        let effect = mv.effect(&map, t);
        match quad_dominant::move_triangle(&mut map, t, mv) {
            Err(r) => {
                assert_eq!(can, Err(r));
                assert!(map == before, "a refused move changed the map");
            }
            Ok(rec) => {
                assert_eq!(can, Ok(()));
                assert_eq!(map.check(), Ok(()));
                let effect = effect.expect("an applied move has an effect");
                assert_eq!(effect.check(&before, &map, &rec), Ok(()));
                for x in &mut tips {
                    *x = rec.follow(*x);
                }
                if let Some(i) = i {
                    tips[i] = rec.tip();
                }
                // Any dart moved an untracked "triangle" only if it was one; tracked tip
                // darts stay on triangles.
                tips.retain(|&x| map.face(x).is_some_and(|f| map.degree(f) == 3));
                done.push(Undo::Move(rec));
            }
        }
        // A collision of two tracked triangles: merge them.
        if k & 8 != 0 && tips.len() >= 2 {
            let (p, q) = (tips[0], tips[1]);
            if quad_dominant::collision(&map, p, q).is_some() {
                let before = map.clone();
                match quad_dominant::merge_collision(&mut map, p, q) {
                    Ok(m) => {
                        assert_eq!(map.check(), Ok(()));
                        tips.drain(..2);
                        for x in &mut tips {
                            *x = m.follow(*x);
                        }
                        done.push(Undo::Merge(m));
                    }
                    Err(_) => assert!(map == before, "a refused merge changed the map"),
                }
            }
        }
    }
    for u in done.iter().rev() {
        match u {
            Undo::Move(r) => r.undo(&mut map).expect("undo in order fits"),
            Undo::Merge(m) => m.undo(&mut map).expect("undo in order fits"),
        }
    }
    assert!(map == start, "undoing everything gave another map");
});
