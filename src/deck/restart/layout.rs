//! The text layout of restart files: JSON that a person can read and edit. An object has one
//! member per line; an array of numbers or strings stays on one line; an array of arrays or
//! objects has one element per line, and an array element that is itself an array is written
//! on one line (a per-atom triple, a bond, a contact).

use serde_json::ser::{CompactFormatter, Formatter};
use std::io::{self, Write};

#[derive(Default)]
pub struct Layout {
    /// Open containers laid out over several lines: whether a line break was written in each
    /// (the closing bracket then goes on a line of its own).
    open: Vec<bool>,
    /// Depth inside a one-line array element (0: not in one).
    inline: usize,
    /// An element of a multi-line array is due (`Some(first)`): its separator depends on
    /// whether it is a container, which the next call tells.
    pending: Option<bool>,
}

impl Layout {
    fn newline<W: ?Sized + Write>(&self, w: &mut W) -> io::Result<()> {
        w.write_all(b"\n")?;
        for _ in 0..self.open.len() {
            w.write_all(b"  ")?;
        }
        Ok(())
    }

    /// Write the separator of a pending array element.
    fn element<W: ?Sized + Write>(&mut self, w: &mut W, container: bool) -> io::Result<()> {
        let Some(first) = self.pending.take() else { return Ok(()) };
        if !first {
            w.write_all(b",")?;
        }
        if container {
            if let Some(broken) = self.open.last_mut() {
                *broken = true;
            }
            self.newline(w)?;
        }
        Ok(())
    }
}

macro_rules! scalars {
    ($($name:ident: $t:ty),*) => {$(
        fn $name<W: ?Sized + Write>(&mut self, w: &mut W, value: $t) -> io::Result<()> {
            self.element(w, false)?;
            CompactFormatter.$name(w, value)
        }
    )*};
}

impl Formatter for Layout {
    scalars!(write_bool: bool, write_i8: i8, write_i16: i16, write_i32: i32, write_i64: i64, write_i128: i128, write_u8: u8, write_u16: u16, write_u32: u32, write_u64: u64, write_u128: u128, write_f32: f32, write_f64: f64, write_number_str: &str);

    fn write_null<W: ?Sized + Write>(&mut self, w: &mut W) -> io::Result<()> {
        self.element(w, false)?;
        w.write_all(b"null")
    }

    fn begin_string<W: ?Sized + Write>(&mut self, w: &mut W) -> io::Result<()> {
        self.element(w, false)?;
        w.write_all(b"\"")
    }

    fn begin_array<W: ?Sized + Write>(&mut self, w: &mut W) -> io::Result<()> {
        if self.inline > 0 || self.pending.is_some() {
            self.element(w, true)?;
            self.inline += 1;
        } else {
            self.open.push(false);
        }
        w.write_all(b"[")
    }

    fn end_array<W: ?Sized + Write>(&mut self, w: &mut W) -> io::Result<()> {
        if self.inline > 0 {
            self.inline -= 1;
        } else if self.open.pop() == Some(true) {
            self.newline(w)?;
        }
        w.write_all(b"]")
    }

    fn begin_array_value<W: ?Sized + Write>(&mut self, w: &mut W, first: bool) -> io::Result<()> {
        if self.inline > 0 {
            return if first { Ok(()) } else { w.write_all(b",") };
        }
        self.pending = Some(first);
        Ok(())
    }

    fn begin_object<W: ?Sized + Write>(&mut self, w: &mut W) -> io::Result<()> {
        if self.inline > 0 {
            self.inline += 1;
        } else {
            self.element(w, true)?;
            self.open.push(false);
        }
        w.write_all(b"{")
    }

    fn end_object<W: ?Sized + Write>(&mut self, w: &mut W) -> io::Result<()> {
        if self.inline > 0 {
            self.inline -= 1;
        } else if self.open.pop() == Some(true) {
            self.newline(w)?;
        }
        w.write_all(b"}")
    }

    fn begin_object_key<W: ?Sized + Write>(&mut self, w: &mut W, first: bool) -> io::Result<()> {
        if !first {
            w.write_all(b",")?;
        }
        if self.inline == 0 {
            if let Some(broken) = self.open.last_mut() {
                *broken = true;
            }
            self.newline(w)?;
        }
        Ok(())
    }

    fn begin_object_value<W: ?Sized + Write>(&mut self, w: &mut W) -> io::Result<()> {
        w.write_all(if self.inline > 0 { b":" } else { b": " })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn lay(v: &serde_json::Value) -> String {
        let mut out = Vec::new();
        serde::Serialize::serialize(v, &mut serde_json::Serializer::with_formatter(&mut out, Layout::default())).unwrap();
        String::from_utf8(out).unwrap()
    }

    #[test]
    fn nested_arrays_one_element_per_line() {
        let v = serde_json::json!({"a": 1, "ids": [1, 2], "x": [[0.5, -0.0], [1e-300, 2.0]], "e": [], "o": {}, "f": [{"n": "w", "rows": [[1.0]]}]});
        let text = lay(&v);
        let expect = "{\n  \"a\": 1,\n  \"e\": [],\n  \"f\": [\n    {\n      \"n\": \"w\",\n      \"rows\": [\n        [1.0]\n      ]\n    }\n  ],\n  \"ids\": [1,2],\n  \"o\": {},\n  \"x\": [\n    [0.5,-0.0],\n    [1e-300,2.0]\n  ]\n}";
        assert_eq!(text, expect);
        assert_eq!(serde_json::from_str::<serde_json::Value>(&text).unwrap(), v);
    }
}
