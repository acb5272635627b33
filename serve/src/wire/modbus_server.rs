//! The Modbus TCP server: frames off TCP (linc's own decoder, ADR 0019)
//! for this device go to the plant thread; the connection loop, cap,
//! timeouts and logs are the ones both servers share.

use super::modbus::MbAnswer;
use super::net::{Next, Wire};
use crate::Ask;
use linc_comms::modbus::{self, Deframer, Header};
use tokio::sync::oneshot;

/// One client's Modbus state: its frames, and the header of the request
/// the plant is answering.
pub(crate) struct Modbus {
    unit: u8,
    frames: Deframer,
    asked: Option<Header>,
}

impl Modbus {
    pub(crate) fn new(unit: u8) -> Modbus {
        Modbus { unit, frames: Deframer::default(), asked: None }
    }
}

impl Wire for Modbus {
    type Answer = MbAnswer;
    const NAME: &'static str = "modbus";

    fn push(&mut self, bytes: &[u8]) {
        self.frames.push(bytes);
    }

    fn pending(&self) -> usize {
        self.frames.pending()
    }

    /// Requests for the map's unit, or for 0 or 255 (which Modbus TCP
    /// devices take as "this device"), go to the plant; others get no
    /// reply, as from a gateway with no such device; one that does not
    /// decode gets its exception here. A stream that is not Modbus TCP (a
    /// protocol identifier other than 0, a length no frame has) can't be
    /// resynchronised, so the connection is closed.
    fn next(&mut self, peer: &str) -> Option<Next<MbAnswer>> {
        let (head, pdu) = match self.frames.next_frame()? {
            Ok(f) => f,
            Err(e) => return Some(Next::Close(format!("not Modbus TCP ({e:?})"))),
        };
        if head.unit != self.unit && head.unit != 0 && head.unit != 255 {
            return Some(Next::Skip);
        }
        Some(match modbus::decode(&pdu) {
            Err((function, e)) => Next::Reply(modbus::encode(head, function, &Err(e))),
            Ok(request) => {
                let (reply, answer) = oneshot::channel();
                self.asked = Some(head);
                Next::Ask(Ask::Modbus { request, peer: peer.to_string(), reply }, answer)
            }
        })
    }

    fn answered(&mut self, answer: MbAnswer) -> (Option<Vec<u8>>, Vec<String>) {
        let bytes = self.asked.take().map(|head| modbus::encode(head, answer.function, &answer.reply));
        (bytes, answer.log)
    }
}
