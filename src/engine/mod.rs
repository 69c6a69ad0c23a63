//! The state the stages borrow and the machinery every model shares.

pub mod atoms;
pub mod boundary;
pub mod contact_history;
pub mod domain;
pub mod groups;
pub mod neighbor;
pub mod random_park;
pub mod special;
pub mod timing;
pub mod topology;
pub mod units;
pub mod water;
