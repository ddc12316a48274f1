#!/usr/bin/env python3
"""Side by side: `spiralcam plan` against a vectorised NumPy pipeline of the same job.

The jobs (issue 16's table): the asphere of `crate/jobs/asphere-f20.json` (R 40 mm, k -1.2,
A4 1.5e-6, A6 -2e-9) and the paper 004 lens array (`crate/jobs/lens-array-paper004.json`), both
on a Ø10 mm part with a nose of r 0.5 mm and 100°, constant-angle spirals of 4 000 001 points
(1 000 revolutions of 4 000) and 28 400 001 points (5 000 of 5 680), ISO NC written to a file.

The NumPy pipeline is what a research group writes in an afternoon: the equal-angle spiral from
the point index, one-way compensation as the largest of F(a) = f(ρ_s + r·sin a) + r·cos a over
17 nose angles refined by 4 Newton steps on F'(a) = 0 (paper 003 eqs 19-20), and
`numpy.savetxt` of `G1 X Z C` lines, in chunks of 250 000 points. It is not gouge-checked: it is
a yardstick for the time, not a reference for the heights.

Each row runs spiralcam and then NumPy on the same job, back to back, and prints both times,
their ratio and the 1-minute load average before each (the build machine is shared; peak memory:
`tests/bench/peak_memory.py`).

    python3 tests/bench/plan_numpy.py [--sizes 4000001,28400001] [--only spiralcam|numpy]
                                      [--baseline OTHER_SPIRALCAM_BINARY]

`--baseline` runs another build of the tool on the same job in the same row (before/after).
Times are wall clock and, in brackets, CPU seconds (user + system, all threads).

Needs numpy: when it is missing, the script makes a virtual environment in
/tmp/spiralcam-numpy-venv, installs it there from PyPI (once) and runs itself in it. Build the
command-line tool first (`cargo build --release -p spiralcam`).
"""

import json
import os
import resource
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
VENV = "/tmp/spiralcam-numpy-venv"
CHUNK = 250_000
GRID = 17
NEWTON = 4


def ensure_numpy():
    try:
        import numpy  # noqa: F401
    except ImportError:
        python = os.path.join(VENV, "bin", "python")
        if not os.path.exists(python):
            subprocess.run([sys.executable, "-m", "venv", VENV], check=True)
            subprocess.run([python, "-m", "pip", "install", "-q", "numpy"], check=True)
        os.execv(python, [python] + sys.argv)


def job(kind, points):
    """The job of one row: `kind` 'asphere' or 'lens_array', `points` = revs·ppr + 1."""
    revs = 1000 if points <= 4_000_001 else 5000
    ppr = (points - 1) // revs
    name = "asphere-f20.json" if kind == "asphere" else "lens-array-paper004.json"
    with open(os.path.join(ROOT, "crate", "jobs", name)) as f:
        j = json.load(f)
    j["part"] = {"diameter_mm": 10.0}
    j["strategy"] = {
        "feed_mm_per_rev": 5.0 / revs,
        "sampling": {"type": "constant_angle", "points_per_rev": ppr},
        "direction": "ccw",
        "start_angle_deg": 0.0,
    }
    j["output"] = {"dialect": "iso"}
    return j


def asphere_section(s):
    """f, f', f'' along a radial line (t signed) of the even asphere `s`."""
    import numpy as np

    c = 1.0 / s["radius_mm"]
    k = s.get("conic", 0.0)
    coef = s.get("coefficients", [])

    def section(t, cos_t, sin_t):
        t2 = t * t
        q = np.sqrt(1.0 - (1.0 + k) * c * c * t2)
        f = c * t2 / (1.0 + q)
        f1 = c * t / q
        f2 = c / (q * q * q)
        for i, a in enumerate(coef):
            n = 2 * i + 4
            f = f + a * t ** n
            f1 = f1 + n * a * t ** (n - 1)
            f2 = f2 + n * (n - 1) * a * t ** (n - 2)
        return f, f1, f2

    return section


def lens_array_section(s, part_radius):
    """f, f', f'' along a radial line of the rectangular lens array `s` (paper 004)."""
    import numpy as np

    p, h, big = s["pitch_mm"], s["aperture_mm"] / 2.0, s["lens_radius_mm"]
    sign = 1.0 if s["form"] == "concave" else -1.0
    rim_w = np.sqrt(big * big - h * h)
    cut2 = (part_radius - h + 1e-9) ** 2

    def section(t, cos_t, sin_t):
        x, y = t * cos_t, t * sin_t
        cx, cy = np.floor(x / p + 0.5) * p, np.floor(y / p + 0.5) * p
        dx, dy = x - cx, y - cy
        rho2 = dx * dx + dy * dy
        inside = (rho2 <= h * h) & (cx * cx + cy * cy <= cut2)
        w = np.sqrt(np.maximum(big * big - rho2, 1e-300))
        w3 = w * w * w
        zx, zy = sign * dx / w, sign * dy / w
        zxx = sign * (big * big - dy * dy) / w3
        zxy = sign * dx * dy / w3
        zyy = sign * (big * big - dx * dx) / w3
        f = np.where(inside, sign * (rim_w - w), 0.0)
        f1 = np.where(inside, zx * cos_t + zy * sin_t, 0.0)
        f2 = np.where(
            inside, zxx * cos_t * cos_t + 2.0 * zxy * cos_t * sin_t + zyy * sin_t * sin_t, 0.0
        )
        return f, f1, f2

    return section


def numpy_plan(j, out_path):
    """The NumPy pipeline (see the module docs); returns the number of points written."""
    import numpy as np

    radius = j["part"]["diameter_mm"] / 2.0
    st = j["strategy"]
    feed, ppr = st["feed_mm_per_rev"], st["sampling"]["points_per_rev"]
    n = int(round(radius / feed * ppr)) + 1
    r = j["tool"]["nose_radius_mm"]
    half = np.radians(j["tool"].get("included_angle_deg", 100.0) / 2.0)
    s = j["surface"]
    section = asphere_section(s) if s["type"] == "asphere" else lens_array_section(s, radius)
    grid = np.linspace(-half, half, GRID)
    with open(out_path, "w") as out:
        out.write("G21 G18 G90 G40 G94\nG93\n")
        for start in range(0, n, CHUNK):
            i = np.arange(start, min(n, start + CHUNK), dtype=np.float64)
            rho = radius - i * (feed / ppr)
            theta = i * (2.0 * np.pi / ppr)
            cos_t, sin_t = np.cos(theta), np.sin(theta)
            # F on the grid of nose angles, N x GRID, limited to the part.
            u = r * np.sin(grid)[None, :]
            t = rho[:, None] + u
            f, _, _ = section(t, cos_t[:, None], sin_t[:, None])
            big_f = np.where(np.abs(t) <= radius, f + r * np.cos(grid)[None, :], -np.inf)
            a = grid[np.argmax(big_f, axis=1)]
            for _ in range(NEWTON):
                sa, ca = np.sin(a), np.cos(a)
                f, f1, f2 = section(rho + r * sa, cos_t, sin_t)
                g = r * ca * f1 - r * sa
                gg = r * r * ca * ca * f2 - r * sa * f1 - r * ca
                step = np.where(gg < 0.0, g / np.where(gg < 0.0, gg, -1.0), 0.0)
                a = np.clip(a - step, -half, half)
            sa, ca = np.sin(a), np.cos(a)
            f, _, _ = section(rho + r * sa, cos_t, sin_t)
            z_tip = f + r * ca - r
            rows = np.column_stack((rho, z_tip, np.degrees(theta)))
            np.savetxt(out, rows, fmt="G1 X%.6f Z%.6f C%.5f")
        out.write("M2\n")
    return n


def cpu_children():
    u = resource.getrusage(resource.RUSAGE_CHILDREN)
    return u.ru_utime + u.ru_stime


def cpu_self():
    u = resource.getrusage(resource.RUSAGE_SELF)
    return u.ru_utime + u.ru_stime


def spiralcam_plan(binary, job_path, nc_path):
    """Runs the command-line tool; returns (seconds, CPU seconds, points). The disk's write-back
    of earlier files is finished first (`os.sync`): a 1.4 GB program removed just before would
    otherwise be flushed during the run and count against it."""
    report = nc_path + ".report.json"
    os.sync()
    cpu = cpu_children()
    t = time.perf_counter()
    subprocess.run(
        [binary, "plan", job_path, "--nc", nc_path, "--report", report, "--max-points", "1e9"],
        check=True,
        stderr=subprocess.DEVNULL,
    )
    seconds = time.perf_counter() - t
    cpu = cpu_children() - cpu
    with open(report) as f:
        points = json.load(f)["points"]
    return seconds, cpu, points


def main():
    ensure_numpy()
    args = sys.argv[1:]
    sizes = [4_000_001, 28_400_001]
    only = None
    baseline = None
    while args:
        flag = args.pop(0)
        if flag == "--sizes":
            sizes = [int(float(v)) for v in args.pop(0).split(",")]
        elif flag == "--only":
            only = args.pop(0)
        elif flag == "--baseline":
            baseline = args.pop(0)
        else:
            sys.exit(f"unknown argument {flag}")
    binary = os.path.join(ROOT, "target", "release", "spiralcam")
    tools = [("spiralcam", binary)] + ([("baseline", baseline)] if baseline else [])
    print(f"{os.cpu_count()} CPUs; times: wall s [CPU s], load = 1-min load average before")
    with tempfile.TemporaryDirectory() as tmp:
        for points in sizes:
            for kind in ("asphere", "lens_array"):
                j = job(kind, points)
                job_path = os.path.join(tmp, f"{kind}.json")
                with open(job_path, "w") as f:
                    json.dump(j, f)
                nc = os.path.join(tmp, "out.ngc")
                line = f"{kind:10} {points:>10}:"
                times = {}
                if only in (None, "spiralcam"):
                    for name, path in tools:
                        load = os.getloadavg()[0]
                        t, cpu, n = spiralcam_plan(path, job_path, nc)
                        size = os.path.getsize(nc) / 1e6
                        times[name] = t
                        line += f" {name} {t:6.2f} s [{cpu:5.2f}] ({n / t / 1e6:5.2f} M/s,"
                        line += f" {size:.0f} MB, load {load:.1f});"
                        os.remove(nc)
                if only in (None, "numpy"):
                    load = os.getloadavg()[0]
                    os.sync()
                    cpu = cpu_self()
                    t = time.perf_counter()
                    n = numpy_plan(j, nc)
                    t = time.perf_counter() - t
                    cpu = cpu_self() - cpu
                    times["numpy"] = t
                    line += f" numpy {t:6.2f} s [{cpu:5.2f}] ({n / t / 1e6:5.2f} M/s, load {load:.1f});"
                    os.remove(nc)
                if "numpy" in times:
                    for name, _ in tools:
                        if name in times:
                            line += f" numpy/{name} {times['numpy'] / times[name]:4.1f}x"
                print(line, flush=True)


if __name__ == "__main__":
    main()
