//! Fields named as people type them (`PIC1.PV`, `REC1.Bits.Bit3`, an
//! alias, a ROC point `AIN 2-1.EU`), their values as text and new values
//! parsed by the field's type. Shared by `linc run --set/--show` and the
//! console, so both read and write values the same way.

use crate::store::{Cell, Store};
use linc_stdlib::value::decode_dollar;

/// A cell and maybe a bit of it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Addr {
    pub cell: u32,
    pub bit: Option<u8>,
}

/// Resolves `BLOCK.FIELD[.BitN]` (or an alias) against the store. A block
/// name may hold spaces (`AIN 2-1.EU`).
pub fn address(store: &Store, path: &str) -> Result<Addr, String> {
    let (block, field, bit) = store.db.field_path(path)?;
    Ok(Addr { cell: store.first[block] + field as u32, bit })
}

/// A field's (or bit's) value as `linc run --show` prints it.
pub fn show_value(store: &Store, a: Addr) -> String {
    match (a.bit, store.cells.get(a.cell as usize)) {
        (Some(b), Some(Cell::Bits { v, .. })) => if (v >> b) & 1 == 1 { "TRUE" } else { "FALSE" }.to_string(),
        _ => store.show(a.cell),
    }
}

fn unquote(s: &str) -> &str {
    let b = s.as_bytes();
    if b.len() >= 2 && (b[0] == b'\'' || b[0] == b'"') && b[b.len() - 1] == b[0] {
        &s[1..s.len() - 1]
    } else {
        s
    }
}

fn truth(v: &str) -> Result<bool, String> {
    match v.to_ascii_uppercase().as_str() {
        "TRUE" | "1" => Ok(true),
        "FALSE" | "0" => Ok(false),
        _ => Err(format!("`{v}` is not TRUE or FALSE")),
    }
}

/// A whole number in `lo..=hi`, refused (not wrapped or clamped) outside
/// it, with the range the database loader states for the field type.
fn whole(v: &str, (lo, hi): (i64, i64), ty: &str) -> Result<i64, String> {
    let x = v.parse::<i64>().map_err(|_| format!("`{v}` is not an integer"))?;
    if (lo..=hi).contains(&x) {
        Ok(x)
    } else {
        Err(format!("{x} does not fit a {ty} field (expected a whole number from {lo} to {hi})"))
    }
}

/// A text for a string field, at most as long as the VM lets a string be.
fn text(bytes: Vec<u8>) -> Result<Vec<u8>, String> {
    if bytes.len() > crate::vm::MAX_STRING {
        return Err(format!(
            "the text is {} bytes long; a string field holds at most {} bytes",
            bytes.len(),
            crate::vm::MAX_STRING
        ));
    }
    Ok(bytes)
}

/// The cell `value` makes of the cell at `a`, parsed by the field's type
/// (a bit changes only that bit); the store is not changed.
pub fn parse_value(store: &Store, a: Addr, value: &str) -> Result<Cell, String> {
    let value = value.trim();
    let names = store.enum_names(a.cell);
    let cell = store.cells.get(a.cell as usize).ok_or("no such cell")?;
    Ok(match (cell, a.bit) {
        (Cell::Bits { v, width }, Some(b)) => {
            let v = if truth(value)? { *v | 1 << b } else { *v & !(1 << b) };
            Cell::Bits { v, width: *width }
        }
        (Cell::Real(_), _) => {
            let x: f32 = value.parse().map_err(|_| format!("`{value}` is not a number"))?;
            if !x.is_finite() {
                return Err(format!("`{value}` is not a finite number"));
            }
            Cell::Real(x)
        }
        (Cell::Int(_), _) => Cell::Int(whole(value, (i32::MIN.into(), i32::MAX.into()), "INT")? as i32),
        (Cell::Bool(_), _) => Cell::Bool(truth(value)?),
        (Cell::Bits { width, .. }, None) => {
            let (range, ty) = if *width == 8 { ((0, 255), "BITS8") } else { ((-32_768, 65_535), "BITS16") };
            Cell::Bits { v: whole(value, range, ty)? as u16, width: *width }
        }
        (Cell::Enum { .. }, _) => {
            let text = unquote(value);
            let i = names
                .iter()
                .position(|n| n.eq_ignore_ascii_case(text))
                .ok_or_else(|| format!("`{text}` is not one of {}", names.join(", ")))?;
            Cell::Enum { idx: i as u16 }
        }
        (Cell::Text(_), _) => Cell::Text(text(unquote(value).as_bytes().to_vec())?),
        (Cell::Bseq(_), _) => Cell::Bseq(text(decode_dollar(unquote(value).as_bytes()))?),
        (Cell::Wstr(_), _) => Cell::Wstr(text(decode_dollar(unquote(value).as_bytes()))?),
        (Cell::Alarms(_), _) => return Err("alarm states can't be set with --set".into()),
    })
}

/// Applies `BLOCK.FIELD=VALUE` (`--set`): refused, as by the console's
/// `M`, for a field the block computes or a value the field can't hold.
pub fn set(store: &mut Store, assignment: &str) -> Result<(), String> {
    let (path, value) = assignment.split_once('=').ok_or_else(|| format!("`{assignment}` is not BLOCK.FIELD=VALUE"))?;
    let a = address(store, path.trim())?;
    if store.is_readonly(a.cell) {
        return Err(format!("{} is read-only: the block computes it", store.describe(a.cell)));
    }
    let new = parse_value(store, a, value)?;
    if let Some(slot) = store.cells.get_mut(a.cell as usize) {
        *slot = new;
    }
    Ok(())
}

/// `BLOCK.Field` of a cell and its value, from that field on: up to `n`
/// fields of its block in offset order (`D REC1.A0-`).
pub fn range(store: &Store, a: Addr, n: usize) -> Vec<(String, String)> {
    let b = store.first.partition_point(|&f| f <= a.cell).saturating_sub(1);
    let count = store.db.blocks.get(b).map_or(0, |_| store.db.block_template(b).fields.len() as u32);
    let end = store.first.get(b).copied().unwrap_or(0) + count;
    (a.cell..end.min(a.cell.saturating_add(n as u32)))
        .map(|c| (store.describe(c), show_value(store, Addr { cell: c, bit: None })))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn store() -> Store {
        let db = crate::Database::from_json(
            r#"{"device": "ROC800", "blocks": {"PIC1": {"type": "PID", "values": {"PV": 42.5}}, "AIN 2-1": {"type": "AIN"}},
                "aliases": {"Level": "AIN 2-1.EU"}}"#,
        );
        Store::new(db.expect("database"))
    }

    #[test]
    fn names_with_spaces_and_aliases_resolve_to_the_same_cell() {
        let s = store();
        let a = address(&s, "AIN 2-1.EU").expect("point");
        assert_eq!(address(&s, "Level").expect("alias"), a);
        assert_eq!(address(&s, "PIC1.PV").map(|a| show_value(&s, a)).as_deref(), Ok("42.5"));
        assert!(address(&s, "PIC1.Nope").is_err());
        assert!(address(&s, "PIC1").is_err());
    }

    #[test]
    fn values_are_parsed_by_the_field_type() {
        let s = store();
        let pv = address(&s, "PIC1.PV").expect("pv");
        assert_eq!(parse_value(&s, pv, "5"), Ok(Cell::Real(5.0)));
        assert!(parse_value(&s, pv, "abc").is_err());
        assert!(parse_value(&s, pv, "inf").is_err());
    }

    #[test]
    fn values_a_field_cannot_hold_are_refused_not_wrapped() {
        let db = crate::Database::from_json(
            r#"{"templates": {"T": {"fields": {"B": "BITS8", "W": "BITS16", "N": "INT", "S": "STRING"}}},
                "blocks": {"X": {"type": "T"}}}"#,
        );
        let mut s = Store::new(db.expect("database"));
        let at = |s: &Store, f: &str| address(s, f).expect(f);
        let b = at(&s, "X.B");
        assert_eq!(parse_value(&s, b, "255"), Ok(Cell::Bits { v: 255, width: 8 }));
        let e = parse_value(&s, b, "256").expect_err("BITS8 256");
        assert!(e.contains("does not fit a BITS8 field (expected a whole number from 0 to 255)"), "{e}");
        assert!(parse_value(&s, b, "-1").is_err());
        assert!(parse_value(&s, at(&s, "X.W"), "65536").is_err());
        assert_eq!(parse_value(&s, at(&s, "X.W"), "65535"), Ok(Cell::Bits { v: 65535, width: 16 }));
        assert!(parse_value(&s, at(&s, "X.N"), "2147483648").is_err(), "INT is not clamped");
        let long = "a".repeat(crate::vm::MAX_STRING + 1);
        assert!(parse_value(&s, at(&s, "X.S"), &long).expect_err("long").contains("at most 65535 bytes"));
        assert!(set(&mut s, &format!("X.S={}", "a".repeat(crate::vm::MAX_STRING))).is_ok());
        assert!(set(&mut s, "X.B=256").is_err());
        assert_eq!(show_value(&s, b), "0", "a refused --set changes nothing");
    }
}
