#!/bin/bash
# Full validation run of the point-contact solver (about 40-60 min on 2 shared cores).
# Targets first (timing, not niced), then the studies under nice. Each study keeps finished
# cases in build/validation/point/*.json and resumes where it stopped.
cd "$(dirname "$0")/../.."
# targets: run separately at a quiet moment: python validation/point/targets.py --repeats 3
nice python validation/point/grid_convergence.py
nice python validation/point/cost.py
nice python validation/point/extremes.py
nice python validation/point/fit_check.py
nice python validation/point/robustness.py
