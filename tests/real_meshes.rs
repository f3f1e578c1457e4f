//! Every mesh in `tests/data/` against the independently computed table in its
//! `SOURCES.md`: valid meshes load, pass `check()`, and match every column; invalid ones
//! are refused with an error naming a face line.

use std::collections::BTreeMap;
use std::fs;
use std::path::{Path, PathBuf};
use zipmesh::invariants::{gauss_bonnet, Counts, Histograms, MeshKind};
use zipmesh::io;

/// One row of the "Combinatorics" table.
#[derive(Debug)]
struct Row {
    file: String,
    v: usize,
    e: usize,
    f: usize,
    face_degrees: BTreeMap<usize, usize>,
    boundary_loops: usize,
    chi: i64,
    components: usize,
    genus: Option<i64>,
    interior_valences: BTreeMap<usize, usize>,
    boundary_valences: BTreeMap<usize, usize>,
    valid: bool,
}

fn data_dir() -> PathBuf {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data");
    assert!(
        dir.join("SOURCES.md").is_file(),
        "the test meshes are missing: expected {} with SOURCES.md \
         (the test meshes ship in the repository under tests/data)",
        dir.display()
    );
    dir
}

/// `value:count` pairs separated by spaces; `-` for none.
fn histogram(cell: &str) -> BTreeMap<usize, usize> {
    if cell == "-" {
        return BTreeMap::new();
    }
    cell.split_whitespace()
        .map(|pair| {
            let (k, v) = pair
                .split_once(':')
                .unwrap_or_else(|| panic!("bad histogram entry {pair:?}"));
            (k.parse().unwrap(), v.parse().unwrap())
        })
        .collect()
}

fn table(dir: &Path) -> Vec<Row> {
    let text = fs::read_to_string(dir.join("SOURCES.md")).unwrap();
    let mut lines = text
        .lines()
        .skip_while(|l| !l.starts_with("| file | V | E | F |"));
    let header: Vec<String> = cells(lines.next().expect("no Combinatorics table in SOURCES.md"));
    assert_eq!(
        header,
        [
            "file",
            "V",
            "E",
            "F",
            "face degrees",
            "boundary loops",
            "chi",
            "components",
            "genus",
            "interior valences",
            "boundary valences",
            "valid manifold"
        ],
        "the table's columns changed"
    );
    lines
        .skip(1) // the |---| line
        .take_while(|l| l.starts_with('|'))
        .map(|l| {
            let c = cells(l);
            assert_eq!(c.len(), 12, "row {l:?}");
            Row {
                file: c[0].clone(),
                v: c[1].parse().unwrap(),
                e: c[2].parse().unwrap(),
                f: c[3].parse().unwrap(),
                face_degrees: histogram(&c[4]),
                boundary_loops: c[5].parse().unwrap(),
                chi: c[6].parse().unwrap(),
                components: c[7].parse().unwrap(),
                genus: c[8].parse().ok(),
                interior_valences: histogram(&c[9]),
                boundary_valences: histogram(&c[10]),
                valid: match c[11].as_str() {
                    "yes" => true,
                    "no" => false,
                    other => panic!("valid manifold = {other:?}"),
                },
            }
        })
        .collect()
}

fn cells(line: &str) -> Vec<String> {
    line.trim()
        .trim_matches('|')
        .split('|')
        .map(|c| c.trim().to_string())
        .collect()
}

/// Every mesh file below `dir`, as `subdir/name`.
fn mesh_files(dir: &Path) -> Vec<String> {
    let mut out = Vec::new();
    for sub in fs::read_dir(dir).unwrap() {
        let sub = sub.unwrap().path();
        if sub.is_dir() {
            for f in fs::read_dir(&sub).unwrap() {
                let f = f.unwrap().path();
                if io::Format::from_path(&f).is_some() {
                    let rel = f.strip_prefix(dir).unwrap();
                    out.push(rel.to_string_lossy().replace('\\', "/"));
                }
            }
        }
    }
    out.sort();
    out
}

/// One row of the second "Combinatorics" table (the quad and quad-dominant meshes listed
/// under "More real quad and quad-dominant meshes"), in its own notation.
#[derive(Debug)]
struct MoreRow {
    file: String,
    v: usize,
    f: usize,
    e: usize,
    face_degrees: BTreeMap<usize, usize>,
    interior_valences: BTreeMap<usize, usize>,
    boundary_loops: usize,
    boundary_edges: usize,
    components: usize,
    chi: i64,
    genus: i64,
}

/// `{4: 27352}` or `{3: 1, 4: 864}`.
fn braced_histogram(cell: &str) -> BTreeMap<usize, usize> {
    cell.trim_matches(|c| c == '{' || c == '}')
        .split(',')
        .map(|pair| {
            let (k, v) = pair
                .split_once(':')
                .unwrap_or_else(|| panic!("bad histogram entry {pair:?}"));
            (k.trim().parse().unwrap(), v.trim().parse().unwrap())
        })
        .collect()
}

/// An integer written with a Unicode minus or in bold (`−2`, `**1**`).
fn integer(cell: &str) -> i64 {
    cell.trim_matches('*')
        .replace('\u{2212}', "-")
        .parse()
        .unwrap()
}

fn more_table(dir: &Path) -> Vec<MoreRow> {
    let text = fs::read_to_string(dir.join("SOURCES.md")).unwrap();
    let mut lines = text
        .lines()
        .skip_while(|l| !l.starts_with("| file | V | F | E | face-degree histogram"));
    let header = cells(
        lines
            .next()
            .expect("no second Combinatorics table in SOURCES.md"),
    );
    assert_eq!(
        header.len(),
        11,
        "the second table's columns changed: {header:?}"
    );
    lines
        .skip(1)
        .take_while(|l| l.starts_with('|'))
        .map(|l| {
            let c = cells(l);
            assert_eq!(c.len(), 11, "row {l:?}");
            // `4 (328)`: loops and their edges; `0` without boundary.
            let mut loops = c[7].split([' ', '(', ')']);
            let boundary_loops = loops.next().unwrap().parse().unwrap();
            let boundary_edges = loops
                .find(|w| !w.is_empty())
                .map_or(0, |w| w.parse().unwrap());
            MoreRow {
                file: c[0].trim_matches('`').to_string(),
                v: c[1].parse().unwrap(),
                f: c[2].parse().unwrap(),
                e: c[3].parse().unwrap(),
                face_degrees: braced_histogram(&c[4]),
                interior_valences: braced_histogram(&c[5]),
                boundary_loops,
                boundary_edges,
                components: c[8].parse().unwrap(),
                chi: integer(&c[9]),
                genus: integer(&c[10]),
            }
        })
        .collect()
}

#[test]
fn more_meshes_match_their_table() {
    let dir = data_dir();
    let rows = more_table(&dir);
    assert_eq!(rows.len(), 10, "{rows:?}");
    for row in &rows {
        let (mesh, _) = io::read_mesh(dir.join(&row.file)).unwrap_or_else(|e| panic!("{e}"));
        let map = &mesh.map;
        map.check()
            .unwrap_or_else(|v| panic!("{}: check() failed: {v:?}", row.file));
        let c = Counts::of(map);
        let h = Histograms::of(map);
        let boundary_edges = map.darts().filter(|&d| map.is_boundary_dart(d)).count();
        assert_eq!(
            (
                c.vertices,
                c.faces,
                c.edges,
                c.boundary_loops,
                boundary_edges
            ),
            (row.v, row.f, row.e, row.boundary_loops, row.boundary_edges),
            "{}: (V, F, E, loops, boundary edges)",
            row.file
        );
        assert_eq!(
            (c.components, c.euler_characteristic, c.genus),
            (row.components, row.chi, row.genus),
            "{}: (components, chi, genus)",
            row.file
        );
        assert_eq!(h.face_degrees, row.face_degrees, "{}", row.file);
        assert_eq!(h.interior_valences, row.interior_valences, "{}", row.file);
    }
}

/// Both tables together list every mesh file of `tests/data` but the counterexamples, which
/// `counterexamples/README.md` lists (and the Q-zip tests replay).
#[test]
fn the_table_covers_every_mesh_file() {
    let dir = data_dir();
    let rows = table(&dir);
    let mut listed: Vec<String> = rows.iter().map(|r| r.file.clone()).collect();
    listed.extend(more_table(&dir).into_iter().map(|r| r.file));
    listed.sort();
    let (counterexamples, files): (Vec<String>, Vec<String>) = mesh_files(&dir)
        .into_iter()
        .partition(|f| f.starts_with("counterexamples/"));
    assert_eq!(listed, files);
    let readme = fs::read_to_string(dir.join("counterexamples/README.md")).unwrap();
    for f in &counterexamples {
        let name = f.trim_start_matches("counterexamples/");
        assert!(
            readme.contains(name),
            "{name} is not in counterexamples/README.md"
        );
    }
    assert!(rows.iter().any(|r| r.valid) && rows.iter().any(|r| !r.valid));
}

#[test]
fn valid_meshes_match_the_table() {
    let dir = data_dir();
    let rows = table(&dir);
    let mut checked = 0;
    for row in rows.iter().filter(|r| r.valid) {
        let path = dir.join(&row.file);
        let (mesh, _) = io::read_mesh(&path).unwrap_or_else(|e| panic!("{e}"));
        let map = &mesh.map;
        map.check()
            .unwrap_or_else(|v| panic!("{}: check() failed: {v:?}", row.file));
        let c = Counts::of(map);
        let h = Histograms::of(map);
        let got = (
            c.vertices,
            c.edges,
            c.faces,
            c.boundary_loops,
            c.euler_characteristic,
            c.components,
            Some(c.genus),
        );
        let want = (
            row.v,
            row.e,
            row.f,
            row.boundary_loops,
            row.chi,
            row.components,
            row.genus,
        );
        assert_eq!(
            got, want,
            "{}: (V, E, F, loops, chi, components, genus)",
            row.file
        );
        assert_eq!(
            h.face_degrees, row.face_degrees,
            "{}: face degrees",
            row.file
        );
        assert_eq!(
            h.interior_valences, row.interior_valences,
            "{}: interior valences",
            row.file
        );
        assert_eq!(
            h.boundary_valences, row.boundary_valences,
            "{}: boundary valences",
            row.file
        );
        for kind in [MeshKind::of(map), MeshKind::Quad, MeshKind::Triangle] {
            let gb = gauss_bonnet(map, kind);
            assert!(
                gb.holds(),
                "{}: Gauss-Bonnet fails in {kind:?} frame: {gb:?}",
                row.file
            );
        }
        checked += 1;
    }
    assert!(checked >= 11, "only {checked} valid meshes checked");
}

#[test]
fn invalid_meshes_are_refused_at_a_face_line() {
    let dir = data_dir();
    let rows = table(&dir);
    let mut checked = 0;
    for row in rows.iter().filter(|r| !r.valid) {
        let path = dir.join(&row.file);
        let err = match io::read_mesh(&path) {
            Ok(_) => panic!("{} loaded, but it is not a manifold", row.file),
            Err(e) => e,
        };
        let line = err
            .line()
            .unwrap_or_else(|| panic!("{}: error names no line: {err}", row.file));
        let text = fs::read_to_string(&path).unwrap();
        let content = text.lines().nth(line - 1).unwrap_or("");
        assert!(
            content.trim_start().starts_with("f "),
            "{}: line {line} is not a face: {content:?} ({err})",
            row.file
        );
        let msg = err.to_string();
        assert!(
            msg.starts_with(&format!("{}:{line}: ", path.display())),
            "{msg}"
        );
        checked += 1;
    }
    assert!(checked >= 2);
}
