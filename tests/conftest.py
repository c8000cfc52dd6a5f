import os

import matplotlib

# Tests never open windows; numba uses its on-disk cache (cache=True kernels).
matplotlib.use("Agg")
os.environ.setdefault("MPLBACKEND", "Agg")
