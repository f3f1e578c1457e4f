//! Unit tests of the triangle operators.
