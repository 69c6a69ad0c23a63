#!/usr/bin/env python3
"""Write OUT/quat.txt: the orientations (atom_style bpm/sphere quaternions) at the end of DECK,
as LAMMPS integrates them (`compute property/atom quatw quati quatj quatk`, dumped with %.17g
after the deck's run). Used by regenerate.sh for the bpm_sphere_nve deck (tests/bpm.rs).

    python bpm_quat.py decks/in.bpm_sphere_nve refs/bpm_sphere_nve
"""

import os
import sys
import tempfile

from lammps import lammps


def main():
    deck, out = (os.path.abspath(p) for p in sys.argv[1:3])
    text = open(deck).read()
    with tempfile.TemporaryDirectory() as tmp:
        dump = os.path.join(tmp, "quat.dump")
        extra = ("compute dmhs_q all property/atom quatw quati quatj quatk\n"
                 f"dump dq all custom ${{nsteps}} {dump} id c_dmhs_q[1] c_dmhs_q[2] c_dmhs_q[3] c_dmhs_q[4]\n"
                 "dump_modify dq sort id format float %.17g\nrun ")
        text = text.replace("\nrun ", "\n" + extra, 1)
        os.chdir(os.path.dirname(deck))
        lmp = lammps(cmdargs=["-log", "none", "-screen", "none"])
        lmp.commands_string(text)
        lmp.close()
        last = open(dump).read().rsplit("ITEM: ATOMS", 1)[1].splitlines()[1:]
    with open(os.path.join(out, "quat.txt"), "w") as f:
        f.write("# id quatw quati quatj quatk\n" + "\n".join(l for l in last if l.strip()) + "\n")


if __name__ == "__main__":
    main()
