//! `change_box group-ID x|y|z final lo hi | delta dlo dhi | scale f  xy|xz|yz final t | delta dt
//! boundary x y z  ortho  triclinic  remap [x]  set  [units lattice|box]`, as LAMMPS'
//! ChangeBox: atoms are first wrapped into the current box (and shrink-wrapped faces reset),
//! the parameters are applied in the order given, `remap` maps the group's atoms from the box
//! saved last (at the start, by `set` or by the previous `remap`) to the current one through
//! box fractions, and at the end every owned atom is remapped into a periodic box.

use super::need_box;
use crate::engine::boundary::{reset_shrink_wrap, reset_shrink_wrap_box_coords, to_box, to_fractions};
use crate::engine::domain::Domain;
use crate::sim::Simulation;
use dmhs_parser::{Args, Command, DResult, Diagnostic, SourceMap, Word};

const SYNTAX: &str = "change_box group-ID  x|y|z final lo hi | delta dlo dhi | scale factor  xy|xz|yz final t | delta dt  boundary x y z  ortho  triclinic  remap [x]  set ... [units lattice|box]";

enum Op<'a> {
    /// dimension, flavour (final/delta/scale) and its values (lo, hi or the factor twice)
    Xyz(usize, usize, [f64; 2]),
    /// tilt (0 xy, 1 xz, 2 yz), final (or delta), value
    Tilt(usize, bool, f64, &'a Word),
    /// `ortho` (false) or `triclinic` (true)
    Shape(bool, &'a Word),
    Boundary(&'a [Word]),
    Remap,
    Set,
}

pub fn change_box(sim: &mut Simulation, cmd: &Command, _: &mut SourceMap) -> DResult<()> {
    need_box(sim, cmd)?;
    let mut a = Args::new(cmd, SYNTAX);
    let gw = a.word("group ID")?;
    let bit = sim.state.groups.bit(&gw.text).ok_or_else(|| a.error_at(gw, format!("group `{}` does not exist", gw.text), "unknown group"))?;
    let dim = sim.state.dimension;
    let mut ops = vec![];
    let mut lattice_units = true;
    const PARAMS: &[&str] = &["x", "y", "z", "xy", "xz", "yz", "boundary", "ortho", "triclinic", "remap", "set", "units"];
    if a.peek().is_none() {
        return Err(Diagnostic::at(cmd.span, "change_box needs at least one parameter", "nothing to change").with_help(format!("syntax: {SYNTAX}")));
    }
    while let Some(w) = a.peek() {
        a.skip(1);
        match w.text.as_str() {
            "x" | "y" | "z" => {
                let d = (w.text.as_bytes()[0] - b'x') as usize;
                if dim == 2 && d == 2 {
                    return Err(a.error_at(w, "cannot change box z dimension for a 2d simulation", "z in 2d"));
                }
                let fw = a.peek();
                let flavor = a.choice("change style", &["final", "delta", "scale", "volume"])?;
                let v = match flavor {
                    0 => [a.f64("lo")?, a.f64("hi")?],
                    1 => [a.f64("dlo")?, a.f64("dhi")?],
                    2 => {
                        let f = a.f64("scale factor")?;
                        [f, f]
                    }
                    _ => return Err(a.error_at(fw.unwrap(), "change_box ... volume is not supported by dmhs", "not supported").with_help("use final, delta or scale")),
                };
                ops.push(Op::Xyz(d, flavor, v));
            }
            "boundary" => {
                let words = a.remaining().get(..3).ok_or_else(|| a.error_at(w, "change_box boundary needs 3 values (x y z)", "too few values"))?;
                a.skip(3);
                ops.push(Op::Boundary(words));
            }
            "remap" => {
                // LAMMPS accepts `remap x` (atoms' coordinates); `remap v` is not an option
                if a.peek().is_some_and(|n| n.text == "x") {
                    a.skip(1);
                }
                ops.push(Op::Remap);
            }
            "set" => ops.push(Op::Set),
            "units" => lattice_units = a.choice("units", &["box", "lattice"])? == 1,
            "xy" | "xz" | "yz" => {
                let k = ["xy", "xz", "yz"].iter().position(|t| *t == w.text).unwrap();
                if dim == 2 && k > 0 {
                    return Err(a.error_at(w, "Cannot change_box in xz or yz for 2d simulation", "z tilt in 2d"));
                }
                let flavor = a.choice("change style", &["final", "delta"])?;
                ops.push(Op::Tilt(k, flavor == 0, a.f64("tilt")?, w));
            }
            "ortho" | "triclinic" => {
                if !sim.dumps.is_empty() {
                    return Err(a.error_at(w, "Cannot change box ortho/triclinic with dumps defined", "a dump is defined"));
                }
                ops.push(Op::Shape(w.text == "triclinic", w));
            }
            _ => return Err(a.unknown_keyword(w, PARAMS)),
        }
    }
    let scale = match lattice_units {
        true => sim.state.lattice_scale().map_err(|e| Diagnostic::at(cmd.span, e, "needs a lattice"))?,
        false => [1.0; 3],
    };
    sim.out.print("Changing box ...");
    let st = &mut sim.state;
    st.atoms.clear_ghosts();
    let mut domain = st.domain.clone().unwrap();
    // atoms into the current box first (LAMMPS pbc and reset_box, in box fractions on a
    // triclinic box), then save it
    let tilted = domain.triclinic();
    if tilted {
        to_fractions(&domain, &mut st.atoms);
    }
    for i in 0..st.atoms.nlocal {
        domain.pbc(&mut st.atoms.x[i], &mut st.atoms.image[i], None);
    }
    if let Some(initial) = st.box_initial.as_ref() {
        reset_shrink_wrap(&mut domain, initial, &mut st.atoms);
    }
    if tilted {
        to_box(&domain, &mut st.atoms);
    }
    let mut saved = domain.clone();
    for op in &ops {
        match op {
            Op::Xyz(d, flavor, v) => {
                let d = *d;
                match flavor {
                    0 => {
                        domain.lo[d] = scale[d] * v[0];
                        domain.hi[d] = scale[d] * v[1];
                    }
                    1 => {
                        domain.lo[d] += scale[d] * v[0];
                        domain.hi[d] += scale[d] * v[1];
                    }
                    _ => {
                        let mid = 0.5 * (domain.lo[d] + domain.hi[d]);
                        domain.lo[d] = mid + v[0] * (domain.lo[d] - mid);
                        domain.hi[d] = mid + v[0] * (domain.hi[d] - mid);
                    }
                }
                if !(domain.hi[d] > domain.lo[d]) {
                    return Err(Diagnostic::at(cmd.span, format!("change_box makes the box empty or inverted in {}: {} to {}", ["x", "y", "z"][d], domain.lo[d], domain.hi[d]), "bad box"));
                }
                set_initial_box(&mut domain, &mut st.box_initial);
                sim.out.print(&format!("  {}", crate::deck::box_text(&domain)));
            }
            Op::Tilt(k, fin, v, w) => {
                let Some(tilt) = domain.tilt.as_mut() else {
                    return Err(Diagnostic::at(w.span, "Cannot change box tilt factors for orthogonal box", "orthogonal box").with_help("make it triclinic first: change_box all triclinic"));
                };
                // xy and xz in x lattice spacings, yz in y ones
                let v = scale[if *k == 2 { 1 } else { 0 }] * v;
                tilt[*k] = if *fin { v } else { tilt[*k] + v };
                if let Some(m) = crate::deck::tilt_check(&domain).map_err(|e| Diagnostic::at(w.span, e, "z tilt in 2d"))? {
                    sim.out.print(&m);
                }
                set_initial_box(&mut domain, &mut st.box_initial);
                sim.out.print(&format!("  {}", crate::deck::box_text(&domain)));
            }
            Op::Shape(tri, w) => {
                if !tri && domain.tilts() != [0.0; 3] {
                    return Err(Diagnostic::at(w.span, "Cannot change box to orthogonal when tilt is non-zero", "tilted box"));
                }
                domain.tilt = tri.then_some([0.0; 3]);
                crate::deck::tilt_check(&domain).map_err(|e| Diagnostic::at(w.span, e, "triclinic box"))?;
                set_initial_box(&mut domain, &mut st.box_initial);
                sim.out.print(&format!("  {}", crate::deck::box_text(&domain)));
            }
            Op::Boundary(words) => {
                domain.boundary = super::settings::parse_boundary(words, dim)?;
                crate::deck::tilt_check(&domain).map_err(|e| Diagnostic::at(words[0].span, e, "triclinic box"))?;
                st.boundary = domain.boundary;
                set_initial_box(&mut domain, &mut st.box_initial);
                // image flags of non-periodic dimensions are reset (LAMMPS' warning)
                let mut reset = false;
                for img in st.atoms.image[..st.atoms.nlocal].iter_mut() {
                    for d in (0..3).filter(|&d| !domain.periodic(d)) {
                        reset |= img[d] != 0;
                        img[d] = 0;
                    }
                }
                if reset {
                    sim.out.print("WARNING: Resetting image flags for non-periodic dimensions");
                }
            }
            Op::Set => saved = domain.clone(),
            Op::Remap => {
                for i in 0..st.atoms.nlocal {
                    if st.atoms.mask[i] & bit != 0 {
                        st.atoms.x[i] = remap_point(st.atoms.x[i], &saved, &domain);
                    }
                }
                saved = domain.clone();
            }
        }
    }
    if let Some(initial) = st.box_initial.as_ref() {
        reset_shrink_wrap_box_coords(&mut domain, initial, &mut st.atoms);
    }
    // (LAMMPS leaves the atoms alone when the command only makes the box ortho or triclinic:
    // a remap in a triclinic box moves them through box fractions)
    if ops.iter().any(|o| !matches!(o, Op::Shape(..))) {
        crate::engine::boundary::remap_and_migrate(&mut domain, st.box_initial.as_ref(), &mut st.atoms);
    }
    st.domain = Some(domain);
    st.lists_valid = false;
    Ok(())
}

/// LAMMPS' Domain::set_initial_box after each change: the box becomes the one shrink-wrapped
/// faces keep their margins (1e-4 of its lengths) and `m` faces their bounds from, and its
/// shrink-wrapped (`s`) faces move out by that margin.
fn set_initial_box(domain: &mut Domain, initial: &mut Option<Domain>) {
    *initial = Some(domain.clone());
    *domain = crate::engine::boundary::pad_shrink_faces(domain);
}

/// A point's fractional coordinates in `from`, placed in `to` (LAMMPS x2lamda with the saved
/// box then lamda2x with the current one; h_inv = 1/prd as LAMMPS stores it).
fn remap_point(x: [f64; 3], from: &Domain, to: &Domain) -> [f64; 3] {
    if from.triclinic() || to.triclinic() {
        let mut y = x;
        crate::engine::domain::Dilation::new(from, to).apply(&mut y);
        return y;
    }
    let (pf, pt) = (from.prd(), to.prd());
    std::array::from_fn(|d| {
        let lamda = (1.0 / pf[d]) * (x[d] - from.lo[d]);
        pt[d] * lamda + to.lo[d]
    })
}
