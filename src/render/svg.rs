//! Writing a [`Scene`] as SVG: a white background, the seen faces far to near (fill and
//! edge stroke), the seen path stretches, then the seen balls far to near.

use super::{BallColour, Scene};
use alloc::string::String;
use core::fmt::Write;

fn hex(c: [u8; 3]) -> String {
    alloc::format!("#{:02x}{:02x}{:02x}", c[0], c[1], c[2])
}

/// The SVG text of `scene`.
pub(super) fn write(scene: &Scene) -> String {
    let (w, h) = scene.size();
    let view = scene.camera().view();
    let seen = scene.balls().iter().filter(|b| b.visible).count();
    let mut s = String::new();
    // Writing into a String cannot fail.
    let _ = write_head(&mut s, w, h);
    let _ = writeln!(
        s,
        "<desc>zipmesh render: view azimuth {} elevation {}; {} of {} faces drawn; {} of {} \
         interior singularities seen</desc>",
        view.azimuth,
        view.elevation,
        scene.faces().len(),
        scene.total_faces(),
        seen,
        scene.balls().len()
    );
    let _ = write_faces(&mut s, scene);
    let _ = write_paths(&mut s, scene);
    let _ = write_balls(&mut s, scene);
    if scene.legend {
        let _ = super::legend::write(&mut s, scene);
    }
    s.push_str("</svg>\n");
    s
}

fn write_head(s: &mut String, w: u32, h: u32) -> core::fmt::Result {
    writeln!(s, "<?xml version=\"1.0\" encoding=\"UTF-8\"?>")?;
    writeln!(
        s,
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{h}\" \
         viewBox=\"0 0 {w} {h}\">"
    )?;
    writeln!(s, "<defs>")?;
    for c in BallColour::ALL {
        writeln!(
            s,
            "<radialGradient id=\"ball-{}\" cx=\"0.5\" cy=\"0.5\" r=\"0.5\" fx=\"0.35\" \
             fy=\"0.35\"><stop offset=\"0\" stop-color=\"{}\"/><stop offset=\"1\" \
             stop-color=\"{}\"/></radialGradient>",
            c.name(),
            hex(c.highlight()),
            hex(c.rgb())
        )?;
    }
    writeln!(s, "</defs>")?;
    writeln!(s, "<rect width=\"{w}\" height=\"{h}\" fill=\"#ffffff\"/>")
}

fn write_faces(s: &mut String, scene: &Scene) -> core::fmt::Result {
    writeln!(
        s,
        "<g id=\"faces\" stroke=\"#262626\" stroke-width=\"{:.2}\" stroke-linejoin=\"round\">",
        scene.stroke
    )?;
    for f in scene.faces() {
        if f.folded {
            // The depth buffer's fan triangles, filled without edges, under the outline.
            s.push_str("<path stroke=\"none\" d=\"");
            for i in 1..f.corners.len() - 1 {
                polygon(s, &[f.corners[0], f.corners[i], f.corners[i + 1]])?;
            }
            writeln!(s, "\" fill=\"{}\"/>", hex(f.fill))?;
            s.push_str("<path fill=\"none\" d=\"");
            polygon(s, &f.corners)?;
            writeln!(s, "\"/>")?;
        } else {
            s.push_str("<path d=\"");
            polygon(s, &f.corners)?;
            writeln!(s, "\" fill=\"{}\"/>", hex(f.fill))?;
        }
    }
    writeln!(s, "</g>")
}

/// One closed sub-path `M x y L x y ... Z`.
fn polygon(s: &mut String, corners: &[[f64; 2]]) -> core::fmt::Result {
    for (i, [x, y]) in corners.iter().enumerate() {
        write!(s, "{}{:.1} {:.1}", if i == 0 { "M" } else { "L" }, x, y)?;
    }
    s.push('Z');
    Ok(())
}

fn write_paths(s: &mut String, scene: &Scene) -> core::fmt::Result {
    let width = (0.5 * scene.radius()).max(2.0);
    writeln!(
        s,
        "<g id=\"paths\" fill=\"none\" stroke=\"#c51b7d\" stroke-width=\"{width:.2}\" \
         stroke-linecap=\"round\" stroke-linejoin=\"round\">"
    )?;
    for run in scene.polylines() {
        s.push_str("<polyline class=\"path\" points=\"");
        for (i, [x, y]) in run.iter().enumerate() {
            write!(s, "{}{:.1},{:.1}", if i == 0 { "" } else { " " }, x, y)?;
        }
        writeln!(s, "\"/>")?;
    }
    writeln!(s, "</g>")
}

fn write_balls(s: &mut String, scene: &Scene) -> core::fmt::Result {
    writeln!(
        s,
        "<g id=\"singularities\" stroke=\"#202020\" stroke-width=\"{:.2}\">",
        0.5 * scene.stroke
    )?;
    for b in scene.balls().iter().filter(|b| b.visible) {
        writeln!(
            s,
            "<circle class=\"v{}\" data-vertex=\"{}\" cx=\"{:.2}\" cy=\"{:.2}\" r=\"{:.2}\" \
             fill=\"url(#ball-{})\"/>",
            b.valence,
            b.vertex.index(),
            b.centre.x,
            b.centre.y,
            scene.radius(),
            b.colour.name()
        )?;
    }
    writeln!(s, "</g>")
}
