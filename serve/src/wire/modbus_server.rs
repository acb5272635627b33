//! The Modbus TCP server: frames off TCP (linc's own decoder, ADR 0019),
//! answered by the plant thread, with the same cap, timeouts and logs as
//! the ROC server.

use super::modbus::MbAnswer;
use super::net::{self, Limits, Log};
use crate::Ask;
use linc_comms::modbus::{self, Deframer};
use std::net::SocketAddr;
use std::sync::mpsc::Sender;
use std::time::Instant;
use tokio::net::TcpStream;
use tokio::sync::oneshot;

/// Serves one client. Requests for the map's unit, or for 0 or 255 (which
/// Modbus TCP devices take as "this device"), go to the plant; others get
/// no reply, as from a gateway with no such device. A stream that is not
/// Modbus TCP (a protocol identifier other than 0, a length no frame has)
/// can't be resynchronised, so the connection is closed and logged.
pub(crate) async fn client(
    mut stream: TcpStream,
    peer: SocketAddr,
    unit: u8,
    asks: Sender<Ask>,
    limits: Limits,
    log: Log,
) {
    let mut frames = Deframer::default();
    let mut buf = [0u8; 4096];
    let mut begun: Option<Instant> = None;
    let stop = 'conn: loop {
        let n = match net::read_some(&mut stream, &mut buf, &limits, begun).await {
            Ok(n) => n,
            Err(stop) => break stop,
        };
        frames.push(&buf[..n]);
        while let Some(next) = frames.next_frame() {
            let (head, pdu) = match next {
                Ok(f) => f,
                Err(e) => {
                    log(format!("modbus {peer}: dropped: not Modbus TCP ({e:?})"));
                    return;
                }
            };
            if head.unit != unit && head.unit != 0 && head.unit != 255 {
                continue;
            }
            let bytes = match modbus::decode(&pdu) {
                Err((function, e)) => modbus::encode(head, function, &Err(e)),
                Ok(request) => {
                    let (reply, answer) = oneshot::channel();
                    if asks.send(Ask::Modbus { request, peer: peer.to_string(), reply }).is_err() {
                        return;
                    }
                    let Ok(MbAnswer { reply, function, log: lines }) = answer.await else { return };
                    for line in lines {
                        log(line);
                    }
                    modbus::encode(head, function, &reply)
                }
            };
            if let Err(stop) = net::reply(&mut stream, &bytes, &limits).await {
                break 'conn stop;
            }
        }
        begun = net::waiting_since(frames.pending(), begun);
    };
    if let Some(why) = stop.why(&limits) {
        log(format!("modbus {peer}: dropped: {why}"));
    }
}
