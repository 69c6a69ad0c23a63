//! What the temperature computes with a velocity bias share (LAMMPS' `tempbias` computes
//! temp/partial, temp/com, temp/region, temp/ramp, temp/profile and temp/deform): the thermal velocity each leaves, the degrees of
//! freedom each counts, and the bias that thermostats (`fix_modify temp`) and `velocity ...
//! temp ID bias yes` remove before they scale velocities and restore after (LAMMPS'
//! remove_bias_all, restore_bias_all, reapply_bias_all). Sums run in LAMMPS' atom order.

use crate::engine::region::Region;
use super::Compute;
use crate::engine::state::State;
use crate::models::world::World;

/// The velocity bias of a temperature compute.
#[derive(Clone, Debug, PartialEq)]
pub enum Bias {
    /// compute temp: none.
    None,
    /// temp/partial: only the flagged components are thermal; the others are the bias.
    Partial([bool; 3]),
    /// temp/com: the group's centre-of-mass velocity.
    Com,
    /// temp/region (region ID): an atom outside the region is all bias; the degrees of freedom
    /// are counted with each temperature, from the atoms inside.
    Region(String),
    /// temp/ramp: a velocity component ramped along a coordinate.
    Ramp(Ramp),
    /// temp/profile: the mean velocity of the spatial bin an atom is in.
    Profile(Profile),
    /// temp/deform: the streaming velocity of fix deform's box at the atom's box fractions.
    Deform,
}

/// temp/profile's bins: `nbin` per direction over the box, the `flags` components biased.
#[derive(Clone, Debug, PartialEq)]
pub struct Profile {
    pub flags: [bool; 3],
    pub nbin: [usize; 3],
}

/// The bin of each owned atom of a group (None outside it) and each bin's mean velocity of the
/// flagged components (0 for the others and for empty bins).
struct BinAverages {
    bin: Vec<Option<usize>>,
    mean: Vec<[f64; 3]>,
}

impl Profile {
    /// LAMMPS' bin_assign and bin_average: periodic coordinates folded once into the box, bin
    /// indices truncated and clamped; velocities summed in LAMMPS' atom order, over the ranks.
    fn averages(&self, state: &State, groupbit: u32) -> Result<BinAverages, String> {
        let d = state.domain()?;
        let (a, prd) = (&state.atoms, d.prd());
        let nbins = self.nbin.iter().product::<usize>();
        let bin: Vec<Option<usize>> = (0..a.nlocal)
            .map(|i| {
                (a.mask[i] & groupbit != 0).then(|| {
                    let mut ib = [0usize; 3];
                    for k in (0..3).filter(|&k| self.nbin[k] > 1) {
                        let mut c = a.x[i][k];
                        if d.periodic(k) {
                            if c < d.lo[k] {
                                c += prd[k];
                            }
                            if c >= d.hi[k] {
                                c -= prd[k];
                            }
                        }
                        let invdelta = self.nbin[k] as f64 / prd[k];
                        ib[k] = (((c - d.lo[k]) * invdelta) as i64).clamp(0, self.nbin[k] as i64 - 1) as usize;
                    }
                    self.nbin[0] * self.nbin[1] * ib[2] + self.nbin[0] * ib[1] + ib[0]
                })
            })
            .collect();
        // per bin: the three component sums, then the count
        let mut sums = vec![0.0; 4 * nbins];
        for &i in state.lammps_order.indices(a.nlocal).iter() {
            if let Some(b) = bin[i] {
                for k in (0..3).filter(|&k| self.flags[k]) {
                    sums[4 * b + k] += a.v[i][k];
                }
                sums[4 * b + 3] += 1.0;
            }
        }
        state.sum_ranks(&mut sums);
        let mean = sums
            .chunks(4)
            .map(|s| {
                let n = s[3];
                [0, 1, 2].map(|k| if n > 0.0 { s[k] / n } else { s[k] })
            })
            .collect();
        Ok(BinAverages { bin, mean })
    }
    /// The degrees of freedom the bins' streaming velocities take beyond the centre of mass's
    /// (Evans and Morriss): ncount (nbins - 1), as LAMMPS 22 Jul 2025 counts them (measured:
    /// 3N - 3 - 4 with vx over 5 bins, 3N - 3 - 10 with vx vy over 6, 3N - 3 - 21 with all three
    /// over 8).
    fn nstreaming(&self) -> f64 {
        (self.flags.iter().filter(|&&f| f).count() * (self.nbin.iter().product::<usize>() - 1)) as f64
    }
}

/// temp/ramp's profile (box units): component `vdim` has the bias vlo + f (vhi - vlo), f the
/// position along `dim` between clo and chi, clamped to [0, 1].
#[derive(Clone, Debug, PartialEq)]
pub struct Ramp {
    pub vdim: usize,
    pub vlo: f64,
    pub vhi: f64,
    pub dim: usize,
    pub clo: f64,
    pub chi: f64,
}

impl Ramp {
    /// The ramp velocity at position `x` (LAMMPS' operation order).
    fn at(&self, x: &[f64; 3]) -> f64 {
        let fraction = ((x[self.dim] - self.clo) / (self.chi - self.clo)).max(0.0).min(1.0);
        self.vlo + fraction * (self.vhi - self.vlo)
    }
}

/// A temperature as a compute measures it, copied into the thermostats that `fix_modify temp`
/// points at the compute and used by `velocity ... temp ID`.
#[derive(Clone, Debug, PartialEq)]
pub struct TempSpec {
    pub groupbit: u32,
    /// `compute_modify extra/dof` (None: the dimension).
    pub extra: Option<f64>,
    pub bias: Bias,
}

impl TempSpec {
    pub fn plain(groupbit: u32) -> TempSpec {
        TempSpec { groupbit, extra: None, bias: Bias::None }
    }
    /// The degrees of freedom at setup (LAMMPS' dof_compute) with `fix_dof` removed by fixes;
    /// temp/region has none until it measures.
    pub fn dof(&self, state: &State, fix_dof: f64) -> f64 {
        let d = state.dimension as f64;
        let extra = self.extra.unwrap_or(d);
        let count = state.group_count(self.groupbit) as f64;
        match &self.bias {
            // extra and fix dof spread evenly over the counted components
            Bias::Partial(keep) => {
                let nper = keep.iter().filter(|&&k| k).count() as f64;
                nper * count - (nper / d) * (fix_dof + extra)
            }
            Bias::Region(_) => 0.0,
            Bias::None | Bias::Com | Bias::Ramp(_) | Bias::Deform => d * count - (extra + fix_dof),
            Bias::Profile(p) => d * count - (extra + fix_dof + p.nstreaming()),
        }
    }
    /// The temperature now and the degrees of freedom it used: `dof` (from [`TempSpec::dof`])
    /// except for temp/region, which counts dim * (atoms inside) - extra each time.
    pub fn temperature(&self, state: &State, dof: f64) -> Result<(f64, f64), String> {
        let (t, count) = self.sum_mv2(state)?;
        let u = &state.units;
        if let Bias::Region(_) = self.bias {
            let dof = state.dimension as f64 * count - self.extra.unwrap_or(state.dimension as f64);
            if dof < 0.0 && count > 0.0 {
                return Err("Temperature compute degrees of freedom < 0".into());
            }
            // LAMMPS' operation order for this style: mvv2e t / (dof kB)
            return Ok((if dof > 0.0 { u.mvv2e * t / (dof * u.boltz) } else { 0.0 }, dof));
        }
        let tfactor = if dof > 0.0 { u.mvv2e / (dof * u.boltz) } else { 0.0 };
        Ok((t * tfactor, dof))
    }
    /// sum m |v_thermal|^2 over the group and the atoms counted (LAMMPS order, summed over ranks).
    fn sum_mv2(&self, state: &State) -> Result<(f64, f64), String> {
        let mut s = [0.0; 2];
        self.each_thermal(state, |m, vt| {
            s[0] += (vt[0] * vt[0] + vt[1] * vt[1] + vt[2] * vt[2]) * m;
            s[1] += 1.0;
        })?;
        state.sum_ranks(&mut s);
        Ok((s[0], s[1]))
    }
    /// The kinetic energy tensor of the thermal velocities, mvv2e sum m vt_a vt_b (xx yy zz xy xz yz).
    pub fn tensor(&self, state: &State) -> Result<[f64; 6], String> {
        let mut t = [0.0; 6];
        self.each_thermal(state, |m, v| super::temp::add_tensor(&mut t, m, v))?;
        state.sum_ranks(&mut t);
        for x in &mut t {
            *x *= state.units.mvv2e;
        }
        Ok(t)
    }
    /// Calls `f(mass, thermal velocity)` for each counted atom of the group in LAMMPS' order
    /// (temp/region counts only the atoms inside its region).
    fn each_thermal(&self, state: &State, mut f: impl FnMut(f64, [f64; 3])) -> Result<(), String> {
        let a = &state.atoms;
        let vcm = if self.bias == Bias::Com { state.group_vcm(self.groupbit) } else { [0.0; 3] };
        let region = self.region(state)?;
        let bins = self.bins(state)?;
        let domain = state.domain()?;
        for &i in state.lammps_order.indices(a.nlocal).iter() {
            if a.mask[i] & self.groupbit == 0 || region.is_some_and(|r| !r.matches(a.x[i])) {
                continue;
            }
            let v = a.v[i];
            let vt = match &self.bias {
                Bias::Partial(keep) => [0, 1, 2].map(|k| if keep[k] { v[k] } else { 0.0 }),
                Bias::Com => [v[0] - vcm[0], v[1] - vcm[1], v[2] - vcm[2]],
                Bias::Ramp(r) => {
                    let mut vt = v;
                    vt[r.vdim] -= r.at(&a.x[i]);
                    vt
                }
                Bias::Profile(p) => {
                    let b = bins.as_ref().and_then(|b| b.bin[i].map(|k| b.mean[k])).unwrap_or([0.0; 3]);
                    [0, 1, 2].map(|k| if p.flags[k] { v[k] - b[k] } else { v[k] })
                }
                Bias::Deform => {
                    let s = domain.stream_velocity(a.x[i]);
                    [v[0] - s[0], v[1] - s[1], v[2] - s[2]]
                }
                Bias::None | Bias::Region(_) => v,
            };
            f(state.mass(i), vt);
        }
        Ok(())
    }
    fn bins(&self, state: &State) -> Result<Option<BinAverages>, String> {
        match &self.bias {
            Bias::Profile(p) => p.averages(state, self.groupbit).map(Some),
            _ => Ok(None),
        }
    }
    fn region<'a>(&self, state: &'a State) -> Result<Option<&'a Region>, String> {
        match &self.bias {
            Bias::Region(id) => state.regions.iter().find(|r| &r.id == id).map(Some).ok_or_else(|| format!("Region {id} for compute temp/region does not exist")),
            _ => Ok(None),
        }
    }
    /// The bias of every owned atom of group `over` (zero for the others); None without a bias.
    /// `over` is the compute's group for remove_bias_all (velocity), the group of the fix or
    /// compute that calls LAMMPS' per-atom remove_bias (thermostats, stress/atom): temp/com's
    /// bias is the compute group's centre-of-mass velocity either way.
    pub fn field(&self, state: &State, over: u32) -> Result<Option<Vec<[f64; 3]>>, String> {
        let a = &state.atoms;
        let vcm = if self.bias == Bias::Com { state.group_vcm(self.groupbit) } else { [0.0; 3] };
        let region = self.region(state)?;
        let bins = self.bins(state)?;
        let domain = state.domain()?;
        if self.bias == Bias::None {
            return Ok(None);
        }
        Ok(Some(
            (0..a.nlocal)
                .map(|i| {
                    let v = a.v[i];
                    match &self.bias {
                        _ if a.mask[i] & over == 0 => [0.0; 3],
                        Bias::Partial(keep) => [0, 1, 2].map(|k| if keep[k] { 0.0 } else { v[k] }),
                        Bias::Com => vcm,
                        Bias::Region(_) if region.is_some_and(|r| r.matches(a.x[i])) => [0.0; 3],
                        Bias::Ramp(r) => {
                            let mut b = [0.0; 3];
                            b[r.vdim] = r.at(&a.x[i]);
                            b
                        }
                        // an atom outside the compute's group has no bin: no bias
                        Bias::Profile(p) => {
                            let b = bins.as_ref().and_then(|b| b.bin[i].map(|k| b.mean[k])).unwrap_or([0.0; 3]);
                            [0, 1, 2].map(|k| if p.flags[k] { b[k] } else { 0.0 })
                        }
                        Bias::Deform => domain.stream_velocity(a.x[i]),
                        _ => v,
                    }
                })
                .collect(),
        ))
    }
    /// temp/partial's reapply_bias_all after velocity create: the biased components of the
    /// group's atoms back to 0 (the other styles leave the velocities).
    pub fn reapply(&self, state: &State, v: &mut [[f64; 3]]) {
        if let Bias::Partial(keep) = self.bias {
            for (i, vi) in v.iter_mut().enumerate() {
                if state.atoms.mask[i] & self.groupbit != 0 {
                    for k in (0..3).filter(|&k| !keep[k]) {
                        vi[k] = 0.0;
                    }
                }
            }
        }
    }
}

/// v -= bias (remove_bias) for the atoms of `groupbit`.
pub fn remove(v: &mut [[f64; 3]], mask: &[u32], groupbit: u32, field: &[[f64; 3]]) {
    for ((vi, b), _) in v.iter_mut().zip(field).zip(mask).filter(|(_, &m)| m & groupbit != 0) {
        for k in 0..3 {
            vi[k] -= b[k];
        }
    }
}

/// v += bias (restore_bias) for the atoms of `groupbit`.
pub fn restore(v: &mut [[f64; 3]], mask: &[u32], groupbit: u32, field: &[[f64; 3]]) {
    for ((vi, b), _) in v.iter_mut().zip(field).zip(mask).filter(|(_, &m)| m & groupbit != 0) {
        for k in 0..3 {
            vi[k] += b[k];
        }
    }
}

/// A temperature compute with a bias (the styles differ only in their [`Bias`]).
pub struct ComputeTempBias {
    id: String,
    style: &'static str,
    groupbit: u32,
    bias: Bias,
    dof: super::temp::Dof,
}

impl ComputeTempBias {
    pub fn new(id: String, style: &'static str, groupbit: u32, bias: Bias) -> Self {
        ComputeTempBias { id, style, groupbit, bias, dof: super::temp::Dof::default() }
    }
    fn spec(&self) -> TempSpec {
        TempSpec { groupbit: self.groupbit, extra: self.dof.extra, bias: self.bias.clone() }
    }
    fn count_dof(&self, w: &World) -> f64 {
        self.spec().dof(w.state, w.fix_dof(self.groupbit))
    }
    fn measure(&self, w: &World) -> Result<(f64, f64), String> {
        self.spec().temperature(w.state, self.dof.current(|| self.count_dof(w)))
    }
}

impl Compute for ComputeTempBias {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        self.style
    }
    fn groupbit(&self) -> u32 {
        self.groupbit
    }
    fn scalar(&self, w: &World) -> Result<f64, String> {
        Ok(self.measure(w)?.0)
    }
    fn vector(&self, w: &World) -> Result<Vec<f64>, String> {
        Ok(self.spec().tensor(w.state)?.to_vec())
    }
    fn size_vector(&self) -> Option<usize> {
        Some(6)
    }
    /// The kinetic energy tensor is extensive; the temperature is not.
    fn extensive(&self, index: Option<usize>) -> bool {
        index.is_some()
    }
    fn dof(&self, w: &World) -> Option<f64> {
        Some(match self.bias {
            // counted with the temperature; a region that no longer exists leaves none (the
            // scalar says why)
            Bias::Region(_) => self.measure(w).map_or(0.0, |m| m.1),
            _ => self.dof.current(|| self.count_dof(w)),
        })
    }
    fn setup(&mut self, w: &World) {
        self.dof.at_setup = Some(self.count_dof(w));
    }
    /// temp/deform expects the stream fix deform's `remap v` (or none) keeps.
    fn init_warnings(&self, w: &World) -> Vec<String> {
        if self.bias != Bias::Deform {
            return Vec::new();
        }
        match w.fixes.iter().find(|f| f.style() == "deform") {
            None => vec!["Using compute temp/deform with no fix deform defined".into()],
            Some(f) if f.deform_remap() == Some(crate::models::fix::deform::Remap::X) => vec!["Using compute temp/deform with inconsistent fix deform remap option".into()],
            Some(_) => Vec::new(),
        }
    }
    fn modify_dof(&mut self, extra: Option<f64>, dynamic: Option<bool>) {
        self.dof.modify(extra, dynamic);
    }
    fn temp_spec(&self) -> Option<TempSpec> {
        Some(self.spec())
    }
}
