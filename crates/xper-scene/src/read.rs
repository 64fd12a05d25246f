//! Typed, error-collecting access to the positioned TOML tree.

use std::path::Path;

use crate::error::SceneError;
use crate::tree::{Entry, Kind, Node, Pos};

/// Collects errors for one file.
pub(crate) struct Ctx<'f> {
    pub file: &'f Path,
    pub errors: Vec<SceneError>,
}

impl<'f> Ctx<'f> {
    pub fn new(file: &'f Path) -> Self {
        Self {
            file,
            errors: Vec::new(),
        }
    }

    /// Records an error.
    pub fn err(&mut self, pos: Pos, field: &str, message: impl Into<String>) {
        self.errors.push(SceneError {
            file: self.file.to_path_buf(),
            line: pos.line as usize,
            column: pos.column as usize,
            field: field.to_string(),
            message: message.into(),
        });
    }

    /// Records a type error.
    pub fn expected(&mut self, node: &Node, field: &str, what: &str) {
        self.err(
            node.pos,
            field,
            format!("expected {what}, found {}", node.describe()),
        );
    }
}

/// The result of looking a key up: absent, present but invalid (already reported), or valid.
pub(crate) enum Got<T> {
    Absent,
    Bad,
    Val(T, Pos),
}

impl<T> Got<T> {
    /// The value and its position, if valid.
    pub fn ok(self) -> Option<(T, Pos)> {
        match self {
            Got::Val(v, p) => Some((v, p)),
            _ => None,
        }
    }

    /// The value, if valid.
    pub fn val(self) -> Option<T> {
        self.ok().map(|(v, _)| v)
    }

    /// Whether the key is absent.
    pub fn is_absent(&self) -> bool {
        matches!(self, Got::Absent)
    }

    /// The value; reports a missing-key error (at the table) when absent.
    pub fn req(self, ctx: &mut Ctx, t: &Tbl, key: &str) -> Option<(T, Pos)> {
        if self.is_absent() {
            t.missing(ctx, key);
        }
        self.ok()
    }

    /// The value, `default` when absent, `None` when invalid.
    pub fn or(self, default: T) -> Option<T> {
        match self {
            Got::Absent => Some(default),
            Got::Bad => None,
            Got::Val(v, _) => Some(v),
        }
    }
}

/// A table of the tree with its field path.
#[derive(Clone)]
pub(crate) struct Tbl<'a> {
    pub entries: &'a [Entry],
    pub pos: Pos,
    pub path: String,
}

impl<'a> Tbl<'a> {
    /// Views `node` as a table, reporting a type error otherwise.
    pub fn of(ctx: &mut Ctx, node: &'a Node, path: String) -> Option<Self> {
        match &node.kind {
            Kind::Table(entries) => Some(Self {
                entries,
                pos: node.pos,
                path,
            }),
            _ => {
                ctx.expected(node, &path, "a table");
                None
            }
        }
    }

    /// The path of one of this table's fields.
    pub fn field(&self, key: &str) -> String {
        if self.path.is_empty() {
            key.to_string()
        } else {
            format!("{}.{}", self.path, key)
        }
    }

    /// The raw value of a key.
    pub fn get(&self, key: &str) -> Option<&'a Node> {
        self.entries.iter().find(|e| e.key == key).map(|e| &e.value)
    }

    /// Whether the key is present.
    pub fn has(&self, key: &str) -> bool {
        self.get(key).is_some()
    }

    /// Reports every key not in `known`.
    pub fn check_keys(&self, ctx: &mut Ctx, known: &[&str]) {
        for e in self.entries {
            if !known.contains(&e.key.as_str()) {
                ctx.err(
                    e.key_pos,
                    &self.field(&e.key),
                    format!("unknown key `{}` (known: {})", e.key, known.join(", ")),
                );
            }
        }
    }

    /// Reports that a required key is missing (at the table's position).
    pub fn missing(&self, ctx: &mut Ctx, key: &str) {
        ctx.err(
            self.pos,
            &self.field(key),
            format!("missing required key `{key}`"),
        );
    }

    /// Reports that `key` is present although it must not be (`why` explains).
    pub fn forbid(&self, ctx: &mut Ctx, key: &str, why: &str) {
        if let Some(n) = self.get(key) {
            ctx.err(n.pos, &self.field(key), why.to_string());
        }
    }

    fn typed<T>(&self, key: &str, f: impl FnOnce(&'a Node) -> Option<T>) -> Got<T> {
        match self.get(key) {
            None => Got::Absent,
            Some(n) => match f(n) {
                Some(v) => Got::Val(v, n.pos),
                None => Got::Bad,
            },
        }
    }

    /// A finite number (integer or float).
    pub fn num(&self, ctx: &mut Ctx, key: &str) -> Got<f64> {
        let field = self.field(key);
        self.typed(key, |n| as_num(ctx, n, &field))
    }

    /// An integer.
    pub fn int(&self, ctx: &mut Ctx, key: &str) -> Got<i64> {
        let field = self.field(key);
        self.typed(key, |n| match n.kind {
            Kind::Int(i) => Some(i),
            _ => {
                ctx.expected(n, &field, "an integer");
                None
            }
        })
    }

    /// A string.
    pub fn string(&self, ctx: &mut Ctx, key: &str) -> Got<&'a str> {
        let field = self.field(key);
        self.typed(key, |n| match &n.kind {
            Kind::Str(s) => Some(s.as_str()),
            _ => {
                ctx.expected(n, &field, "a string");
                None
            }
        })
    }

    /// A boolean.
    pub fn boolean(&self, ctx: &mut Ctx, key: &str) -> Got<bool> {
        let field = self.field(key);
        self.typed(key, |n| match n.kind {
            Kind::Bool(b) => Some(b),
            _ => {
                ctx.expected(n, &field, "a boolean");
                None
            }
        })
    }

    /// A pair of finite numbers `[a, b]`.
    pub fn vec2(&self, ctx: &mut Ctx, key: &str) -> Got<[f64; 2]> {
        let field = self.field(key);
        self.typed(key, |n| as_vec2(ctx, n, &field))
    }

    /// A triple of finite numbers `[a, b, c]`.
    pub fn vec3(&self, ctx: &mut Ctx, key: &str) -> Got<[f64; 3]> {
        let field = self.field(key);
        self.typed(key, |n| as_vec3(ctx, n, &field))
    }

    /// `D` (2 or 3) finite numbers.
    pub fn vector<const D: usize>(&self, ctx: &mut Ctx, key: &str) -> Got<[f64; D]> {
        let field = self.field(key);
        self.typed(key, |n| as_vector(ctx, n, &field))
    }

    /// A sub-table.
    pub fn table(&self, ctx: &mut Ctx, key: &str) -> Got<Tbl<'a>> {
        let field = self.field(key);
        self.typed(key, |n| Tbl::of(ctx, n, field))
    }

    /// An array of tables (`[[key]]`), each with its index; absent -> empty.
    pub fn tables(&self, ctx: &mut Ctx, key: &str) -> Vec<(usize, Tbl<'a>)> {
        let Some(n) = self.get(key) else {
            return Vec::new();
        };
        let Kind::Array(elems) = &n.kind else {
            ctx.expected(n, &self.field(key), "an array of tables");
            return Vec::new();
        };
        elems
            .iter()
            .enumerate()
            .filter_map(|(i, e)| {
                Tbl::of(ctx, e, format!("{}[{i}]", self.field(key))).map(|t| (i, t))
            })
            .collect()
    }
}

/// A finite number (integers are converted).
pub(crate) fn as_num(ctx: &mut Ctx, n: &Node, field: &str) -> Option<f64> {
    let v = match n.kind {
        Kind::Int(i) => i as f64,
        Kind::Float(f) => f,
        _ => {
            ctx.expected(n, field, "a number");
            return None;
        }
    };
    if v.is_finite() {
        Some(v)
    } else {
        ctx.err(n.pos, field, format!("must be finite, got {v}"));
        None
    }
}

/// A pair of finite numbers.
pub(crate) fn as_vec2(ctx: &mut Ctx, n: &Node, field: &str) -> Option<[f64; 2]> {
    as_vector(ctx, n, field)
}

/// A triple of finite numbers `[x, y, z]`.
pub(crate) fn as_vec3(ctx: &mut Ctx, n: &Node, field: &str) -> Option<[f64; 3]> {
    as_vector(ctx, n, field)
}

/// `D` (2 or 3) finite numbers `[x, y]` or `[x, y, z]`; every element is checked.
pub(crate) fn as_vector<const D: usize>(ctx: &mut Ctx, n: &Node, field: &str) -> Option<[f64; D]> {
    match &n.kind {
        Kind::Array(a) if a.len() == D => {
            let values: Vec<Option<f64>> = (a.iter().enumerate())
                .map(|(k, e)| as_num(ctx, e, &format!("{field}[{k}]")))
                .collect();
            let values: Vec<f64> = values.into_iter().collect::<Option<_>>()?;
            Some(std::array::from_fn(|k| values[k]))
        }
        _ => {
            let what = match D {
                2 => "a pair of numbers [x, y]",
                _ => "a triple of numbers [x, y, z]",
            };
            ctx.expected(n, field, what);
            None
        }
    }
}

/// Checks a numeric value with `ok`, reporting "must be {what}, got {v}" otherwise.
pub(crate) fn ensure(
    ctx: &mut Ctx,
    got: Option<(f64, Pos)>,
    field: &str,
    ok: impl Fn(f64) -> bool,
    what: &str,
) -> Option<f64> {
    let (v, pos) = got?;
    if ok(v) {
        Some(v)
    } else {
        ctx.err(pos, field, format!("must be {what}, got {v}"));
        None
    }
}

/// Checks an integer lies in `[min, max]`.
pub(crate) fn int_in(
    ctx: &mut Ctx,
    got: Option<(i64, Pos)>,
    field: &str,
    min: i64,
    max: i64,
) -> Option<i64> {
    let (v, pos) = got?;
    if (min..=max).contains(&v) {
        Some(v)
    } else if max == i64::MAX {
        ctx.err(pos, field, format!("must be >= {min}, got {v}"));
        None
    } else {
        ctx.err(pos, field, format!("must be in [{min}, {max}], got {v}"));
        None
    }
}

/// Matches a string against a list of names, reporting "unknown {what} `x` (known: ...)".
pub(crate) fn choose<T: Copy>(
    ctx: &mut Ctx,
    got: Option<(&str, Pos)>,
    field: &str,
    what: &str,
    choices: &[(&str, T)],
) -> Option<T> {
    let (s, pos) = got?;
    if let Some((_, v)) = choices.iter().find(|(name, _)| *name == s) {
        return Some(*v);
    }
    let known: Vec<&str> = choices.iter().map(|(n, _)| *n).collect();
    ctx.err(
        pos,
        field,
        format!("unknown {what} `{s}` (known: {})", known.join(", ")),
    );
    None
}
