//! `compute ID group heat/flux ke-ID pe-ID stress-ID`: the heat flux of the group's atoms, as
//! LAMMPS' compute heat/flux (Irving-Kirkwood, no volume normalisation), from three per-atom
//! computes: J = sum_i (ke_i + pe_i) v_i - sum_i S_i v_i / nktv2p, with S_i the per-atom stress
//! (xx yy zz xy xz yz, pressure times volume). The global vector is (Jx, Jy, Jz, Jcx, Jcy, Jcz):
//! the total flux and its convective part, summed in LAMMPS' atom order; extensive.

use super::{Compute, PerAtom};
use crate::models::world::World;
use dmhs_parser::{Command, DResult, Diagnostic, Word};

const SYNTAX: &str = "compute ID group heat/flux ke-ID pe-ID stress-ID";

pub struct ComputeHeatFlux {
    id: String,
    groupbit: u32,
    /// The ke/atom, pe/atom and stress/atom computes.
    inputs: [String; 3],
}

impl ComputeHeatFlux {
    pub fn from_lammps(id: String, groupbit: u32, args: &[Word], cmd: &Command, w: &World) -> DResult<Self> {
        if args.len() != 3 {
            return Err(Diagnostic::at(cmd.span, format!("compute heat/flux takes 3 compute IDs, found {} arguments", args.len()), "expected ke-ID pe-ID stress-ID").with_help(format!("syntax: {SYNTAX}")));
        }
        // LAMMPS' checks: ke/atom itself, any compute with per-atom energies, any with
        // per-atom stresses
        let wants: [(&str, fn(&dyn Compute) -> bool); 3] = [
            ("ke/atom", |c| c.style() == "ke/atom"),
            ("pe/atom", |c| c.style() == "pe/atom"),
            ("stress/atom", |c| c.style() == "stress/atom"),
        ];
        for (word, (what, ok)) in args.iter().zip(wants) {
            match w.compute(&word.text) {
                None => return Err(Diagnostic::at(word.span, format!("Could not find compute heat/flux compute ID {}", word.text), "no such compute")),
                Some(c) if !ok(c) => return Err(Diagnostic::at(word.span, format!("Compute heat/flux compute ID {} does not compute {what}", word.text), format!("a {} compute", c.style()))),
                Some(_) => {}
            }
        }
        Ok(ComputeHeatFlux { id, groupbit, inputs: [args[0].text.clone(), args[1].text.clone(), args[2].text.clone()] })
    }

    fn input(&self, w: &World, k: usize) -> Result<PerAtom, String> {
        let c = w.compute(&self.inputs[k]).ok_or_else(|| format!("Could not find compute heat/flux compute ID {}", self.inputs[k]))?;
        c.peratom(w)
    }
}

impl Compute for ComputeHeatFlux {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        "heat/flux"
    }
    fn groupbit(&self) -> u32 {
        self.groupbit
    }
    fn vector(&self, w: &World) -> Result<Vec<f64>, String> {
        let (ke, pe, stress) = (self.input(w, 0)?, self.input(w, 1)?, self.input(w, 2)?);
        let (s, a) = (w.state, &w.state.atoms);
        let (mut jc, mut jv) = ([0.0; 3], [0.0; 3]);
        for &i in s.lammps_order.indices(a.nlocal).iter() {
            if a.mask[i] & self.groupbit == 0 {
                continue;
            }
            let (v, st) = (a.v[i], |c: usize| stress.get(i, c));
            let eng = pe.get(i, 0) + ke.get(i, 0);
            for d in 0..3 {
                jc[d] += eng * v[d];
            }
            jv[0] -= st(0) * v[0] + st(3) * v[1] + st(4) * v[2];
            jv[1] -= st(3) * v[0] + st(1) * v[1] + st(5) * v[2];
            jv[2] -= st(4) * v[0] + st(5) * v[1] + st(2) * v[2];
        }
        let nktv2p = s.units.nktv2p;
        jv.iter_mut().for_each(|j| *j /= nktv2p);
        let mut data = vec![jc[0] + jv[0], jc[1] + jv[1], jc[2] + jv[2], jc[0], jc[1], jc[2]];
        s.sum_ranks(&mut data);
        Ok(data)
    }
    fn size_vector(&self) -> Option<usize> {
        Some(6)
    }
    fn extensive(&self, _index: Option<usize>) -> bool {
        true
    }
    fn reads(&self) -> Vec<(bool, String)> {
        self.inputs.iter().map(|id| (false, id.clone())).collect()
    }
}
