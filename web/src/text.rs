//! Text without a heap: [`Text`] writes into a caller's byte buffer (the page reads it from linear
//! memory), [`StackStr`] is a small string on the stack, and [`json_str`] escapes a JSON string.

use core::fmt::{self, Write};

/// UTF-8 text written into a borrowed buffer; what does not fit is dropped and remembered
/// ([`Text::overflowed`]), never a panic.
#[derive(Debug)]
pub struct Text<'a> {
    buf: &'a mut [u8],
    len: usize,
    overflowed: bool,
}

impl<'a> Text<'a> {
    /// An empty text over `buf`.
    pub fn new(buf: &'a mut [u8]) -> Self {
        Self { buf, len: 0, overflowed: false }
    }

    /// Bytes written.
    #[must_use]
    pub const fn len(&self) -> usize {
        self.len
    }

    /// `true` when nothing was written.
    #[must_use]
    pub const fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// `true` when some text did not fit.
    #[must_use]
    pub const fn overflowed(&self) -> bool {
        self.overflowed
    }

    /// The text written (whole characters only: a character that did not fit is not cut).
    #[must_use]
    pub fn as_str(&self) -> &str {
        core::str::from_utf8(&self.buf[..self.len]).unwrap_or("")
    }
}

impl Write for Text<'_> {
    fn write_str(&mut self, s: &str) -> fmt::Result {
        let room = self.buf.len() - self.len;
        let mut take = s.len().min(room);
        while !s.is_char_boundary(take) {
            take -= 1;
        }
        self.buf[self.len..self.len + take].copy_from_slice(&s.as_bytes()[..take]);
        self.len += take;
        if take < s.len() {
            self.overflowed = true;
        }
        Ok(())
    }
}

/// A string of at most `N` bytes on the stack (longer writes are cut at a character boundary).
#[derive(Debug, Clone, Copy)]
pub struct StackStr<const N: usize> {
    buf: [u8; N],
    len: usize,
}

impl<const N: usize> Default for StackStr<N> {
    fn default() -> Self {
        Self { buf: [0; N], len: 0 }
    }
}

impl<const N: usize> StackStr<N> {
    /// The text formatted from `args` (cut at `N` bytes).
    #[must_use]
    pub fn of(args: fmt::Arguments<'_>) -> Self {
        let mut s = Self::default();
        let _ = s.write_fmt(args);
        s
    }

    /// The text.
    #[must_use]
    pub fn as_str(&self) -> &str {
        core::str::from_utf8(&self.buf[..self.len]).unwrap_or("")
    }
}

impl<const N: usize> Write for StackStr<N> {
    fn write_str(&mut self, s: &str) -> fmt::Result {
        let mut text = Text { buf: &mut self.buf, len: self.len, overflowed: false };
        text.write_str(s)?;
        self.len = text.len;
        Ok(())
    }
}

/// Writes `s` as a JSON string literal (quotes included).
///
/// # Errors
/// Those of `out`.
pub fn json_str(out: &mut impl Write, s: &str) -> fmt::Result {
    out.write_char('"')?;
    for c in s.chars() {
        match c {
            '"' => out.write_str("\\\"")?,
            '\\' => out.write_str("\\\\")?,
            '\n' => out.write_str("\\n")?,
            c if u32::from(c) < 0x20 => write!(out, "\\u{:04x}", u32::from(c))?,
            c => out.write_char(c)?,
        }
    }
    out.write_char('"')
}

/// Writes `v` as a JSON number (`null` when it is not finite: JSON has no NaN).
///
/// # Errors
/// Those of `out`.
pub fn json_num(out: &mut impl Write, v: f64) -> fmt::Result {
    if v.is_finite() { write!(out, "{v}") } else { out.write_str("null") }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;

    #[test]
    fn text_cuts_at_its_end_without_splitting_a_character() {
        let mut buf = [0u8; 5];
        let mut t = Text::new(&mut buf);
        write!(t, "ab").unwrap();
        assert!(!t.overflowed());
        write!(t, "c\u{e9}\u{e9}").unwrap(); // 1 + 2 + 2 bytes: the second é does not fit
        assert_eq!(t.as_str(), "abc\u{e9}");
        assert!(t.overflowed());
    }

    #[test]
    fn json_escapes() {
        let mut s = StackStr::<64>::default();
        json_str(&mut s, "a\"b\\c\n\u{1}").unwrap();
        assert_eq!(s.as_str(), r#""a\"b\\c\n\u0001""#);
        let mut n = StackStr::<16>::default();
        json_num(&mut n, f64::NAN).unwrap();
        json_num(&mut n, 0.25).unwrap();
        assert_eq!(n.as_str(), "null0.25");
    }
}
