//! `linc disasm OUT.sto`: a readable listing of an object file.

use linc_runtime::isa::Op;
use linc_runtime::object::ObjectFile;
use linc_runtime::text::format_value;
use linc_stdlib::{Value, SIGNATURES};
use std::fmt::Write;
use std::path::Path;

pub fn run(path: &Path) -> u8 {
    let bytes = match crate::files::read_input(path) {
        Ok(b) => b,
        Err(e) => {
            eprintln!("error[E0900]: can't read `{}`: {e}", path.display());
            return 2;
        }
    };
    match linc_runtime::load(&bytes) {
        Ok(obj) => {
            print!("{}", listing(&obj));
            0
        }
        Err(e) => {
            eprintln!("error[{}]: {}: {e}", e.code(), path.display());
            2
        }
    }
}

/// The listing: symbols, constants, then each action's code with the
/// source line of each statement (when the source file can be read).
pub fn listing(obj: &ObjectFile) -> String {
    let mut out = String::new();
    let _ = writeln!(out, "; object compiled from {}", obj.source);
    let _ = writeln!(out, "; symbols");
    for (i, s) in obj.symbols.iter().enumerate() {
        let _ = writeln!(out, ";   #{i:<3} {} ({:?})", s.text(), s.class);
    }
    if !obj.strings.is_empty() {
        let _ = writeln!(out, "; strings");
        for (i, s) in obj.strings.iter().enumerate() {
            let _ = writeln!(out, ";   ${i:<3} {}", format_value(&Value::Bytes(s.clone())));
        }
    }
    for a in &obj.actions {
        // The object names its source; it is read under the input rules, so
        // a name that is now a FIFO or a device can't hang the listing.
        let source: Vec<String> = crate::files::read_input_text(std::path::Path::new(&a.file))
            .map(|t| t.lines().map(str::to_string).collect())
            .unwrap_or_default();
        let kind = if a.block_type.is_empty() { String::new() } else { format!(" : {}", a.block_type) };
        let _ = writeln!(
            out,
            "\naction {}{kind}    ; {}, {} instructions, {} locals",
            a.name,
            a.file,
            a.ops.len(),
            a.locals
        );
        let mut shown_line = 0;
        for (pc, op) in a.ops.iter().enumerate() {
            for e in a.lines.iter().filter(|e| e.op as usize == pc) {
                if e.line == shown_line {
                    continue;
                }
                shown_line = e.line;
                let text = source.get(e.line as usize - 1).map(|s| s.trim()).unwrap_or("");
                let _ = writeln!(out, "    ; {}:{}  {text}", e.line, e.col);
            }
            let _ = writeln!(out, "  {pc:>5}  {}", describe(obj, op));
        }
    }
    out
}

fn describe(obj: &ObjectFile, op: &Op) -> String {
    let name = op.name();
    let sym = |s: u16| obj.symbols.get(usize::from(s)).map(|s| s.text()).unwrap_or_else(|| format!("#{s}?"));
    match *op {
        Op::PushI { v } => format!("{name:<12} {v}"),
        Op::PushR { v } => format!("{name:<12} {}", linc_runtime::text::format_real(v)),
        Op::PushS { k } => {
            let s = obj.strings.get(k as usize).cloned().unwrap_or_default();
            format!("{name:<12} {}", format_value(&Value::Bytes(s)))
        }
        Op::Call { func, argc, .. } => {
            let f = SIGNATURES.get(usize::from(func)).map(|s| s.name).unwrap_or("?");
            format!("{name:<12} {f}/{argc}")
        }
        Op::LoadBit { sym: s, bit } | Op::StoreBit { sym: s, bit } => {
            format!("{name:<12} {}.Bit{bit}", sym(s))
        }
        _ => match (op.symbol(), op.target()) {
            (Some(s), _) => format!("{name:<12} {}", sym(s)),
            (_, Some(t)) => format!("{name:<12} -> {t}"),
            _ => {
                let operands = op.operands().join(" ");
                format!("{name:<12} {operands}").trim_end().to_string()
            }
        },
    }
}
