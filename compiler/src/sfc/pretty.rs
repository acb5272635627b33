//! A compact S-expression view of a sequence tree, for snapshots and
//! `--tree`: how the text was grouped, without spans. ST inside is shown as
//! [`crate::st::pretty`] shows it.

use super::ast::{ActionBody, Chart, Sequence};
use crate::diag::render::escape;
use crate::st::ast::SourceFile;
use std::fmt::Write;

pub fn sequence(s: &Sequence) -> String {
    let mut out = String::from("(chart\n");
    chart(&mut out, &s.chart, 1);
    out.push_str(")\n");
    for a in &s.actions {
        match &a.body {
            ActionBody::St(st) => out.push_str(&crate::st::pretty::file(&SourceFile { actions: vec![st.clone()] })),
            ActionBody::Chart(c) => {
                let _ = writeln!(out, "(action {} : CHART", escape(&a.name.text));
                chart(&mut out, c, 1);
                out.push_str(")\n");
            }
        }
    }
    out
}

fn chart(out: &mut String, c: &Chart, depth: usize) {
    let pad = "  ".repeat(depth);
    for s in &c.steps {
        let kind = if s.initial { "initial-step" } else { "step" };
        let _ = write!(out, "{pad}({kind} {}", escape(&s.name.text));
        for a in &s.assocs {
            let _ = write!(out, " ({} {}", escape(&a.action.text), escape(&a.qualifier.text));
            if let Some((t, _)) = a.time {
                let _ = write!(out, " {t}s");
            }
            out.push(')');
        }
        out.push_str(")\n");
    }
    for t in &c.transitions {
        let _ = write!(out, "{pad}(transition \"{}\"", escape(&t.display_name()));
        if let Some(&(p, _)) = t.priority.as_deref() {
            let _ = write!(out, " (priority {p})");
        }
        let names = |v: &[crate::st::ast::Ident]| v.iter().map(|i| escape(&i.text)).collect::<Vec<_>>().join(" ");
        let _ = write!(out, " (from {}) (to {}) ", names(&t.from), names(&t.to));
        match &t.cond {
            Some(e) => out.push_str(&crate::st::pretty::expr(e)),
            None => out.push_str("(error)"),
        }
        out.push_str(")\n");
    }
}
