"""Helper processes that compile the later stages' kernels during the film stage
(``ehl_multigrid.app.warmup``)."""

import subprocess
import sys
from types import SimpleNamespace

from ehl_multigrid.app import warmup


def _layer(cold):
    def is_cold(kind):
        if isinstance(cold, Exception):
            raise cold
        return cold

    calls = []
    module = SimpleNamespace(cold=is_cold, compile_kernels=calls.append)
    return SimpleNamespace(load=lambda: module), calls


def _record_popen(monkeypatch):
    launched, real = [], subprocess.Popen

    def popen(args, **kw):
        launched.append((args, kw))
        # a stand-in helper that would run for a while
        return real([sys.executable, "-c", "import time; time.sleep(30)"])

    monkeypatch.setattr(warmup.subprocess, "Popen", popen)
    return launched


def test_a_cold_layer_gets_one_single_threaded_helper_and_stop_ends_it(monkeypatch):
    monkeypatch.delenv("EHL_WARMUP", raising=False)
    ep, _ = _layer(True)
    monkeypatch.setattr(warmup, "_layers", lambda: {"thermal": ep})
    launched = _record_popen(monkeypatch)
    helpers = warmup.start("circular")
    assert len(helpers) == 1
    args, kw = launched[0]
    assert args[1:] == ["-m", "ehl_multigrid.app.warmup", "thermal", "point"]
    assert kw["env"]["NUMBA_NUM_THREADS"] == "1" and kw["stdout"] == subprocess.DEVNULL
    warmup.stop(helpers)
    assert helpers[0].poll() is not None


def test_no_helper_for_a_warm_layer_one_that_cannot_say_or_with_ehl_warmup_0(monkeypatch):
    launched = _record_popen(monkeypatch)
    warm, _ = _layer(False)
    broken, _ = _layer(RuntimeError("no cache"))
    monkeypatch.setattr(warmup, "_layers", lambda: {"a": warm, "b": broken})
    assert warmup.start("line") == []
    cold, _ = _layer(True)
    monkeypatch.setattr(warmup, "_layers", lambda: {"c": cold})
    monkeypatch.setenv("EHL_WARMUP", "0")
    assert warmup.start("line") == []
    assert launched == []


def test_the_helper_compiles_the_named_layer_for_the_kind(monkeypatch):
    ep, calls = _layer(True)
    monkeypatch.setattr(warmup, "_layers", lambda: {"thermal": ep})
    assert warmup.main(["thermal", "line"]) == 0
    assert calls == ["line"]


def test_the_thermal_layer_is_registered_and_says_whether_its_march_is_cached():
    from thermal import warm

    assert "thermal" in warmup._layers()
    assert isinstance(warm.cold("point"), bool)
    assert set(warm.SCENES) == {"line", "point"}
