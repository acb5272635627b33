//! The plant on the wire end to end: a ROC host (linc's own, the
//! communication module's master side) writes a setpoint over ROC Plus,
//! the FST table acts on it in real time, and a Modbus client
//! (tokio-modbus) reads what the table wrote — one running plant, real
//! TCP on 127.0.0.1.

mod common;

use linc_comms::roc::host::{commands, Host, TcpLink, Words};
use linc_comms::roc::Address;
use linc_serve::{Config, Speed};
use std::time::Duration;
use tokio_modbus::client::Reader;

#[test]
fn a_roc_host_sets_the_point_the_fst_acts_on_and_a_modbus_client_reads_the_result() {
    let cfg = Config {
        speed: Speed::Times(1.0),
        allow_writes: true,
        roc: Some(("127.0.0.1:0".parse().unwrap(), Address { unit: 1, group: 2 })),
        modbus: Some("127.0.0.1:0".parse().unwrap()),
        ..common::config()
    };
    let server = common::serve("examples/roc/plant.json", cfg);
    let rt = tokio::runtime::Builder::new_current_thread().enable_all().build().unwrap();
    let mut mb = rt.block_on(tokio_modbus::client::tcp::connect(server.modbus_addr().unwrap())).unwrap();
    let valve = |mb: &mut tokio_modbus::client::Context| {
        let r1 = rt.block_on(mb.read_input_registers(2, 2)).unwrap().unwrap();
        f32::from_bits(u32::from(r1[0]) << 16 | u32::from(r1[1]))
    };
    // The tank is at 50 % and the setpoint 80 %: the drain stays shut.
    assert_eq!(valve(&mut mb), 0.0, "FST 1.R1: the valve is shut");
    // The host writes a setpoint of 40 % to SFP 1,DATA1 (17,0,2 on an
    // FB107) as a float from words 100-101, low word first.
    let list = commands::parse(
        "PORT,SLV UNIT,SLV GROUP,OP CODE,CNT,SRC ADDR,DEST ADDR,TYPE,POLL TIME,STORE FWD\n1,1,2,181,1,0,100,4,0,0\n",
        commands::Protocol::RocPlus,
    )
    .unwrap();
    let bits = 40.0f32.to_bits();
    let words = Words::parse(&format!(r#"{{"0": [17, 0, 2], "100": [{}, {}]}}"#, bits & 0xFFFF, bits >> 16)).unwrap();
    let mut host = Host { me: Address { unit: 3, group: 1 }, words };
    let mut link = TcpLink::new(server.roc_addr().unwrap(), Duration::from_secs(1));
    assert_eq!(host.run(&list[0], &mut link), 0, "the write was acknowledged");
    // Within a few cycles of the table, it opens the drain and says so in
    // R1, which the Modbus client reads; the valve's discrete input too.
    common::eventually("the table's answer to the new setpoint", || valve(&mut mb) == 1.0);
    assert_eq!(rt.block_on(mb.read_discrete_inputs(0, 1)).unwrap().unwrap(), vec![true]);
    let done = server.stop();
    assert!(done.busiest <= 2, "{} requests of two clients waited for a scan", done.busiest);
}
