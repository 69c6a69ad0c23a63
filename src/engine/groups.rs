//! Named groups of atoms as bits of the per-atom `mask` (at most 32, as in LAMMPS).

pub const MAX_GROUPS: usize = 32;

#[derive(Clone, Debug)]
pub struct Groups {
    names: Vec<Option<String>>,
    /// Groups whose members an internal fix `GROUP_name` recomputes (`group ID dynamic`).
    dynamic: u32,
}

impl Default for Groups {
    fn default() -> Self {
        let mut names = vec![None; MAX_GROUPS];
        names[0] = Some("all".to_string());
        Groups { names, dynamic: 0 }
    }
}

impl Groups {
    pub fn find(&self, name: &str) -> Option<usize> {
        self.names.iter().position(|n| n.as_deref() == Some(name))
    }
    /// Bitmask of a group by name.
    pub fn bit(&self, name: &str) -> Option<u32> {
        self.find(name).map(|k| 1u32 << k)
    }
    /// Index of an existing group or a new one.
    pub fn find_or_create(&mut self, name: &str) -> Result<usize, String> {
        if let Some(k) = self.find(name) {
            return Ok(k);
        }
        match self.names.iter().position(|n| n.is_none()) {
            Some(k) => {
                self.names[k] = Some(name.to_string());
                Ok(k)
            }
            None => Err(format!("too many groups (at most {MAX_GROUPS}, including `all`)")),
        }
    }
    /// Give group `k` (its bit in the atom masks) a name (read_restart).
    pub fn set_index(&mut self, k: usize, name: &str) -> Result<(), String> {
        if k >= MAX_GROUPS {
            return Err(format!("group index {k} out of range (at most {MAX_GROUPS} groups)"));
        }
        self.names[k] = Some(name.to_string());
        Ok(())
    }
    pub fn delete(&mut self, k: usize) {
        if k > 0 {
            self.names[k] = None;
            self.set_dynamic(k, false);
        }
    }
    /// Whether group `k` is dynamic.
    pub fn is_dynamic(&self, k: usize) -> bool {
        k < MAX_GROUPS && self.dynamic & (1 << k) != 0
    }
    /// Whether any group of the bitmask `bit` is dynamic.
    pub fn bit_is_dynamic(&self, bit: u32) -> bool {
        self.dynamic & bit != 0
    }
    pub fn set_dynamic(&mut self, k: usize, on: bool) {
        if on {
            self.dynamic |= 1 << k;
        } else {
            self.dynamic &= !(1 << k);
        }
    }
    pub fn names(&self) -> impl Iterator<Item = (usize, &str)> {
        self.names.iter().enumerate().filter_map(|(k, n)| n.as_deref().map(|s| (k, s)))
    }
}
