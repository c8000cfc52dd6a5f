"""The meniscus search of a finer grid brackets the root around the coarser grid's root,
stepping towards the contact only while the flux still exceeds the supply: a box next to the
Hertzian edge (X_m = -1.003) ends in the dense Newton last resort (roller bearing with 30 nm at
1025 points: 6.4 s, where the whole search takes 2.6 s) and must not be solved when the root
lies further out."""

import math

import pytest

from ehl_multigrid.starved import meniscus as mn


class FakeFlux:
    """F(X_m) growing with the inlet length, as the box solves give it; records the calls."""

    def __init__(self, root: float, hoil: float = 1.0) -> None:
        self.root, self.hoil, self.calls = root, hoil, []

    def flux(self, x: float) -> float:
        self.calls.append(x)
        return self.hoil * math.exp(-(x - self.root))


@pytest.mark.parametrize("near, root", [(-1.0154, -1.0149), (-1.0149, -1.0154), (-1.2, -1.35), (-1.05, -1.01)])
def test_the_bracket_holds_the_root_and_leaves_positions_beyond_it_unsolved(near, root):
    fm = FakeFlux(root)
    lo, hi = mn._bracket(fm, 1.0, -10.0, near=near)
    assert lo < hi and lo <= root <= hi
    assert fm.flux(lo) >= 1.0 > fm.flux(hi)
    # nothing closer to the contact than the start or the bracket's inner end was solved
    assert max(fm.calls) <= max(hi, near)


def test_a_root_beyond_the_steps_falls_back_to_the_full_scan():
    fm = FakeFlux(-7.5)
    lo, hi = mn._bracket(fm, 1.0, -50.0, near=-1.2)
    assert lo <= -7.5 <= hi
