//! The registry of diagnostic codes: every code any stage emits, with a
//! one-line title and an explanation page (`docs/errors/CODE.md`: what it
//! means, a wrong and a right example) that `linc explain CODE` prints.
//!
//! A code is a [`Code`], not a string: an error can only carry a code that
//! is registered here, with its page (the build fails on a missing page),
//! and every stage's error type (compile, database, load, runtime, strategy,
//! state, console, scenario, usage) uses the same type.

use std::fmt;

macro_rules! codes {
    ($($code:ident => $title:literal,)*) => {
        /// A registered diagnostic code.
        #[derive(Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
        pub enum Code {
            $($code,)*
        }

        impl Code {
            /// Every code, in order.
            pub const ALL: &'static [Code] = &[$(Code::$code,)*];

            /// The code as it is printed (`E0010`).
            pub fn as_str(self) -> &'static str {
                match self {
                    $(Code::$code => stringify!($code),)*
                }
            }

            /// Its one-line title.
            pub fn title(self) -> &'static str {
                match self {
                    $(Code::$code => $title,)*
                }
            }

            /// Its explanation page, in Markdown.
            pub fn explanation(self) -> &'static str {
                match self {
                    $(Code::$code => include_str!(concat!("../../docs/errors/", stringify!($code), ".md")),)*
                }
            }
        }
    };
}

codes! {
    E0001 => "unexpected character",
    E0002 => "string constant is not closed",
    E0003 => "comment is not closed",
    E0004 => "space inside a name, operator or constant",
    E0005 => "identifier longer than 8 characters",
    E0006 => "invalid identifier",
    E0007 => "word operator not separated from its operand",
    E0008 => "invalid based integer constant",
    E0009 => "invalid time constant",
    E0010 => "unexpected token",
    E0011 => "unexpected end of file",
    E0012 => "a dot that does not join a name",
    E0013 => "bracketed name is not closed",
    E0014 => "invalid action name",
    E0015 => "more than one offset on one name part",
    E0016 => "statement outside an action",
    E0017 => "source file is not UTF-8",
    E0018 => "object file given as source",
    E0019 => "REAL constant out of range",
    E0020 => "time constant out of range",
    E0021 => "statements nested too deeply",
    E0022 => "expression nested too deeply",
    E0023 => "more errors in a file than are shown",
    E0024 => "sequence or FST table compiled with other files",
    E0025 => "FST table compiled without its point database",
    W0001 => "last statement without a semicolon",
    E0100 => "unknown name",
    E0101 => "unknown field",
    E0102 => "unknown sub-field",
    E0103 => "value of the wrong type stored in a field",
    E0104 => "unknown enumeration value",
    E0105 => "MOD on non-integers",
    E0106 => "FOR step is not a constant",
    E0107 => "EXIT outside a loop",
    E0108 => "assignment to something that cannot be written",
    E0109 => "invalid offset base or offset out of range",
    E0110 => "unknown function",
    E0111 => "wrong number of arguments",
    E0112 => "argument of the wrong type",
    E0113 => "step variable outside a sequence",
    E0114 => "operator applied to operands of the wrong type",
    E0115 => "name that is not a value",
    E0116 => "unknown block type in an action header",
    E0117 => "action defined twice",
    E0118 => "offset is not a number",
    E0119 => "condition is not BOOL or INT",
    E0120 => "unknown step",
    E0121 => "FOR step of zero",
    E0130 => "type of a name unknown when compiling",
    E0131 => "step variable in a plain action",
    E0132 => "too many steps, references, constants, loops or arguments",
    E0133 => "chart action that uses itself",
    E0200 => "unexpected token in a sequence",
    E0201 => "unexpected end of file in a sequence",
    E0202 => "chart without an initial step",
    E0203 => "step defined twice",
    E0204 => "transition from or to an unknown step",
    E0205 => "association names an unknown action",
    E0206 => "action defined twice in a sequence",
    E0207 => "unknown action qualifier",
    E0208 => "IEC qualifier that LIN does not have",
    E0209 => "qualifier needs a time",
    E0210 => "qualifier takes no time",
    E0211 => "transition defined twice",
    E0212 => "chart action that runs itself",
    E0213 => "chart actions nested too deeply",
    E0214 => "too many steps in one sequence",
    E0215 => "sequence too large for one object",
    W0200 => "action never used",
    W0201 => "step can never become active",
    W0202 => "unsafe chart: a step activated while active",
    E0250 => "generic name missing from the map",
    E0251 => "map file is not a JSON object of strings",
    E0252 => "map target names a block the database does not have",
    E0253 => "not a valid generic name",
    E0254 => "map target is not a database name",
    E0255 => "step with the name of a generic name",
    W0250 => "generic name missing from the map (allowed)",
    W0251 => "sequence uses more than the instrument allows",
    E0300 => "unexpected text in a rung",
    E0301 => "contact is not closed",
    E0302 => "label longer than 16 characters",
    E0303 => "label defined twice",
    E0304 => "unresolved jump",
    E0305 => "backward jump",
    E0306 => "contact on a value that is not digital",
    E0307 => "coil on a variable that is not digital",
    E0308 => "coil without a variable",
    E0309 => "rung outside an action",
    E0310 => "function box with the wrong number of inputs",
    E0311 => "empty contact",
    E0312 => "jumps nest or cross too deeply",
    E0313 => "ladder action with too many elements",
    E0314 => "rung too large to draw",
    E0400 => "FST table without its header row",
    E0401 => "malformed CSV row",
    E0402 => "FST step numbers out of order",
    E0403 => "unknown FST command",
    W0400 => "rows after the end of an FST program",
    E0404 => "invalid FST label",
    E0405 => "FST label that is a command name",
    E0406 => "FST label defined twice",
    E0407 => "branch to an unknown FST label",
    E0408 => "more than one END in an FST",
    E0409 => "argument given to an FST command that takes none",
    E0410 => "missing FST argument",
    E0411 => "value where an FST label is expected",
    E0412 => "FST label used as a value",
    E0413 => "constant where an FST parameter is expected",
    E0414 => "FST parameter that is not numeric",
    E0415 => "FST write to a read-only parameter",
    E0416 => "invalid FST timer",
    E0417 => "FST constant out of range",
    E0418 => "invalid FST month/day constant",
    E0419 => "FST number out of the REAL range",
    E0420 => "unreadable FST argument",
    E0421 => "unknown ROC point",
    E0422 => "unknown ROC point parameter",
    E0423 => "ROC point without a parameter",
    E0424 => "numeric TLP with an unknown point type",
    E0425 => "numeric TLP with an unknown logical number",
    E0426 => "numeric TLP with an unknown parameter number",
    E0427 => "FST output command on the wrong kind of point",
    E0430 => "FST step without a faithful translation",
    E0431 => "FST loop without a wait",
    E0432 => "FST cycle longer than the steps-per-cycle limit",
    E0433 => "FST branches too tangled to translate",
    E0434 => "FST sequence translation needs an exit field",
    W0401 => "FST message text cut to length",
    E0500 => "scenario target missing or repeated",
    E0501 => "`at` without a console command",
    E0502 => "scenario time not understood",
    E0503 => "unknown scenario line",
    E0504 => "unknown kind of expectation",
    E0505 => "scenario `state` or `set` line not understood",
    E0700 => "not a linc object file",
    E0701 => "unsupported object format version",
    E0702 => "object file checksum mismatch",
    E0703 => "truncated or malformed object file",
    E0704 => "unknown instruction",
    E0705 => "jump out of range",
    E0706 => "string constant out of range",
    E0707 => "symbol out of range or of the wrong kind",
    E0708 => "unbalanced stack or code that runs off its end",
    E0709 => "object does not fit the database",
    E0710 => "invalid function call or result kind",
    E0711 => "local variable or retained slot out of range",
    E0712 => "line or loop table outside the code",
    E0713 => "reference register used before it is set",
    E0714 => "sequence chart table out of range",
    R0001 => "division by zero",
    R0002 => "MOD by zero",
    R0003 => "offset outside its run of fields",
    R0004 => "not a value of an ENUM field",
    R0005 => "math domain error or non-finite result",
    R0006 => "watchdog: too many instructions in one run",
    R0007 => "string too long, or too many string bytes in one run",
    R0008 => "write to a read-only field through an offset",
    R0010 => "FST table: invalid point reference",
    R0011 => "FST table: invalid history point or index",
    R0099 => "object and database disagree at run time",
    C0001 => "console: unknown command",
    C0002 => "console: command written wrongly",
    C0003 => "console: no such block or field",
    C0004 => "console: not a value of the field's type",
    C0005 => "console: the field is read-only",
    C0006 => "console: the block runs no such program",
    C0007 => "console: the sequence has no such step or transition",
    C0008 => "console: not a duration",
    C0009 => "console: the field is forced, or not forced",
    C0010 => "console: not a runtime error code",
    C0011 => "console: the error status already holds an error",
    C0012 => "console: SAVE without a state file",
    C0013 => "console: ADVANCE beyond the server's limit",
    E0800 => "database file is not valid JSON",
    E0801 => "database file has the wrong shape",
    E0802 => "unknown field type in a template",
    E0803 => "block of an unknown type",
    E0804 => "invalid initial value",
    E0805 => "invalid alias target",
    E0806 => "name declared twice",
    E0807 => "key repeated in a JSON object",
    E0808 => "not a user task number",
    E0809 => "invalid task period",
    E0810 => "block runs in a task that is not defined",
    E0811 => "empty name",
    E0812 => "name too long",
    E0813 => "too many ENUM values",
    E0814 => "`readonly` is not true or false",
    E0815 => "initial value out of range",
    E0816 => "aliases form a cycle",
    E0817 => "alias expansion too large",
    E0818 => "unknown ROC device family",
    E0819 => "database with too many fields",
    E0830 => "action-type block names only half of its action",
    E0831 => "action-type block names an action its file does not have",
    E0832 => "error program is not an action-type block",
    E0833 => "SFC_CON block's file holds no sequence",
    E0834 => "FST block's file holds no FST table",
    E0850 => "Modbus map entry is malformed",
    E0851 => "Modbus map names a field the database lacks",
    E0852 => "Modbus map type does not fit its field",
    E0853 => "Modbus map addresses overlap",
    E0854 => "ROC operator entry is malformed",
    E0855 => "ROC configurable opcode table is malformed",
    E0856 => "ROC store-and-forward link is malformed",
    E0840 => "state file is damaged or cut short",
    E0841 => "state file is of another version",
    E0842 => "state file was saved from another strategy",
    E0900 => "file cannot be read or written",
    E0901 => "output path is not a regular file",
    E0902 => "output file is one of the inputs, or another output",
    E0903 => "invalid command-line value",
    E0904 => "--block names a block of another type",
    E0905 => "serial port cannot be opened",
    E0910 => "trace line is not a trace record",
    E0911 => "trend field the trace never writes",
    E0912 => "coverage file is not an lcov tracefile, or a name lcov cannot hold",
    E0913 => "coverage is under the share asked for",
    E0920 => "ROC host word file is invalid",
    E0921 => "ROC command list has the wrong shape",
    E0922 => "ROC command has a value out of range",
    E0923 => "ROC command asks for what the host does not support",
    I0001 => "how many errors and warnings a check found",
    I0002 => "how many code blocks ran compiled",
    I0003 => "how many scenarios ran, and how long they took",
    I0004 => "what a wire server did with a client",
}

impl Code {
    /// Looks a code up, ignoring case (`e0001` works too).
    pub fn lookup(text: &str) -> Option<Code> {
        let text = text.trim();
        Code::ALL.iter().copied().find(|c| c.as_str().eq_ignore_ascii_case(text))
    }

    /// Whether this is a note's code (`I…`): information, never a problem.
    pub fn is_note(self) -> bool {
        self.as_str().starts_with('I')
    }

    /// Whether this is a warning's code (`W…`); every other kind but a
    /// note's is an error.
    pub fn is_warning(self) -> bool {
        self.as_str().starts_with('W')
    }
}

impl fmt::Display for Code {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

/// Written as the string it was before it had a type, so snapshots of
/// diagnostics read the same.
impl fmt::Debug for Code {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{:?}", self.as_str())
    }
}

impl PartialEq<str> for Code {
    fn eq(&self, other: &str) -> bool {
        self.as_str() == other
    }
}

impl PartialEq<&str> for Code {
    fn eq(&self, other: &&str) -> bool {
        self.as_str() == *other
    }
}

impl PartialEq<Code> for &str {
    fn eq(&self, other: &Code) -> bool {
        *self == other.as_str()
    }
}

impl PartialEq<Code> for str {
    fn eq(&self, other: &Code) -> bool {
        self == other.as_str()
    }
}

/// A code is written into JSON (diagnostics, traces, state files) as its
/// text.
impl serde::Serialize for Code {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(self.as_str())
    }
}

impl From<Code> for serde_json::Value {
    fn from(c: Code) -> serde_json::Value {
        serde_json::Value::String(c.as_str().to_string())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_page_has_its_title_line_and_examples() {
        for &c in Code::ALL {
            let page = c.explanation();
            assert!(page.starts_with(&format!("# {}: {}", c, c.title())), "{c} title line");
            if c.is_note() {
                assert!(page.contains("## Example"), "{c} example");
            } else {
                assert!(page.contains("## Wrong") && page.contains("## Right"), "{c} examples");
            }
        }
    }

    #[test]
    fn codes_are_looked_up_by_their_text() {
        assert_eq!(Code::lookup(" e0010 "), Some(Code::E0010));
        assert_eq!(Code::lookup("E9999"), None);
        assert_eq!(Code::E0010, "E0010");
        assert_eq!(format!("{} {:?}", Code::W0001, Code::W0001), "W0001 \"W0001\"");
    }
}
