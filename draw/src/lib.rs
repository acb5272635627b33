//! Pictures of linc's sources (docs/pictures.md): a sequence as an IEC
//! 61131-3 chart, ladder rungs between their rails, an FST table as a
//! flow, each optionally with the state a run left; and trends of a
//! `--trace` file. Every picture is deterministic SVG with real text.
//!
//! Each drawing also returns its [`geom::Geometry`], the numbers the SVG
//! is written from, which the layout tests check.

/// An FST table as a flow.
pub mod fst;
/// The geometry every drawing is written from, which the layout tests check.
pub mod geom;
/// Ladder rungs between their rails, as SVG.
pub mod ladder;
/// The same rungs in text (`linc ladder show`).
pub mod ladder_text;
/// A sequence as an IEC 61131-3 chart.
pub mod sfc;
mod svg;
/// Trends of a `--trace` file, read a line at a time.
pub mod trend;
