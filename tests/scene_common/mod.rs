//! Shared by the scene tests (tests/scene_casting.rs, tests/scene_lava.rs): reading a scene's
//! final state.

use dmhs::deck::DeckRun;
use std::collections::HashMap;

/// Bonded fragments: groups of atoms of type `solid` held together by bonds (connected components
/// of the bond graph) with at least `min` atoms, largest first. Bonds form only between solid
/// atoms, so a fragment is a piece of crust or block; a crack through one splits it in two.
pub fn fragments(r: &DeckRun, solid: usize, min: usize) -> Vec<usize> {
    let a = &r.sim.state.atoms;
    let index: HashMap<i64, usize> = (0..a.nlocal).map(|i| (a.tag[i], i)).collect();
    let mut parent: Vec<usize> = (0..a.nlocal).collect();
    fn root(p: &mut [usize], mut i: usize) -> usize {
        while p[i] != i {
            p[i] = p[p[i]];
            i = p[i];
        }
        i
    }
    for b in &r.sim.state.topo.bonds {
        let (i, j) = (index[&b.atoms[0]], index[&b.atoms[1]]);
        let (ri, rj) = (root(&mut parent, i), root(&mut parent, j));
        parent[ri] = rj;
    }
    let mut size: HashMap<usize, usize> = HashMap::new();
    for i in (0..a.nlocal).filter(|&i| a.typ[i] == solid) {
        *size.entry(root(&mut parent, i)).or_default() += 1;
    }
    let mut s: Vec<usize> = size.into_values().filter(|&n| n >= min).collect();
    s.sort_unstable_by(|x, y| y.cmp(x));
    s
}
