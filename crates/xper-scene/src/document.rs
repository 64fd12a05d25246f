//! TOML text to the positioned tree of [`crate::tree`], in time and memory linear in the text.
//!
//! The text is lexed by `toml_parser` (the lexer and event parser of the `toml` crates) and
//! parsed in runs of whole top-level statements, so that only one run's tokens are held at a
//! time; this module assembles the parser's events into tables by the rules of TOML
//! (<https://toml.io/en/v1.1.0>, a superset of 1.0): headers `[a.b]` and `[[a.b]]`, dotted keys,
//! inline tables and arrays, every key defined once, a table defined once, dotted keys never
//! extending a table that a header defined. No intermediate document is built: a 50 MB scene
//! of disks is read into the tree with about a third of the memory a span-preserving document
//! needs (BENCHMARKS.md, "Reading scenes").

use crate::tree::{Entry, Kind, LineIndex, Node, Pos};
use std::borrow::Cow;
use std::collections::HashMap;
use toml_parser::decoder::{Encoding, ScalarKind};
use toml_parser::lexer::{Token, TokenKind};
use toml_parser::parser::{EventReceiver, RecursionGuard, ValidateWhitespace};
use toml_parser::{ErrorSink, Expected, ParseError, Raw, Source, Span};

/// The first error of a document: its byte offset and what is wrong.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct SyntaxError {
    pub offset: usize,
    pub message: String,
}

/// Tokens gathered before the statements they complete are parsed (the memory a run holds).
const RUN_TOKENS: usize = 1 << 16;
/// Nesting of arrays and inline tables beyond which a document is refused.
const MAX_DEPTH: u32 = 64;
/// Entries from which a table keeps a hash index of its keys (linear search below).
const INDEXED_FROM: usize = 16;

/// Parses `text` into the tree of its root table; `idx` gives positions.
pub(crate) fn parse(text: &str, idx: &LineIndex) -> Result<Node, SyntaxError> {
    parse_in_runs(text, idx, RUN_TOKENS)
}

/// [`parse`] with the token count of a run as a parameter (tests cut runs short on purpose).
pub(crate) fn parse_in_runs(
    text: &str,
    idx: &LineIndex,
    run_tokens: usize,
) -> Result<Node, SyntaxError> {
    let source = Source::new(text);
    let mut builder = Builder::new(source, idx);
    let mut tokens: Vec<Token> = Vec::new();
    let mut depth = 0usize;
    // tokens[..cut] end with a newline outside any bracket: a whole number of statements.
    let mut cut = 0;
    for token in source.lex() {
        match token.kind() {
            TokenKind::LeftSquareBracket | TokenKind::LeftCurlyBracket => depth += 1,
            TokenKind::RightSquareBracket | TokenKind::RightCurlyBracket => {
                depth = depth.saturating_sub(1)
            }
            TokenKind::Newline if depth == 0 => cut = tokens.len() + 1,
            _ => {}
        }
        tokens.push(token);
        if tokens.len() >= run_tokens && cut > 0 {
            builder.feed(&tokens[..cut])?;
            tokens.drain(..cut);
            cut = 0;
        }
    }
    builder.feed(&tokens)?;
    builder.finish()
}

/// A key as read: its name, position and byte offset.
struct Key {
    name: String,
    pos: Pos,
    offset: usize,
}

/// How a table came to exist, which decides what may later add to it.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Origin {
    /// As a parent of a header's table (`a` of `[a.b]`): a header may still define it.
    Implicit,
    /// By its own header.
    Header,
    /// By a dotted key (`a` of `a.b = 1`): only dotted keys of its section extend it.
    Dotted,
}

/// A table being built.
struct Table {
    entries: Vec<Slot>,
    /// Boxed: most tables have a few keys and no index, and a table is in every slot.
    #[allow(clippy::box_collection)]
    index: Option<Box<HashMap<String, usize>>>,
    pos: Pos,
    origin: Origin,
}

struct Slot {
    key: String,
    key_pos: Pos,
    item: Item,
}

enum Item {
    /// A value: scalar, array or inline table (closed to every later addition).
    Value(Node),
    Table(Table),
    /// An array of tables (`[[a]]`), with the position of its first header.
    Tables(Vec<Table>, Pos),
}

impl Table {
    fn new(pos: Pos, origin: Origin) -> Self {
        Self {
            entries: Vec::new(),
            index: None,
            pos,
            origin,
        }
    }

    fn find(&self, key: &str) -> Option<usize> {
        match &self.index {
            Some(index) => index.get(key).copied(),
            None => self.entries.iter().position(|s| s.key == key),
        }
    }

    fn push(&mut self, key: &Key, item: Item) -> usize {
        let at = self.entries.len();
        if let Some(index) = &mut self.index {
            index.insert(key.name.clone(), at);
        }
        self.entries.push(Slot {
            key: key.name.clone(),
            key_pos: key.pos,
            item,
        });
        if self.index.is_none() && self.entries.len() >= INDEXED_FROM {
            let index = (self.entries.iter().enumerate())
                .map(|(i, s)| (s.key.clone(), i))
                .collect();
            self.index = Some(Box::new(index));
        }
        at
    }

    /// Adds `value` at the dotted key `keys` (TOML: dotted keys create or extend tables that
    /// dotted keys created, never others; each key is defined once).
    fn insert(&mut self, keys: &[Key], value: Node) -> Result<(), SyntaxError> {
        let Some((last, path)) = keys.split_last() else {
            return Err(SyntaxError {
                offset: 0,
                message: "a value without a key".into(),
            });
        };
        let mut table = self;
        for (k, key) in path.iter().enumerate() {
            let at = match table.find(&key.name) {
                Some(at) => at,
                None => table.push(key, Item::Table(Table::new(key.pos, Origin::Dotted))),
            };
            table = match &mut table.entries[at].item {
                Item::Table(sub) if sub.origin == Origin::Dotted => sub,
                _ => {
                    return Err(error(
                        key,
                        format!(
                            "`{}` is already defined: a dotted key cannot add to it",
                            dotted(&keys[..=k])
                        ),
                    ))
                }
            };
        }
        if table.find(&last.name).is_some() {
            return Err(error(last, format!("duplicate key `{}`", dotted(keys))));
        }
        table.push(last, Item::Value(value));
        Ok(())
    }

    /// The table a header's key path names (the last table of an array of tables), creating
    /// implicit parents; an error when the path goes through a value.
    fn descend<'t>(&'t mut self, path: &[Key]) -> Result<&'t mut Table, SyntaxError> {
        let mut table = self;
        for (k, key) in path.iter().enumerate() {
            let at = match table.find(&key.name) {
                Some(at) => at,
                None => table.push(key, Item::Table(Table::new(key.pos, Origin::Implicit))),
            };
            table = match &mut table.entries[at].item {
                Item::Table(sub) => sub,
                Item::Tables(list, _) => match list.last_mut() {
                    Some(sub) => sub,
                    None => return Err(error(key, "an empty array of tables".into())),
                },
                Item::Value(_) => {
                    return Err(error(
                        key,
                        format!("`{}` is a value, not a table", dotted(&path[..=k])),
                    ))
                }
            };
        }
        Ok(table)
    }

    /// Defines the table `[keys]` (or appends one to `[[keys]]` when `array`) at `pos`.
    fn define(&mut self, keys: &[Key], array: bool, pos: Pos) -> Result<(), SyntaxError> {
        let Some((last, path)) = keys.split_last() else {
            return Err(SyntaxError {
                offset: 0,
                message: "a table header without a name".into(),
            });
        };
        let table = self.descend(path)?;
        let Some(at) = table.find(&last.name) else {
            let item = if array {
                Item::Tables(vec![Table::new(pos, Origin::Header)], pos)
            } else {
                Item::Table(Table::new(pos, Origin::Header))
            };
            table.push(last, item);
            return Ok(());
        };
        match (&mut table.entries[at].item, array) {
            (Item::Table(sub), false) if sub.origin == Origin::Implicit => {
                sub.origin = Origin::Header;
                sub.pos = pos;
                Ok(())
            }
            (Item::Tables(list, _), true) => {
                list.push(Table::new(pos, Origin::Header));
                Ok(())
            }
            (Item::Tables(..), false) => Err(error(
                last,
                format!("`{}` is an array of tables: `[[{0}]]`", dotted(keys)),
            )),
            (_, true) => Err(error(
                last,
                format!(
                    "`{}` is already defined, not as an array of tables",
                    dotted(keys)
                ),
            )),
            (_, false) => Err(error(
                last,
                format!("table `{}` is defined twice", dotted(keys)),
            )),
        }
    }

    /// The final tree of this table, in the order its keys were defined.
    fn into_node(self) -> Node {
        // Collected into a new vector of the exact length: collecting in place would keep the
        // larger allocation of the slots (twice the memory for a scene of many bodies).
        let mut entries = Vec::with_capacity(self.entries.len());
        entries.extend(self.entries.into_iter().map(|slot| Entry {
            key: slot.key,
            key_pos: slot.key_pos,
            value: match slot.item {
                Item::Value(node) => node,
                Item::Table(table) => table.into_node(),
                Item::Tables(list, pos) => Node {
                    kind: Kind::Array(list.into_iter().map(Table::into_node).collect()),
                    pos,
                },
            },
        }));
        Node {
            kind: Kind::Table(entries),
            pos: self.pos,
        }
    }
}

fn dotted(keys: &[Key]) -> String {
    let names: Vec<&str> = keys.iter().map(|k| k.name.as_str()).collect();
    names.join(".")
}

fn error(key: &Key, message: String) -> SyntaxError {
    SyntaxError {
        offset: key.offset,
        message,
    }
}

/// An array or inline table whose closing bracket has not been read yet.
enum Open {
    Array { pos: Pos, items: Vec<Node> },
    Inline { table: Table, keys: Vec<Key> },
}

/// Receives the parser's events and builds the document.
struct Builder<'s, 'i> {
    source: Source<'s>,
    idx: &'i LineIndex<'s>,
    root: Table,
    /// Key path of the current `[header]` (empty: the root table).
    section: Vec<Key>,
    /// Keys read since the last `=`, header bracket or value.
    keys: Vec<Key>,
    /// Keys of the top-level key/value pair whose value is being read.
    pending: Vec<Key>,
    /// Position of the header being read.
    header: Pos,
    open: Vec<Open>,
    error: Option<SyntaxError>,
}

impl<'s, 'i> Builder<'s, 'i> {
    fn new(source: Source<'s>, idx: &'i LineIndex<'s>) -> Self {
        Self {
            source,
            idx,
            root: Table::new(Pos::START, Origin::Header),
            section: Vec::new(),
            keys: Vec::new(),
            pending: Vec::new(),
            header: Pos::START,
            open: Vec::new(),
            error: None,
        }
    }

    /// Parses a run of whole statements; the earliest error of the document so far, if any.
    fn feed(&mut self, tokens: &[Token]) -> Result<(), SyntaxError> {
        let mut parse_errors: Vec<ParseError> = Vec::new();
        let source = self.source;
        {
            let mut valid = ValidateWhitespace::new(self, source);
            let mut guard = RecursionGuard::new(&mut valid, MAX_DEPTH);
            toml_parser::parser::parse_document(tokens, &mut guard, &mut parse_errors);
        }
        let parse_error = parse_errors.first().map(describe);
        match (parse_error, self.error.take()) {
            (None, None) => Ok(()),
            (Some(e), None) | (None, Some(e)) => Err(e),
            (Some(a), Some(b)) => Err(if b.offset < a.offset { b } else { a }),
        }
    }

    fn finish(self) -> Result<Node, SyntaxError> {
        if !self.open.is_empty() {
            return Err(SyntaxError {
                offset: self.source.input().len(),
                message: "unclosed array or inline table".into(),
            });
        }
        Ok(self.root.into_node())
    }

    fn fail(&mut self, e: SyntaxError) {
        if self.error.is_none() {
            self.error = Some(e);
        }
    }

    fn raw(&self, span: Span, encoding: Option<Encoding>) -> Raw<'s> {
        let text = self
            .source
            .input()
            .get(span.start()..span.end())
            .unwrap_or("");
        Raw::new_unchecked(text, encoding, span)
    }

    /// A value is complete: it goes into the array or inline table being read, or into the
    /// current section at the pending key.
    fn value(&mut self, node: Node) {
        let done = match self.open.last_mut() {
            Some(Open::Array { items, .. }) => {
                items.push(node);
                Ok(())
            }
            Some(Open::Inline { table, keys }) => {
                let keys = std::mem::take(keys);
                table.insert(&keys, node)
            }
            None => {
                let pending = std::mem::take(&mut self.pending);
                self.root
                    .descend(&self.section)
                    .and_then(|table| table.insert(&pending, node))
            }
        };
        if let Err(e) = done {
            self.fail(e);
        }
    }

    fn header_close(&mut self, array: bool) {
        let keys = std::mem::take(&mut self.keys);
        let done = self.root.define(&keys, array, self.header);
        match done {
            Ok(()) => self.section = keys,
            Err(e) => self.fail(e),
        }
    }
}

/// A parser error as offset and message (`what: expected x, y`).
fn describe(e: &ParseError) -> SyntaxError {
    let offset = e
        .unexpected()
        .or(e.context())
        .map_or(0, |span| span.start());
    let mut message = e.description().to_string();
    if let Some(expected) = e.expected().filter(|x| !x.is_empty()) {
        let names: Vec<String> = (expected.iter())
            .map(|x| match x {
                Expected::Literal(s) => format!("`{s}`"),
                Expected::Description(s) => s.to_string(),
                _ => String::new(),
            })
            .collect();
        message = format!("{message}, expected {}", names.join(", "));
    }
    SyntaxError { offset, message }
}

impl EventReceiver for Builder<'_, '_> {
    fn std_table_open(&mut self, span: Span, _error: &mut dyn ErrorSink) {
        self.keys.clear();
        self.header = self.idx.pos(span.start());
    }
    fn std_table_close(&mut self, _span: Span, _error: &mut dyn ErrorSink) {
        self.header_close(false);
    }
    fn array_table_open(&mut self, span: Span, _error: &mut dyn ErrorSink) {
        self.keys.clear();
        self.header = self.idx.pos(span.start());
    }
    fn array_table_close(&mut self, _span: Span, _error: &mut dyn ErrorSink) {
        self.header_close(true);
    }
    fn inline_table_open(&mut self, span: Span, _error: &mut dyn ErrorSink) -> bool {
        let pos = self.idx.pos(span.start());
        self.open.push(Open::Inline {
            table: Table::new(pos, Origin::Dotted),
            keys: Vec::new(),
        });
        true
    }
    fn inline_table_close(&mut self, _span: Span, _error: &mut dyn ErrorSink) {
        if let Some(Open::Inline { table, .. }) = self.open.pop() {
            self.value(table.into_node());
        }
    }
    fn array_open(&mut self, span: Span, _error: &mut dyn ErrorSink) -> bool {
        let pos = self.idx.pos(span.start());
        self.open.push(Open::Array {
            pos,
            items: Vec::new(),
        });
        true
    }
    fn array_close(&mut self, _span: Span, _error: &mut dyn ErrorSink) {
        if let Some(Open::Array { pos, items }) = self.open.pop() {
            self.value(Node {
                kind: Kind::Array(items),
                pos,
            });
        }
    }
    fn simple_key(&mut self, span: Span, encoding: Option<Encoding>, error: &mut dyn ErrorSink) {
        let mut name = Cow::Borrowed("");
        self.raw(span, encoding).decode_key(&mut name, error);
        self.keys.push(Key {
            name: name.into_owned(),
            pos: self.idx.pos(span.start()),
            offset: span.start(),
        });
    }
    fn key_val_sep(&mut self, _span: Span, _error: &mut dyn ErrorSink) {
        let keys = std::mem::take(&mut self.keys);
        match self.open.last_mut() {
            Some(Open::Inline { keys: pending, .. }) => *pending = keys,
            _ => self.pending = keys,
        }
    }
    fn scalar(&mut self, span: Span, encoding: Option<Encoding>, error: &mut dyn ErrorSink) {
        let mut text = Cow::Borrowed("");
        let kind = self.raw(span, encoding).decode_scalar(&mut text, error);
        let kind = match kind {
            ScalarKind::String => Kind::Str(text.into_owned()),
            ScalarKind::Boolean(b) => Kind::Bool(b),
            ScalarKind::DateTime => match text.parse::<toml_datetime::Datetime>() {
                Ok(d) => Kind::Datetime(d.to_string()),
                Err(e) => {
                    self.fail(SyntaxError {
                        offset: span.start(),
                        message: format!("an invalid date-time: {e}"),
                    });
                    Kind::Datetime(text.into_owned())
                }
            },
            ScalarKind::Float => match text.parse::<f64>() {
                Ok(f) if f.is_finite() || text.contains("inf") || text.contains("nan") => {
                    Kind::Float(f)
                }
                _ => {
                    self.fail(SyntaxError {
                        offset: span.start(),
                        message: "a float too large for 64 bits".into(),
                    });
                    Kind::Float(0.0)
                }
            },
            ScalarKind::Integer(radix) => match i64::from_str_radix(&text, radix.value()) {
                Ok(i) => Kind::Int(i),
                Err(_) => {
                    self.fail(SyntaxError {
                        offset: span.start(),
                        message: "an integer out of the 64-bit range".into(),
                    });
                    Kind::Int(0)
                }
            },
        };
        let pos = self.idx.pos(span.start());
        self.value(Node { kind, pos });
    }
}

#[cfg(test)]
#[path = "document_tests.rs"]
mod tests;
