//! (being written) The variable store.

/// All variables of a run.
#[derive(Debug, Default)]
pub struct Variables {}
