"""Slide-to-roll values from the command line (``--slip``), shared by ``ehl traction`` and
``ehl tehl``."""

from __future__ import annotations

from ehl_multigrid.model.errors import InputError

#: Most slip values one ``ehl traction`` computes (each is a full thermal solve).
MAX_SLIPS = 1000


def parse_slips(text: str) -> list[float]:
    """``"0,0.1,0.5"`` (S values, thesis 100 % = 1) or ``"min:max:n"``; each S in [-2, 2]."""
    try:
        if ":" in text:
            lo_s, hi_s, n_s = text.split(":")
            lo, hi, n = float(lo_s), float(hi_s), int(n_s)
        else:
            vals = [float(s) for s in text.split(",") if s.strip()]
    except ValueError:
        raise InputError(f"--slip {text!r} must be a comma list of numbers or min:max:n") from None
    if ":" in text:
        if not 1 <= n <= MAX_SLIPS:
            raise InputError(f"--slip {text!r}: n = {n} must be an integer in [1, {MAX_SLIPS}]")
        vals = [lo] if n == 1 else [lo + (hi - lo) * i / (n - 1) for i in range(n)]
    if not vals:
        raise InputError("--slip is empty")
    if len(vals) > MAX_SLIPS:
        raise InputError(f"--slip gives {len(vals)} values; at most {MAX_SLIPS}")
    for v in vals:
        if not -2.0 <= v <= 2.0:  # also catches nan
            raise InputError(f"--slip value {v:g} is outside [-2, 2] (S = 2(u1-u2)/(u1+u2); 2 = pure sliding)")
    return vals
