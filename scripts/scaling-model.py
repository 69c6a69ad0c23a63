#!/usr/bin/env python3
"""A model of dmhs's time per step on P ranks (issue 19, docs/performance.md "Scaling beyond this
machine"), calibrated with runs of the 3D LJ benchmark deck here, and its prediction of strong and
weak scaling to 1,000 ranks for a 1e8-particle 3D deck.

    scripts/scaling-model.py [--mpi-bin target/mpi/release/dmhs] [--mpiexec mpiexec.mpich]
        [--repeat 3] [--alpha 1.5e-6] [--bandwidth 12.5e9]

What it runs (examples/bench/in.lj3d, 32,000 atoms; each timing the least of --repeat runs):
  * counts (`-var nsteps 0`) on 1, 2, 4, 8 and 27 ranks: ghosts and list entries per rank, against
    the geometric model below;
  * 200 steps on 1 rank: seconds per list entry (Pair), per atom and step (Modify), per owned or
    ghost atom and rebuild (Neigh);
  * 200 steps on 2 ranks: the most loaded rank's stages against the model's.

The model, per rank, for n = N/P atoms in a cube of side L = (n/rho)^(1/3), list cutoff r (cutoff
plus skin, also the ghost cutoff), rebuilds every k steps:
  ghosts      g = rho ((L + 2r)^3 - L^3)
  entries     E = n z/2 + 3 c L^2   (z = rho 4/3 pi r^3 partners, c = rho^2 pi r^4 / 4 pairs that
              cross a unit area of face; a pair with a ghost is listed on both sides, newton off)
  step        T = E t_pair + n t_int + (n + g) t_nb / k + (m alpha + 2 log2(P) alpha)
                  + g (2 t_ghost + 24 / bandwidth) + (g 120 / bandwidth) / k
with t_ghost a serial run's cost of refreshing one periodic image (packing and unpacking a ghost
cost about one such copy each), m = 26 messages (a 3D grid of at least 3 ranks a side), 24 bytes per ghost per step
(positions), 120 per ghost record at a rebuild, and the network's alpha and bandwidth given as
assumptions (this machine's shared memory is not a network).
"""
import argparse
import math
import os
import re
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DECK = os.path.join(ROOT, "examples/bench/in.lj3d")
RHO, R = 0.8442, 2.8
Z = RHO * 4.0 / 3.0 * math.pi * R ** 3
C = RHO ** 2 * math.pi * R ** 4 / 4.0
STAGES = ["Pair", "Bond", "Neigh", "Comm", "Output", "Modify"]


def run(args, np, extra):
    cmd = [args.mpiexec, "-np", str(np), args.mpi_bin, "-in", DECK, "-threads", "1", "-log", "none"] + extra
    p = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True)
    if p.returncode != 0:
        sys.exit("failed: %s\n%s" % (" ".join(cmd), p.stdout[-2000:] + p.stderr[-2000:]))
    out = p.stdout
    r = {"loop": float(re.search(r"Loop time of (\S+)", out).group(1))}
    for s in STAGES + ["Other"]:
        m = re.search(r"^%s\s*\|(.*)$" % s, out, re.M)
        cols = [float(v) for v in re.findall(r"[-+0-9.eE]+", m.group(1))]
        r[s] = cols
    for key in ["Nlocal", "Nghost", "Neighs"]:
        m = re.search(r"^%s:\s+(\S+) ave (\S+) max (\S+) min" % key, out, re.M)
        r[key] = [float(m.group(k)) for k in (1, 2, 3)]
    r["builds"] = int(re.search(r"Neighbor list builds = (\d+)", out).group(1))
    return r


def best(args, np, extra):
    runs = [run(args, np, extra) for _ in range(args.repeat)]
    return min(runs, key=lambda r: r["loop"])


def geometry(n):
    """Ghosts and list entries per rank for n atoms in a cube."""
    L = (n / RHO) ** (1.0 / 3.0)
    return RHO * ((L + 2 * R) ** 3 - L ** 3), n * Z / 2 + 3 * C * L * L


def box_geometry(N, grid):
    """The same for the LJ deck's box cut into grid[0] x grid[1] x grid[2] sub-domains."""
    side = (N / RHO) ** (1.0 / 3.0)
    l = [side / p for p in grid]
    g = RHO * ((l[0] + 2 * R) * (l[1] + 2 * R) * (l[2] + 2 * R) - l[0] * l[1] * l[2])
    area = l[0] * l[1] + l[0] * l[2] + l[1] * l[2]
    n = N / (grid[0] * grid[1] * grid[2])
    return g, n * Z / 2 + C * area


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--mpi-bin", default=os.path.join(ROOT, "target/mpi/release/dmhs"))
    ap.add_argument("--mpiexec", default="mpiexec.mpich")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--alpha", type=float, default=1.5e-6, help="network latency per message, s (assumed)")
    ap.add_argument("--bandwidth", type=float, default=12.5e9, help="network bandwidth per rank, bytes/s (assumed)")
    args = ap.parse_args()
    N = 32000

    print("## Counts per rank: measured (dmhs, run 0) against the model")
    print("| ranks | grid | ghosts measured | ghosts model | entries measured | entries model |")
    print("|---|---|---|---|---|---|")
    for np, grid in [(1, (1, 1, 1)), (2, (1, 1, 2)), (4, (1, 2, 2)), (8, (2, 2, 2)), (27, (3, 3, 3))]:
        r = run(args, np, ["-var", "nsteps", "0"])
        g, e = box_geometry(N, grid)
        print("| %d | %s | %.0f | %.0f | %.0f | %.0f |" % (np, "x".join(map(str, grid)), r["Nghost"][0], g, r["Neighs"][0], e))

    steps = 200
    one = best(args, 1, [])
    n1, g1, e1 = one["Nlocal"][0], one["Nghost"][0], one["Neighs"][0]
    t_pair = one["Pair"][1] / (steps * e1)
    t_int = one["Modify"][1] / (steps * n1)
    t_nb = one["Neigh"][1] / (one["builds"] * (n1 + g1))
    t_ghost = one["Comm"][1] / (steps * g1)
    k = steps / one["builds"]
    print("\n## Calibration (1 rank, 200 steps, least loop time of %d)" % args.repeat)
    print("loop %.3f s; t_pair %.2f ns per list entry; t_int %.2f ns per atom-step; t_nb %.3f us per atom per rebuild; "
          "t_ghost %.2f ns per ghost-step (a serial run's images); a rebuild every %.1f steps"
          % (one["loop"], t_pair * 1e9, t_int * 1e9, t_nb * 1e6, t_ghost * 1e9, k))

    two = best(args, 2, [])
    g2, e2 = two["Nghost"][0] / 2, two["Neighs"][0] / 2
    n2 = N / 2
    print("\n## Check on 2 ranks (200 steps, least loop time of %d): the most loaded rank's stages against the model" % args.repeat)
    print("| stage | measured s (max over ranks) | model s |")
    print("|---|---|---|")
    print("| Pair | %.3f | %.3f |" % (two["Pair"][2], steps * e2 * t_pair))
    print("| Neigh | %.3f | %.3f |" % (two["Neigh"][2], two["builds"] * (n2 + g2) * t_nb))
    print("| Modify | %.3f | %.3f |" % (two["Modify"][2], steps * n2 * t_int))
    print("| Comm | %.3f (least: %.3f) | %.3f + latency |" % (two["Comm"][2], two["Comm"][0], (steps - two["builds"]) * g2 * 2 * t_ghost))
    print("| loop | %.3f | |" % two["loop"])

    def step_time(n, P):
        g, e = geometry(n)
        m = 0 if P == 1 else min(26, P - 1)
        lat = (m + 2 * math.log2(P)) * args.alpha if P > 1 else 0.0
        # a ghost is packed and unpacked (each about a serial image's copy) and sent
        comm = lat + g * (2 * t_ghost + 24 / args.bandwidth) + (g * 120 / args.bandwidth) / k if P > 1 else g * t_ghost
        return e * t_pair + n * t_int + (n + g) * t_nb / k + comm, comm, g

    print("\n## Strong scaling, 1e8 atoms (alpha %.1f us, %.1f GB/s assumed)" % (args.alpha * 1e6, args.bandwidth / 1e9))
    print("| ranks | atoms per rank | ghosts per rank | step s | comm share | speed-up | efficiency |")
    print("|---|---|---|---|---|---|---|")
    t1 = step_time(1e8, 1)[0]
    for P in [1, 8, 64, 125, 216, 512, 1000]:
        t, comm, g = step_time(1e8 / P, P)
        print("| %d | %.3g | %.3g | %.4g | %.1f%% | %.0f | %.0f%% |" % (P, 1e8 / P, g, t, 100 * comm / t, t1 / t, 100 * t1 / (P * t)))
    print("\n## Weak scaling, 1e5 atoms per rank")
    print("| ranks | atoms | step s | comm share | efficiency |")
    print("|---|---|---|---|---|")
    w1 = step_time(1e5, 1)[0]
    for P in [1, 8, 64, 125, 216, 512, 1000]:
        t, comm, _ = step_time(1e5, P)
        print("| %d | %.3g | %.4g | %.1f%% | %.0f%% |" % (P, 1e5 * P, t, 100 * comm / t, 100 * w1 / t))


if __name__ == "__main__":
    main()
