"""dmhs' own behaviour behind the lammps API: errors, closed instances, the GIL, Ctrl-C."""

import ctypes
import os
import signal
import threading
import time

import numpy as np
import pytest

import dmhs
from conftest import make
from test_parity import LJ_MELT

LONG_RUN = 10_000_000


def test_constants_and_api_surface():
    import dmhs.constants as c

    assert (dmhs.LMP_STYLE_GLOBAL, dmhs.LMP_STYLE_ATOM, dmhs.LMP_STYLE_LOCAL) == (0, 1, 2)
    assert (c.LMP_TYPE_SCALAR, c.LMP_TYPE_VECTOR, c.LMP_TYPE_ARRAY) == (0, 1, 2)
    assert (dmhs.LAMMPS_INT, dmhs.LAMMPS_DOUBLE, dmhs.LMP_VAR_STRING) == (0, 2, 3)
    assert issubclass(dmhs.DmhsError, Exception)
    with dmhs.lammps(cmdargs=["-screen", "none", "-log", "none"]) as lmp:
        assert lmp.version() == 20250722
        assert lmp.has_exceptions and not lmp.has_mpi_support


def test_constants_match_lammps():
    from conftest import lammps_module

    theirs = lammps_module().constants
    for name in dir(dmhs.constants):
        if name.isupper():
            assert getattr(dmhs.constants, name) == getattr(theirs, name), name


def test_cmdargs_var_and_unknown_flag(tmp_path):
    lmp = dmhs.lammps(cmdargs=["-screen", "none", "-log", str(tmp_path / "log.txt"), "-var", "n", "7"])
    assert lmp.extract_variable("n") == "7"
    assert lmp.extract_variable("n", vartype=dmhs.LMP_VAR_EQUAL) == "7"  # as LAMMPS: an index variable is a string
    lmp.command('print "n is ${n}"')
    lmp.close()
    assert "n is 7" in (tmp_path / "log.txt").read_text()
    with pytest.raises(dmhs.DmhsError, match="-sf"):
        dmhs.lammps(cmdargs=["-sf", "omp"])


def test_bad_command_raises_located_error(tmp_path):
    lmp = make("dmhs")
    with pytest.raises(Exception) as e:
        lmp.command("pair_style lj/cutt 2.5")
    assert isinstance(e.value, dmhs.DmhsError)
    assert "<command>:1:12" in str(e.value) and "lj/cut" in str(e.value)
    with pytest.raises(dmhs.DmhsError, match=r"<commands_string>:2:1"):
        lmp.commands_string("print hello\nfrobnicate 3\n")
    # the instance is still usable after errors
    lmp.commands_string(LJ_MELT)
    lmp.command("run 2")
    assert lmp.extract_global("ntimestep") == 2
    deck = tmp_path / "in.bad"
    deck.write_text("# a deck\nprint one\nprint two\n\nmass 1 nonsense\n")
    with pytest.raises(dmhs.DmhsError, match=r"in\.bad:5:8"):
        lmp.file(str(deck))
    lmp.close()


def test_bad_commands_raise_in_lammps_too():
    lmp = make("lammps")
    with pytest.raises(Exception):
        lmp.command("pair_style lj/cutt 2.5")
    lmp.close()


def test_unknown_names_and_wrong_types_raise():
    lmp = make("dmhs")
    lmp.commands_string(LJ_MELT)
    lmp.command("run 0")
    for call in (
        lambda: lmp.extract_global("no_such_thing"),
        lambda: lmp.numpy.extract_atom("no_such_thing"),
        lambda: lmp.extract_atom("radius"),  # not defined by atom_style atomic
        lambda: lmp.get_thermo("no_such_keyword"),
        lambda: lmp.extract_compute("nope", 0, 0),
        lambda: lmp.extract_compute("t", dmhs.LMP_STYLE_LOCAL, dmhs.LMP_TYPE_VECTOR),
        lambda: lmp.extract_fix("nope", 0, 0),
        lambda: lmp.extract_variable("nope"),
        lambda: lmp.gather_atoms("x", 0, 3),  # doubles asked as ints
        lambda: lmp.gather_atoms("x", 1, 2),  # wrong count
        lambda: lmp.reset_box([0, 0, 0], [1, 1, 1], 0.1, 0, 0),
    ):
        with pytest.raises(dmhs.DmhsError):
            call()
    n = lmp.get_natoms()
    with pytest.raises(TypeError, match="dtype"):
        lmp.scatter_atoms("x", 1, 3, (ctypes.c_int32 * (3 * n))())
    with pytest.raises(TypeError, match="dtype"):
        lmp.scatter_atoms("x", 1, 3, np.zeros(3 * n, dtype=np.float32))
    with pytest.raises(TypeError, match="integers"):
        lmp.scatter_atoms("type", 0, 1, [1.5] * n)
    with pytest.raises(dmhs.DmhsError, match="expected"):
        lmp.scatter_atoms("x", 1, 3, np.zeros(3 * n - 3))
    with pytest.raises(dmhs.DmhsError, match="dtype"):
        lmp.scatter_atoms("type", 1, 1, np.ones(n))
    with pytest.raises(dmhs.DmhsError, match="out of range"):
        lmp.scatter_atoms("type", 0, 1, np.full(n, 5, dtype=np.int32))
    lmp.close()


def test_closed_instance_raises():
    lmp = make("dmhs")
    lmp.command("units lj")
    lmp.close()
    for call in (lambda: lmp.command("units lj"), lmp.get_natoms, lambda: lmp.extract_global("dt"), lambda: lmp.numpy.extract_atom("x")):
        with pytest.raises(dmhs.DmhsError, match="closed"):
            call()
    lmp.close()  # closing twice is fine
    with make("dmhs") as lmp2:
        lmp2.command("units lj")
    with pytest.raises(dmhs.DmhsError, match="closed"):
        lmp2.command("units lj")


def test_reset_box():
    lmp = make("dmhs")
    lmp.commands_string(LJ_MELT)
    lo, hi = lmp.extract_global("boxlo"), lmp.extract_global("boxhi")
    lmp.reset_box([v - 0.5 for v in lo], [v + 0.5 for v in hi], 0.0, 0.0, 0.0)
    assert lmp.extract_global("boxlo") == [v - 0.5 for v in lo]
    assert lmp.extract_global("boxhi") == [v + 0.5 for v in hi]
    lmp.command("run 1")
    lmp.close()


def _counting(stop):
    count = [0]

    def spin():
        while not stop.is_set():
            count[0] += 1

    t = threading.Thread(target=spin)
    t.start()
    return count, t


@pytest.mark.parametrize("from_thread", [False, True])
def test_gil_released_during_run(from_thread):
    lmp = make("dmhs", ["-threads", "1"])
    lmp.commands_string(LJ_MELT)
    lmp.command("run 10")
    t0 = time.perf_counter()
    lmp.command("run 200")
    t_run = time.perf_counter() - t0
    steps = max(600, int(200 * 0.5 / t_run))  # about half a second of run
    # a Python thread counts while the run goes on; with the GIL held it would stall
    stop = threading.Event()
    count, counter = _counting(stop)
    time.sleep(0.05)
    before = count[0]
    t0 = time.perf_counter()
    if from_thread:
        worker = threading.Thread(target=lmp.command, args=(f"run {steps}",))
        worker.start()
        worker.join()
    else:
        lmp.command(f"run {steps}")
    elapsed = time.perf_counter() - t0
    during = count[0] - before
    stop.set()
    counter.join()
    # the same counter alone for a moment: its rate
    stop2 = threading.Event()
    count2, counter2 = _counting(stop2)
    time.sleep(0.2)
    stop2.set()
    counter2.join()
    rate = count2[0] / 0.2
    assert elapsed > 0.1, f"the run was too short to tell ({elapsed:.3f} s; 200 steps took {t_run:.3f} s)"
    assert during > 0.2 * rate * elapsed, f"the counter advanced {during} times in {elapsed:.2f} s of run; alone it does {rate:.0f}/s"
    lmp.close()


def test_keyboard_interrupt_stops_a_run_cleanly():
    # a process started in the background by a non-interactive shell inherits SIGINT ignored,
    # and Python then installs no KeyboardInterrupt handler: install it for this test
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        _interrupt_a_long_run()
    finally:
        signal.signal(signal.SIGINT, previous)


def _interrupt_a_long_run():
    lmp = make("dmhs")
    lmp.commands_string(LJ_MELT)
    # the melt's steady push would make a run of millions of steps unstable: a loaded machine
    # can deliver the signal seconds late, and the run must still be going then
    lmp.command("unfix push")
    lmp.command("run 0")
    timer = threading.Timer(0.5, os.kill, (os.getpid(), signal.SIGINT))
    timer.start()
    t0 = time.perf_counter()
    with pytest.raises(KeyboardInterrupt):
        lmp.command(f"run {LONG_RUN}")
    elapsed = time.perf_counter() - t0
    timer.join()
    assert elapsed < 30.0, f"the interrupt took {elapsed:.1f} s to stop the run"
    step = lmp.extract_global("ntimestep")
    assert 0 < step < LONG_RUN
    # still usable: the next run goes on from where the interrupted one stopped
    lmp.command("run 5")
    assert lmp.extract_global("ntimestep") == step + 5
    assert np.all(np.isfinite(lmp.numpy.extract_atom("x")))
    lmp.close()
