//! Diagnostics: an error (or warning) with the offending text underlined, `file:line:col`,
//! and help lines, rendered like a compiler message.

use crate::span::{SourceMap, Span};
use std::fmt::Write;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Severity {
    Error,
    Warning,
}

/// A span with a short message written under it.
#[derive(Clone, Debug, PartialEq)]
pub struct Label {
    pub span: Span,
    pub message: String,
}

#[derive(Clone, Debug, PartialEq)]
pub struct Diagnostic {
    pub severity: Severity,
    pub message: String,
    /// The first label is the primary location.
    pub labels: Vec<Label>,
    /// `help:` lines (e.g. the syntax of the command, a "did you mean").
    pub help: Vec<String>,
    /// `note:` lines.
    pub notes: Vec<String>,
}

pub type DResult<T> = Result<T, Diagnostic>;

impl Diagnostic {
    pub fn error(message: impl Into<String>) -> Diagnostic {
        Diagnostic { severity: Severity::Error, message: message.into(), labels: vec![], help: vec![], notes: vec![] }
    }
    pub fn warning(message: impl Into<String>) -> Diagnostic {
        Diagnostic { severity: Severity::Warning, ..Diagnostic::error(message) }
    }
    /// Error located at `span` with `label` written under the underlined text.
    pub fn at(span: Span, message: impl Into<String>, label: impl Into<String>) -> Diagnostic {
        Diagnostic::error(message).with_label(span, label)
    }
    pub fn with_label(mut self, span: Span, message: impl Into<String>) -> Diagnostic {
        self.labels.push(Label { span, message: message.into() });
        self
    }
    pub fn with_help(mut self, help: impl Into<String>) -> Diagnostic {
        self.help.push(help.into());
        self
    }
    pub fn with_note(mut self, note: impl Into<String>) -> Diagnostic {
        self.notes.push(note.into());
        self
    }
    pub fn primary_span(&self) -> Option<Span> {
        self.labels.first().map(|l| l.span)
    }
    pub fn is_error(&self) -> bool {
        self.severity == Severity::Error
    }

    /// Render as text:
    /// ```text
    /// error: expected a number for the cutoff, found `abc`
    ///   --> in.lj:12:19
    ///    |
    /// 12 | pair_style lj/cut abc
    ///    |                   ^^^ not a number
    ///    = help: syntax: pair_style lj/cut Rc
    /// ```
    pub fn render(&self, sm: &SourceMap) -> String {
        let mut out = String::new();
        let kind = match self.severity {
            Severity::Error => "error",
            Severity::Warning => "warning",
        };
        let _ = writeln!(out, "{}: {}", kind, self.message);
        // gutter width from the largest line number shown
        let mut width = 1;
        for l in &self.labels {
            if let Some(f) = sm.get(l.span.file) {
                let (line, _) = f.line_col(l.span.lo);
                width = width.max(line.to_string().len());
            }
        }
        let pad = " ".repeat(width);
        for (k, l) in self.labels.iter().enumerate() {
            let Some(f) = sm.get(l.span.file) else { continue };
            let (line, col) = f.line_col(l.span.lo);
            let arrow = if k == 0 { "-->" } else { ":::" };
            let _ = writeln!(out, "{pad}{arrow} {}:{}:{}", f.name, line, col);
            let _ = writeln!(out, "{pad} |");
            let text = f.line_text(line);
            let _ = writeln!(out, "{:>width$} | {}", line, text.replace('\t', " "), width = width);
            // underline: from col to the end of the span, clipped to this line
            let (end_line, end_col) = f.line_col(l.span.hi);
            let line_chars = text.chars().count();
            let stop = if end_line == line { end_col } else { line_chars + 1 };
            let n = stop.saturating_sub(col).max(1);
            let mark = if k == 0 { '^' } else { '-' };
            let _ = writeln!(
                out,
                "{pad} | {}{} {}",
                " ".repeat(col - 1),
                mark.to_string().repeat(n),
                l.message
            );
        }
        for h in &self.help {
            let _ = writeln!(out, "{pad} = help: {h}");
        }
        for n in &self.notes {
            let _ = writeln!(out, "{pad} = note: {n}");
        }
        out
    }
}

impl std::fmt::Display for Diagnostic {
    /// Without a source map: the message, help and notes only.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}", self.message)?;
        for h in &self.help {
            write!(f, "\n  help: {h}")?;
        }
        for n in &self.notes {
            write!(f, "\n  note: {n}")?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    #[test]
    fn renders_location_and_underline() {
        let mut sm = SourceMap::new();
        let id = sm.add("in.lj", "units lj\npair_style lj/cut abc\n");
        let d = Diagnostic::at(Span::new(id, 27, 30), "expected a number for the cutoff, found `abc`", "not a number")
            .with_help("syntax: pair_style lj/cut Rc");
        let s = d.render(&sm);
        assert!(s.contains("--> in.lj:2:19"), "{s}");
        assert!(s.contains("2 | pair_style lj/cut abc"), "{s}");
        assert!(s.contains("  |                   ^^^ not a number"), "{s}");
        assert!(s.contains("= help: syntax: pair_style lj/cut Rc"), "{s}");
    }
}
