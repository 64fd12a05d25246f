//! Whitespace-separated tokens of a text file, with their index and line, and typed reads
//! that turn every surprise (end of file, bad number, out-of-range size) into a
//! [`ReadError`] at the token concerned.

use crate::error::{Position, ReadError, ReadErrorKind};
use std::path::Path;

/// One token: its text, 1-based index among all tokens, 1-based line.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Tok<'a> {
    pub text: &'a str,
    pub index: usize,
    pub line: usize,
}

/// A cursor over the tokens of a text.
#[derive(Clone)]
pub(crate) struct Lexer<'a> {
    path: &'a Path,
    text: &'a str,
    pos: usize,
    line: usize,
    read: usize,
    total: usize,
}

impl<'a> Lexer<'a> {
    /// A cursor at the start of `text`; `path` names it in errors.
    pub fn new(text: &'a str, path: &'a Path) -> Self {
        Lexer {
            path,
            text,
            pos: 0,
            line: 1,
            read: 0,
            total: text.split_ascii_whitespace().count(),
        }
    }

    /// Number of tokens in the whole text: an upper bound for any size read from it.
    pub fn total(&self) -> usize {
        self.total
    }

    /// Number of tokens not read yet.
    pub fn remaining(&self) -> usize {
        self.total - self.read
    }

    fn skip_space(&mut self) {
        let bytes = self.text.as_bytes();
        while self.pos < bytes.len() && bytes[self.pos].is_ascii_whitespace() {
            if bytes[self.pos] == b'\n' {
                self.line += 1;
            }
            self.pos += 1;
        }
    }

    /// The next token, if any.
    pub fn next_tok(&mut self) -> Option<Tok<'a>> {
        self.skip_space();
        let bytes = self.text.as_bytes();
        let start = self.pos;
        while self.pos < bytes.len() && !bytes[self.pos].is_ascii_whitespace() {
            self.pos += 1;
        }
        if start == self.pos {
            return None;
        }
        self.read += 1;
        Some(Tok {
            text: &self.text[start..self.pos],
            index: self.read,
            line: self.line,
        })
    }

    /// The next `n` tokens without consuming them (fewer at the end of the text).
    pub fn peek(&self, n: usize) -> Vec<Tok<'a>> {
        let mut ahead = self.clone();
        (0..n).map_while(|_| ahead.next_tok()).collect()
    }

    /// Skips the rest of the current line (after the last token read).
    pub fn skip_line(&mut self) {
        let rest = &self.text[self.pos..];
        let skipped = rest.find('\n').unwrap_or(rest.len());
        self.read += rest[..skipped].split_ascii_whitespace().count();
        self.pos += skipped;
    }

    /// An error at token `tok`.
    pub fn error_at(
        &self,
        tok: &Tok<'_>,
        kind: ReadErrorKind,
        reason: impl Into<String>,
    ) -> ReadError {
        ReadError::new(
            self.path,
            Position::Token {
                index: tok.index,
                line: tok.line,
            },
            kind,
            reason,
        )
    }

    /// An error at the next token (or just past the end of the text).
    pub fn error_here(&self, kind: ReadErrorKind, reason: impl Into<String>) -> ReadError {
        let mut ahead = self.clone();
        let tok = ahead.next_tok().unwrap_or(Tok {
            text: "",
            index: self.read + 1,
            line: ahead.line,
        });
        self.error_at(&tok, kind, reason)
    }

    /// The next token, or an error saying the file ends before `what`.
    pub fn expect(&mut self, what: &str) -> Result<Tok<'a>, ReadError> {
        match self.next_tok() {
            Some(t) => Ok(t),
            None => Err(self.error_here(
                ReadErrorKind::Format,
                format!("the file ends early: expected {what}"),
            )),
        }
    }

    /// The next token, which must be exactly `word`.
    pub fn literal(&mut self, word: &str, context: &str) -> Result<(), ReadError> {
        let t = self.expect(&format!("\"{word}\" ({context})"))?;
        if t.text != word {
            return Err(self.error_at(
                &t,
                ReadErrorKind::Format,
                format!("expected \"{word}\" ({context}), found \"{}\"", t.text),
            ));
        }
        Ok(())
    }

    /// The next token as an integer.
    pub fn int(&mut self, what: &str) -> Result<(i64, Tok<'a>), ReadError> {
        let t = self.expect(what)?;
        match t.text.parse::<i64>() {
            Ok(v) => Ok((v, t)),
            Err(_) => Err(self.error_at(
                &t,
                ReadErrorKind::Format,
                format!("expected an integer ({what}), found \"{}\"", t.text),
            )),
        }
    }

    /// The next token as a size or index in `0..=max`.
    pub fn size(&mut self, what: &str, max: usize) -> Result<usize, ReadError> {
        let (v, t) = self.int(what)?;
        usize::try_from(v)
            .ok()
            .filter(|&u| u <= max)
            .ok_or_else(|| {
                self.error_at(
                    &t,
                    ReadErrorKind::Format,
                    format!("{what} = {v} is outside 0..={max}"),
                )
            })
    }

    /// The next token as an index in `0..bound`.
    pub fn index(&mut self, what: &str, bound: usize) -> Result<usize, ReadError> {
        let (v, t) = self.int(what)?;
        usize::try_from(v)
            .ok()
            .filter(|&u| u < bound)
            .ok_or_else(|| {
                self.error_at(
                    &t,
                    ReadErrorKind::Format,
                    format!("{what} = {v} is outside 0..{bound}"),
                )
            })
    }

    /// The next token as a size; bounded by the token count of the file, since every
    /// dimension of a problem is the length of some vector stored in it.
    pub fn dimension(&mut self, what: &str) -> Result<usize, ReadError> {
        let max = self.total;
        self.size(what, max)
    }

    /// The next token as a finite real number.
    pub fn real(&mut self, what: &str) -> Result<f64, ReadError> {
        let t = self.expect(what)?;
        match t.text.parse::<f64>() {
            Ok(v) if v.is_finite() => Ok(v),
            Ok(v) => Err(self.error_at(
                &t,
                ReadErrorKind::Invalid,
                format!("{what} = {v} is not finite"),
            )),
            Err(_) => Err(self.error_at(
                &t,
                ReadErrorKind::Format,
                format!("expected a real number ({what}), found \"{}\"", t.text),
            )),
        }
    }

    /// `n` real numbers, named `what[k]` in errors.
    pub fn reals(&mut self, n: usize, what: &str) -> Result<Vec<f64>, ReadError> {
        if n > self.remaining() {
            return Err(self.error_here(
                ReadErrorKind::Format,
                format!(
                    "{what} needs {n} values but only {} tokens are left in the file",
                    self.remaining()
                ),
            ));
        }
        (0..n).map(|k| self.real(&format!("{what}[{k}]"))).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tokens_lines_and_errors() {
        let p = Path::new("x.dat");
        let mut lx = Lexer::new("2\n 3 4.5\nCSparse a b\n  7 ", p);
        assert_eq!(lx.total(), 7);
        assert_eq!(lx.int("d").unwrap().0, 2);
        let t = lx.peek(2);
        assert_eq!((t[0].text, t[0].index, t[0].line), ("3", 2, 2));
        assert_eq!(lx.size("n", 3).unwrap(), 3);
        assert_eq!(lx.real("x").unwrap(), 4.5);
        lx.literal("CSparse", "header").unwrap();
        lx.skip_line();
        assert_eq!(lx.remaining(), 1);
        let e = lx.size("n", 5).unwrap_err();
        assert_eq!(e.position, Position::Token { index: 7, line: 4 });
        let e = lx.real("q").unwrap_err();
        assert_eq!(e.position, Position::Token { index: 8, line: 4 });
        assert!(e.to_string().contains("ends early"), "{e}");
    }
}
