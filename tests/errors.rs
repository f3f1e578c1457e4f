//! Every error that wraps another returns it from `source()`, so a caller walking the chain
//! (anyhow, `{:#}` reports) reaches the kernel's reason.

use std::error::Error;
use zipmesh::map::{BuildError, Violation};
use zipmesh::ops::Refusal;
use zipmesh::quad_dominant::compass::WalkError;
use zipmesh::qzip::{Broken, PlanError, PrepareError, Qzip, QzipError, SketchError, Tag, ZipError};
use zipmesh::tri_edit::TriEditError;
use zipmesh::{gen, io, Dart, Vert};

/// The cause `e` gives, as a `T` (panics with `what` if there is none or it is another type).
fn cause<'e, T: Error + 'static>(e: &'e (dyn Error + 'static), what: &str) -> &'e T {
    e.source()
        .unwrap_or_else(|| panic!("{what}: no source"))
        .downcast_ref::<T>()
        .unwrap_or_else(|| panic!("{what}: the source is another type"))
}

#[test]
fn a_qzip_error_returns_its_stage_error() {
    let mut map = gen::torus_grid(6, 6).map;
    let v = Vert::new(0);
    let e = Qzip::new().zip(&mut map, v, v, Tag::LS).unwrap_err();
    assert!(matches!(e, QzipError::Sketch(_)));
    assert_eq!(
        cause::<SketchError>(&e, "sketch"),
        &SketchError::SameVertex(v)
    );
    let plan = PlanError::StalePath { index: 2 };
    let prepare = PrepareError::Carry(plan.clone());
    assert_eq!(
        cause::<PlanError>(&QzipError::Plan(plan.clone()), "plan"),
        &plan
    );
    assert_eq!(cause::<PlanError>(&prepare, "carry"), &plan);
    assert_eq!(
        cause::<PrepareError>(&QzipError::Prepare(prepare.clone()), "prepare"),
        &prepare
    );
    let refused = ZipError::Cleanup {
        vertex: v,
        refusal: Refusal::Loop,
    };
    assert_eq!(cause::<Refusal>(&refused, "cleanup"), &Refusal::Loop);
    let execute = QzipError::Execute(refused.clone());
    assert_eq!(cause::<ZipError>(&execute, "execute"), &refused);
}

#[test]
fn edit_errors_return_the_operators_refusal() {
    let tri = TriEditError::from(Refusal::LinkCondition);
    assert_eq!(cause::<Refusal>(&tri, "tri"), &Refusal::LinkCondition);
    let walk = WalkError::BadArguments(Refusal::DeadHandle);
    assert_eq!(cause::<Refusal>(&walk, "walk"), &Refusal::DeadHandle);
    let broken = Broken::Invalid(Violation::TwinOrigin(Dart::new(3)));
    assert_eq!(
        cause::<Violation>(&broken, "broken"),
        &Violation::TwinOrigin(Dart::new(3))
    );
    // Errors without a cause say so.
    assert!(TriEditError::NotAPair.source().is_none());
    assert!(WalkError::Unreachable.source().is_none());
}

#[test]
fn a_mesh_file_error_returns_the_kernels_build_error() {
    // Three triangles on one edge: not a surface.
    let obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nf 1 2 3\nf 2 1 4\nf 1 2 5\n";
    let e = io::obj::parse(obj).unwrap_err();
    let _: &BuildError = cause(&e, "mesh file");
}
