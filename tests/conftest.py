import os
import sys

# Workers that together fill the cores run their kernels on their share of the threads
# (two workers on two cores: one each; 131 -> 122 s for the default run, docs/testing.md).
# BLAS reads its variables when numpy loads, numba's count is set per test (a test that sets
# its own count does not leak it into the next).
_WORKERS = int(os.environ.get("PYTEST_XDIST_WORKER_COUNT", "1"))
_THREADS_PER_WORKER = max(1, (os.cpu_count() or 1) // _WORKERS)
if "PYTEST_XDIST_WORKER" in os.environ:
    for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
        os.environ.setdefault(_var, str(_THREADS_PER_WORKER))

import matplotlib  # noqa: E402
import pytest  # noqa: E402

# Compiled modules are cached even where the environment sets PYTHONDONTWRITEBYTECODE: the
# assertion-rewritten test modules and the package then compile once, not in every xdist worker
# and CLI subprocess (collection 5.3 s -> 2.6 s per worker; docs/testing.md)
sys.dont_write_bytecode = False

# Tests never open windows; numba uses its on-disk cache (cache=True kernels).
matplotlib.use("Agg")
os.environ.setdefault("MPLBACKEND", "Agg")
# Two xdist workers share two cores: waiting OpenMP threads sleep instead of spinning, as the
# `ehl` command sets them (multigrid.threads.passive_openmp_wait); before numba is imported
os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")

_KERNEL_HELPERS = pytest.StashKey[tuple]()

#: per-test timeout [s] of a `slow` study without its own @pytest.mark.timeout (the default run's
#: is `timeout` in pyproject's [tool.pytest.ini_options])
SLOW_TIMEOUT = 1800


#: seconds a worker waits for the kernel-cache helpers before it compiles for itself
KERNEL_CACHE_WAIT = 300.0


@pytest.hookimpl(tryfirst=True)
def pytest_sessionstart(session: pytest.Session) -> None:
    """On the xdist controller, before the workers start, when numba's cache is fresh (a new
    clone, CI): one helper process per part of tests/kernel_cache.py fills it, each holding a
    lock that the workers wait on before their first test (docs/testing.md, "Workers"), so that
    the workers load the kernels instead of both compiling them. ``EHL_TEST_KERNEL_CACHE=0``
    turns it off."""
    config = session.config
    if (hasattr(config, "workerinput") or config.pluginmanager.getplugin("dsession") is None
            or config.option.collectonly or os.environ.get("EHL_TEST_KERNEL_CACHE") == "0"):
        return
    try:
        import fcntl
    except ImportError:  # no flock: the workers compile for themselves
        return
    import importlib.util
    import subprocess
    import tempfile
    from pathlib import Path

    here = Path(__file__).parent
    spec = importlib.util.spec_from_file_location("_kernel_cache", here / "kernel_cache.py")
    kernel_cache = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(kernel_cache)
    if not kernel_cache.cold():
        return
    # the helpers import the package this process (and so each worker) finds
    import ehl_multigrid

    root = str(Path(ehl_multigrid.__file__).parent.parent)
    env = {**os.environ, "NUMBA_NUM_THREADS": "1",
           "PYTHONPATH": os.pathsep.join(filter(None, [root, os.environ.get("PYTHONPATH")]))}
    folder = Path(tempfile.mkdtemp(prefix="ehl-kernel-cache-"))
    helpers = []
    for part in kernel_cache.PARTS:
        fd = os.open(folder / f"{part}.lock", os.O_CREAT | os.O_RDWR)
        fcntl.flock(fd, fcntl.LOCK_EX)  # held by the helper until it exits
        with open(folder / f"{part}.err", "w") as err:
            helpers.append((part, subprocess.Popen([sys.executable, str(here / "kernel_cache.py"), part],
                                                   env=env, pass_fds=(fd,), stdin=subprocess.DEVNULL,
                                                   stdout=subprocess.DEVNULL, stderr=err)))
        os.close(fd)
    os.environ["EHL_TEST_KERNEL_LOCKS"] = str(folder)
    config.stash[_KERNEL_HELPERS] = (folder, helpers)


@pytest.hookimpl(tryfirst=True)
def pytest_runtestloop(session: pytest.Session) -> None:
    """An xdist worker waits for the kernel-cache helpers (:func:`pytest_sessionstart`) before
    its first test, at most :data:`KERNEL_CACHE_WAIT` seconds."""
    folder = os.environ.get("EHL_TEST_KERNEL_LOCKS")
    if not folder or "PYTEST_XDIST_WORKER" not in os.environ:
        return
    import fcntl
    import time
    from pathlib import Path

    end = time.monotonic() + KERNEL_CACHE_WAIT
    for lock in Path(folder).glob("*.lock"):
        with open(lock) as f:
            while time.monotonic() < end:
                try:
                    fcntl.flock(f, fcntl.LOCK_SH | fcntl.LOCK_NB)
                    break
                except BlockingIOError:
                    time.sleep(0.1)


def pytest_sessionfinish(session: pytest.Session) -> None:
    """The controller ends its kernel-cache helpers (long done unless the run was short) and
    says which failed: not a test failure, the workers compiled what was missing."""
    folder, helpers = session.config.stash.get(_KERNEL_HELPERS, (None, []))
    for part, p in helpers:
        if p.poll() is None:
            p.kill()
            p.wait()
        elif p.returncode:
            last = ((folder / f"{part}.err").read_text().strip().splitlines() or [""])[-1]
            sys.stderr.write(f"tests/kernel_cache.py {part} exited {p.returncode}: {last}\n")
    if folder is not None:
        import shutil

        shutil.rmtree(folder, ignore_errors=True)


#: where the test run started: no test may leave the default output folder there
_LAUNCH_OUT = os.path.join(os.getcwd(), "ehl_out")


@pytest.fixture(autouse=True)
def _no_output_in_the_launch_folder():
    """Fail a test that writes the default ``./ehl_out`` where the run started (a command
    without ``--out`` run outside a temporary folder): nothing is written outside the output
    folders the tests choose."""
    existed = os.path.exists(_LAUNCH_OUT)
    yield
    if not existed and os.path.exists(_LAUNCH_OUT):
        import shutil
        import time

        # a refused command on the other worker creates the folder and removes it at once
        # (app.console.locked_command): only a folder that stays is a test's leftover
        for _ in range(20):
            time.sleep(0.05)
            if not os.path.exists(_LAUNCH_OUT):
                return

        shutil.rmtree(_LAUNCH_OUT, ignore_errors=True)
        pytest.fail(f"the test wrote {_LAUNCH_OUT}: give the command --out under tmp_path, or chdir there")


def pytest_runtest_setup(item: pytest.Item) -> None:
    """An xdist worker's solves use its share of the cores (numba's ceiling stays the machine's,
    so tests that switch threads still can)."""
    if "PYTEST_XDIST_WORKER" in os.environ:
        import numba

        numba.set_num_threads(min(_THREADS_PER_WORKER, numba.config.NUMBA_NUM_THREADS))


def pytest_collection_modifyitems(config: pytest.Config, items: list[pytest.Item]) -> None:
    """Tiers (docs/testing.md): `slow` studies run only when the -m expression names them, so
    the quick tier ``-m "not solver"`` and ``-m solver`` leave them out as the default run
    does; each study gets :data:`SLOW_TIMEOUT` unless it sets its own."""
    run_slow = "slow" in (config.getoption("markexpr", "") or "")
    kept, dropped = [], []
    for item in items:
        if item.get_closest_marker("slow") is None:
            kept.append(item)
            continue
        if not run_slow:
            dropped.append(item)
            continue
        if item.get_closest_marker("timeout") is None:
            item.add_marker(pytest.mark.timeout(SLOW_TIMEOUT))
        kept.append(item)
    if dropped:
        config.hook.pytest_deselected(items=dropped)
        items[:] = kept


@pytest.fixture
def scene_with_feature():
    """``make(name, feature)``: the built-in scene ``name`` with its ``[feature]`` table
    replaced by ``feature``."""
    from ehl_multigrid.model.scene import Scene, load_scene

    def make(name, feature):
        d = load_scene(name).to_dict()
        d["feature"] = feature
        return Scene.from_dict(d)

    return make


#: the two contacts of the issue-41 report: a 10 mm steel ball on a steel flat (50 N) and a
#: 10 mm roller, 10 mm long, on a flat (5000 N); T9 at 60 degC, us 2 m/s, slip 0.05
REPORT_CONTACTS = {
    "ball": {"contact": {"kind": "point"},
             "geometry": {"R1x": 0.01, "R1y": 0.01, "R2x": float("inf"), "R2y": float("inf")},
             "operating": {"load": 50.0, "us": 2.0, "slip": 0.05, "T_oil": 60.0}},
    "roller": {"contact": {"kind": "line", "length": 0.01},
               "geometry": {"R1x": 0.01, "R2x": float("inf")},
               "operating": {"load": 5000.0, "us": 2.0, "slip": 0.05, "T_oil": 60.0}},
}


@pytest.fixture(scope="session")
def report_scene():
    """``write(kind, folder, name, hoil=None) -> Path``: the report's ``"ball"`` or ``"roller"``
    contact as a scene file in ``folder``, with ``[supply] hoil`` [m] when given."""
    import tomli_w

    def write(kind, folder, name, hoil=None):
        d = {"name": name, **REPORT_CONTACTS[kind],
             "solids": {"body1": "steel", "body2": "steel"}, "lubricant": {"preset": "T9"}}
        if hoil is not None:
            d["supply"] = {"hoil": float(hoil)}
        path = folder / f"{name}.toml"
        path.write_text(tomli_w.dumps(d))
        return path

    return write
