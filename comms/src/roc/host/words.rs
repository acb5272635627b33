//! The module database of a ROC host: 4,000 sixteen-bit words (the
//! communication module's data space, `003_…` §1.3.3), read from and
//! written to JSON as runs of words by start address:
//! `{"0": [3, 0, 2, 3, 1, 2], "100": [500, 1000]}`.

use crate::error::FileError;
use linc_format::db::tree::{self, Json};
use linc_format::Code;

/// Words in the module's data space (addresses 0 to 3999).
pub const SIZE: usize = 4000;

/// Zero words in a row that end a run when the table is written: shorter
/// gaps stay inside the run, so a TLP with logical number 0 reads as one.
const GAP: usize = 4;

/// The word table.
#[derive(Clone, Debug, PartialEq)]
pub struct Words(pub Vec<u16>);

impl Default for Words {
    fn default() -> Words {
        Words(vec![0; SIZE])
    }
}

fn bad(message: impl Into<String>, span: (usize, usize)) -> FileError {
    FileError::at(Code::E0920, message, span)
}

impl Words {
    /// Reads a word file. Keys are start addresses; each value is an array
    /// of words from -32768 to 65535 (a PLC's INT file is signed: -1 is
    /// 65535). A `"status"` member (what `--out` adds) is ignored. Runs may
    /// not overlap or pass word 3999.
    pub fn parse(text: &str) -> Result<Words, FileError> {
        let root = tree::parse_named(text, "the word file").map_err(|e| FileError {
            code: Code::E0920,
            message: e.message,
            span: e.span,
        })?;
        let Json::Obj(members) = &root.v else {
            return Err(bad(format!("a word file is a JSON object of runs, not {}", root.kind()), root.span));
        };
        let mut words = Words::default();
        let mut set = vec![false; SIZE];
        for m in members.iter().filter(|m| m.key != "status") {
            let start = m
                .key
                .parse::<usize>()
                .ok()
                .filter(|&s| s < SIZE)
                .ok_or_else(|| bad(format!("`{}` is not a word address (0 to {})", m.key, SIZE - 1), m.key_span))?;
            let Json::Arr(items) = &m.value.v else {
                return Err(bad(format!("the run at {start} must be an array of words"), m.value.span));
            };
            if start + items.len() > SIZE {
                let message = format!("the run at {start} has {} words and passes word {}", items.len(), SIZE - 1);
                return Err(bad(message, m.value.span));
            }
            for (i, item) in items.iter().enumerate() {
                let w = item
                    .whole(-32768.0, 65535.0)
                    .ok_or_else(|| bad("a word is a whole number from -32768 to 65535", item.span))?
                    as u16;
                if std::mem::replace(&mut set[start + i], true) {
                    return Err(bad(format!("word {} is given twice (runs overlap)", start + i), item.span));
                }
                words.0[start + i] = w;
            }
        }
        Ok(words)
    }

    /// The table as runs of words by start address: each run starts and
    /// ends with a word that is not 0, and fewer than four zeros in a row
    /// stay inside it. `status` (each command's error code, in list order)
    /// is added as `"status"` when given.
    pub fn to_json(&self, status: Option<&[u16]>) -> String {
        let mut out = String::from("{");
        let mut first = true;
        let mut i = 0;
        while i < SIZE {
            if self.0[i] == 0 {
                i += 1;
                continue;
            }
            let start = i;
            let mut end = i + 1; // one past the last word that is not 0
            let mut j = end;
            while j < SIZE && j - end < GAP {
                if self.0[j] != 0 {
                    end = j + 1;
                }
                j += 1;
            }
            let run: Vec<String> = self.0[start..end].iter().map(u16::to_string).collect();
            out.push_str(if first { "\n  " } else { ",\n  " });
            out.push_str(&format!("\"{start}\": [{}]", run.join(", ")));
            first = false;
            i = end;
        }
        if let Some(status) = status {
            let codes: Vec<String> = status.iter().map(u16::to_string).collect();
            out.push_str(if first { "\n  " } else { ",\n  " });
            out.push_str(&format!("\"status\": [{}]", codes.join(", ")));
            first = false;
        }
        out.push_str(if first { "}\n" } else { "\n}\n" });
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn runs_read_and_write_back() {
        let w = Words::parse(r#"{"0": [3, 0, 2, 3, 1, 2], "100": [500, 1000], "200": [-1]}"#).unwrap();
        assert_eq!(&w.0[..6], &[3, 0, 2, 3, 1, 2]);
        assert_eq!((w.0[100], w.0[101], w.0[200]), (500, 1000, 65535));
        let text = w.to_json(Some(&[0, 28]));
        assert_eq!(
            text,
            "{\n  \"0\": [3, 0, 2, 3, 1, 2],\n  \"100\": [500, 1000],\n  \"200\": [65535],\n  \"status\": [0, 28]\n}\n"
        );
        assert_eq!(Words::parse(&text).unwrap(), w, "the written form reads back");
        assert_eq!(Words::default().to_json(None), "{}\n");
    }

    #[test]
    fn four_zeros_end_a_run() {
        let mut w = Words::default();
        w.0[10] = 1;
        w.0[14] = 2; // three zeros between: one run
        w.0[19] = 3; // four zeros between: a new run
        assert_eq!(w.to_json(None), "{\n  \"10\": [1, 0, 0, 0, 2],\n  \"19\": [3]\n}\n");
        w.0[SIZE - 1] = 9;
        assert!(w.to_json(None).contains("\"3999\": [9]"));
    }

    #[test]
    fn bad_files_are_located() {
        for (text, needle) in [
            ("[1]", "JSON object"),
            (r#"{"x": [1]}"#, "`x` is not a word address"),
            (r#"{"4000": [1]}"#, "not a word address"),
            (r#"{"3999": [1, 2]}"#, "passes word 3999"),
            (r#"{"0": 5}"#, "must be an array"),
            (r#"{"0": [70000]}"#, "whole number"),
            (r#"{"0": [1.5]}"#, "whole number"),
            (r#"{"0": [1, 2], "1": [3]}"#, "word 1 is given twice"),
            (r#"{"0": [1"#, ""),
        ] {
            let e = Words::parse(text).unwrap_err();
            assert_eq!(e.code, Code::E0920, "{text}");
            assert!(e.message.contains(needle), "{text}: {}", e.message);
            assert!(e.span.is_some(), "{text}");
        }
    }
}
