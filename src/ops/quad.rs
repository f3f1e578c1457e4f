//! Quad operators (in progress).
