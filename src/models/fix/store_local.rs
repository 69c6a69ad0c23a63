//! LAMMPS' internal fix STORE/LOCAL (src/fix_store_local.cpp), created by `bond_style bpm/spring
//! store/local FIXID N values...`: it collects one row per broken bond (both atoms in the fix's
//! group) and every N steps, after the forces (post_force), publishes the rows collected since
//! the last time as its local vector (one value) or array (several), for `dump local`
//! (`f_FIXID` or `f_FIXID[k]`).

use super::{Fix, FixCtx, FixHooks};
use crate::engine::state::{RunError, State};

pub struct FixStoreLocal {
    id: String,
    groupbit: u32,
    every: i64,
    nvalues: usize,
    pending: Vec<Vec<f64>>,
    published: Vec<Vec<f64>>,
}

impl FixStoreLocal {
    pub fn new(id: String, groupbit: u32, every: i64, nvalues: usize) -> FixStoreLocal {
        FixStoreLocal { id, groupbit, every, nvalues, pending: vec![], published: vec![] }
    }
    /// Rows of broken bonds; `masks` are the group masks of each row's two atoms.
    pub fn add_rows(&mut self, rows: Vec<Vec<f64>>, masks: &[[u32; 2]]) {
        for (row, m) in rows.into_iter().zip(masks) {
            if m[0] & self.groupbit != 0 && m[1] & self.groupbit != 0 {
                self.pending.push(row);
            }
        }
    }
    /// How often rows are published (LAMMPS' `local_freq`).
    pub fn every(&self) -> i64 {
        self.every
    }
}

impl Fix for FixStoreLocal {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        "STORE/LOCAL"
    }
    fn groupbit(&self) -> u32 {
        self.groupbit
    }
    fn hooks(&self) -> FixHooks {
        FixHooks { post_force: true, ..FixHooks::default() }
    }
    fn post_force(&mut self, state: &mut State, _ctx: &mut FixCtx) -> Result<(), RunError> {
        if state.step % self.every == 0 {
            self.published = std::mem::take(&mut self.pending);
        }
        Ok(())
    }
    fn as_store_local(&mut self) -> Option<&mut FixStoreLocal> {
        Some(self)
    }
    fn local(&self) -> Option<(&[Vec<f64>], usize, i64)> {
        Some((&self.published, if self.nvalues == 1 { 0 } else { self.nvalues }, self.every))
    }
    fn describe(&self) -> String {
        format!("fix {} STORE/LOCAL (every {}, {} values)", self.id, self.every, self.nvalues)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rows_of_atoms_outside_the_group_are_dropped() {
        let mut f = FixStoreLocal::new("brk".into(), 0b10, 100, 3);
        f.add_rows(vec![vec![5.0, 1.0, 2.0], vec![7.0, 3.0, 4.0]], &[[0b11, 0b10], [0b01, 0b10]]);
        assert_eq!(f.pending, vec![vec![5.0, 1.0, 2.0]]);
        // nothing is visible before the next publishing step
        assert!(f.local().unwrap().0.is_empty());
        assert_eq!((f.local().unwrap().1, f.every()), (3, 100));
    }
}
