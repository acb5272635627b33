//! Pictures of linc's sources (docs/pictures.md): a sequence as an IEC
//! 61131-3 chart, ladder rungs between their rails, an FST table as a
//! flow, each optionally with the state a run left; and trends of a
//! `--trace` file. Every picture is deterministic SVG with real text.
//!
//! Each drawing also returns its [`geom::Geometry`], the numbers the SVG
//! is written from, which the layout tests check.

pub mod fst;
pub mod geom;
pub mod ladder;
pub mod ladder_text;
pub mod sfc;
pub mod svg;
pub mod trend;
