//! The ROC Plus server: frames off TCP, or off a serial line, for this
//! device's address go to the plant thread; the connection loop is the one
//! both servers share.

use super::net::{Next, Wire};
use super::roc::Answer;
use crate::Ask;
use linc_comms::roc::{Address, Deframer};
use tokio::sync::oneshot;

/// One client's ROC Plus state: its frames, and the operator logged in on
/// the connection (the access level).
pub(crate) struct Roc {
    me: Address,
    frames: Deframer,
    session: Option<u8>,
}

impl Roc {
    pub(crate) fn new(me: Address) -> Roc {
        Roc { me, frames: Deframer::default(), session: None }
    }
}

impl Wire for Roc {
    type Answer = Answer;
    const NAME: &'static str = "roc";

    fn push(&mut self, bytes: &[u8]) {
        self.frames.push(bytes);
    }

    fn pending(&self) -> usize {
        self.frames.pending()
    }

    /// A whole frame for this device goes to the plant; frames for other
    /// addresses and bytes that make no frame (a bad CRC) get no reply.
    fn next(&mut self, peer: &str) -> Option<Next<Answer>> {
        let frame = self.frames.next_frame()?;
        if frame.dst != self.me {
            return Some(Next::Skip);
        }
        let (reply, answer) = oneshot::channel();
        Some(Next::Ask(Ask::Roc { frame, peer: peer.to_string(), session: self.session, reply }, answer))
    }

    fn answered(&mut self, answer: Answer) -> (Option<Vec<u8>>, Vec<String>) {
        self.session = answer.session;
        (answer.reply.encode(), answer.log)
    }

    fn farewell(&self, peer: &str) -> Option<String> {
        let dropped = self.frames.dropped;
        (dropped > 0).then(|| format!("roc {peer}: {dropped} bytes made no frame (bad CRC or noise) and were dropped"))
    }
}
