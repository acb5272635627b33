//! The resources a sequence uses against an instrument's limits (guide
//! §9.5): steps, transitions, actions, associations and SFCs (the root
//! chart and each chart action), counted over the whole sequence.

use super::ast::{ActionBody, Chart, Sequence};
use crate::diag::span::Span;
use crate::diag::Diagnostic;
use linc_format::Code;

/// Which instrument's limits: the guide gives each limit as a pair.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Instrument {
    Small,
    Large,
}

impl Instrument {
    pub fn name(self) -> &'static str {
        match self {
            Instrument::Small => "small",
            Instrument::Large => "large",
        }
    }
}

/// One resource: its name, how many the sequence uses, the limit.
#[derive(Clone, Debug, PartialEq)]
pub struct Use {
    pub resource: &'static str,
    pub used: usize,
    pub limit: usize,
}

/// Limits of §9.5.2 as (resource, small, large).
const LIMITS: [(&str, usize, usize); 5] = [
    ("steps", 150, 390),
    ("transitions", 225, 578),
    ("actions", 300, 780),
    ("associations", 600, 1560),
    ("SFCs", 50, 130),
];

/// Counts every resource of `seq` against the limits of `instrument`.
pub fn count(seq: &Sequence, instrument: Instrument) -> Vec<Use> {
    let charts: Vec<&Chart> = std::iter::once(&seq.chart)
        .chain(seq.actions.iter().filter_map(|a| match &a.body {
            ActionBody::Chart(c) => Some(c),
            ActionBody::St(_) => None,
        }))
        .collect();
    let steps = charts.iter().map(|c| c.steps.len()).sum();
    let transitions = charts.iter().map(|c| c.transitions.len()).sum();
    let assocs = charts.iter().flat_map(|c| &c.steps).map(|s| s.assocs.len()).sum();
    let used = [steps, transitions, seq.actions.len(), assocs, charts.len()];
    LIMITS
        .iter()
        .zip(used)
        .map(|(&(resource, small, large), used)| Use {
            resource,
            used,
            limit: if instrument == Instrument::Small { small } else { large },
        })
        .collect()
}

/// W0251 for each resource past its limit, located at the file's start
/// (a count belongs to the whole sequence).
pub fn over_limit(uses: &[Use], instrument: Instrument) -> Vec<Diagnostic> {
    uses.iter()
        .filter(|u| u.used > u.limit)
        .map(|u| {
            Diagnostic::warning(
                Code::W0251,
                format!(
                    "the sequence uses {} {}; a {} instrument loads at most {}",
                    u.used,
                    u.resource,
                    instrument.name(),
                    u.limit
                ),
                Span::new(0, 0),
            )
            .help("split the sequence, or check it with --instrument large if it is for a large instrument")
        })
        .collect()
}
