//! LAMMPS input-script and data-file syntax for dmhs.
//!
//! Pure syntax, no physics: reading scripts exactly as LAMMPS reads them (comments, `&`
//! continuation, quotes, `$` substitution, variables, expressions, flow control), the names of
//! every LAMMPS command and style, argument parsing with located diagnostics, and the LAMMPS
//! data-file format.

pub mod args;
pub mod ast;
pub mod commands;
pub mod context;
pub mod data_file;
pub mod diag;
pub mod expr;
pub mod follow_on;
pub mod interp;
pub mod lexer;
pub mod molecule_file;
pub mod numfmt;
pub mod random_mars;
pub mod random_park;
pub mod span;
pub mod suggest;
#[cfg(test)]
pub(crate) mod test_context;
pub mod variables;

pub use args::Args;
pub use ast::{Command, Word};
pub use context::{EvalContext, Host};
pub use diag::{DResult, Diagnostic, Severity};
pub use span::{FileId, SourceMap, Span};
