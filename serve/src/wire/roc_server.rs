//! The ROC Plus server: frames off TCP, answered by the plant thread.

use super::net::{self, Limits, Log};
use super::roc::Answer;
use crate::Ask;
use linc_comms::roc::{Address, Deframer};
use std::net::SocketAddr;
use std::sync::mpsc::Sender;
use std::time::Instant;
use tokio::net::TcpStream;
use tokio::sync::oneshot;

/// Serves one client: each whole frame for `me` goes to the plant and its
/// reply back; frames for other addresses and bytes that make no frame
/// (a bad CRC) get no reply.
pub(crate) async fn client(
    mut stream: TcpStream,
    peer: SocketAddr,
    me: Address,
    asks: Sender<Ask>,
    limits: Limits,
    log: Log,
) {
    let mut frames = Deframer::default();
    let mut buf = [0u8; 4096];
    let mut begun: Option<Instant> = None;
    // The operator logged in on this connection (its access level).
    let mut session: Option<u8> = None;
    let stop = 'conn: loop {
        let n = match net::read_some(&mut stream, &mut buf, &limits, begun).await {
            Ok(n) => n,
            Err(stop) => break stop,
        };
        frames.push(&buf[..n]);
        while let Some(frame) = frames.next_frame() {
            if frame.dst != me {
                continue;
            }
            let (reply, answer) = oneshot::channel();
            if asks.send(Ask::Roc { frame, peer: peer.to_string(), session, reply }).is_err() {
                return;
            }
            let Ok(Answer { reply, log: lines, session: after }) = answer.await else { return };
            session = after;
            for line in lines {
                log(line);
            }
            let Some(bytes) = reply.encode() else { continue };
            if let Err(stop) = net::reply(&mut stream, &bytes, &limits).await {
                break 'conn stop;
            }
        }
        begun = net::waiting_since(frames.pending(), begun);
    };
    if frames.dropped > 0 {
        log(format!("roc {peer}: {} bytes made no frame (bad CRC or noise) and were dropped", frames.dropped));
    }
    if let Some(why) = stop.why(&limits) {
        log(format!("roc {peer}: dropped: {why}"));
    }
}
