//! `zipmesh._zipmesh`, the compiled half of the Python package `zipmesh`: a mesh held in
//! Rust and handed to Python as numpy arrays, the three mesh formats, and the `zipmesh`
//! commands run in this process.
//!
//! Every report of the package is the command's own `--json` output: the package writes
//! the mesh to a temporary file, runs the command through [`zipmesh_cli::run_captured`]
//! (the binary's code, not a copy of it) and parses what it printed, so that the two cannot
//! drift apart. The Python half (`python/zipmesh/__init__.py`) builds the arguments.

use glam::DVec3;
use numpy::ndarray::Array2;
use numpy::{AllowTypeChange, IntoPyArray, PyArray2, PyArrayLike2};
use pyo3::exceptions::{PyOSError, PyValueError};
use pyo3::prelude::*;
use std::path::PathBuf;
use zipmesh::io::{self, ErrorKind, MeshFileError};
use zipmesh::Mesh;
use zipmesh_cli::CapturedError;

/// A polygon mesh: positions and faces, every vertex used by a face (the constructor and
/// `load` drop unreferenced vertices and renumber the rest in order).
#[pyclass(name = "Mesh", module = "zipmesh._zipmesh", frozen)]
pub struct PyMesh {
    mesh: Mesh,
}

/// A file error as Python's: `OSError` when reading or writing failed, `ValueError` when
/// the file's content or name is wrong.
fn file_error(e: MeshFileError) -> PyErr {
    match e.kind() {
        ErrorKind::Io(_)
        | ErrorKind::IsDirectory
        | ErrorKind::MissingDirectory { .. }
        | ErrorKind::NotADirectory { .. } => PyOSError::new_err(e.to_string()),
        _ => PyValueError::new_err(e.to_string()),
    }
}

/// `mesh` with its dead slots removed, so that vertex and face numbers are the ones a file
/// written from it has.
fn compacted(mut mesh: Mesh) -> PyMesh {
    mesh.compact();
    PyMesh { mesh }
}

/// The faces as rows of vertex numbers, each checked against `n` vertices.
fn face_rows(faces: &Bound<'_, PyAny>, n: usize) -> PyResult<Vec<Vec<u32>>> {
    let rows: Vec<Vec<i64>> = match faces.extract::<PyArrayLike2<'_, i64, AllowTypeChange>>() {
        Ok(array) => array
            .as_array()
            .rows()
            .into_iter()
            .map(|r| r.to_vec())
            .collect(),
        Err(_) => faces.extract().map_err(|_| {
            PyValueError::new_err("faces: expected an (F, k) integer array or a list of lists")
        })?,
    };
    rows.iter()
        .enumerate()
        .map(|(f, row)| {
            row.iter()
                .map(|&v| match u32::try_from(v) {
                    Ok(x) if (x as usize) < n => Ok(x),
                    _ => Err(PyValueError::new_err(format!(
                        "faces: face {f} names vertex {v}, not one of the {n} vertices"
                    ))),
                })
                .collect()
        })
        .collect()
}

#[pymethods]
impl PyMesh {
    /// Builds a mesh from an (N, 3) array of positions and an (F, k) integer array of
    /// faces, or a list of lists for faces of mixed degrees (vertices numbered from 0).
    #[new]
    fn new(
        vertices: PyArrayLike2<'_, f64, AllowTypeChange>,
        faces: &Bound<'_, PyAny>,
    ) -> PyResult<Self> {
        let v = vertices.as_array();
        if v.ncols() != 3 {
            return Err(PyValueError::new_err(format!(
                "vertices: expected an (N, 3) array, got {} columns",
                v.ncols()
            )));
        }
        let positions: Vec<DVec3> = v
            .rows()
            .into_iter()
            .map(|r| DVec3::new(r[0], r[1], r[2]))
            .collect();
        if positions.iter().any(|p| !p.is_finite()) {
            return Err(PyValueError::new_err(
                "vertices: every coordinate must be finite",
            ));
        }
        let rows = face_rows(faces, positions.len())?;
        let (mesh, _) = Mesh::from_polygons(positions, &rows)
            .map_err(|e| PyValueError::new_err(format!("faces: {e}")))?;
        Ok(compacted(mesh))
    }

    /// The positions, an (N, 3) float64 array.
    #[getter]
    fn vertices<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        let flat: Vec<f64> = self
            .mesh
            .positions
            .iter()
            .flat_map(|p| p.to_array())
            .collect();
        let n = self.mesh.positions.len();
        Array2::from_shape_vec((n, 3), flat)
            .unwrap_or_else(|_| Array2::zeros((0, 3)))
            .into_pyarray(py)
    }

    /// The faces as lists of vertex numbers, in face order, each counter-clockwise.
    fn polygons(&self) -> Vec<Vec<u32>> {
        self.mesh.polygons()
    }

    /// The number of vertices.
    #[getter]
    fn num_vertices(&self) -> usize {
        self.mesh.map.num_vertices()
    }

    /// The number of faces.
    #[getter]
    fn num_faces(&self) -> usize {
        self.mesh.map.num_faces()
    }

    /// Writes the mesh to `path`; the extension (.obj, .off, .ply) picks the format, and
    /// `ascii` writes PLY as text instead of binary.
    #[pyo3(signature = (path, ascii = false))]
    fn save(&self, py: Python<'_>, path: PathBuf, ascii: bool) -> PyResult<()> {
        let mesh = &self.mesh;
        let ascii_ply = ascii && io::Format::from_path(&path) == Some(io::Format::Ply);
        py.detach(|| {
            if ascii_ply {
                io::write_atomic(&path, |w| io::ply::write_ascii(mesh, w))
            } else {
                io::write_mesh(&path, mesh)
            }
        })
        .map_err(file_error)
    }
}

/// Reads a mesh from an .obj, .off or .ply file.
#[pyfunction]
fn load(py: Python<'_>, path: PathBuf) -> PyResult<PyMesh> {
    let (mesh, _) = py.detach(|| io::read_mesh(&path)).map_err(file_error)?;
    Ok(compacted(mesh))
}

/// Runs one `zipmesh` command (its arguments, without the program's name) with the
/// interpreter lock released, and returns what it printed. A usage error or a refusal is
/// a `ValueError` with the command's message.
#[pyfunction]
fn run(py: Python<'_>, args: Vec<String>) -> PyResult<String> {
    py.detach(|| zipmesh_cli::run_captured(args))
        .map_err(|e| match e {
            CapturedError::Usage(m) | CapturedError::Failed(m) => PyValueError::new_err(m),
        })
}

/// The compiled module.
#[pymodule]
fn _zipmesh(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PyMesh>()?;
    m.add_function(wrap_pyfunction!(load, m)?)?;
    m.add_function(wrap_pyfunction!(run, m)?)?;
    Ok(())
}
