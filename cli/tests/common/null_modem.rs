//! A null-modem cable between two pseudo-terminals, for the serial tests
//! of `linc serve --roc-serial` and `linc roc poll --serial`.
#![cfg(unix)]

/// Two pseudo-terminal pairs whose master ends a thread each way joins,
/// as a null-modem cable joins two serial ports: what is written to one
/// slave is read from the other. The slaves stay open here too, so
/// neither terminal hangs up between the programs' opens of it.
pub struct NullModem {
    pub paths: [String; 2],
    _slaves: [serialport::TTYPort; 2],
    stop: std::sync::Arc<std::sync::atomic::AtomicBool>,
    copiers: Vec<std::thread::JoinHandle<()>>,
}

impl NullModem {
    pub fn new() -> NullModem {
        use serialport::SerialPort;
        let (a, sa) = serialport::TTYPort::pair().expect("a pseudo-terminal pair");
        let (b, sb) = serialport::TTYPort::pair().expect("a pseudo-terminal pair");
        let paths = [sa.name().expect("a path"), sb.name().expect("a path")];
        let stop = std::sync::Arc::new(std::sync::atomic::AtomicBool::new(false));
        let copy = |mut from: serialport::TTYPort, mut to: serialport::TTYPort| {
            let stop = stop.clone();
            std::thread::spawn(move || {
                use std::io::{Read, Write};
                from.set_timeout(std::time::Duration::from_millis(50)).unwrap();
                let mut buf = [0u8; 512];
                while !stop.load(std::sync::atomic::Ordering::Relaxed) {
                    match from.read(&mut buf) {
                        Ok(n) => to.write_all(&buf[..n]).expect("copy"),
                        Err(e) if e.kind() == std::io::ErrorKind::TimedOut => {}
                        Err(e) => panic!("the bridge failed: {e}"),
                    }
                }
            })
        };
        let (a2, b2) = (a.try_clone_native().unwrap(), b.try_clone_native().unwrap());
        let copiers = vec![copy(a, b2), copy(b, a2)];
        NullModem { paths, _slaves: [sa, sb], stop, copiers }
    }
}

impl Drop for NullModem {
    fn drop(&mut self) {
        self.stop.store(true, std::sync::atomic::Ordering::Relaxed);
        for c in self.copiers.drain(..) {
            let _ = c.join();
        }
    }
}
