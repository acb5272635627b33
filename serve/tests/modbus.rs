//! The Modbus TCP server over real TCP on 127.0.0.1, driven by
//! tokio-modbus's client: reads agree with the monitor's API, writes are
//! all or none under the console's rules, and each refusal has its
//! exception code (docs/modbus.md).

mod common;

use common::{api, console_line};
use linc_serve::{Config, Server, Speed};
use tokio_modbus::client::{Context, Reader, Writer};
use tokio_modbus::{ExceptionCode, Slave};

fn serve(writes: bool) -> Server {
    serve_logged(writes, std::sync::Arc::new(|_| {}))
}

fn serve_logged(writes: bool, log: linc_serve::Log) -> Server {
    let cfg = Config {
        log,
        // A scan every 100 s of wall time: values hold still while compared.
        speed: Speed::Times(0.001),
        allow_writes: writes,
        modbus: Some("127.0.0.1:0".parse().unwrap()),
        ..common::config()
    };
    common::serve("examples/roc/plant.json", cfg)
}

fn rt() -> tokio::runtime::Runtime {
    tokio::runtime::Builder::new_current_thread().enable_all().build().unwrap()
}

async fn client(s: &Server, unit: u8) -> Context {
    tokio_modbus::client::tcp::connect_slave(s.modbus_addr().unwrap(), Slave(unit)).await.expect("connect")
}

fn high_first(w: &[u16]) -> f32 {
    f32::from_bits(u32::from(w[0]) << 16 | u32::from(w[1]))
}

fn words(x: f32) -> [u16; 2] {
    [(x.to_bits() >> 16) as u16, x.to_bits() as u16]
}

#[test]
fn reads_agree_with_the_monitor() {
    let s = serve(true);
    rt().block_on(async {
        let mut c = client(&s, 1).await;
        let input = c.read_input_registers(0, 5).await.unwrap().unwrap();
        assert_eq!(high_first(&input[0..2]), api(&s, "AIN 3-1", "EU").parse::<f32>().unwrap());
        assert_eq!(high_first(&input[2..4]), api(&s, "FST 1", "R1").parse::<f32>().unwrap());
        assert_eq!(input[4].to_string(), api(&s, "AIN 3-1", "ALARM"));
        let holding = c.read_holding_registers(0, 5).await.unwrap().unwrap();
        assert_eq!(high_first(&holding[0..2]), 80.0);
        assert_eq!(api(&s, "SFP 1", "DATA1"), "80.0");
        // R2 low word first.
        let r2 = f32::from_bits(u32::from(holding[3]) << 16 | u32::from(holding[2]));
        assert_eq!(r2, api(&s, "FST 1", "R2").parse::<f32>().unwrap());
        assert_eq!(holding[4].to_string(), api(&s, "FST 1", "MISC1"));
        let coil = c.read_coils(0, 1).await.unwrap().unwrap();
        assert_eq!(u8::from(coil[0]).to_string(), api(&s, "DOU 2-1", "MODE"));
        let valve = c.read_discrete_inputs(0, 1).await.unwrap().unwrap();
        assert_eq!(u8::from(valve[0]).to_string(), api(&s, "DOU 2-1", "STATUS"));
        // Unit 255 (this device) is answered too; an unmapped address is 02.
        let mut any = client(&s, 255).await;
        assert!(any.read_input_registers(0, 2).await.unwrap().is_ok());
        assert_eq!(c.read_holding_registers(5, 1).await.unwrap(), Err(ExceptionCode::IllegalDataAddress));
        assert_eq!(c.read_input_registers(4, 2).await.unwrap(), Err(ExceptionCode::IllegalDataAddress));
        assert_eq!(c.read_coils(1, 1).await.unwrap(), Err(ExceptionCode::IllegalDataAddress));
    });
    s.stop();
}

#[test]
fn writes_are_all_or_none_with_the_protocols_exceptions() {
    let lines = std::sync::Arc::new(std::sync::Mutex::new(Vec::<String>::new()));
    let kept = lines.clone();
    let s = serve_logged(true, std::sync::Arc::new(move |l| kept.lock().unwrap().push(l)));
    rt().block_on(async {
        let mut c = client(&s, 1).await;
        let [a, b] = words(72.5);
        c.write_multiple_registers(0, &[a, b, 0, 0, 7]).await.unwrap().unwrap();
        assert_eq!(api(&s, "SFP 1", "DATA1"), "72.5");
        assert_eq!(api(&s, "FST 1", "MISC1"), "7");
        c.write_single_register(4, 9).await.unwrap().unwrap();
        assert_eq!(api(&s, "FST 1", "MISC1"), "9");
        // MISC1 is a BITS8: 300 is out of its range (03), and the REAL
        // before it in the same request is not written either.
        let [a, b] = words(1.0);
        assert_eq!(
            c.write_multiple_registers(0, &[a, b, 0, 0, 300]).await.unwrap(),
            Err(ExceptionCode::IllegalDataValue)
        );
        assert_eq!(api(&s, "SFP 1", "DATA1"), "72.5");
        // Half a REAL can't be written.
        assert_eq!(c.write_single_register(0, 1).await.unwrap(), Err(ExceptionCode::IllegalDataValue));
        // A coil.
        c.write_single_coil(0, true).await.unwrap().unwrap();
        assert_eq!(api(&s, "DOU 2-1", "MODE"), "1");
        c.write_multiple_coils(0, &[false]).await.unwrap().unwrap();
        assert_eq!(api(&s, "DOU 2-1", "MODE"), "0");
        // Writing an input register or a discrete input has no function:
        // their addresses are not in the holding and coil tables.
        assert_eq!(c.write_single_register(6, 1).await.unwrap(), Err(ExceptionCode::IllegalDataAddress));
        // A forced field keeps its value: 04.
        console_line(&s, "F SFP 1.DATA1=60");
        let [a, b] = words(10.0);
        assert_eq!(c.write_multiple_registers(0, &[a, b]).await.unwrap(), Err(ExceptionCode::ServerDeviceFailure));
        assert_eq!(api(&s, "SFP 1", "DATA1"), "60.0");
    });
    s.stop();
    // Every refusal left a line, those for the value too.
    let log = lines.lock().unwrap().join("\n");
    for needle in [
        "write refused: FST 1.MISC1 can't hold the register value 300",
        "write refused: SFP 1.DATA1 can't hold half a REAL",
        "write refused: SFP 1.DATA1 is forced",
    ] {
        assert!(log.contains(needle), "the log lacks `{needle}`:\n{log}");
    }
}

#[test]
fn a_read_only_server_refuses_writes() {
    let s = serve(false);
    rt().block_on(async {
        let mut c = client(&s, 1).await;
        assert_eq!(c.write_single_coil(0, true).await.unwrap(), Err(ExceptionCode::IllegalFunction));
        assert!(c.read_coils(0, 1).await.unwrap().is_ok());
    });
    assert_eq!(api(&s, "DOU 2-1", "MODE"), "0");
    s.stop();
}

#[test]
fn a_database_without_a_map_refuses_to_serve_modbus() {
    let cfg = Config { modbus: Some("127.0.0.1:0".parse().unwrap()), ..Config::new("127.0.0.1:0".parse().unwrap()) };
    let e = linc_serve::start(common::plant("examples/fst/plant.json"), cfg).err().expect("refused");
    assert!(e.to_string().contains("\"modbus\" register map"), "{e}");
}
