//! Bounded model checking by exhaustive enumeration.
