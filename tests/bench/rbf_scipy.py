#!/usr/bin/env python3
"""scipy's RBFInterpolator on the data of spiralcam's RBF timing (crate/examples/table2.rs, `bench`).

Paper 004's Table 1 lens array (R 2.84 mm, aperture 1 mm, pitch 1 mm, concave, on a Ø10 mm part)
sampled on the 0.04 mm square grid of nodes (i·h, j·h), |i·h|, |j·h| ≤ 5 + 2h (65 025 points), and
evaluated at the 1 500 132 centres of a 1382 × 1382 grid over the part's bounding square that lie
in the part. Prints points per second (one thread) and the mean and largest error (eq 7) against
the lens array's formula, for scipy's default kernel (thin_plate_spline, degree 1) and for
'cubic' (r³, degree 1: the nearest of scipy's kernels to paper 004's −r³ + 4r² + c, which uses
the L1 distance scipy does not offer), both with neighbors=8.

    python3 tests/bench/rbf_scipy.py

Needs numpy and scipy: when they are missing, the script makes a virtual environment in
/tmp/spiralcam-scipy-venv, installs them there from PyPI (once) and runs itself in it.
"""

import os
import subprocess
import sys
import time

VENV = "/tmp/spiralcam-scipy-venv"


def ensure_scipy():
    try:
        import numpy  # noqa: F401
        import scipy  # noqa: F401
    except ImportError:
        python = os.path.join(VENV, "bin", "python")
        if os.environ.get("SPIRALCAM_IN_VENV"):
            sys.exit("numpy/scipy missing even in " + VENV)
        if not os.path.exists(python):
            subprocess.check_call([sys.executable, "-m", "venv", VENV])
            subprocess.check_call([python, "-m", "pip", "install", "--quiet", "numpy", "scipy"])
        env = dict(os.environ, SPIRALCAM_IN_VENV="1")
        os.execve(python, [python] + sys.argv, env)


def lens(x, y):
    """Paper 004 Table 1: concave spherical lenslets on a 1 mm grid, cut where |c| + a/2 <= 5."""
    import numpy as np

    radius, half = 2.84, 0.5
    cx, cy = np.floor(x + 0.5), np.floor(y + 0.5)
    rho2 = (x - cx) ** 2 + (y - cy) ** 2
    cut = cx * cx + cy * cy <= (5.0 - half + 1e-9) ** 2
    inside = (rho2 <= half * half) & cut
    w = np.sqrt(radius * radius - np.minimum(rho2, half * half))
    return np.where(inside, np.sqrt(radius * radius - half * half) - w, 0.0)


def data(h=0.04, part=5.0):
    import numpy as np

    k = int(np.floor((part + 2.0 * h) / h))
    v = np.arange(-k, k + 1) * h
    x, y = np.meshgrid(v, v)
    pts = np.column_stack([x.ravel(), y.ravel()])
    return pts, lens(pts[:, 0], pts[:, 1])


def queries(n=1382, part=5.0):
    import numpy as np

    q = 2.0 * part / n
    v = -part + (np.arange(n) + 0.5) * q
    x, y = np.meshgrid(v, v)
    pts = np.column_stack([x.ravel(), y.ravel()])
    return pts[(pts ** 2).sum(axis=1) <= part * part]


def run():
    ensure_scipy()
    import numpy as np
    import scipy
    from scipy.interpolate import RBFInterpolator

    pts, z = data()
    q = queries()
    truth = lens(q[:, 0], q[:, 1])
    print(f"scipy {scipy.__version__}, numpy {np.__version__}: {len(pts)} data points, {len(q)} queries")
    for kernel in ("thin_plate_spline", "cubic"):
        interp = RBFInterpolator(pts, z, neighbors=8, kernel=kernel)
        t = time.perf_counter()
        f = interp(q)
        s = time.perf_counter() - t
        e = np.abs(f - truth)
        print(
            f"- {kernel} (degree 1, neighbors 8): {len(q)} points in {s:.2f} s: "
            f"{len(q) / s:.0f} points/s; mean error {e.mean() * 1e6:.2f} nm, max {e.max() * 1e6:.1f} nm"
        )


if __name__ == "__main__":
    # One thread, as the Rust figure: BLAS threads off.
    for var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
        os.environ.setdefault(var, "1")
    run()
