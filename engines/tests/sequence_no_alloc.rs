//! A sequence scan allocates nothing once the chart has run a scan: its
//! working sets are kept in the chart's state.
use linc_engines::sequence::chart::{Action, Assoc, Body, Chart, Step, Transition};
use linc_engines::sequence::engine::Host;
use linc_engines::sequence::{Command, Sequence};
use linc_engines::strategy::qualifier::Qualifier;
use linc_runtime::errors::RuntimeError;
use linc_test_support::alloc::{allocations_in, Counting};

#[global_allocator]
static GLOBAL: Counting = Counting;

struct Toggle(u64);

impl Host for Toggle {
    fn condition(&mut self, _code: usize) -> Result<bool, RuntimeError> {
        Ok(self.0.is_multiple_of(3))
    }
    fn action(&mut self, _code: usize) -> Result<(), RuntimeError> {
        Ok(())
    }
}

#[test]
fn scans_do_not_allocate() {
    let assoc = |action, qualifier| Assoc { action, qualifier, time_us: 500_000 };
    let step = |i: usize| Step {
        name: format!("S{i}"),
        initial: i == 0,
        slot: i,
        assocs: vec![assoc(0, Qualifier::N), assoc(1, Qualifier::D), assoc(2, Qualifier::S), assoc(2, Qualifier::R)],
    };
    let chart = Chart {
        steps: (0..4).map(step).collect(),
        transitions: (0..4)
            .map(|i| Transition {
                name: format!("T{i}"),
                from: vec![i],
                to: vec![(i + 1) % 4],
                priority: None,
                code: i,
            })
            .collect(),
        actions: (0..3).map(|i| Action { name: format!("a{i}"), body: Body::Code(i) }).collect(),
    };
    let mut seq = Sequence::new(chart);
    seq.command(Command::Run);
    let mut host = Toggle(0);
    seq.scan(0, &mut host).expect("scan");
    let ((), allocations) = allocations_in(|| {
        for i in 1..=300u64 {
            host.0 = i;
            seq.scan(i * 100_000, &mut host).expect("scan");
        }
    });
    assert_eq!(allocations, 0, "allocations in 300 scans");
}
