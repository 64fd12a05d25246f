//! A small owned TOML tree where every value and key carries its 1-based line/column,
//! built from `toml_edit`'s span-preserving document.

use std::ops::Range;
use toml_edit::{Item, Table, Value};

/// A 1-based position in the scene text.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Default)]
pub(crate) struct Pos {
    pub line: usize,
    pub column: usize,
}

impl Pos {
    /// The start of the file.
    pub const START: Pos = Pos { line: 1, column: 1 };
}

/// Converts byte offsets into line/column positions, each in time independent of the line's
/// length on ASCII lines and, on other lines, in time proportional to the distance from the
/// previous position asked for (values are visited in document order): reading stays linear
/// in the size of the text however long its lines.
pub(crate) struct LineIndex<'a> {
    text: &'a str,
    starts: Vec<usize>,
    /// Whether each line is pure ASCII (columns are then byte distances).
    ascii: Vec<bool>,
    /// The last non-ASCII position computed: (byte offset, its 0-based column).
    last: std::cell::Cell<(usize, usize)>,
}

impl<'a> LineIndex<'a> {
    pub fn new(text: &'a str) -> Self {
        let mut starts = vec![0];
        starts.extend(text.match_indices('\n').map(|(i, _)| i + 1));
        let ascii = (starts.iter().enumerate())
            .map(|(k, &start)| {
                let end = starts.get(k + 1).copied().unwrap_or(text.len());
                text.as_bytes()[start..end].is_ascii()
            })
            .collect();
        Self {
            text,
            starts,
            ascii,
            last: std::cell::Cell::new((0, 0)),
        }
    }

    /// Position of a byte offset (clamped to the text).
    pub fn pos(&self, offset: usize) -> Pos {
        let offset = offset.min(self.text.len());
        let line = match self.starts.binary_search(&offset) {
            Ok(i) => i,
            Err(i) => i.saturating_sub(1),
        };
        let start = self.starts.get(line).copied().unwrap_or(0).min(offset);
        let column = if self.ascii.get(line).copied().unwrap_or(false) {
            offset - start
        } else {
            let (last, last_column) = self.last.get();
            let (from, base) = if (start..=offset).contains(&last) {
                (last, last_column)
            } else {
                (start, 0)
            };
            let column =
                base + (self.text.get(from..offset)).map_or(offset - from, |s| s.chars().count());
            self.last.set((offset, column));
            column
        };
        Pos {
            line: line + 1,
            column: column + 1,
        }
    }

    /// Position of the start of a span, or `fallback` when there is none.
    pub fn span_pos(&self, span: Option<Range<usize>>, fallback: Pos) -> Pos {
        span.map_or(fallback, |r| self.pos(r.start))
    }
}

/// The kind and contents of a value.
#[derive(Debug, Clone)]
pub(crate) enum Kind {
    Str(String),
    Int(i64),
    Float(f64),
    Bool(bool),
    Datetime(String),
    Array(Vec<Node>),
    Table(Vec<Entry>),
}

/// A value with its position.
#[derive(Debug, Clone)]
pub(crate) struct Node {
    pub kind: Kind,
    pub pos: Pos,
}

/// A key/value pair of a table.
#[derive(Debug, Clone)]
pub(crate) struct Entry {
    pub key: String,
    pub key_pos: Pos,
    pub value: Node,
}

impl Node {
    /// A short description of the value for error messages, e.g. `string "abc"`.
    pub fn describe(&self) -> String {
        match &self.kind {
            Kind::Str(s) => {
                let short: String = s.chars().take(40).collect();
                if short.len() < s.len() {
                    format!("string {short:?}...")
                } else {
                    format!("string {s:?}")
                }
            }
            Kind::Int(i) => format!("integer {i}"),
            Kind::Float(f) => format!("float {f}"),
            Kind::Bool(b) => format!("boolean {b}"),
            Kind::Datetime(d) => format!("datetime {d}"),
            Kind::Array(a) => format!("an array of {} elements", a.len()),
            Kind::Table(_) => "a table".to_string(),
        }
    }
}

/// The root table of a parsed document.
pub(crate) fn root(table: &Table, idx: &LineIndex) -> Node {
    Node {
        kind: Kind::Table(table_entries(table, idx, Pos::START)),
        pos: Pos::START,
    }
}

fn table_entries(t: &Table, idx: &LineIndex, pos: Pos) -> Vec<Entry> {
    let mut out = Vec::new();
    for (k, item) in t.iter() {
        let key_pos = idx.span_pos(t.key(k).and_then(|k| k.span()), pos);
        if let Some(value) = from_item(item, idx, key_pos) {
            out.push(Entry {
                key: k.to_string(),
                key_pos,
                value,
            });
        }
    }
    out
}

fn from_item(item: &Item, idx: &LineIndex, fallback: Pos) -> Option<Node> {
    match item {
        Item::None => None,
        Item::Value(v) => Some(from_value(v, idx, fallback)),
        Item::Table(t) => {
            let pos = idx.span_pos(t.span(), fallback);
            Some(Node {
                kind: Kind::Table(table_entries(t, idx, pos)),
                pos,
            })
        }
        Item::ArrayOfTables(a) => {
            let pos = idx.span_pos(a.span(), fallback);
            let elems = a
                .iter()
                .map(|t| {
                    let tpos = idx.span_pos(t.span(), pos);
                    Node {
                        kind: Kind::Table(table_entries(t, idx, tpos)),
                        pos: tpos,
                    }
                })
                .collect();
            Some(Node {
                kind: Kind::Array(elems),
                pos,
            })
        }
    }
}

fn from_value(v: &Value, idx: &LineIndex, fallback: Pos) -> Node {
    let pos = idx.span_pos(v.span(), fallback);
    let kind = match v {
        Value::String(s) => Kind::Str(s.value().clone()),
        Value::Integer(i) => Kind::Int(*i.value()),
        Value::Float(f) => Kind::Float(*f.value()),
        Value::Boolean(b) => Kind::Bool(*b.value()),
        Value::Datetime(d) => Kind::Datetime(d.value().to_string()),
        Value::Array(a) => Kind::Array(a.iter().map(|e| from_value(e, idx, pos)).collect()),
        Value::InlineTable(t) => {
            let mut out = Vec::new();
            for (k, item) in t.iter() {
                let key_pos = idx.span_pos(t.key(k).and_then(|k| k.span()), pos);
                let value = from_value(item, idx, key_pos);
                out.push(Entry {
                    key: k.to_string(),
                    key_pos,
                    value,
                });
            }
            Kind::Table(out)
        }
    };
    Node { kind, pos }
}
