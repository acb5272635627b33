//! The serial line's options, shared by `linc serve --roc-serial` and
//! `linc roc poll --serial`: the two ends of one line must agree, so they
//! are spelt and defaulted alike.

use linc_driver::roc::{DataBits, Line, Parity, StopBits};

/// `--baud` and the character framing. Only with the command's serial
/// port (its argument has the id `serial`): alone they would be ignored.
/// The group's id, `line`, lets a TCP option refuse them too (a required
/// argument clap finds in conflict is not required, so `requires` alone
/// lets `--host … --baud 9600` through).
#[derive(clap::Args)]
#[group(id = "line", requires = "serial", multiple = true)]
pub struct LineArgs {
    /// The serial line's speed (needed with a serial port).
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..))]
    pub baud: Option<u32>,
    /// Data bits per character.
    #[arg(long, value_name = "5|6|7|8", default_value = "8", value_parser = data_bits)]
    pub data_bits: DataBits,
    /// Parity bit.
    #[arg(long, value_name = "none|odd|even", default_value = "none", value_parser = parity)]
    pub parity: Parity,
    /// Stop bits.
    #[arg(long, value_name = "1|2", default_value = "1", value_parser = stop_bits)]
    pub stop_bits: StopBits,
}

impl LineArgs {
    /// The line, once `--baud` is given (clap requires it with the port).
    pub fn line(&self) -> Option<Line> {
        let baud = self.baud?;
        Some(Line { baud, data_bits: self.data_bits, parity: self.parity, stop_bits: self.stop_bits })
    }
}

fn data_bits(s: &str) -> Result<DataBits, String> {
    s.parse::<u8>().ok().and_then(|n| DataBits::try_from(n).ok()).ok_or_else(|| "data bits are 5, 6, 7 or 8".into())
}

fn parity(s: &str) -> Result<Parity, String> {
    match s {
        "none" => Ok(Parity::None),
        "odd" => Ok(Parity::Odd),
        "even" => Ok(Parity::Even),
        _ => Err("parity is none, odd or even".into()),
    }
}

fn stop_bits(s: &str) -> Result<StopBits, String> {
    s.parse::<u8>().ok().and_then(|n| StopBits::try_from(n).ok()).ok_or_else(|| "stop bits are 1 or 2".into())
}
