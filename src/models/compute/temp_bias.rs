//! What the temperature computes with a velocity bias share (LAMMPS' `tempbias` computes
//! temp/partial, temp/com, temp/region and temp/ramp): the thermal velocity each leaves, the degrees of
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
            Bias::None | Bias::Com | Bias::Ramp(_) => d * count - (extra + fix_dof),
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
                Bias::None | Bias::Region(_) => v,
            };
            f(state.mass(i), vt);
        }
        Ok(())
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
    fn modify_dof(&mut self, extra: Option<f64>, dynamic: Option<bool>) {
        self.dof.modify(extra, dynamic);
    }
    fn temp_spec(&self) -> Option<TempSpec> {
        Some(self.spec())
    }
}
