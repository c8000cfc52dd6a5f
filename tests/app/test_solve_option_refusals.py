"""``ehl solve --thermal`` refuses every option its path does not read (exit 2, naming the
flag) instead of ignoring it: ``--rigid --thermal`` gave the elastic film, bit for bit."""

import argparse

import pytest

from ehl_multigrid.app.cli import main
from ehl_multigrid.app.solve import add_solve_arguments, refuse_unread_options
from ehl_multigrid.model.errors import InputError

UNREAD = [
    ["--rigid"], ["--tol", "1e-6"], ["--tol-load", "1e-6"], ["--levels", "5"], ["--cycle", "W"],
    ["--cycles", "2"], ["--max-cycles", "3"], ["--deformation", "fft"], ["--viscosity", "barus"],
    ["--density", "incompressible"], ["--xmin", "-3"], ["--xmax", "2"], ["--ymax", "2"],
    ["--full-domain"], ["--solver", "newton"], ["--csv"], ["--ellipticity", "2"], ["--alpha", "2e-8"],
    ["--eta0", "0.1"], ["--p0", "2e8"],
]


@pytest.mark.parametrize("flag", UNREAD, ids=lambda f: f[0])
def test_an_option_the_thermal_solve_does_not_read_is_refused(flag, tmp_path, capsys):
    code = main(["solve", "appendix_c_line_4240N", "--thermal", *flag, "--json", "--no-plots",
                 "--out", str(tmp_path)])
    err = capsys.readouterr().err
    assert code == 2
    assert flag[0] in err and "--thermal" in err


def test_the_options_the_thermal_solve_reads_are_accepted():
    p = argparse.ArgumentParser()
    add_solve_arguments(p)
    args = p.parse_args(["appendix_c_line_4240N", "--thermal", "--contact", "line", "--points", "129", "--nz", "8",
                         "--slip", "0.1", "--accuracy", "none", "--max-points", "257", "--time-budget", "10",
                         "--threads", "1", "--no-compression"])
    from thermal.tehl.cli import solve_mode

    refuse_unread_options(args, "thermal", solve_mode.honoured_options)  # no InputError


def test_a_mode_that_declares_nothing_is_only_given_its_scene():
    p = argparse.ArgumentParser()
    add_solve_arguments(p)
    refuse_unread_options(p.parse_args(["s", "--thermal"]), "thermal", frozenset())
    with pytest.raises(InputError, match="--points"):
        refuse_unread_options(p.parse_args(["s", "--thermal", "--points", "129"]), "thermal", frozenset())


def test_half_domain_with_a_thermal_line_contact_is_refused(tmp_path, capsys):
    code = main(["solve", "appendix_c_line_4240N", "--thermal", "--half", "--json", "--no-plots",
                 "--out", str(tmp_path)])
    assert code == 2 and "--half" in capsys.readouterr().err
