"""The FFTs and the DCT-I of the deformation operators, on pocketfft without scipy.fft's dispatch.

``scipy.fft`` passes every call through its backend dispatch and argument checks, about 20 us
a call; the deformation of a coarse grid runs four transforms of a few microseconds each, and a
solve evaluates it thousands of times. These functions call the same pocketfft routines
(``scipy.fft._pocketfft.pypocketfft``) directly when they reproduce ``scipy.fft`` bit for bit
on a probe, checked once per process, and go through ``scipy.fft`` otherwise (another scipy
whose private module moved or changed).

All transforms run on the calling thread unless ``workers`` says otherwise; the arrays are
float64 / complex128.
"""

from __future__ import annotations

import numpy as np

# scipy.fft is imported on the first transform (a line solve on MLMI never needs it)
sfft = _pp = None
_DIRECT: bool | None = None


def _probe() -> bool:
    """Whether the direct calls give scipy.fft's results, bit for bit, on small arrays."""
    global sfft, _pp
    import scipy.fft

    sfft = scipy.fft
    try:  # the routines scipy.fft itself calls; private, hence this probe
        from scipy.fft._pocketfft import pypocketfft as _pp
    except ImportError:  # another scipy
        return False
    rng = np.random.default_rng(7)
    x = rng.random((5, 7))
    try:
        F = sfft.rfft(x, n=12, axis=1)
        c = (rng.random((6, 3)) + 1j * rng.random((6, 3)))
        ok = (np.array_equal(_rfft_direct(x, 12), F)
              and np.array_equal(_irfft_direct(F, 12), sfft.irfft(F, n=12, axis=1))
              and np.array_equal(_dct1_direct(x.copy(), False), sfft.dct(x, type=1, axis=0))
              and np.array_equal(_dct1_direct(x.copy(), True), sfft.idct(x, type=1, axis=0)))
        for inverse in (False, True):
            a = c.copy()
            _fft_direct(a, inverse, 1)
            ok = ok and np.array_equal(a, (sfft.ifft if inverse else sfft.fft)(c, axis=0))
        return bool(ok)
    except Exception:  # noqa: BLE001 - any change of the private API: use scipy.fft
        return False


def direct() -> bool:
    """True when the transforms call pocketfft directly (probed on first use)."""
    global _DIRECT
    if _DIRECT is None:
        _DIRECT = _probe()
    return _DIRECT


def _rfft_direct(x: np.ndarray, n: int) -> np.ndarray:
    m = x.shape[-1]
    if m < n:
        xp = np.zeros(x.shape[:-1] + (n,))
        xp[..., :m] = x
        x = xp
    return _pp.r2c(x, (x.ndim - 1,), True, 0, None, 1)


def _irfft_direct(F: np.ndarray, n: int) -> np.ndarray:
    return _pp.c2r(F, (F.ndim - 1,), n, False, 2, None, 1)


def _dct1_direct(V: np.ndarray, inverse: bool) -> np.ndarray:
    return _pp.dct(V, 1, (0,), 2 if inverse else 0, V, 1)


def _fft_direct(a: np.ndarray, inverse: bool, workers: int) -> np.ndarray:
    return _pp.c2c(a, (0,), not inverse, 2 if inverse else 0, a, workers)


def rfft(x: np.ndarray, n: int) -> np.ndarray:
    """Real-to-complex FFT along the last axis of ``x`` zero-padded to ``n``
    (``scipy.fft.rfft(x, n=n, axis=-1)``)."""
    if direct():
        return _rfft_direct(x, n)
    return sfft.rfft(x, n=n, axis=-1, workers=1)


def irfft(F: np.ndarray, n: int) -> np.ndarray:
    """Inverse of :func:`rfft`: ``n`` real points along the last axis
    (``scipy.fft.irfft(F, n=n, axis=-1)``)."""
    if direct():
        return _irfft_direct(F, n)
    return sfft.irfft(F, n=n, axis=-1, workers=1)


def dct1(V: np.ndarray, inverse: bool = False) -> None:
    """DCT-I (or its inverse) along axis 0 of ``V``, in place (``V`` may be a view)."""
    if direct():
        _dct1_direct(V, inverse)
        return
    r = (sfft.idct if inverse else sfft.dct)(V, type=1, axis=0, overwrite_x=True, workers=1)
    if not np.may_share_memory(r, V):  # pocketfft wrote into a new array
        V[...] = r


def fft_inplace(a: np.ndarray, inverse: bool = False, workers: int = 1) -> None:
    """Complex FFT (or its inverse) along axis 0 of ``a``, in place."""
    if direct():
        _fft_direct(a, inverse, workers)
        return
    r = (sfft.ifft if inverse else sfft.fft)(a, axis=0, overwrite_x=True, workers=workers)
    if not np.may_share_memory(r, a):
        a[...] = r
