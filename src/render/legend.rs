//! The legend of a picture: one row per valence of the balls drawn, its colour and
//! `vK: N` (N the interior singularities of valence K), in the picture's top-left corner.
//!
//! The labels are strokes of a small font of our own (`v`, digits, `:`, `.`): resvg, which
//! makes the PNG from the same SVG, draws no text without a font database and a font file,
//! and these eleven glyphs are all a legend needs.

use super::{BallColour, Scene};
use alloc::collections::BTreeMap;
use alloc::string::String;
use alloc::vec::Vec;
use core::fmt::Write;

/// One row of the legend.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(super) struct Row {
    pub colour: BallColour,
    pub label: String,
}

/// The most rows drawn; further valences share the last row (`vK...: N`).
const MAX_ROWS: usize = 8;

/// The legend's rows: every valence among the scene's balls (seen or not), in increasing
/// order, with its count.
pub(super) fn rows(scene: &Scene) -> Vec<Row> {
    let mut by_valence: BTreeMap<usize, (BallColour, usize)> = BTreeMap::new();
    for b in scene.balls() {
        by_valence.entry(b.valence).or_insert((b.colour, 0)).1 += 1;
    }
    let mut rows: Vec<Row> = Vec::new();
    for (i, (valence, (colour, n))) in by_valence.iter().enumerate() {
        if i + 1 == MAX_ROWS && by_valence.len() > MAX_ROWS {
            let rest: usize = by_valence.values().skip(i).map(|&(_, n)| n).sum();
            rows.push(Row {
                colour: *colour,
                label: alloc::format!("v{valence}...: {rest}"),
            });
            break;
        }
        rows.push(Row {
            colour: *colour,
            label: alloc::format!("v{valence}: {n}"),
        });
    }
    rows
}

/// The strokes of a glyph on a 4 x 6 grid (y down), as polylines; a dot is a stroke of
/// length 0 drawn with round caps. Unknown characters (and the space) draw nothing.
fn glyph(c: char) -> &'static [&'static [(u8, u8)]] {
    match c {
        '0' => &[&[(0, 0), (4, 0), (4, 6), (0, 6), (0, 0)]],
        '1' => &[&[(1, 1), (2, 0), (2, 6)]],
        '2' => &[&[(0, 0), (4, 0), (4, 3), (0, 3), (0, 6), (4, 6)]],
        '3' => &[&[(0, 0), (4, 0), (4, 6), (0, 6)], &[(0, 3), (4, 3)]],
        '4' => &[&[(0, 0), (0, 3), (4, 3)], &[(4, 0), (4, 6)]],
        '5' => &[&[(4, 0), (0, 0), (0, 3), (4, 3), (4, 6), (0, 6)]],
        '6' => &[&[(4, 0), (0, 0), (0, 6), (4, 6), (4, 3), (0, 3)]],
        '7' => &[&[(0, 0), (4, 0), (4, 6)]],
        '8' => &[&[(0, 0), (4, 0), (4, 6), (0, 6), (0, 0)], &[(0, 3), (4, 3)]],
        '9' => &[&[(4, 3), (0, 3), (0, 0), (4, 0), (4, 6), (0, 6)]],
        'v' => &[&[(0, 2), (2, 6), (4, 2)]],
        ':' => &[&[(2, 2), (2, 2)], &[(2, 5), (2, 5)]],
        '.' => &[&[(2, 6), (2, 6)]],
        _ => &[],
    }
}

/// The SVG path data of `text` with its top-left corner at `(x, y)`, `unit` pixels to a
/// grid step (a glyph is 4 units wide and 6 high, and advances 6).
pub(super) fn text_path(text: &str, x: f64, y: f64, unit: f64) -> String {
    let mut d = String::new();
    for (i, c) in text.chars().enumerate() {
        let left = x + 6.0 * unit * i as f64;
        for stroke in glyph(c) {
            for (j, &(gx, gy)) in stroke.iter().enumerate() {
                let (px, py) = (left + f64::from(gx) * unit, y + f64::from(gy) * unit);
                // Writing into a String cannot fail.
                let _ = write!(d, "{}{px:.1} {py:.1}", if j == 0 { "M" } else { "L" });
            }
        }
    }
    d
}

/// Writes the legend of `scene` (nothing without balls): a white box in the top-left
/// corner, and per row a ball of the row's colour and its label.
pub(super) fn write(s: &mut String, scene: &Scene) -> core::fmt::Result {
    let rows = rows(scene);
    if rows.is_empty() {
        return Ok(());
    }
    let (w, h) = scene.size();
    // A row is 1/30 of the smaller side, at least 12 pixels: legible and out of the way.
    let row = (f64::from(w.min(h)) / 30.0).max(12.0);
    let unit = row / 10.0;
    let longest = rows
        .iter()
        .map(|r| r.label.chars().count())
        .max()
        .unwrap_or(0);
    let (box_w, box_h) = (
        row * 1.6 + 6.0 * unit * longest as f64,
        row * rows.len() as f64 + 0.6 * row,
    );
    writeln!(s, "<g id=\"legend\">")?;
    writeln!(
        s,
        "<rect x=\"{:.1}\" y=\"{:.1}\" width=\"{box_w:.1}\" height=\"{box_h:.1}\" fill=\"#ffffff\" \
         fill-opacity=\"0.85\" stroke=\"#808080\" stroke-width=\"1\"/>",
        0.3 * row,
        0.3 * row
    )?;
    for (i, r) in rows.iter().enumerate() {
        let top = 0.6 * row + row * i as f64;
        writeln!(
            s,
            "<circle class=\"legend\" cx=\"{:.1}\" cy=\"{:.1}\" r=\"{:.1}\" fill=\"url(#ball-{})\" \
             stroke=\"#202020\" stroke-width=\"0.5\"/>",
            0.6 * row + 0.35 * row,
            top + 0.5 * row,
            0.35 * row,
            r.colour.name()
        )?;
        writeln!(
            s,
            "<path data-label=\"{}\" d=\"{}\" fill=\"none\" stroke=\"#202020\" \
             stroke-width=\"{:.2}\" stroke-linecap=\"round\" stroke-linejoin=\"round\"/>",
            r.label,
            text_path(&r.label, 0.6 * row + row, top + 0.2 * row, unit),
            unit.max(1.0)
        )?;
    }
    writeln!(s, "</g>")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_label_character_has_a_glyph() {
        for c in "v0123456789:.".chars() {
            assert!(!glyph(c).is_empty(), "{c}");
        }
        assert!(glyph(' ').is_empty());
        // Two glyphs side by side do not overlap: the second starts 6 units on.
        assert_eq!(text_path("1", 0.0, 0.0, 1.0), "M1.0 1.0L2.0 0.0L2.0 6.0");
        assert_eq!(
            text_path("v1", 0.0, 0.0, 1.0),
            "M0.0 2.0L2.0 6.0L4.0 2.0M7.0 1.0L8.0 0.0L8.0 6.0"
        );
    }
}
