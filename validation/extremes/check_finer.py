"""Check converged records of an accuracy map whose own check was skipped (check grid above the
map run's limit: 2049-point results checked on 4097 points, 4097-point ones on 8193): the same
independent check as ``accuracy_map.check_case`` (one grid
finer on the result's box, judged at a quarter of the target), for the cases selected.

Usage: ``python validation/extremes/check_finer.py MAP.json '[{"M": 20.0, "L": 0.0, "theta": 4.0}]' OUT.json``
(each selector's keys must match a record's case). Writes the updated records to OUT.json after
every check; a record already in OUT.json for the same result is not checked again (resumable; a
result solved again since is checked again).
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from _paths import require  # noqa: E402
from accuracy_map import check_case, classify  # noqa: E402


def main() -> None:
    path, selectors, out_path = sys.argv[1], json.loads(sys.argv[2]), sys.argv[3]
    records = json.loads(require(Path(path), "python validation/extremes/accuracy_map.py").read_text())
    out = json.loads(Path(out_path).read_text()) if Path(out_path).is_file() else {}
    for want in selectors:
        for key, rec in records.items():
            if not all(rec["case"].get(a) == b for a, b in want.items()):
                continue
            if key in out and out[key].get("result") == rec["result"]:
                continue
            res = check_case(rec["case"], rec["accuracy"], rec["result"])
            new = {**rec, **res}
            new["class"] = classify(new)
            out[key] = new
            print(json.dumps({"case": rec["case"], "check": res.get("check", {}).get("status"),
                              "difference": res.get("check_difference"), "wrong": res.get("wrong")}), flush=True)
            tmp = Path(out_path).with_suffix(".tmp")
            tmp.write_text(json.dumps(out, indent=1))
            tmp.replace(out_path)


if __name__ == "__main__":
    main()
