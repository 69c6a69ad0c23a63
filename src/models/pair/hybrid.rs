//! `pair_style hybrid` and `hybrid/overlay`: several pair styles, each assigned to type pairs
//! by `pair_coeff I J STYLE [k] args...`. With `hybrid` each type pair has at most one style
//! (a later assignment replaces an earlier one); with `hybrid/overlay` the styles add up.

use super::{new_pair_style, PairInput, PairModify, PairOutput, PairSetup, PairStyle, Tally};
use dmhs_parser::{Args, Command, DResult, Diagnostic, Word};
use crate::engine::neighbor::NeighList;
use std::time::Instant;

pub const SYNTAX: &str = "pair_style hybrid|hybrid/overlay style1 args1 style2 args2 ...";
pub const COEFF_SYNTAX: &str = "pair_coeff I J style [k] args...  (k picks among repeated styles; `none` clears a pair under hybrid)";

pub struct Hybrid {
    overlay: bool,
    styles: Vec<Box<dyn PairStyle>>,
    /// For each sub-style, the type pairs assigned to it (row-major over 0..=ntypes).
    assigned: Vec<Vec<bool>>,
    /// Pairs explicitly set to `none`.
    none: Vec<bool>,
    ntypes: usize,
    /// Seconds spent in each sub-style (density and force passes) since the last reset.
    seconds: Vec<f64>,
    /// Per sub-style, the engine's list reduced to its type pairs (None: it has all of them),
    /// made from the list of build `sublists_of`, so a sub-style loops only over its own pairs.
    sublists: Vec<Option<NeighList>>,
    sublists_of: Option<u64>,
    /// The atom types the sub-lists were filtered with (a fix that changes types without a
    /// list rebuild makes them stale too).
    sublists_typ: Vec<usize>,
    /// Each sub-style's own pair_modify settings (`pair_modify pair M ...`); None: the global.
    modify: Vec<Option<PairModify>>,
}

impl Hybrid {
    pub fn from_lammps(name: &Word, args: &[Word], cmd: &Command) -> DResult<Hybrid> {
        let overlay = name.text == "hybrid/overlay";
        if args.is_empty() {
            return Err(Diagnostic::at(cmd.span, "pair_style hybrid needs at least one sub-style", "no sub-style").with_help(format!("syntax: {SYNTAX}")));
        }
        // a word starts a new sub-style if it names a pair style (as LAMMPS decides)
        let supported = super::supported();
        let is_style = |w: &Word| {
            supported.contains(&w.text.as_str()) || dmhs_parser::commands::is_lammps_style(dmhs_parser::commands::StyleKind::Pair, &w.text)
        };
        if !is_style(&args[0]) {
            return Err(Diagnostic::at(args[0].span, format!("`{}` is not a pair style", args[0].text), "expected a pair style name").with_help(format!("syntax: {SYNTAX}")));
        }
        let mut styles = Vec::new();
        let mut k = 0;
        while k < args.len() {
            let start = k + 1;
            let mut end = start;
            while end < args.len() && !is_style(&args[end]) {
                end += 1;
            }
            if args[k].text.starts_with("hybrid") {
                return Err(Diagnostic::at(args[k].span, "pair_style hybrid cannot contain another hybrid style", "not allowed here"));
            }
            styles.push(new_pair_style(&args[k], &args[start..end], cmd)?);
            k = end;
        }
        let seconds = vec![0.0; styles.len()];
        let modify = vec![None; styles.len()];
        Ok(Hybrid { overlay, styles, assigned: vec![], none: vec![], ntypes: 0, seconds, sublists: vec![], sublists_of: None, sublists_typ: vec![], modify })
    }

    fn grow(&mut self, n: usize) {
        if n <= self.ntypes && !self.assigned.is_empty() {
            return;
        }
        let old = self.ntypes;
        let s_old = old + 1;
        let s = n + 1;
        let regrid = |v: &Vec<bool>| {
            let mut g = vec![false; s * s];
            for i in 0..=old {
                for j in 0..=old {
                    if let Some(&b) = v.get(i * s_old + j) {
                        g[i * s + j] = b;
                    }
                }
            }
            g
        };
        let mut assigned: Vec<Vec<bool>> = self.assigned.iter().map(regrid).collect();
        assigned.resize(self.styles.len(), vec![false; s * s]);
        self.assigned = assigned;
        self.none = regrid(&self.none);
        self.ntypes = n;
    }

    /// Which sub-style `pair_coeff` names: the style word and, for a repeated style, an index.
    fn pick(&self, args: &mut Args) -> DResult<Option<usize>> {
        let w = args.word("sub-style name")?;
        if w.text == "none" {
            return Ok(None);
        }
        self.pick_named(args, &w, "pair_coeff").map(Some)
    }

    /// The sub-style named `w` (its instance number next in `args` when listed more than once).
    fn pick_named(&self, args: &mut Args, w: &Word, command: &str) -> DResult<usize> {
        let matches: Vec<usize> = (0..self.styles.len()).filter(|&k| self.styles[k].style() == w.text).collect();
        match matches.len() {
            0 => {
                let names: Vec<&str> = self.styles.iter().map(|s| s.style()).collect();
                Err(args.error_at(w, format!("{command} names `{}`, which is not a sub-style of this pair_style", w.text), format!("sub-styles: {}", names.join(", "))))
            }
            1 => Ok(matches[0]),
            n => {
                let k = args.i64_in("sub-style index", 1, n as i64)? as usize;
                Ok(matches[k - 1])
            }
        }
    }
}

impl Hybrid {
    /// Bring the sub-lists up to date with the engine's list (after a rebuild) and the atom
    /// types; returns true if they were remade.
    fn refresh_sublists(&mut self, input: &PairInput) -> bool {
        let typ = &input.atoms.typ;
        if self.sublists_of == Some(input.list.generation) && self.sublists.len() == self.styles.len() && self.sublists_typ == *typ {
            return false;
        }
        self.sublists_typ.clone_from(typ);
        let s = self.ntypes + 1;
        let n = self.ntypes;
        self.sublists = self
            .assigned
            .iter()
            .map(|a| {
                let all = (1..=n).all(|i| (i..=n).all(|j| a[i * s + j]));
                if all { None } else { Some(input.list.filtered(&input.atoms.typ, a)) }
            })
            .collect();
        self.sublists_of = Some(input.list.generation);
        true
    }

    /// Remake the sub-lists if types changed since the last list build, and let the sub-styles
    /// re-key their contact histories to them (as after a rebuild; no atom moved).
    fn refresh_between_builds(&mut self, input: &PairInput) {
        if self.refresh_sublists(input) {
            let order: Vec<usize> = (0..input.atoms.nlocal).collect();
            for (k, style) in self.styles.iter_mut().enumerate() {
                let sub = Self::sub_input(&self.sublists, k, input);
                style.rebuilt(&sub, &order);
            }
        }
    }

    /// The input of sub-style `k`: its own list, no type filter left to apply.
    fn sub_input<'a>(sublists: &'a [Option<NeighList>], k: usize, input: &PairInput<'a>) -> PairInput<'a> {
        match &sublists[k] {
            Some(list) => PairInput { list, type_filter: None, ..*input },
            None => PairInput { type_filter: None, ..*input },
        }
    }

    /// The type pairs I-J (I <= J) assigned to sub-style `k`, e.g. `1-1 1-2`, or `none`.
    fn pairs_of(&self, k: usize) -> String {
        let s = self.ntypes + 1;
        let pairs: Vec<String> = (1..=self.ntypes)
            .flat_map(|i| (i..=self.ntypes).map(move |j| (i, j)))
            .filter(|&(i, j)| self.assigned.get(k).is_some_and(|a| a[i * s + j]))
            .map(|(i, j)| format!("{i}-{j}"))
            .collect();
        if pairs.is_empty() { "none".to_string() } else { pairs.join(" ") }
    }
}

impl PairStyle for Hybrid {
    fn style(&self) -> &str {
        if self.overlay { "hybrid/overlay" } else { "hybrid" }
    }
    fn sub_styles(&self) -> Vec<&str> {
        self.styles.iter().flat_map(|s| s.sub_styles()).collect()
    }

    fn sub_modify(&mut self, args: &mut Args, global: &PairModify) -> DResult<&mut PairModify> {
        let w = args.word("sub-style name")?;
        let k = self.pick_named(args, &w, "pair_modify pair")?;
        Ok(self.modify[k].get_or_insert(*global))
    }
    fn each_sub_modify(&mut self, f: &mut dyn FnMut(&mut PairModify)) {
        self.modify.iter_mut().flatten().for_each(f);
    }
    fn coeff(&mut self, ilo: usize, ihi: usize, jlo: usize, jhi: usize, args: &mut Args) -> DResult<()> {
        self.grow(ihi.max(jhi));
        let s = self.ntypes + 1;
        let which = self.pick(args)?;
        if let Some(k) = which {
            let rest = args.remaining();
            let mut sub = Args::from_words(rest, rest.first().map(|w| w.span).unwrap_or_default(), args.syntax);
            self.styles[k].coeff(ilo, ihi, jlo, jhi, &mut sub)?;
            args.skip(rest.len());
        } else {
            args.finish()?;
        }
        for i in ilo..=ihi {
            for j in jlo.max(i)..=jhi {
                for (m, a) in self.assigned.iter_mut().enumerate() {
                    let on = match which {
                        Some(k) if m == k => true,
                        _ if self.overlay && which.is_some() => a[i * s + j],
                        _ => false,
                    };
                    a[i * s + j] = on;
                    a[j * s + i] = on;
                }
                let none = which.is_none();
                self.none[i * s + j] = none;
                self.none[j * s + i] = none;
            }
        }
        Ok(())
    }

    fn init_sim(&mut self, setup: &PairSetup) -> Result<(), String> {
        for style in self.styles.iter_mut() {
            style.init_sim(setup)?;
        }
        Ok(())
    }

    fn histories(&mut self) -> Vec<&mut crate::engine::contact_history::ContactHistory> {
        self.styles.iter_mut().flat_map(|s| s.histories()).collect()
    }

    fn init(&mut self, ntypes: usize, modify: &PairModify, _active: Option<&[bool]>) -> Result<(), String> {
        self.grow(ntypes);
        let s = ntypes + 1;
        for i in 1..=ntypes {
            for j in i..=ntypes {
                let any = self.assigned.iter().any(|a| a[i * s + j]) || self.none[i * s + j];
                if !any {
                    // mixed pairs: assigned to a style only if I,I and J,J both use it alone
                    let k_of = |t: usize| {
                        let ks: Vec<usize> = (0..self.styles.len()).filter(|&k| self.assigned[k][t * s + t]).collect();
                        if ks.len() == 1 { Some(ks[0]) } else { None }
                    };
                    match (k_of(i), k_of(j)) {
                        (Some(a), Some(b)) if a == b && i != j => {
                            self.assigned[a][i * s + j] = true;
                            self.assigned[a][j * s + i] = true;
                        }
                        _ => return Err(format!("pair coefficients for types {i} {j} are not set (hybrid pair styles cannot mix different sub-styles)")),
                    }
                }
            }
        }
        for ((style, active), own) in self.styles.iter_mut().zip(&self.assigned).zip(&self.modify) {
            style.init(ntypes, own.as_ref().unwrap_or(modify), Some(active)).map_err(|e| format!("{e} (sub-style {})", style.style()))?;
        }
        check_density_diffusion(&self.styles)
    }

    fn cutoff(&self, it: usize, jt: usize) -> f64 {
        let s = self.ntypes + 1;
        (0..self.styles.len())
            .filter(|&k| self.assigned[k][it * s + jt])
            .map(|k| self.styles[k].cutoff(it, jt))
            .fold(0.0, f64::max)
    }

    /// A size list when every sub-style asks for one (the others' type cutoffs hold their
    /// pairs otherwise: a granular sub-style beside them gets the type-cutoff list, a
    /// superset of LAMMPS' size list, the same forces).
    fn size_list(&self) -> bool {
        self.styles.iter().all(|s| s.size_list())
    }

    fn compute(&mut self, input: &PairInput, out: &mut PairOutput) -> Tally {
        self.refresh_between_builds(input);
        let mut total = Tally::default();
        for (k, style) in self.styles.iter_mut().enumerate() {
            let sub = Self::sub_input(&self.sublists, k, input);
            let t0 = Instant::now();
            total.add(&style.compute(&sub, out));
            self.seconds[k] += t0.elapsed().as_secs_f64();
        }
        total
    }

    fn tally_peratom(&mut self, input: &PairInput, out: &mut crate::engine::tally::PerAtomTally) -> Result<(), String> {
        self.refresh_between_builds(input);
        for (k, style) in self.styles.iter_mut().enumerate() {
            style.tally_peratom(&Self::sub_input(&self.sublists, k, input), out)?;
        }
        Ok(())
    }

    /// hybrid: the largest of the sub-styles' (one style per type pair); hybrid/overlay: their
    /// sum, each sub-style's values in its place (LAMMPS' copy_svector of both).
    fn single_extra(&self) -> Option<usize> {
        let extras: Vec<usize> = self.styles.iter().filter_map(|s| s.single_extra()).collect();
        if extras.is_empty() {
            return None;
        }
        Some(if self.overlay { extras.iter().sum() } else { extras.iter().copied().max().unwrap_or(0) })
    }

    /// LAMMPS' PairHybrid::single: the sum over the sub-styles of the type pair that reach rsq
    /// (each checked against its own cutoff); a sub-style it does not reach leaves zeros.
    fn single(&self, input: &PairInput, i: usize, j: usize, rsq: f64, factor_coul: f64, factor_lj: f64) -> Result<super::Single, String> {
        let s = self.ntypes + 1;
        let (ti, tj) = (input.atoms.typ[i], input.atoms.typ[j]);
        if !self.assigned.iter().any(|a| a[ti * s + tj]) {
            return Err("Invoked pair single on pair style none".into());
        }
        let mut out = super::Single::default();
        let mut at = 0;
        for (k, style) in self.styles.iter().enumerate() {
            let width = if self.overlay { style.single_extra().unwrap_or(0) } else { 0 };
            let cut = style.cutoff(ti, tj);
            if self.assigned[k][ti * s + tj] && rsq < cut * cut {
                if style.single_extra().is_none() {
                    return Err(format!("Pair hybrid sub-style {} does not support single call (compute pair/local)", style.style()));
                }
                let one = style.single(&Self::sub_input(&self.sublists, k, input), i, j, rsq, factor_coul, factor_lj)?;
                out.eng += one.eng;
                out.fpair += one.fpair;
                let n = style.single_extra().unwrap_or(0);
                if at + n > super::MAX_SINGLE_EXTRA {
                    return Err(format!("compute pair/local: the sub-styles of pair hybrid/overlay give more than {} extra values together", super::MAX_SINGLE_EXTRA));
                }
                out.extra[at..at + n].copy_from_slice(&one.extra[..n]);
            }
            at += width;
        }
        Ok(out)
    }

    fn rebuilt(&mut self, input: &PairInput, order: &[usize]) {
        self.refresh_sublists(input);
        for (k, style) in self.styles.iter_mut().enumerate() {
            let sub = Self::sub_input(&self.sublists, k, input);
            style.rebuilt(&sub, order);
        }
    }

    fn needs_type_mass(&self) -> bool {
        self.styles.iter().any(|s| s.needs_type_mass())
    }

    fn density_pass(&mut self, input: &PairInput, rho: &mut [f64]) -> bool {
        self.refresh_between_builds(input);
        let mut any = false;
        for (k, style) in self.styles.iter_mut().enumerate() {
            let sub = Self::sub_input(&self.sublists, k, input);
            let t0 = Instant::now();
            any |= style.density_pass(&sub, rho);
            self.seconds[k] += t0.elapsed().as_secs_f64();
        }
        any
    }

    fn density_diffusivity(&self, t: usize) -> f64 {
        self.styles.iter().map(|s| s.density_diffusivity(t)).sum()
    }

    fn dt_limits(&self) -> Vec<crate::models::Limit> {
        self.styles.iter().flat_map(|s| s.dt_limits()).collect()
    }
    fn sph_info(&self) -> Option<super::SphInfo> {
        // the most restrictive values over the SPH sub-styles
        let infos: Vec<super::SphInfo> = self.styles.iter().filter_map(|s| s.sph_info()).collect();
        let first = infos.first()?.clone();
        Some(infos.iter().skip(1).fold(first, |a, b| super::SphInfo {
            h_min: a.h_min.min(b.h_min),
            c_max: a.c_max.max(b.c_max),
            rho0_min: a.rho0_min.min(b.rho0_min),
            mu_max: match (a.mu_max, b.mu_max) {
                (Some(x), Some(y)) => Some(x.max(y)),
                (x, y) => x.or(y),
            },
            rho0: if a.rho0.iter().any(|&r| r > 0.0) { a.rho0.clone() } else { b.rho0.clone() },
            sound_visc: a.sound_visc.iter().chain(&b.sound_visc).copied().collect(),
        }))
    }

    fn describe(&self) -> String {
        let mut s = self.style().to_string();
        for (k, st) in self.styles.iter().enumerate() {
            let d = st.describe();
            let (first, rest) = d.split_once('\n').map(|(a, b)| (a, format!("\n{b}"))).unwrap_or((&d, String::new()));
            s += &format!("\n  {first} [type pairs {}]{}", self.pairs_of(k), rest.replace('\n', "\n  "));
        }
        s
    }

    fn model_seconds(&self) -> Vec<(String, f64)> {
        self.styles.iter().enumerate().map(|(k, st)| (format!("{} ({})", st.style(), self.pairs_of(k)), self.seconds[k])).collect()
    }

    fn contact_stiffness(&self) -> Option<f64> {
        self.styles.iter().filter_map(|s| s.contact_stiffness()).reduce(f64::max)
    }

    fn well_stiffness(&self) -> Option<f64> {
        self.styles.iter().filter_map(|s| s.well_stiffness()).reduce(f64::max)
    }

    fn reset_model_seconds(&mut self) {
        self.seconds.iter_mut().for_each(|t| *t = 0.0);
    }
}

/// A sub-style that only diffuses density (dmhs/sph/delta) needs an SPH density style
/// beside it with the same rest density for every type it covers.
fn check_density_diffusion(styles: &[Box<dyn PairStyle>]) -> Result<(), String> {
    for (k, style) in styles.iter().enumerate() {
        let Some(rho0) = style.diffuses_density() else { continue };
        let dens: Vec<Vec<f64>> = styles.iter().enumerate().filter(|&(m, _)| m != k).filter_map(|(_, s)| s.sph_info()).map(|i| i.rho0).collect();
        if dens.is_empty() {
            return Err(format!("pair {} adds to the density rate of an SPH density style, and this hybrid has none (add sph/taitwater or sph/taitwater/morris)", style.style()));
        }
        for (t, &r) in rho0.iter().enumerate().skip(1).filter(|&(_, &r)| r > 0.0) {
            let theirs = dens.iter().filter_map(|d| d.get(t).copied()).find(|&x| x > 0.0);
            match theirs {
                None => return Err(format!("pair {}: type {t} has no SPH density style (no rho0 for it in another sub-style)", style.style())),
                Some(x) if x != r => return Err(format!("pair {}: rho0 of type {t} is {r}, the density style's is {x} (they must be the same)", style.style())),
                _ => {}
            }
        }
    }
    Ok(())
}
