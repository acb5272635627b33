//! The ROC operators of a database (`"users"`, docs/roc-protocol.md): when
//! a database names any, a ROC Plus host must log in (opcode 17) before it
//! reads or writes.

use super::json::{code, DbError};
use super::tree::{Json, Node};

/// One operator: a three-character ID, a numeric password and the
/// highest access level it may ask for (0 reads only; 1–5 may write).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct RocUser {
    pub id: String,
    pub password: u16,
    pub level: u8,
}

/// The highest access level.
pub const MAX_LEVEL: u8 = 5;

/// `"users": {"LOI": {"password": 1000, "level": 5}, …}`.
pub(super) fn load(node: &Node) -> Result<Vec<RocUser>, DbError> {
    let bad = |message: String, span| DbError::at(code::USERS, message, span);
    let Json::Obj(members) = &node.v else {
        return Err(bad("`users` is an object of operator IDs".into(), node.span));
    };
    let mut users = Vec::new();
    for m in members {
        if m.key.is_empty() || m.key.len() > 3 || !m.key.bytes().all(|b| b.is_ascii_graphic()) {
            return Err(bad(format!("`{}` is not an operator ID: one to three letters or digits", m.key), m.key_span));
        }
        let Json::Obj(spec) = &m.value.v else {
            return Err(bad(format!("operator `{}` is an object with `password` and `level`", m.key), m.value.span));
        };
        let (mut password, mut level) = (None, None);
        for f in spec {
            match f.key.as_str() {
                "password" => {
                    password = Some(
                        f.value
                            .whole(0.0, 65535.0)
                            .ok_or_else(|| bad("a password is a whole number from 0 to 65535".into(), f.value.span))?
                            as u16,
                    )
                }
                "level" => {
                    level = Some(f.value.whole(0.0, f64::from(MAX_LEVEL)).ok_or_else(|| {
                        bad(format!("an access level is a whole number from 0 to {MAX_LEVEL}"), f.value.span)
                    })? as u8)
                }
                other => return Err(bad(format!("unknown key `{other}` (expected password, level)"), f.key_span)),
            }
        }
        let password = password.ok_or_else(|| bad(format!("operator `{}` has no `password`", m.key), m.key_span))?;
        users.push(RocUser { id: m.key.clone(), password, level: level.unwrap_or(MAX_LEVEL) });
    }
    Ok(users)
}

#[cfg(test)]
mod tests {
    use super::super::Database;
    use super::*;

    #[test]
    fn operators_load_and_mistakes_are_located() {
        let d = Database::from_json(r#"{"users": {"LOI": {"password": 1000, "level": 1}, "ENG": {"password": 7}}}"#)
            .unwrap();
        assert_eq!(
            d.users,
            vec![
                RocUser { id: "LOI".into(), password: 1000, level: 1 },
                RocUser { id: "ENG".into(), password: 7, level: 5 },
            ]
        );
        for (text, at) in [
            (r#"{"users": {"LONG": {"password": 1}}}"#, "\"LONG\""),
            (r#"{"users": {"LOI": {"password": 70000}}}"#, "70000"),
            (r#"{"users": {"LOI": {"password": 1, "level": 6}}}"#, "6"),
            (r#"{"users": {"LOI": {"level": 1}}}"#, "\"LOI\""),
            (r#"{"users": {"LOI": {"password": 1, "pin": 2}}}"#, "\"pin\""),
            (r#"{"users": []}"#, "[]"),
        ] {
            let e = Database::from_json(text).unwrap_err();
            assert_eq!(e.code, code::USERS, "{text}");
            let (s, _) = e.span.unwrap();
            assert!(text[s..].starts_with(at), "{text}: at {}", &text[s..]);
        }
    }
}
