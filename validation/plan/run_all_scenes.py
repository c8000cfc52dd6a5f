"""`ehl run` on every built-in scene: exit code, wall time, what the plan chose and what each
stage reported.

Usage: python validation/plan/run_all_scenes.py [--fidelity standard]
Writes build/validation/plan/run_all_<fidelity>.json (resumes: finished scenes are kept when the
package sources are the same, `_paths.package_hash`).
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import tempfile
from pathlib import Path

from scene_run import run_scene

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from _paths import out_dir, package_hash  # noqa: E402

OUT = out_dir("plan")


def scenes() -> list[str]:
    out = subprocess.run([sys.executable, "-m", "ehl_multigrid", "scenes", "--json"], capture_output=True,
                         text=True, check=True).stdout
    data = json.loads(out)
    return sorted(s["name"] if isinstance(s, dict) else s for s in (data["scenes"] if isinstance(data, dict) else data))


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--fidelity", default="standard", choices=["fast", "standard", "reference"])
    a = ap.parse_args()
    OUT.mkdir(exist_ok=True)
    path = OUT / f"run_all_{a.fidelity}.json"
    code = package_hash()
    done = json.loads(path.read_text()) if path.exists() else {}
    # rows of another package version are computed again, not mixed in
    done = {n: r for n, r in done.items() if r.get("code") == code}
    from tqdm import tqdm

    for name in tqdm(scenes(), desc=f"ehl run ({a.fidelity})"):
        if name in done:
            continue
        with tempfile.TemporaryDirectory() as tmp:
            p, wall = run_scene(name, a.fidelity, tmp)
        row = {"exit_code": p.returncode, "wall_s": wall, "code": code}
        try:
            d = json.loads(p.stdout)
            row["plan"] = d.get("plan")
            film = d.get("film") or {}
            row["film"] = {k: film.get(k) for k in ("Hc", "hc", "hm", "points", "converged", "solver_fallback") if k in film}
            row["stages"] = [k for k in d if k not in ("plan", "hdf5", "report", "scene")]
        except json.JSONDecodeError:
            row["stderr"] = p.stderr[-2000:]
        done[name] = row
        tmpf = path.with_suffix(".tmp")
        tmpf.write_text(json.dumps(done, indent=1))
        tmpf.replace(path)
    ok = sum(1 for r in done.values() if r["exit_code"] == 0)
    print(f"{ok}/{len(done)} scenes exit 0; wall {min(r['wall_s'] for r in done.values()):.1f}-"
          f"{max(r['wall_s'] for r in done.values()):.1f} s")
    for n, r in done.items():
        print(n, r["exit_code"], f"{r['wall_s']:.1f} s", r.get("plan"), r.get("film"))


if __name__ == "__main__":
    main()
