"""Start-up: registering every subcommand (what each ``ehl`` start does) imports no solver, no
numba kernel and no FFT, so ``ehl solve --help`` and bad-input errors stay fast (measured
0.45 s for ``ehl solve --help`` at load 4)."""

import subprocess
import sys

HEAVY = ("numba", "scipy.fft", "ehl_multigrid.line.solver", "ehl_multigrid.point.fas",
         "thermal.kernels", "thermal.tehl.hierarchy", "ehl_multigrid.transient.solve",
         "ehl_multigrid.starved.line", "mixed.stribeck")


def test_registering_the_subcommands_imports_no_solver():
    code = (
        "import sys\n"
        "from ehl_multigrid.app.cli import build_parser\n"
        "build_parser()\n"
        f"print('loaded:' + ','.join(m for m in {HEAVY!r} if m in sys.modules))\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    line = [x for x in out.stdout.splitlines() if x.startswith("loaded:")][-1]
    assert line == "loaded:", f"imported at start-up: {line[7:]}"
