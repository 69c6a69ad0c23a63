//! The syntax tree of an input script is flat: a script is a sequence of commands, each a
//! list of words (after `$` substitution and quote removal), every word with its source span.

use crate::span::Span;

/// One word of a command. `text` is the word after substitution with its quotes removed.
#[derive(Clone, Debug, PartialEq)]
pub struct Word {
    pub text: String,
    pub span: Span,
    /// The word was written in quotes (single, double or triple).
    pub quoted: bool,
}

impl Word {
    pub fn new(text: impl Into<String>, span: Span) -> Word {
        Word { text: text.into(), span, quoted: false }
    }
    pub fn as_str(&self) -> &str {
        &self.text
    }
}

/// One command: its name and its arguments.
#[derive(Clone, Debug, PartialEq)]
pub struct Command {
    pub name: Word,
    pub args: Vec<Word>,
    /// The whole logical line (for errors that concern the command as a whole).
    pub span: Span,
}

impl Command {
    pub fn name(&self) -> &str {
        &self.name.text
    }
    /// The arguments as plain strings.
    pub fn arg_strs(&self) -> Vec<&str> {
        self.args.iter().map(|w| w.text.as_str()).collect()
    }
}
