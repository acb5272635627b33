//! The JSON of the block browser: the blocks of the database, and one
//! block's fields with their values, forced and read-only flags.

use linc_runtime::Store;
use serde_json::{json, Value};

/// Every block: its name and type, in database order.
pub fn blocks(store: &Store) -> Value {
    let list: Vec<Value> =
        store.db.blocks.iter().map(|b| json!({"name": b.name, "type": store.db.templates[b.template].name})).collect();
    Value::Array(list)
}

/// One block's fields, or `None` if the database has no such block.
pub fn block(store: &Store, name: &str) -> Option<Value> {
    let b = store.db.block(name)?;
    let block = &store.db.blocks[b];
    let template = &store.db.templates[block.template];
    let first = store.first[b];
    let fields: Vec<Value> = template
        .fields
        .iter()
        .enumerate()
        .map(|(i, f)| {
            let cell = first + i as u32;
            json!({"name": f.name, "value": store.show(cell), "forced": store.is_forced(cell),
                   "readonly": store.is_readonly(cell)})
        })
        .collect();
    Some(json!({"name": block.name, "type": template.name, "fields": fields}))
}
