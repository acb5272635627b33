//! Usage problems of the command line, through the one reporter.

pub use linc_driver::report::{refused, usage};
