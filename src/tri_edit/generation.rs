//! The generations named by a configuration and the valence of the vertex they start at
//! (docs/tri-edit.md), and the inverse edits that are not stored in a record: the
//! generation that undoes an adjacent triple cancellation, and the type edit that undoes a
//! type edit. Each inverse is checked by isomorphism with the input, so what is returned
//! is known to restore it.

use super::{
    aggregate_type, can_generate_pair, can_generate_pair_v7, can_generate_quadruple,
    can_generate_quadruple_apart, generate_pair, generate_pair_v7, split_type, Direction, Moved,
    Quadruple, TriEditError, TripleCancel, TypeEdit, Via, Via7,
};
use crate::is_isomorphic;
use crate::map::{Dart, Map, Vert};

/// How a generation is made (docs/tri-edit.md); what it does depends on the valence of the
/// vertex it starts at.
///
/// See [`Generation::of`] for an example.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum GenerationConfig {
    /// Regular V: flip V-W (v5 at V and W). v5 V: flip the link edge W-B. v7 V: flip V-W.
    Flip,
    /// Regular V: split V along V->W and the opposite dart. v5 V: split W along W->V and
    /// the opposite dart. v7 V: split V along V->W and four darts clockwise.
    Split,
    /// v5 V only: collapse V into W.
    Collapse,
    /// Regular V only: collapse V into W, then flip a spoke of W: a 5-7-7-5 chain, not a
    /// quadruple in two triangles ([`super::remove_quadruple`] does not remove it).
    CollapseFlip,
}

impl GenerationConfig {
    /// The configuration's name in the docs and on the command line.
    ///
    /// ```
    /// use zipmesh::tri_edit::GenerationConfig;
    /// assert_eq!(GenerationConfig::CollapseFlip.name(), "collapse-flip");
    /// ```
    pub fn name(self) -> &'static str {
        match self {
            GenerationConfig::Flip => "flip",
            GenerationConfig::Split => "split",
            GenerationConfig::Collapse => "collapse",
            GenerationConfig::CollapseFlip => "collapse-flip",
        }
    }
}

/// What a generation makes at a vertex: a 5-5-7-7 quadruple at a regular vertex, a 5-5-7
/// triple at a v5, a 5-7-7 triple at a v7.
///
/// See [`Generation::of`] for an example.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Generation {
    /// [`super::generate_quadruple`] at a regular interior vertex.
    Quadruple(Quadruple),
    /// [`generate_pair`] at an interior v5.
    Five(Via),
    /// [`generate_pair_v7`] at an interior v7.
    Seven(Via7),
}

impl Generation {
    /// The generation `config` names at an interior vertex of valence `valence`, if there is
    /// one (a regular vertex takes flip, split or collapse-flip, a v5 flip, collapse or
    /// split, a v7 flip or split).
    ///
    /// ```
    /// use zipmesh::tri_edit::{Generation, GenerationConfig, Via};
    /// assert_eq!(Generation::of(5, GenerationConfig::Collapse), Some(Generation::Five(Via::Collapse)));
    /// assert_eq!(Generation::of(7, GenerationConfig::Collapse), None);
    /// ```
    pub fn of(valence: usize, config: GenerationConfig) -> Option<Generation> {
        use GenerationConfig as C;
        Some(match (valence, config) {
            (6, C::Flip) => Generation::Quadruple(Quadruple::Flip),
            (6, C::Split) => Generation::Quadruple(Quadruple::Split),
            (6, C::CollapseFlip) => Generation::Quadruple(Quadruple::CollapseFlip),
            (5, C::Flip) => Generation::Five(Via::Flip),
            (5, C::Collapse) => Generation::Five(Via::Collapse),
            (5, C::Split) => Generation::Five(Via::Split),
            (7, C::Flip) => Generation::Seven(Via7::Flip),
            (7, C::Split) => Generation::Seven(Via7::Split),
            _ => return None,
        })
    }

    /// Checks whether the generation applies along `d` (for a quadruple with `apart`, also
    /// the walk of [`super::generate_quadruple_apart`]: `(steps, direction)`).
    ///
    /// See [`Generation::first_dart`] for an example.
    pub fn can(
        self,
        map: &Map,
        d: Dart,
        apart: Option<(usize, Direction)>,
    ) -> Result<(), TriEditError> {
        match (self, apart) {
            (Generation::Quadruple(q), Some((k, dir))) => {
                can_generate_quadruple_apart(map, d, q, dir, k)
            }
            (_, Some(_)) => Err(TriEditError::WrongValence),
            (Generation::Quadruple(how), None) => can_generate_quadruple(map, d, how),
            (Generation::Five(via), None) => can_generate_pair(map, d, via),
            (Generation::Seven(via), None) => can_generate_pair_v7(map, d, via),
        }
    }

    /// The first of `darts` along which the generation applies, or the last refusal
    /// ([`TriEditError::WrongValence`] when `darts` is empty).
    ///
    /// ```
    /// use zipmesh::tri_edit::{Generation, GenerationConfig};
    /// use zipmesh::{gen, Vert};
    /// let map = gen::geodesic_sphere(2);
    /// let v = map.vertices().find(|&v| map.valence(v) == 6).unwrap();
    /// let how = Generation::of(6, GenerationConfig::Flip).unwrap();
    /// let d = how.first_dart(&map, map.vertex_darts(v), None).unwrap();
    /// assert_eq!(map.origin(d), v);
    /// assert!(how.can(&map, d, None).is_ok());
    /// ```
    pub fn first_dart(
        self,
        map: &Map,
        darts: impl IntoIterator<Item = Dart>,
        apart: Option<(usize, Direction)>,
    ) -> Result<Dart, TriEditError> {
        let mut last = TriEditError::WrongValence;
        for d in darts {
            match self.can(map, d, apart) {
                Ok(()) => return Ok(d),
                Err(e) => last = e,
            }
        }
        Err(last)
    }
}

impl TripleCancel {
    /// The generation that undoes this cancellation: a dart out of the vertex left and a
    /// configuration whose generation (the moved vertex [`Moved::First`]) turns `edited`, the
    /// map after this cancellation, into one isomorphic to `original`, the map before it.
    /// Found by trying every dart and configuration and checked by isomorphism; `None` when
    /// the pair walked before cancelling (one generation then does not restore the input)
    /// or when none restores it.
    ///
    /// ```
    /// use zipmesh::tri_edit::{cancel_triple_along, generate_pair, Moved, Via};
    /// use zipmesh::gen;
    /// let original = gen::geodesic_sphere(2);
    /// let v = original.vertices().find(|&v| original.valence(v) == 5).unwrap();
    /// let d = original.vertex_darts(v).next().unwrap();
    /// let mut map = original.clone();
    /// let g = generate_pair(&mut map, d, Via::Flip, Moved::First).unwrap();
    /// let before = map.clone();
    /// let (p, q) = g.pair().unwrap();
    /// let t = cancel_triple_along(&mut map, &[g.moved(), p, q], 8).unwrap();
    /// let (d, config) = t.inverse_generation(&map, &before).unwrap();
    /// assert_eq!(map.origin(d), t.remaining());
    /// # let _ = config;
    /// ```
    pub fn inverse_generation(
        &self,
        edited: &Map,
        original: &Map,
    ) -> Option<(Dart, GenerationConfig)> {
        if !self.moves().is_empty() {
            return None;
        }
        let at = self.remaining();
        let k = edited.valence(at);
        let configs = [
            GenerationConfig::Flip,
            GenerationConfig::Split,
            GenerationConfig::Collapse,
        ];
        edited.vertex_darts(at).find_map(|d| {
            configs.into_iter().find_map(|config| {
                let mut m = edited.clone();
                let ok = match Generation::of(k, config)? {
                    Generation::Five(via) => generate_pair(&mut m, d, via, Moved::First).is_ok(),
                    Generation::Seven(via) => {
                        generate_pair_v7(&mut m, d, via, Moved::First).is_ok()
                    }
                    Generation::Quadruple(_) => false,
                };
                (ok && is_isomorphic(&m, original)).then_some((d, config))
            })
        })
    }
}

impl TypeEdit {
    /// Whether the inverse type edit (aggregating what a split left, splitting what an
    /// aggregation made) turns `edited`, the map after this edit, into one isomorphic to
    /// `original`, the map before it. Gathering v7 may put the vk elsewhere, so this is
    /// checked, not assumed.
    ///
    /// ```
    /// use zipmesh::tri_edit::split_type;
    /// use zipmesh::gen;
    /// let original = gen::subdivided_tetrahedron(2);
    /// let v = original.vertices().find(|&v| original.valence(v) == 3).unwrap();
    /// let mut map = original.clone();
    /// let e = split_type(&mut map, v).unwrap();
    /// assert!(e.inverse_restores(&map, &original));
    /// ```
    pub fn inverse_restores(&self, edited: &Map, original: &Map) -> bool {
        let mut m = edited.clone();
        let vs: &[Vert] = self.vertices();
        let done = if self.is_split() {
            aggregate_type(&mut m, vs).is_ok()
        } else {
            vs.first().is_some_and(|&v| split_type(&mut m, v).is_ok())
        };
        done && is_isomorphic(&m, original)
    }
}
