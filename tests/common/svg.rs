//! Reading back what `zipmesh::render` writes: the SVG's elements and attributes, by plain
//! text scanning (the writer emits one element per line, attributes in double quotes).

/// One `<circle>` of the SVG: its attributes.
#[derive(Clone, Debug, PartialEq)]
pub struct Circle {
    pub class: String,
    pub vertex: usize,
    pub cx: f64,
    pub cy: f64,
    pub r: f64,
    pub fill: String,
}

/// The value of attribute `name` in the element text `el`.
pub fn attr<'a>(el: &'a str, name: &str) -> Option<&'a str> {
    let key = format!(" {name}=\"");
    let start = el.find(&key)? + key.len();
    let len = el[start..].find('"')?;
    Some(&el[start..start + len])
}

/// The text of every element `<tag ...>` (up to its closing `>`).
pub fn elements<'a>(svg: &'a str, tag: &str) -> Vec<&'a str> {
    let open = format!("<{tag} ");
    let mut out = Vec::new();
    let mut rest = svg;
    while let Some(i) = rest.find(&open) {
        let el = &rest[i..];
        let end = el.find('>').expect("an element ends with >");
        out.push(&el[..=end]);
        rest = &el[end..];
    }
    out
}

/// Every singularity's circle, with its attributes parsed (the legend's circles, of class
/// `legend`, are left out).
pub fn circles(svg: &str) -> Vec<Circle> {
    elements(svg, "circle")
        .into_iter()
        .filter(|el| attr(el, "class") != Some("legend"))
        .map(|el| {
            let num = |n| attr(el, n).unwrap().parse::<f64>().unwrap();
            Circle {
                class: attr(el, "class").unwrap().to_string(),
                vertex: attr(el, "data-vertex").unwrap().parse().unwrap(),
                cx: num("cx"),
                cy: num("cy"),
                r: num("r"),
                fill: attr(el, "fill").unwrap().to_string(),
            }
        })
        .collect()
}

/// Checks that the text is well formed at the level the writer promises: an XML
/// declaration, one `<svg>` root closed at the end, and every `<` of an element start
/// matched by a `>`, no stray `&`.
pub fn assert_xmlish(svg: &str) {
    assert!(svg.starts_with("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<svg xmlns="));
    assert!(svg.trim_end().ends_with("</svg>"));
    assert_eq!(svg.matches("<svg ").count(), 1);
    assert_eq!(svg.matches('<').count(), svg.matches('>').count());
    assert!(!svg.contains('&'));
}
