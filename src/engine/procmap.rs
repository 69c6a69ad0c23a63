//! The processor grid of a run on several ranks and where each rank sits in it (LAMMPS'
//! `processors` command: `grid onelevel|twolevel|custom`, `map cart|cart/reorder|xyz|...`,
//! `file`), chosen as LAMMPS chooses it, so that a deck's ranks own the sub-domains they own in
//! LAMMPS.

/// The settings of the `processors` command.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ProcSettings {
    /// Px Py Pz (None: `*`, chosen).
    pub user: [Option<usize>; 3],
    pub grid: GridStyle,
    pub map: MapStyle,
    /// `file outfile`: where rank 0 writes the grid when a run lays the ranks out.
    pub file: Option<String>,
}

#[derive(Clone, Debug, Default, PartialEq)]
pub enum GridStyle {
    #[default]
    OneLevel,
    /// `twolevel Nc Cx Cy Cz`: blocks of Nc consecutive ranks (a node's cores) own contiguous
    /// sub-grids of Cx x Cy x Cz.
    TwoLevel { ncores: usize, user_cores: [Option<usize>; 3] },
    /// `custom infile`: the grid and each rank's place (0-based) read from a file.
    Custom { procs: [usize; 3], places: Vec<[usize; 3]> },
}

#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum MapStyle {
    /// MPI's Cartesian numbering (row-major: z fastest), with or without `reorder` (MPICH
    /// does not reorder).
    #[default]
    Cart,
    CartReorder,
    /// `xyz`, `xzy`, ...: the dimensions from the fastest-varying to the slowest.
    Ijk([usize; 3]),
}

impl MapStyle {
    pub fn parse(word: &str) -> Option<MapStyle> {
        match word {
            "cart" => Some(MapStyle::Cart),
            "cart/reorder" => Some(MapStyle::CartReorder),
            _ if word.len() == 3 => {
                let mut order = [0; 3];
                for (k, c) in word.chars().enumerate() {
                    order[k] = "xyz".find(c)?;
                }
                let mut seen = order;
                seen.sort_unstable();
                (seen == [0, 1, 2]).then_some(MapStyle::Ijk(order))
            }
            _ => None,
        }
    }
}

/// A processor grid and the place of every rank in it.
#[derive(Clone, Debug, PartialEq)]
pub struct Layout {
    pub procs: [usize; 3],
    /// Each rank's grid coordinates.
    places: Vec<[usize; 3]>,
    /// The rank at each grid point, at `(i * Py + j) * Pz + k`.
    ranks: Vec<usize>,
}

impl Layout {
    /// A layout from each rank's place (which must cover the grid once).
    fn from_places(procs: [usize; 3], places: Vec<[usize; 3]>) -> Result<Layout, String> {
        let n = procs[0] * procs[1] * procs[2];
        let mut ranks = vec![usize::MAX; n];
        if places.len() != n {
            return Err(format!("{} ranks for a {} by {} by {} grid", places.len(), procs[0], procs[1], procs[2]));
        }
        for (r, c) in places.iter().enumerate() {
            if (0..3).any(|d| c[d] >= procs[d]) {
                return Err(format!("rank {r} at {} {} {} lies outside the {} by {} by {} grid", c[0] + 1, c[1] + 1, c[2] + 1, procs[0], procs[1], procs[2]));
            }
            let slot = &mut ranks[(c[0] * procs[1] + c[1]) * procs[2] + c[2]];
            if *slot != usize::MAX {
                return Err(format!("ranks {} and {r} both at {} {} {}", *slot, c[0] + 1, c[1] + 1, c[2] + 1));
            }
            *slot = r;
        }
        Ok(Layout { procs, places, ranks })
    }
    /// The grid with MPI's Cartesian numbering (z fastest).
    pub fn cartesian(procs: [usize; 3]) -> Layout {
        let places = (0..procs[0] * procs[1] * procs[2]).map(|r| row_major(r, procs)).collect();
        Layout::from_places(procs, places).expect("a Cartesian numbering covers its grid")
    }
    pub fn place(&self, rank: usize) -> [usize; 3] {
        self.places[rank]
    }
    pub fn rank_at(&self, c: [usize; 3]) -> usize {
        self.ranks[(c[0] * self.procs[1] + c[1]) * self.procs[2] + c[2]]
    }
    /// The text of `processors ... file outfile` (LAMMPS' header and, per rank, `world-ID
    /// universe-ID original-ID: I J K: name`; one partition, no reordering).
    pub fn file_text(&self, names: &[String]) -> String {
        let p = self.procs;
        let mut s = format!("LAMMPS mapping of processors to 3d grid\npartition = 1\nPx Py Pz = {} {} {}\nworld-ID universe-ID original-ID: I J K: name\n\n", p[0], p[1], p[2]);
        for (r, c) in self.places.iter().enumerate() {
            s += &format!("{r} {r} {r}: {} {} {}: {}\n", c[0] + 1, c[1] + 1, c[2] + 1, names.get(r).map_or("", |n| n.as_str()));
        }
        s
    }
}

/// Coordinates of index `r` in row-major order (the last dimension fastest).
fn row_major(r: usize, p: [usize; 3]) -> [usize; 3] {
    [r / (p[1] * p[2]), (r / p[2]) % p[1], r % p[2]]
}

/// Coordinates of index `r` with the dimensions `order` varying from the fastest to the slowest.
fn ijk(r: usize, p: [usize; 3], order: [usize; 3]) -> [usize; 3] {
    let mut c = [0; 3];
    c[order[0]] = r % p[order[0]];
    c[order[1]] = (r / p[order[0]]) % p[order[1]];
    c[order[2]] = r / (p[order[0]] * p[order[1]]);
    c
}

/// Every factoring of `n` into three counts, Px outermost and Pz innermost (LAMMPS' order).
fn factors(n: usize) -> Vec<[usize; 3]> {
    let mut out = vec![];
    for i in (1..=n).filter(|i| n % i == 0) {
        let rest = n / i;
        for j in (1..=rest).filter(|j| rest % j == 0) {
            out.push([i, j, rest / j]);
        }
    }
    out
}

/// Drop the factorings `keep` refuses the way LAMMPS culls them: the last one takes the place
/// of each removed one (which changes the order, and so which of equal surfaces wins).
fn cull<T>(list: &mut Vec<T>, keep: impl Fn(&T) -> bool) {
    let mut i = 0;
    while i < list.len() {
        if keep(&list[i]) {
            i += 1;
        } else {
            list.swap_remove(i);
        }
    }
}

fn fits(p: &[usize; 3], user: &[Option<usize>; 3]) -> bool {
    (0..3).all(|d| user[d].is_none_or(|u| u == p[d]))
}

/// The index of the first factoring with the least sub-domain surface, the box's face areas
/// (`areas`: xy, xz, yz, [`Domain::face_areas`](crate::engine::domain::Domain::face_areas))
/// divided by `s` (LAMMPS' best_factors).
fn best(list: &[[usize; 3]], areas: [f64; 3], s: [usize; 3]) -> Option<usize> {
    let area = [areas[0] / (s[0] * s[1]) as f64, areas[1] / (s[0] * s[2]) as f64, areas[2] / (s[1] * s[2]) as f64];
    let mut bestsurf = 2.0 * (area[0] + area[1] + area[2]);
    let mut index = None;
    for (m, f) in list.iter().enumerate() {
        let surf = area[0] / f[0] as f64 / f[1] as f64 + area[1] / f[0] as f64 / f[2] as f64 + area[2] / f[1] as f64 / f[2] as f64;
        if surf < bestsurf {
            bestsurf = surf;
            index = Some(m);
        }
    }
    index
}

fn fixed(user: &[Option<usize>; 3]) -> String {
    user.iter().map(|u| u.map_or("*".to_string(), |u| u.to_string())).collect::<Vec<_>>().join(" ")
}

/// LAMMPS' one-level grid (`ProcMap::onelevel_grid`): among the factorings of `n` that agree
/// with the user's counts (and Pz = 1 in 2D), the one with the least sub-domain surface.
pub fn choose_grid(n: usize, user: [Option<usize>; 3], areas: [f64; 3], dimension: usize) -> Result<[usize; 3], String> {
    let mut list = factors(n);
    if dimension == 2 {
        cull(&mut list, |p| p[2] == 1);
    }
    cull(&mut list, |p| fits(p, &user));
    best(&list, areas, [1; 3]).map(|m| list[m]).ok_or_else(|| format!("processors {} cannot be arranged for {n} ranks{}", fixed(&user), if dimension == 2 { " (Pz must be 1 in 2D)" } else { "" }))
}

/// LAMMPS' two-level grid (`ProcMap::twolevel_grid`): node grids times core grids of
/// `ncores`; the grid and the core sub-grid.
fn twolevel_grid(n: usize, user: [Option<usize>; 3], ncores: usize, user_cores: [Option<usize>; 3], areas: [f64; 3], dimension: usize) -> Result<([usize; 3], [usize; 3]), String> {
    if ncores == 0 || n % ncores != 0 {
        return Err(format!("processors grid twolevel needs the number of ranks ({n}) to be a multiple of the cores per node ({ncores})"));
    }
    let mut nodes = factors(n / ncores);
    let mut cores = factors(ncores);
    if dimension == 2 {
        cull(&mut nodes, |p| p[2] == 1);
        cull(&mut cores, |p| p[2] == 1);
    }
    cull(&mut cores, |p| fits(p, &user_cores));
    // node-major, each with the index of its core grid
    let mut combined: Vec<([usize; 3], usize)> = nodes.iter().flat_map(|nf| cores.iter().enumerate().map(move |(k, cf)| ([nf[0] * cf[0], nf[1] * cf[1], nf[2] * cf[2]], k))).collect();
    cull(&mut combined, |(p, _)| fits(p, &user));
    let grids: Vec<[usize; 3]> = combined.iter().map(|c| c.0).collect();
    let m = best(&grids, areas, [1; 3]).ok_or_else(|| format!("processors {} grid twolevel {ncores} {} cannot be arranged for {n} ranks", fixed(&user), fixed(&user_cores)))?;
    Ok((combined[m].0, cores[combined[m].1]))
}

/// The layout a run on `n` ranks uses: the grid (`settings` and the box's face areas `areas`)
/// and each rank's place.
pub fn layout(n: usize, settings: &ProcSettings, areas: [f64; 3], dimension: usize) -> Result<Layout, String> {
    let ijk_or_xyz = |m: MapStyle| match m {
        MapStyle::Ijk(o) => o,
        _ => [0, 1, 2],
    };
    match &settings.grid {
        GridStyle::OneLevel => {
            let procs = choose_grid(n, settings.user, areas, dimension)?;
            Ok(match settings.map {
                MapStyle::Cart | MapStyle::CartReorder => Layout::cartesian(procs),
                MapStyle::Ijk(o) => Layout::from_places(procs, (0..n).map(|r| ijk(r, procs, o)).collect())?,
            })
        }
        GridStyle::TwoLevel { ncores, user_cores } => {
            let (procs, cores) = twolevel_grid(n, settings.user, *ncores, *user_cores, areas, dimension)?;
            let nodes = [0, 1, 2].map(|d| procs[d] / cores[d]);
            // nodes placed by the map (cart: MPI's numbering), a node's cores x fastest (cart)
            // or by the map's order
            let places = (0..n)
                .map(|r| {
                    let (node, core) = (r / ncores, r % ncores);
                    let (nc, cc) = match settings.map {
                        MapStyle::Cart | MapStyle::CartReorder => (row_major(node, nodes), ijk(core, cores, [0, 1, 2])),
                        m => (ijk(node, nodes, ijk_or_xyz(m)), ijk(core, cores, ijk_or_xyz(m))),
                    };
                    [0, 1, 2].map(|d| nc[d] * cores[d] + cc[d])
                })
                .collect();
            Layout::from_places(procs, places)
        }
        GridStyle::Custom { procs, places } => {
            if procs[0] * procs[1] * procs[2] != n || !fits(procs, &settings.user) {
                return Err(format!("the custom grid {} by {} by {} does not fit {n} ranks and processors {}", procs[0], procs[1], procs[2], fixed(&settings.user)));
            }
            if dimension == 2 && procs[2] != 1 {
                return Err(format!("the custom grid {} by {} by {}: Processor count in z must be 1 for 2d simulation", procs[0], procs[1], procs[2]));
            }
            Layout::from_places(*procs, places.clone())
        }
    }
}

/// Read a `grid custom` file: comment (#) and blank lines, then `Px Py Pz`, then one line `ID I
/// J K` per rank (I, J, K from 1). Errors name the line.
pub fn read_custom(text: &str) -> Result<([usize; 3], Vec<[usize; 3]>), (usize, String)> {
    let mut lines = text.lines().enumerate().map(|(k, l)| (k + 1, l.split('#').next().unwrap_or("")));
    let ints = |(k, l): (usize, &str), n: usize, what: &str| -> Result<Vec<usize>, (usize, String)> {
        let v: Vec<usize> = l.split_whitespace().take(n).map(|w| w.parse::<usize>()).collect::<Result<_, _>>().map_err(|_| (k, format!("expected {what}, found `{}`", l.trim())))?;
        if v.len() < n {
            return Err((k, format!("expected {what}, found `{}`", l.trim())));
        }
        Ok(v)
    };
    let head = lines.by_ref().find(|(_, l)| !l.trim().is_empty()).ok_or((0, "the file has no `Px Py Pz` line".to_string()))?;
    let p = ints(head, 3, "Px Py Pz")?;
    let procs = [p[0], p[1], p[2]];
    if procs.contains(&0) {
        return Err((head.0, "Px Py Pz must be positive".into()));
    }
    let n = procs[0] * procs[1] * procs[2];
    let mut places = vec![None; n];
    for _ in 0..n {
        let line = lines.next().ok_or((0, format!("the file ends before its {n} lines `ID I J K`")))?;
        let v = ints(line, 4, "ID I J K")?;
        if v[0] >= n || places[v[0]].is_some() {
            return Err((line.0, format!("processor ID {} is not one of 0 to {} once", v[0], n - 1)));
        }
        if (0..3).any(|d| v[d + 1] == 0 || v[d + 1] > procs[d]) {
            return Err((line.0, format!("I J K must lie in 1..{} 1..{} 1..{}", procs[0], procs[1], procs[2])));
        }
        places[v[0]] = Some([v[1] - 1, v[2] - 1, v[3] - 1]);
    }
    Ok((procs, places.into_iter().map(|p| p.expect("every ID read")).collect()))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The face areas of an orthogonal box of lengths `p`.
    fn areas(p: [f64; 3]) -> [f64; 3] {
        [p[0] * p[1], p[0] * p[2], p[1] * p[2]]
    }

    #[test]
    fn grids_minimise_the_surface_as_lammps() {
        assert_eq!(choose_grid(4, [None; 3], areas([10.0, 10.0, 10.0]), 3).unwrap(), [1, 2, 2]);
        assert_eq!(choose_grid(2, [None; 3], areas([10.0, 10.0, 10.0]), 3).unwrap(), [1, 1, 2]);
        assert_eq!(choose_grid(2, [None; 3], areas([40.0, 10.0, 10.0]), 3).unwrap(), [2, 1, 1]);
        assert_eq!(choose_grid(4, [None; 3], areas([10.0, 10.0, 1.0]), 2).unwrap(), [2, 2, 1]);
        assert_eq!(choose_grid(8, [Some(8), None, None], areas([10.0, 10.0, 10.0]), 3).unwrap(), [8, 1, 1]);
        assert!(choose_grid(4, [Some(3), None, None], areas([10.0; 3]), 3).is_err());
        assert!(choose_grid(2, [Some(1), Some(1), None], areas([10.0, 10.0, 1.0]), 2).is_err());
    }

    #[test]
    fn equal_surfaces_go_to_the_factoring_lammps_culling_leaves_first() {
        // a square 2D box on 2 ranks: LAMMPS 22 Jul 2025 prints "2 by 1 by 1" (culling 1x1x2
        // moves 2x1x1 ahead of 1x2x1)
        assert_eq!(choose_grid(2, [None; 3], areas([10.0, 10.0, 1.0]), 2).unwrap(), [2, 1, 1]);
        // a cube on 8: 2x2x2; on 6 with Py fixed at 1 (culled order 1x1x6, 6x1x1, 3x1x2, 2x1x3:
        // 3x1x2 and 2x1x3 have equal surfaces)
        assert_eq!(choose_grid(8, [None; 3], areas([10.0; 3]), 3).unwrap(), [2, 2, 2]);
        assert_eq!(choose_grid(6, [None, Some(1), None], areas([10.0; 3]), 3).unwrap(), [3, 1, 2]);
    }

    #[test]
    fn maps_number_the_ranks_as_lammps_documents() {
        let s = |map: &str| ProcSettings { map: MapStyle::parse(map).unwrap(), ..Default::default() };
        // processors doc: xyz on 2x2x2, proc 1 = hi x lo y lo z, proc 2 = lo x hi y lo z, ...
        let l = layout(8, &s("xyz"), areas([10.0; 3]), 3).unwrap();
        assert_eq!(l.procs, [2, 2, 2]);
        let places: Vec<[usize; 3]> = (0..8).map(|r| l.place(r)).collect();
        assert_eq!(places, vec![[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0], [0, 0, 1], [1, 0, 1], [0, 1, 1], [1, 1, 1]]);
        // cart: MPI's row-major numbering, z fastest (zyx)
        assert_eq!(layout(8, &s("cart"), areas([10.0; 3]), 3).unwrap(), layout(8, &s("zyx"), areas([10.0; 3]), 3).unwrap());
        assert_eq!(layout(8, &s("cart"), areas([10.0; 3]), 3).unwrap().place(1), [0, 0, 1]);
        let l = layout(8, &s("yzx"), areas([10.0; 3]), 3).unwrap();
        assert_eq!((l.place(1), l.place(2)), ([0, 1, 0], [0, 0, 1]));
        for r in 0..8 {
            assert_eq!(l.rank_at(l.place(r)), r);
        }
        assert!(MapStyle::parse("xxy").is_none() && MapStyle::parse("cartesian").is_none());
    }

    #[test]
    fn two_levels_give_each_node_a_contiguous_block() {
        // 16 ranks as 4 nodes of 4 cores in a square 2D box: LAMMPS' first best grid is nodes
        // 4x1 of 1x4 cores (its file: rank r at I = r/4 + 1, J = r%4 + 1)
        let s = ProcSettings { grid: GridStyle::TwoLevel { ncores: 4, user_cores: [None; 3] }, ..Default::default() };
        let l = layout(16, &s, areas([10.0, 10.0, 1.0]), 2).unwrap();
        assert_eq!(l.procs, [4, 4, 1]);
        for r in 0..16 {
            assert_eq!(l.place(r), [r / 4, r % 4, 0]);
        }
        // 2x2x1 cores per node with map xyz: a node's ranks fill a 2x2 square x fastest
        let s = ProcSettings { grid: GridStyle::TwoLevel { ncores: 4, user_cores: [Some(2), Some(2), Some(1)] }, map: MapStyle::Ijk([0, 1, 2]), ..Default::default() };
        let l = layout(8, &s, areas([10.0; 3]), 3).unwrap();
        assert_eq!((0..4).map(|r| l.place(r)).collect::<Vec<_>>(), vec![[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0]]);
        assert_eq!(l.place(4), [0, 0, 1]);
        let s = ProcSettings { grid: GridStyle::TwoLevel { ncores: 3, user_cores: [None; 3] }, ..Default::default() };
        assert!(layout(8, &s, areas([10.0; 3]), 3).is_err());
    }

    #[test]
    fn custom_files_are_read_and_checked() {
        let (procs, places) = read_custom("# a grid\n\n2 1 1\n1 1 1 1\n0 2 1 1\n").unwrap();
        assert_eq!(procs, [2, 1, 1]);
        assert_eq!(places, vec![[1, 0, 0], [0, 0, 0]]);
        let s = ProcSettings { grid: GridStyle::Custom { procs, places }, ..Default::default() };
        assert_eq!(layout(2, &s, areas([10.0; 3]), 3).unwrap().rank_at([0, 0, 0]), 1);
        assert!(layout(4, &s, areas([10.0; 3]), 3).is_err());
        let (procs, places) = read_custom("1 1 2\n0 1 1 1\n1 1 1 2\n").unwrap();
        let s = ProcSettings { grid: GridStyle::Custom { procs, places }, ..Default::default() };
        assert!(layout(2, &s, areas([10.0; 3]), 3).is_ok() && layout(2, &s, areas([10.0, 10.0, 1.0]), 2).is_err());
        assert_eq!(read_custom("2 1 1\n0 1 1 1\n0 2 1 1\n").unwrap_err().0, 3);
        assert_eq!(read_custom("2 1 1\n0 1 1 1\n1 3 1 1\n").unwrap_err().0, 3);
        assert!(read_custom("2 1 1\n0 1 1 1\n").is_err());
        assert_eq!(read_custom("2 x 1\n").unwrap_err().0, 1);
    }

    #[test]
    fn the_file_lists_each_rank_as_lammps_writes_it() {
        let l = Layout::cartesian([1, 1, 2]);
        let text = l.file_text(&["h".to_string(), "h".to_string()]);
        assert!(text.starts_with("LAMMPS mapping of processors to 3d grid\npartition = 1\nPx Py Pz = 1 1 2\n"), "{text}");
        assert!(text.ends_with("\n0 0 0: 1 1 1: h\n1 1 1: 1 1 2: h\n"), "{text}");
    }
}
