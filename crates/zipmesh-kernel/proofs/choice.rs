//! Choice sources: where a property body gets its inputs.
//!
//! A property is a plain function taking `&mut impl Choice`. The exhaustive driver runs it
//! once for every path through its choices (bounded model checking by enumeration); the
//! random driver samples paths. A symbolic engine such as Kani would implement the same trait
//! with `kani::any()` plus an assumption `x < n`, treating `any` and `sample` alike.

use zipmesh_kernel::rng::Rng;

/// A source of nondeterministic choices.
pub trait Choice {
    /// Any value in `0..n` (`n >= 1`); the exhaustive driver tries every one.
    fn any(&mut self, n: usize) -> usize;

    /// Any value in `0..n` (`n >= 1`) that the property must hold for, but over which the
    /// exhaustive driver does not branch: it draws one at random. Used for choices whose
    /// full enumeration would multiply the state space without adding new maps (for example
    /// a relabelling of a map that the enumeration also reaches directly).
    fn sample(&mut self, n: usize) -> usize;

    /// Any boolean.
    fn any_bool(&mut self) -> bool {
        self.any(2) == 1
    }

    /// Any permutation of `0..n`, as a Lehmer code (every permutation on exactly one path).
    fn any_permutation(&mut self, n: usize) -> Vec<usize> {
        let mut pool: Vec<usize> = (0..n).collect();
        (0..n).map(|_| pool.remove(self.any(pool.len()))).collect()
    }

    /// Like [`Choice::any_permutation`], without branching in the exhaustive driver.
    fn sample_permutation(&mut self, n: usize) -> Vec<usize> {
        let mut pool: Vec<usize> = (0..n).collect();
        (0..n)
            .map(|_| pool.remove(self.sample(pool.len())))
            .collect()
    }
}

/// Depth-first enumeration of every path through a body's `any` choices.
///
/// The body is re-run from the start for each path: the recorded prefix is replayed, new
/// choices start at 0, and after each run the deepest choice that has an untried value is
/// advanced. This needs no cloning of the body's state, only a deterministic body.
pub struct Exhaustive {
    path: Vec<(usize, usize)>,
    pos: usize,
    rng: Rng,
}

impl Exhaustive {
    /// Runs `body` on every path and hands each result to `sink`; returns the number of paths.
    pub fn run<R>(mut body: impl FnMut(&mut Exhaustive) -> R, mut sink: impl FnMut(R)) -> u64 {
        let mut e = Exhaustive {
            path: Vec::new(),
            pos: 0,
            rng: Rng::new(0x5eed),
        };
        let mut paths = 0u64;
        loop {
            e.pos = 0;
            let r = body(&mut e);
            assert_eq!(e.pos, e.path.len(), "body made fewer choices on replay");
            paths += 1;
            sink(r);
            // Advance the deepest choice with an untried value; drop the exhausted tail.
            loop {
                match e.path.pop() {
                    None => return paths,
                    Some((c, n)) if c + 1 < n => {
                        e.path.push((c + 1, n));
                        break;
                    }
                    Some(_) => {}
                }
            }
        }
    }
}

impl Choice for Exhaustive {
    fn any(&mut self, n: usize) -> usize {
        assert!(n >= 1, "a choice needs at least one value");
        let c = if self.pos < self.path.len() {
            let (c, m) = self.path[self.pos];
            assert_eq!(
                m, n,
                "body is not deterministic: choice {} changed range",
                self.pos
            );
            c
        } else {
            self.path.push((0, n));
            0
        };
        self.pos += 1;
        c
    }

    fn sample(&mut self, n: usize) -> usize {
        assert!(n >= 1, "a choice needs at least one value");
        self.rng.below(n)
    }
}

/// Uniformly random choices from a seeded generator.
pub struct Random(pub Rng);

impl Choice for Random {
    fn any(&mut self, n: usize) -> usize {
        assert!(n >= 1, "a choice needs at least one value");
        self.0.below(n)
    }

    fn sample(&mut self, n: usize) -> usize {
        self.any(n)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The driver itself: every permutation of 0..4 is reached exactly once.
    #[test]
    fn exhaustive_reaches_every_path_once() {
        let mut seen = std::collections::HashSet::new();
        let paths = Exhaustive::run(|c| c.any_permutation(4), |p| assert!(seen.insert(p)));
        assert_eq!(paths, 24);
        assert_eq!(seen.len(), 24);
        // Dependent ranges: pairs (a, b) with b < a + 1 for a in 0..3: 1 + 2 + 3 paths.
        let paths = Exhaustive::run(
            |c| {
                let a = c.any(3);
                c.any(a + 1)
            },
            |_| {},
        );
        assert_eq!(paths, 6);
        // A body without choices runs once.
        assert_eq!(Exhaustive::run(|_| (), |_| {}), 1);
    }
}
