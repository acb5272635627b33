//! The FST command set (ROCLINK 800 Table B-9), described once: each
//! command's name, category and what its two arguments may be.

/// What an argument cell may hold.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// Must be empty.
    None,
    /// A numeric constant or a readable numeric parameter.
    In,
    /// A writable numeric parameter (SAV).
    Out,
    /// A label of this table.
    Label,
    /// Message text (MSG, ALM, EVT).
    Text,
    /// A timer: the number 1–4 (this FST's) or an FST point's TMR1–TMR4.
    Timer,
    /// A history point: its number (1–200) as a constant or a parameter.
    Hist,
    /// A history index: a constant, or a writable parameter that the
    /// command advances (WDB, WTM, RDB).
    Index,
    /// An analog output point (`AOU 4-1`, default parameter EU).
    AoPoint,
    /// A discrete output point (`DOU 4-1`, default parameter STATUS).
    DoPoint,
}

macro_rules! commands {
    ($($name:ident $text:literal $cat:literal [$a1:ident $a2:ident] $doc:literal;)*) => {
        /// An FST command.
        #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
        pub enum Cmd { $( #[doc = $doc] $name, )* }

        impl Cmd {
            /// Every command, in Table B-9's order.
            pub const ALL: &'static [Cmd] = &[$(Cmd::$name),*];

            /// The command as written in the CMD column.
            pub fn text(self) -> &'static str {
                match self { $( Cmd::$name => $text, )* }
            }

            /// Table B-9's category.
            pub fn category(self) -> &'static str {
                match self { $( Cmd::$name => $cat, )* }
            }

            /// What ARGUMENT1 and ARGUMENT2 may hold.
            pub fn args(self) -> (Kind, Kind) {
                match self { $( Cmd::$name => (Kind::$a1, Kind::$a2), )* }
            }

            /// One line on what the command does.
            pub fn doc(self) -> &'static str {
                match self { $( Cmd::$name => $doc, )* }
            }
        }
    };
}

commands! {
    Add "+" "Math" [In None] "RR = RR + ARGUMENT1.";
    Sub "-" "Math" [In None] "RR = RR - ARGUMENT1.";
    Mul "*" "Math" [In None] "RR = RR * ARGUMENT1.";
    Div "/" "Math" [In None] "RR = RR / ARGUMENT1; RR unchanged when ARGUMENT1 is 0.";
    Pow "**" "Math" [In None] "RR = RR ** ARGUMENT1; nothing when RR <= 0.";
    Abs "ABS" "Math" [None None] "RR = |RR|.";
    Exp "EXP" "Math" [None None] "RR = e ** RR.";
    Int "INT" "Math" [None None] "RR = integer part of RR.";
    Log "LOG" "Math" [None None] "RR = log10(RR); nothing when RR <= 0.";
    Ln "LN" "Math" [None None] "RR = ln(RR); nothing when RR <= 0.";
    Sqr "SQR" "Math" [None None] "RR = square root of RR; nothing when RR < 0.";
    P3 "P3" "Math" [None None] "RR = R1*RR**3 + R2*RR**2 + R3*RR + R4.";
    Not "NOT" "Logical" [None None] "CF = 1 if CF is 0, else 0.";
    And "AND" "Logical" [In None] "CF = CF AND ARGUMENT1 (8 bits).";
    Or "OR" "Logical" [In None] "CF = CF OR ARGUMENT1 (8 bits).";
    Xor "XOR" "Logical" [In None] "CF = CF XOR ARGUMENT1 (8 bits).";
    Eq "==" "Comparison" [In Label] "Go to ARGUMENT2 if RR equals ARGUMENT1, bit for bit.";
    Ne "!=" "Comparison" [In Label] "Go to ARGUMENT2 if RR differs from ARGUMENT1.";
    Lt "<" "Comparison" [In Label] "Go to ARGUMENT2 if RR < ARGUMENT1.";
    Le "<=" "Comparison" [In Label] "Go to ARGUMENT2 if RR <= ARGUMENT1.";
    Gt ">" "Comparison" [In Label] "Go to ARGUMENT2 if RR > ARGUMENT1.";
    Ge ">=" "Comparison" [In Label] "Go to ARGUMENT2 if RR >= ARGUMENT1.";
    St "ST" "Time" [Timer In] "Set timer ARGUMENT1 to ARGUMENT2 intervals of 100 ms.";
    Ct "CT" "Time" [Timer Label] "Go to ARGUMENT2 while timer ARGUMENT1 is above 0.";
    Wt "WT" "Time" [In None] "Suspend for ARGUMENT1 seconds (0.1 to 999,999).";
    Dwk "DWK" "Time" [None None] "RR = day of week (1 = Sunday).";
    Mnd "MND" "Time" [None None] "RR = minutes since midnight.";
    Ao "AO" "Control" [AoPoint In] "Analog output ARGUMENT1 = ARGUMENT2, unless in manual.";
    Do "DO" "Control" [DoPoint In] "Discrete output ARGUMENT1 = ARGUMENT2, unless in manual.";
    Tdo "TDO" "Control" [DoPoint In] "Timed discrete output ARGUMENT1 on for ARGUMENT2 seconds.";
    Val "VAL" "Database" [In None] "RR = ARGUMENT1.";
    Sav "SAV" "Database" [Out None] "ARGUMENT1 = RR.";
    Rdb "RDB" "Database" [Hist Index] "RR = history point ARGUMENT1 at index ARGUMENT2.";
    Wdb "WDB" "Database" [Hist Index] "History point ARGUMENT1 at index ARGUMENT2 = RR.";
    Wtm "WTM" "Database" [Hist Index] "History point ARGUMENT1 at index ARGUMENT2 = the time.";
    Dhv "DHV" "Database" [Hist In] "RR = daily history value at index ARGUMENT2.";
    Dht "DHT" "Database" [Hist In] "RR = daily history time stamp at index ARGUMENT2.";
    Phv "PHV" "Database" [Hist In] "RR = periodic history value at index ARGUMENT2.";
    Pht "PHT" "Database" [Hist In] "RR = periodic history time stamp at index ARGUMENT2.";
    Mhv "MHV" "Database" [Hist In] "RR = minute history value at index ARGUMENT2 (the minute).";
    Dis "DIS" "Database" [Hist In] "RR = first daily index of month/day ARGUMENT2 (MMDD), or -1.";
    Din "DIN" "Database" [Hist In] "RR = number of daily indexes of month/day ARGUMENT2, or -1.";
    Pis "PIS" "Database" [Hist In] "RR = first periodic index of month/day ARGUMENT2, or -1.";
    Pin "PIN" "Database" [Hist In] "RR = number of periodic indexes of month/day ARGUMENT2, or -1.";
    Gte "GTE" "Database" [In In] "RR = element ARGUMENT2 (0 month … 5 second) of time ARGUMENT1.";
    Go "GO" "Miscellaneous" [Label None] "Go to ARGUMENT1.";
    Msg "MSG" "Miscellaneous" [Text In] "MSG1 = ARGUMENT1; message data = ARGUMENT2.";
    End "END" "Miscellaneous" [None None] "End of the table: the next cycle starts at step 0.";
    Brk "BRK" "Miscellaneous" [In None] "Delay ARGUMENT1 × 100 ms between the commands that follow.";
    Alm "ALM" "Miscellaneous" [Text In] "Alarm log: the first 10 characters of ARGUMENT1 and ARGUMENT2.";
    Evt "EVT" "Miscellaneous" [Text In] "Event log: the first 10 characters of ARGUMENT1 and ARGUMENT2.";
}

impl Cmd {
    /// A command by its text, ignoring case.
    pub fn parse(text: &str) -> Option<Cmd> {
        Cmd::ALL.iter().copied().find(|c| c.text().eq_ignore_ascii_case(text))
    }

    /// Whether `word` is a command name (labels may not be).
    pub fn is_command(word: &str) -> bool {
        Cmd::parse(word).is_some()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_command_of_table_b9_is_here_once() {
        let texts: Vec<&str> = Cmd::ALL.iter().map(|c| c.text()).collect();
        assert_eq!(texts.len(), 51);
        let mut unique = texts.clone();
        unique.sort_unstable();
        unique.dedup();
        assert_eq!(unique.len(), texts.len());
        for t in texts {
            assert_eq!(Cmd::parse(&t.to_ascii_lowercase()).map(Cmd::text), Some(t));
        }
    }
}
