"""dmhs driven from Python with the API of LAMMPS' ``lammps`` module.

A LAMMPS user's script changes one line::

    from dmhs import lammps          # instead of: from lammps import lammps

    with lammps(cmdargs=["-screen", "none", "-log", "none"]) as lmp:
        lmp.file("in.melt")
        x = lmp.numpy.extract_atom("x")      # (nlocal, 3) float64 array

Differences from LAMMPS (docs/python.md): arrays are copies of the engine's data, never views
(write back with ``scatter_atoms``); ``extract_atom`` returns numpy arrays where LAMMPS returns
ctypes pointers (indexing ``x[i][k]`` works the same); engine errors raise :class:`DmhsError`
(a subclass of ``Exception``, as LAMMPS' errors are) carrying the located message
(``file:line:col``); names dmhs does not know raise instead of returning ``None``.

``run`` releases the GIL, and Ctrl-C (KeyboardInterrupt) stops a run at its next step: the
instance stays usable, at the step where the run stopped.
"""

import ctypes
import threading

from . import constants
from .constants import *  # noqa: F401,F403  (LAMMPS' module exports them too)
from ._dmhs import Core as _Core, DmhsError, DMHS_VERSION

__all__ = ["lammps", "DmhsError", "constants", "numpy_wrapper"] + [n for n in dir(constants) if n.isupper()]
__version__ = DMHS_VERSION


def _to_numpy(packed):
    """(dtype, bytearray, shape) from the extension -> a numpy array that owns a copy."""
    import numpy as np

    dtype, buf, shape = packed
    return np.frombuffer(buf, dtype=np.dtype(dtype)).reshape(shape)


def _value(result):
    return _to_numpy(result) if isinstance(result, tuple) else result


class lammps:
    """One dmhs simulation, driven as ``lammps.lammps`` drives one LAMMPS instance.

    ``cmdargs``: LAMMPS command-line flags; dmhs honours ``-var``/``-v``, ``-log``,
    ``-screen none``, ``-echo``, ``-nocite`` and its own ``-threads N``; other flags raise.
    ``name`` (LAMMPS' shared-library suffix) is ignored; ``ptr`` (attach to an existing
    instance) is not supported; ``comm`` must be None or a communicator of one process.
    """

    def __init__(self, name="", cmdargs=None, ptr=None, comm=None):
        if ptr is not None:
            raise DmhsError("lammps(ptr=...): dmhs cannot attach to an existing instance")
        if comm is not None and getattr(comm, "Get_size", lambda: 1)() != 1:
            raise DmhsError("lammps(comm=...): dmhs runs on one process (threads: cmdargs -threads N)")
        self._core = _Core([str(a) for a in (cmdargs or [])])
        self._numpy = None
        self._running = False

    # ---- life cycle -------------------------------------------------------------------
    def close(self):
        """Destroy the simulation; any later call on this instance raises DmhsError."""
        if getattr(self, "_core", None) is not None:
            self._core.close()

    def finalize(self):
        """As LAMMPS: close (dmhs has no MPI or accelerator state to shut down)."""
        self.close()

    def __del__(self):
        try:
            self.close()
        except Exception:
            pass

    def __enter__(self):
        return self

    def __exit__(self, ex_type, ex_value, ex_traceback):
        self.close()

    @property
    def numpy(self):
        """The numpy interface (``lmp.numpy.extract_atom`` ...), as LAMMPS' ``numpy_wrapper``."""
        if self._numpy is None:
            self._numpy = numpy_wrapper(self)
        return self._numpy

    @property
    def has_exceptions(self):
        return True

    @property
    def has_mpi_support(self):
        return False

    @property
    def is_running(self):
        return self._running

    def version(self):
        """The LAMMPS version whose behaviour dmhs follows (22 Jul 2025 -> 20250722)."""
        return self._core.version()

    # ---- commands ---------------------------------------------------------------------
    def _execute(self, method, *args):
        """Run a command on a worker thread (the GIL is released while the engine works) and
        wait for it here, so that Ctrl-C raises KeyboardInterrupt in this thread: the run is
        cancelled at its next step and the instance stays usable."""
        # before the command's thread starts, so that a Ctrl-C from now on is never lost
        self._core.clear_cancel()
        if threading.current_thread() is not threading.main_thread():
            # signals only reach the main thread: run here
            return self._run_flagged(method, *args)
        box = {}
        done = threading.Event()

        def work():
            try:
                box["result"] = self._run_flagged(method, *args)
            except BaseException as e:  # handed to the waiting thread
                box["error"] = e
            finally:
                done.set()

        threading.Thread(target=work, name="dmhs-command", daemon=True).start()
        interrupted = False
        while True:
            # Ctrl-C may land anywhere in this loop: cancel the run and keep waiting for it
            # (an Event, not Thread.join: an interrupted join can mark a live thread stopped)
            try:
                while not done.wait(0.05):
                    pass
                break
            except KeyboardInterrupt:
                interrupted = True
                self._core.cancel()
        if interrupted:
            raise KeyboardInterrupt("dmhs run interrupted; the instance is still usable")
        if "error" in box:
            raise box.pop("error")
        return box.get("result")

    def _run_flagged(self, method, *args):
        self._running = True
        try:
            return method(*args)
        finally:
            self._running = False

    def file(self, path):
        """Run the commands of an input file."""
        self._execute(self._core.file, str(path))

    def command(self, cmd):
        """Run one command line."""
        self._execute(self._core.command, str(cmd))

    def commands_list(self, cmdlist):
        """Run a list of command lines (joined as lines of one script, as LAMMPS)."""
        self._execute(self._core.commands_string, "<commands_list>", "\n".join(str(c) for c in cmdlist))

    def commands_string(self, multicmd):
        """Run a block of commands separated by newlines."""
        self._execute(self._core.commands_string, "<commands_string>", str(multicmd))

    def flush_buffers(self):
        """Nothing to do: dmhs flushes its log and screen after every command."""

    # ---- global data ------------------------------------------------------------------
    def get_natoms(self):
        return self._core.get_natoms()

    def get_thermo(self, name):
        """The value of a thermo keyword now (e.g. "temp", "pe", "step", "c_ID", "v_name")."""
        return self._core.get_thermo(name)

    def extract_global(self, name, dtype=constants.LAMMPS_AUTODETECT):
        """A global property: ints, floats, strings; boxlo/boxhi/periodicity as 3-lists."""
        return self._core.extract_global(name)

    def extract_setting(self, name):
        """An integer setting: dimension, box_exist, nlocal, nghost, nall, nmax, ntypes, the
        topology type counts, bigint/tagint/imageint sizes, newton flags, atom-style flags."""
        return self._core.extract_setting(name)

    def extract_box(self):
        """(boxlo, boxhi, xy, yz, xz, periodicity, box_change) as LAMMPS."""
        g = self._core.extract_global
        return g("boxlo"), g("boxhi"), 0.0, 0.0, 0.0, g("periodicity"), 0

    def reset_box(self, boxlo, boxhi, xy, yz, xz):
        """New box bounds (orthogonal boxes only: xy, yz, xz must be 0)."""
        self._core.reset_box([float(v) for v in boxlo], [float(v) for v in boxhi], float(xy), float(yz), float(xz))

    # ---- per-atom data ----------------------------------------------------------------
    def extract_atom(self, name, dtype=constants.LAMMPS_AUTODETECT):
        """Per-atom data of the owned atoms, as a numpy array (a copy: LAMMPS returns a ctypes
        pointer into its storage; indexing x[i][k] reads the same). "mass" is per type."""
        return _to_numpy(self._core.extract_atom(name))

    def gather_atoms(self, name, dtype, count):
        """All atoms' values sorted by ID as a ctypes array (c_int for dtype 0, c_double for 1)."""
        arr = _to_numpy(self._core.gather_atoms(name, int(dtype), int(count)))
        ctype = ctypes.c_int32 if dtype == 0 else ctypes.c_double
        return (ctype * len(arr)).from_buffer_copy(arr)

    gather = gather_atoms
    gather_atoms_concat = gather_atoms

    def scatter_atoms(self, name, dtype, count, data):
        """Set all atoms' values (sorted by ID) from a ctypes array, a numpy array or a list.
        A dtype that does not match the property or the data, or a wrong count, raises."""
        import numpy as np

        dtype, count = int(dtype), int(count)
        want = {0: np.int32, 1: np.float64}.get(dtype)
        if want is None:
            raise TypeError(f"scatter_atoms: dtype must be 0 (int) or 1 (double), not {dtype}")
        if isinstance(data, ctypes.Array):
            have = {ctypes.c_int32: np.int32, ctypes.c_double: np.float64}.get(data._type_)
            if have is not want:
                raise TypeError(f"scatter_atoms {name}: data is a ctypes array of {data._type_.__name__}, dtype {dtype} needs {'c_int' if dtype == 0 else 'c_double'}")
            arr = np.frombuffer(data, dtype=want)
        elif isinstance(data, np.ndarray):
            if data.dtype != want:
                raise TypeError(f"scatter_atoms {name}: data has dtype {data.dtype}, dtype {dtype} needs {np.dtype(want)}")
            arr = np.ascontiguousarray(data).reshape(-1)
        else:
            arr = np.asarray(list(data))
            if dtype == 0 and arr.size and not np.issubdtype(arr.dtype, np.integer):
                raise TypeError(f"scatter_atoms {name}: dtype 0 needs integers, the data holds {arr.dtype}")
            arr = arr.astype(want)
        self._core.scatter_atoms(name, dtype, count, arr.tobytes())

    scatter = scatter_atoms

    # ---- computes, fixes, variables ---------------------------------------------------
    def extract_compute(self, cid, cstyle, ctype):
        """A compute's global scalar (float), global vector or per-atom data (numpy copies), or
        a size (LMP_SIZE_*: int)."""
        return _value(self._core.extract_compute(cid, int(cstyle), int(ctype)))

    def extract_fix(self, fid, fstyle, ftype, nrow=0, ncol=0):
        """A fix's global scalar, or element ``nrow`` of its global vector (LAMMPS' semantics);
        LMP_SIZE_VECTOR gives the vector's length."""
        v = self._core.extract_fix(fid, int(fstyle), int(ftype), int(nrow))
        return int(v) if ftype == constants.LMP_SIZE_VECTOR else v

    def extract_variable(self, name, group=None, vartype=None):
        """An equal-style value (float) or a string; vartype None detects it from the style."""
        return self._core.extract_variable(name, None if vartype is None else int(vartype))

    def set_string_variable(self, name, value):
        """Set (or create) a string-style variable: 0, or -1 if ``name`` has another style."""
        if not name or value is None or value == "":
            return -1
        return self._core.set_string_variable(str(name), str(value))

    set_variable = set_string_variable

    def set_internal_variable(self, name, value):
        """Set (or create) an internal-style variable: 0, or -1 if ``name`` has another style."""
        return self._core.set_internal_variable(str(name), float(value))


class numpy_wrapper:
    """``lmp.numpy``: the same extractors returning numpy arrays (LAMMPS' numpy_wrapper)."""

    def __init__(self, lmp):
        self.lmp = lmp

    def extract_atom(self, name, dtype=constants.LAMMPS_AUTODETECT, nelem=constants.LAMMPS_AUTODETECT, dim=constants.LAMMPS_AUTODETECT):
        arr = self.lmp.extract_atom(name, dtype)
        if nelem is not None:
            if nelem > len(arr):
                raise DmhsError(f"extract_atom {name}: nelem {nelem} is more than the {len(arr)} owned atoms (dmhs gives no ghost data)")
            arr = arr[:nelem]
        return arr

    def extract_compute(self, cid, cstyle, ctype):
        return self.lmp.extract_compute(cid, cstyle, ctype)

    def extract_fix(self, fid, fstyle, ftype, nrow=0, ncol=0):
        return self.lmp.extract_fix(fid, fstyle, ftype, nrow, ncol)

    def extract_variable(self, name, group=None, vartype=constants.LMP_VAR_EQUAL):
        return self.lmp.extract_variable(name, group, vartype)
