//! A small owned TOML tree where every value and key carries its 1-based line/column, built
//! by [`crate::document`].

/// A 1-based position in the scene text (32 bits each: every value of the tree carries one;
/// beyond 2^32 - 1 lines or columns the figure saturates).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Default)]
pub(crate) struct Pos {
    pub line: u32,
    pub column: u32,
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
    /// The line of the last position asked for: the next one is usually on it or the next.
    line: std::cell::Cell<usize>,
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
            line: std::cell::Cell::new(0),
        }
    }

    /// Position of a byte offset (clamped to the text).
    pub fn pos(&self, offset: usize) -> Pos {
        let offset = offset.min(self.text.len());
        let on = |line: usize| {
            self.starts.get(line).is_some_and(|&s| s <= offset)
                && self.starts.get(line + 1).is_none_or(|&next| offset < next)
        };
        let hint = self.line.get();
        let line = if on(hint) {
            hint
        } else if on(hint + 1) {
            hint + 1
        } else {
            match self.starts.binary_search(&offset) {
                Ok(i) => i,
                Err(i) => i.saturating_sub(1),
            }
        };
        self.line.set(line);
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
        let narrow = |n: usize| u32::try_from(n + 1).unwrap_or(u32::MAX);
        Pos {
            line: narrow(line),
            column: narrow(column),
        }
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
