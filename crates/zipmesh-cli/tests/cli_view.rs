//! `zipmesh view`: the page, rendered for real in headless Chromium (Debian's
//! `chromium-headless-shell`, software WebGL): the page's reported state (the singularity
//! count, the view and picks set from the URL, the commands shown, picking at the picks'
//! places) and the screenshot's pixels (the mesh covers the page, balls of the colours the
//! library gives are drawn, the picks where the page says). Without Chromium the browser
//! tests say so and pass, unless `ZIPMESH_REQUIRE_CHROMIUM=1` (as `.ci/run` sets), which
//! makes a missing browser a failure. Also: bad input exits 2 and writes no page.

#[path = "../../../tests/common/mod.rs"]
mod common;
mod run;

use common::shared;
use run::{s, stderr, stdout, temp_dir, zipmesh};
use serde_json::Value;
use std::fs;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};
use zipmesh::io;
use zipmesh::render::view::{Page, PageOptions};
use zipmesh::render::{singularities, BallColour, Options, Scene, View};

const WIDTH: u32 = 800;
const HEIGHT: u32 = 600;

/// The headless browser: `ZIPMESH_CHROMIUM`, else `chromium-headless-shell` or `chromium`
/// on the PATH (or where Debian puts them). `None` (and a message) when there is none and
/// none is required.
fn chromium() -> Option<PathBuf> {
    let required = std::env::var("ZIPMESH_REQUIRE_CHROMIUM").is_ok_and(|v| v == "1");
    let given = std::env::var_os("ZIPMESH_CHROMIUM").map(PathBuf::from);
    let path = std::env::var_os("PATH").unwrap_or_default();
    let found = given.or_else(|| {
        ["chromium-headless-shell", "chromium"]
            .iter()
            .find_map(|name| {
                std::env::split_paths(&path)
                    .chain([PathBuf::from("/usr/lib/chromium")])
                    .map(|dir| dir.join(name))
                    .find(|p| p.is_file())
            })
    });
    if found.is_none() {
        assert!(
            !required,
            "ZIPMESH_REQUIRE_CHROMIUM=1 but no chromium-headless-shell (apt-get install \
             chromium-headless-shell, or set ZIPMESH_CHROMIUM)"
        );
        // Straight to the standard error, past the test harness's capture, so that the
        // skip shows in a passing run.
        let _ = writeln!(
            std::io::stderr(),
            "SKIPPED: no chromium-headless-shell on this machine (apt-get install \
             chromium-headless-shell); the page was not rendered"
        );
    }
    found
}

/// Runs the browser on `url` with `args` (software WebGL, 800x600), at most 120 s; its
/// standard output (through a file: the dumped DOM may exceed a pipe's buffer).
fn browse(browser: &Path, dir: &Path, args: &[&str], url: &str) -> String {
    let profile = dir.join("profile");
    let log = dir.join("chromium.out");
    let mut child = Command::new(browser)
        .args([
            "--no-sandbox",
            "--use-angle=swiftshader",
            "--enable-unsafe-swiftshader",
            "--hide-scrollbars",
            "--no-first-run",
            "--force-device-scale-factor=1",
        ])
        .arg(format!("--window-size={WIDTH},{HEIGHT}"))
        .arg(format!("--user-data-dir={}", profile.display()))
        .args(args)
        .arg(url)
        .stdout(fs::File::create(&log).unwrap())
        .stderr(Stdio::null())
        .spawn()
        .expect("chromium starts");
    let start = Instant::now();
    while child.try_wait().unwrap().is_none() {
        if start.elapsed() > Duration::from_secs(120) {
            let _ = child.kill();
            panic!("chromium took more than 120 s on {url}");
        }
        std::thread::sleep(Duration::from_millis(50));
    }
    assert!(child.wait().unwrap().success(), "chromium failed on {url}");
    String::from_utf8_lossy(&fs::read(&log).unwrap()).into_owned()
}

/// The state the page reports in its `<pre id="state">`, from the dumped DOM.
fn state(browser: &Path, dir: &Path, page: &Path, hash: &str) -> Value {
    let url = format!("file://{}#{hash}", page.display());
    let dom = browse(browser, dir, &["--dump-dom"], &url);
    let start = dom
        .find("<pre id=\"state\">")
        .expect("the page has its state")
        + 16;
    let end = start + dom[start..].find("</pre>").unwrap();
    let text = dom[start..end]
        .replace("&lt;", "<")
        .replace("&gt;", ">")
        .replace("&quot;", "\"")
        .replace("&amp;", "&");
    serde_json::from_str(&text).unwrap_or_else(|e| panic!("state {text:?}: {e}"))
}

/// A screenshot of the page: RGB pixels, row by row.
fn screenshot(browser: &Path, dir: &Path, page: &Path, hash: &str, png: &Path) -> Vec<[u8; 3]> {
    let url = format!("file://{}#{hash}", page.display());
    let arg = format!("--screenshot={}", png.display());
    browse(browser, dir, &[&arg], &url);
    let decoder = png::Decoder::new(fs::File::open(png).expect("a screenshot"));
    let mut reader = decoder.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size()];
    let info = reader.next_frame(&mut buf).unwrap();
    assert_eq!((info.width, info.height), (WIDTH, HEIGHT));
    assert_eq!(info.bit_depth, png::BitDepth::Eight);
    let step = info.color_type.samples();
    assert!(step >= 3, "{:?}", info.color_type);
    buf[..info.buffer_size()]
        .chunks(step)
        .map(|p| [p[0], p[1], p[2]])
        .collect()
}

fn near(a: [u8; 3], b: [u8; 3], tolerance: i32) -> bool {
    a.iter()
        .zip(b)
        .all(|(&x, y)| (i32::from(x) - i32::from(y)).abs() <= tolerance)
}

/// Two interior singularities that `render` sees from `view` near the picture's middle, of
/// two colours when the mesh has two, and the colours of every ball `render` sees.
fn two_seen(mesh: &zipmesh::Mesh, view: View) -> (usize, usize, Vec<BallColour>) {
    let o = Options {
        view: Some(view),
        width: WIDTH,
        height: HEIGHT,
        ..Options::default()
    };
    let scene = Scene::new(mesh, &o).unwrap();
    let middle: Vec<_> = scene
        .balls()
        .iter()
        .filter(|b| b.visible)
        .filter(|b| (0.3..0.7).contains(&(b.centre.x / f64::from(WIDTH))))
        .filter(|b| (0.3..0.7).contains(&(b.centre.y / f64::from(HEIGHT))))
        .collect();
    let a = middle[0];
    let b = middle
        .iter()
        .find(|b| b.colour != a.colour)
        .unwrap_or(&middle[1]);
    let mut colours: Vec<BallColour> = scene
        .balls()
        .iter()
        .filter(|b| b.visible)
        .map(|b| b.colour)
        .collect();
    colours.sort_by_key(|c| c.name());
    colours.dedup();
    (a.vertex.index(), b.vertex.index(), colours)
}

/// Writes the view of `file`, renders it in Chromium from `view` with two seen
/// singularities picked, and checks the state and the pixels.
fn check_in_chromium(file: &Path, name: &str, view: View, command: &str) {
    let Some(browser) = chromium() else { return };
    let dir = temp_dir(&format!("view-{name}"));
    let page = dir.join(format!("{name}.html"));
    let o = zipmesh(&["view", s(file), "-o", s(&page)]);
    assert!(o.status.success(), "{}", stderr(&o));
    let (mesh, _) = io::read_mesh(file).unwrap();
    let library = Page::new(&mesh, &PageOptions::new(s(file))).unwrap();
    assert_eq!(library.balls().len(), singularities(&mesh.map).len());
    let (a, b, colours) = two_seen(&mesh, view);
    let hash = format!(
        "view={},{}&zoom=1&pick={a},{b}",
        view.azimuth, view.elevation
    );

    let st = state(&browser, &dir, &page, &hash);
    assert_eq!(st["ready"], true, "{st}");
    assert_eq!(st["errors"], serde_json::json!([]), "{st}");
    assert_eq!(st["singularities"], library.balls().len(), "{st}");
    let seen: Vec<f64> = st["view"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    assert_eq!(seen, [view.azimuth, view.elevation], "{st}");
    assert_eq!(st["picks"], serde_json::json!([a, b]), "{st}");
    let shown = st["command"].as_str().unwrap();
    let words = format!("{command} {} ", s(file));
    assert!(shown.starts_with(&words), "{shown}");
    let pair = if command == "zipmesh tri-move" {
        format!("--pair {a},{b} ")
    } else {
        format!("--from {a} --to {b}")
    };
    assert!(shown.contains(&pair), "{shown}");
    // Picking where the page draws each pick finds it (and not a ball behind the mesh).
    let picked = st["picked"].as_array().unwrap();
    for (p, v) in picked.iter().zip([a, b]) {
        assert_eq!(p["hit"], v, "{st}");
    }

    let png = dir.join(format!("{name}.png"));
    let pixels = screenshot(&browser, &dir, &page, &format!("{hash}&ui=0"), &png);
    let white = pixels.iter().filter(|&&p| p == [255, 255, 255]).count();
    let covered = 1.0 - white as f64 / pixels.len() as f64;
    assert!(
        (0.2..0.95).contains(&covered),
        "the mesh covers {covered:.2} of the page"
    );
    // Every colour of a ball that `render` sees from this view is on the page.
    assert!(!colours.is_empty());
    for colour in colours {
        let c = colour.rgb();
        let n = pixels.iter().filter(|&&p| near(p, c, 24)).count();
        assert!(n >= 10, "{}: {n} pixels of {c:?}", colour.name());
    }
    for (p, v) in picked.iter().zip([a, b]) {
        let (x, y) = (p["x"].as_f64().unwrap(), p["y"].as_f64().unwrap());
        let px = pixels[y.round() as usize * WIDTH as usize + x.round() as usize];
        let ball = library
            .balls()
            .iter()
            .find(|b| b.vertex.index() == v)
            .unwrap();
        assert!(
            near(px, ball.colour.rgb(), 30),
            "vertex {v} at ({x}, {y}): {px:?}, not {:?}",
            ball.colour.rgb()
        );
    }
    // The grey of the faces is there too (not only the balls on white).
    let grey = pixels
        .iter()
        .filter(|p| p[0] == p[1] && p[0] > 80 && p[0] < 250)
        .count();
    assert!(grey > pixels.len() / 10, "{grey} grey pixels");
}

#[test]
fn spot_quads_in_chromium() {
    let view = View::new(60.0, 20.0).unwrap();
    let spot = shared("quad/spot_quadrangulated.obj");
    check_in_chromium(&spot, "spot", view, "zipmesh moves");
}

#[test]
fn spot_triangles_in_chromium() {
    let view = View::new(-30.0, 15.0).unwrap();
    let spot = shared("tri/spot_triangulated.obj");
    check_in_chromium(&spot, "spot-tri", view, "zipmesh tri-move");
}

#[test]
fn the_url_sets_the_view_and_bad_entries_are_reported() {
    let Some(browser) = chromium() else { return };
    let dir = temp_dir("view-url");
    let page = dir.join("cube.html");
    let cube = shared("quad/spot_quadrangulated.obj");
    let o = zipmesh(&[
        "view",
        s(&cube),
        "-o",
        s(&page),
        "--title",
        "Spot </script>",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let st = state(&browser, &dir, &page, "view=-45,80&zoom=2.5&pick=0&bogus=1");
    assert_eq!(st["view"], serde_json::json!([-45, 80]), "{st}");
    assert_eq!(st["zoom"], 2.5, "{st}");
    // Vertex 0 is no singularity: the pick is refused and said so, as is the unknown key.
    assert_eq!(st["picks"], serde_json::json!([]), "{st}");
    let errors = st["errors"].to_string();
    assert!(
        errors.contains("pick=0") && errors.contains("bogus=1"),
        "{st}"
    );
    assert_eq!(st["command"], "", "{st}");
    assert_eq!(st["ready"], true, "{st}");
}

#[test]
fn the_page_is_self_contained_and_paths_come_from_a_report() {
    let dir = temp_dir("view-page");
    let spot = shared("quad/spot_quadrangulated.obj");
    let report = dir.join("report.json");
    fs::write(
        &report,
        r#"{"path": [15, 2], "paths": [[[0, 0, 0], [0.1, 0.2, 0.3]]]}"#,
    )
    .unwrap();
    let page = dir.join("spot.html");
    let o = zipmesh(&["view", s(&spot), "-o", s(&page), "--paths", s(&report)]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        stdout(&o).contains("100 interior singularities, 2 paths"),
        "{}",
        stdout(&o)
    );
    let html = fs::read_to_string(&page).unwrap();
    for outside in ["http:", "https:", "<link", " src="] {
        assert!(!html.contains(outside), "the page has {outside}");
    }
    assert_eq!(html.matches("<script").count(), 2); // the data and the viewer
    let open = "id=\"zipmesh-data\">";
    let start = html.find(open).unwrap() + open.len();
    let end = start + html[start..].find("</script>").unwrap();
    let data: Value = serde_json::from_str(&html[start..end]).unwrap();
    assert_eq!(data["paths"].as_array().unwrap().len(), 2);
    assert_eq!(data["balls"].as_array().unwrap().len(), 100);
    let colours = data["colours"].as_array().unwrap();
    for (c, want) in colours.iter().zip(BallColour::ALL) {
        assert_eq!(c["rgb"], serde_json::json!(want.rgb()));
    }
}

#[test]
fn bad_input_writes_no_page() {
    let dir = temp_dir("view-bad");
    let spot = shared("quad/spot_quadrangulated.obj");
    let page = dir.join("spot.html");
    let report = dir.join("report.json");
    fs::write(&report, r#"{"path": [0, 999999]}"#).unwrap();
    let o = zipmesh(&["view", s(&spot), "-o", s(&page), "--paths", s(&report)]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("999999"), "{}", stderr(&o));
    assert!(!page.exists());
    let missing = dir.join("missing.obj");
    let o = zipmesh(&["view", s(&missing), "-o", s(&page)]);
    assert_eq!(o.status.code(), Some(2));
    assert!(!page.exists());
    let o = zipmesh(&["view", s(&spot), "-o", s(&dir.join("no/such/dir/v.html"))]);
    assert_eq!(o.status.code(), Some(2));
}
