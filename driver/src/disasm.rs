//! `linc disasm OUT.sto`: a readable listing of an object file, written
//! as it is made (a listing is several times its object).

use linc_compiler::diag::Problems;
use linc_runtime::isa::Op;
use linc_runtime::object::{CodeBlock, ObjectFile};
use linc_runtime::text::format_value;
use linc_stdlib::{Value, SIGNATURES};
use std::collections::HashMap;
use std::io::Write;
use std::path::Path;

/// Loads and verifies an object file; one that can't be read or is
/// refused is a refused request.
pub fn load(path: &Path) -> Result<linc_runtime::Verified, Problems> {
    let name = path.display().to_string();
    let bytes = crate::files::read_input(path)
        .map_err(|e| Problems::whole_file(&name, linc_format::Code::E0900, format!("can't read `{name}`: {e}")))?;
    linc_runtime::load(&bytes).map_err(|e| Problems::whole_file(&name, e.code(), e.to_string()))
}

/// The listing: symbols, constants, then each unit's code blocks with
/// labels, retained slots and the source line of each statement (when the
/// source file can be read). Linear in the object's size: each source file
/// is read once, and the line table is walked alongside the code; a string
/// constant is listed whole once, in the strings table, and by its number
/// `$k` with its first bytes where it is pushed, and source lines are cut.
pub fn listing(obj: &ObjectFile, out: &mut dyn Write) -> std::io::Result<()> {
    writeln!(out, "; object compiled from {} (format version {})", obj.source, linc_runtime::object::VERSION)?;
    writeln!(out, "; symbols")?;
    for (i, s) in obj.symbols.iter().enumerate() {
        writeln!(out, ";   #{i:<3} {} ({:?})", s.text(), s.class)?;
    }
    if !obj.strings.is_empty() {
        writeln!(out, "; strings")?;
        for (i, s) in obj.strings.iter().enumerate() {
            writeln!(out, ";   ${i:<3} {}", format_value(&Value::Bytes(s.0.clone())))?;
        }
    }
    let mut sources: HashMap<&str, Vec<String>> = HashMap::new();
    for u in &obj.units {
        // The object names its source; it is read under the input rules, so
        // a name that is now a FIFO or a device can't hang the listing.
        let source = sources.entry(u.file.as_str()).or_insert_with(|| {
            crate::files::read_input_text(std::path::Path::new(&u.file))
                .map(|t| t.lines().map(str::to_string).collect())
                .unwrap_or_default()
        });
        let kind = if u.block_type.is_empty() { String::new() } else { format!(" : {}", u.block_type) };
        writeln!(
            out,
            "\n{} {}{kind}    ; {}, {} code block{}, {} retained slot{}",
            format!("{:?}", u.kind).to_lowercase(),
            u.name,
            u.file,
            u.blocks.len(),
            if u.blocks.len() == 1 { "" } else { "s" },
            u.retained,
            if u.retained == 1 { "" } else { "s" },
        )?;
        for (ci, c) in u.charts.iter().enumerate() {
            chart(out, u, ci, c)?;
        }
        for (bi, b) in u.blocks.iter().enumerate() {
            block(out, obj, bi, b, source)?;
        }
    }
    Ok(())
}

/// A sequence's chart table: steps with their slots and associations,
/// transitions with their condition blocks, actions.
fn chart(
    out: &mut dyn Write,
    u: &linc_runtime::object::Unit,
    index: usize,
    c: &linc_runtime::object::ChartRec,
) -> std::io::Result<()> {
    let title = if index == 0 { "ROOT".to_string() } else { format!("#{index}") };
    writeln!(out, "  chart {title}")?;
    let block_name = |b: u16| u.blocks.get(usize::from(b)).map(|b| b.name.clone()).unwrap_or_else(|| format!("#{b}"));
    for s in &c.steps {
        let assocs: Vec<String> = s
            .assocs
            .iter()
            .map(|a| {
                let name = c.actions.get(usize::from(a.action)).map_or("?", |x| x.name.as_str());
                let q = char::from(a.qualifier);
                if a.time_us > 0 {
                    format!("{name}({q}, {} s)", a.time_us as f64 / 1e6)
                } else {
                    format!("{name}({q})")
                }
            })
            .collect();
        let kind = if s.initial != 0 { "initial step" } else { "step" };
        writeln!(out, "    {kind} {} [slot {}]: {}", s.name, s.slot, assocs.join(", "))?;
    }
    let steps = |v: &[u16]| {
        v.iter().map(|&i| c.steps.get(usize::from(i)).map_or("?", |s| s.name.as_str())).collect::<Vec<_>>().join(", ")
    };
    for t in &c.transitions {
        let p = if t.priority == u32::MAX { String::new() } else { format!(" priority {}", t.priority) };
        writeln!(
            out,
            "    transition `{}`{p}: ({}) -> ({}) when {}",
            t.name,
            steps(&t.from),
            steps(&t.to),
            block_name(t.block)
        )?;
    }
    for a in &c.actions {
        let body = if a.kind == 1 { format!("chart #{}", a.index) } else { format!("block {}", block_name(a.index)) };
        writeln!(out, "    action {}: {body}", a.name)?;
    }
    Ok(())
}

fn block(out: &mut dyn Write, obj: &ObjectFile, index: usize, b: &CodeBlock, source: &[String]) -> std::io::Result<()> {
    let name = if b.name.is_empty() { format!("#{index}") } else { b.name.clone() };
    writeln!(out, "  block {name}    ; {} instructions, {} locals, {} labels", b.ops.len(), b.locals, b.labels.len())?;
    let mut labels_at: Vec<(u32, usize)> = b.labels.iter().enumerate().map(|(l, &at)| (at, l)).collect();
    labels_at.sort_unstable();
    let (mut next_line, mut next_label, mut shown_line) = (0, 0, 0);
    for (pc, op) in b.ops.iter().enumerate() {
        while let Some(&(at, l)) = labels_at.get(next_label).filter(|(at, _)| *at as usize <= pc) {
            if at as usize == pc {
                writeln!(out, "  L{l}:")?;
            }
            next_label += 1;
        }
        while let Some(e) = b.lines.get(next_line).filter(|e| e.op as usize <= pc) {
            next_line += 1;
            if e.op as usize != pc || e.line == shown_line {
                continue;
            }
            shown_line = e.line;
            let text = source.get((e.line as usize).wrapping_sub(1)).map(|s| s.trim()).unwrap_or("");
            writeln!(out, "    ; {}:{}  {}", e.line, e.col, cut(text))?;
        }
        writeln!(out, "  {pc:>5}  {}", describe(obj, op))?;
    }
    Ok(())
}

/// The most bytes of a string constant shown where it is used; the whole
/// constant is in the strings table, once (a 1 MiB constant pushed 4,000
/// times made 4 GB of listing).
const PREVIEW: usize = 32;

/// The most characters of a source line shown above its instructions.
const LINE: usize = 120;

/// A string constant at a use: whole when short, else its first bytes and
/// its length.
fn preview(s: &[u8]) -> String {
    if s.len() <= PREVIEW {
        return format_value(&Value::Bytes(s.to_vec()));
    }
    let head = format_value(&Value::Bytes(s[..PREVIEW].to_vec()));
    format!("{}…' ({} bytes)", head.strip_suffix('\'').unwrap_or(&head), s.len())
}

/// A source line, cut to [`LINE`] characters.
fn cut(text: &str) -> String {
    match text.char_indices().nth(LINE) {
        Some((at, _)) => format!("{}…", &text[..at]),
        None => text.to_string(),
    }
}

fn describe(obj: &ObjectFile, op: &Op) -> String {
    let name = op.name();
    let sym = |s: u16| obj.symbols.get(usize::from(s)).map(|s| s.text()).unwrap_or_else(|| format!("#{s}?"));
    match *op {
        Op::PushI { v } => format!("{name:<12} {v}"),
        Op::PushR { v } => format!("{name:<12} {}", linc_runtime::text::format_real(v)),
        Op::PushS { k } => {
            let s = obj.strings.get(k as usize).map(|s| s.0.as_slice()).unwrap_or_default();
            format!("{name:<12} ${k} {}", preview(s))
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
            (_, Some(t)) => format!("{name:<12} -> L{t}"),
            _ => {
                let operands = op.operands().join(" ");
                format!("{name:<12} {operands}").trim_end().to_string()
            }
        },
    }
}
