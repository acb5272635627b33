//! Structured Text, the language every other one is lowered through: its
//! lexer ([`lexer`], [`token`]), the LALR grammar and the parser around it
//! ([`parser`], [`parse_support`], `depth_guard`), the syntax tree
//! ([`ast`]), the checks against a database (`check`) into the checked
//! program (`hir`), and the lowering to instructions ([`lower`]), which
//! sequences, ladder and FST tables use too.

pub mod ast;
pub(crate) mod check;
pub(crate) mod depth_guard;
pub(crate) mod errors;
pub(crate) mod hir;
pub mod lexer;
pub mod lower;
pub mod parse_support;
pub mod parser;
pub mod pretty;
pub(crate) mod split;
pub mod token;
