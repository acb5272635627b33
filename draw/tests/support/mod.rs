//! What the picture tests share: reading an SVG back with an XML parser.

use quick_xml::events::Event;
use quick_xml::Reader;

/// Every element of an SVG as (name, id, class), after checking that the
/// document is well-formed XML with one `svg` root.
pub fn elements(svg: &str) -> Vec<(String, String, String)> {
    let mut reader = Reader::from_str(svg);
    let mut out = Vec::new();
    let mut depth = 0i32;
    loop {
        let ev = reader.read_event().unwrap_or_else(|e| panic!("not XML: {e}"));
        let (start, empty) = match &ev {
            Event::Start(s) => (Some(s.clone()), false),
            Event::Empty(s) => (Some(s.clone()), true),
            Event::End(_) => {
                depth -= 1;
                (None, false)
            }
            Event::Eof => break,
            _ => (None, false),
        };
        if let Some(s) = start {
            if depth == 0 {
                assert_eq!(s.name().as_ref(), b"svg", "the root is svg");
                assert!(out.is_empty(), "one root");
            }
            let attr = |n: &[u8]| {
                s.attributes()
                    .flatten()
                    .find(|a| a.key.as_ref() == n)
                    .map(|a| String::from_utf8_lossy(&a.value).into_owned())
                    .unwrap_or_default()
            };
            out.push((String::from_utf8_lossy(s.name().as_ref()).into_owned(), attr(b"id"), attr(b"class")));
            if !empty {
                depth += 1;
            }
        }
    }
    assert_eq!(depth, 0, "every element closed");
    out
}

/// Groups whose id starts with `prefix` and whose class list has `class`.
pub fn groups<'a>(els: &'a [(String, String, String)], prefix: &str, class: &str) -> Vec<&'a str> {
    els.iter()
        .filter(|(n, id, c)| n == "g" && id.starts_with(prefix) && c.split(' ').any(|x| x == class))
        .map(|(_, id, _)| id.as_str())
        .collect()
}
