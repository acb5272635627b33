//! The live page's trend (`linc serve`), drawn by the same code as `linc
//! draw`'s trend of a trace: a plot with a value scale, strips for BOOLs
//! and a time axis in simulated time, over the window asked for.

use linc_draw::trend::{recent, Recent};

fn field(name: &str, start: &str, changes: &[(f64, &str)]) -> Recent {
    Recent {
        name: name.to_string(),
        start: Some(start.to_string()),
        changes: changes.iter().map(|(t, v)| (*t, v.to_string())).collect(),
    }
}

#[test]
fn a_live_trend_has_a_value_scale_and_a_time_axis() {
    let level = field("R1.Level", "10.0", &[(30.0, "99.0"), (62.0, "20.0"), (90.0, "30.0")]);
    let valve = field("R1.FillVlv", "FALSE", &[(70.0, "TRUE")]);
    let svg = recent(vec![level, valve], 60.0, 120.0);
    assert!(svg.starts_with("<svg xmlns=\"http://www.w3.org/2000/svg\" class=\"linc trend\""), "{svg}");
    assert!(svg.contains("<g id=\"trend-R1.Level\" class=\"series\">"));
    assert!(svg.contains("<g id=\"strip-R1.FillVlv\" class=\"strip\">"));
    // The value scale: five values from the lowest to the highest in the
    // window (the 99 before it is not drawn).
    for v in ["10", "15", "20", "25", "30"] {
        assert!(svg.contains(&format!("class=\"dim\" text-anchor=\"end\">{v}</text>")), "value {v}: {svg}");
    }
    assert!(!svg.contains(">99</text>"));
    // The time axis: a tick every 10 s of the minute shown.
    for t in ["1m00s", "1m10s", "1m20s", "1m30s", "1m40s", "1m50s", "2m00s"] {
        assert!(svg.contains(&format!("class=\"dim\" text-anchor=\"middle\">{t}</text>")), "tick {t}: {svg}");
    }
    assert!(!svg.contains(">50s</text>"), "nothing before the window");
}

#[test]
fn a_field_with_nothing_known_is_left_out_and_an_empty_window_still_draws() {
    let unknown = Recent { name: "X.Y".into(), start: None, changes: Vec::new() };
    let svg = recent(vec![unknown], 0.0, 0.0);
    assert!(svg.starts_with("<svg") && !svg.contains("X.Y"), "{svg}");
}
