"""Peak memory of `spiralcam plan` (NC and CSV written to files) for 1 M and 10 M points.

Memory must stay flat: the planner streams, so the peak resident set should not grow with the
point count. Prints one line per size. Then the machine dynamics, which hold the path (1 M points
of the sine grid `sinusoid-grid-fts.json` at 1 000 points a revolution, each kind of split and
machine limits alone, and the same part at HCAA, whose grid has more samples than points): their
peak against the estimate the plan is admitted on (`dynamics::memory_bytes`, the report's
`estimate.dynamics_memory_bytes` beside its `dynamics_samples`), each run measured alone. Usage: python3 tests/bench/peak_memory.py [BINARY] (default target/release/spiralcam;
build it with `cargo build --release`).
"""
import json
import os
import resource
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def main():
    binary = sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, "target", "release", "spiralcam")
    with open(os.path.join(ROOT, "crate", "jobs", "lens-array-paper004.json")) as f:
        base = json.load(f)
    with tempfile.TemporaryDirectory() as tmp:
        for points in (1_000_000, 10_000_000):
            revs = 1000
            job = json.loads(json.dumps(base))
            job["strategy"]["feed_mm_per_rev"] = 5.0 / revs
            job["strategy"]["sampling"] = {"type": "constant_angle", "points_per_rev": points // revs}
            path = os.path.join(tmp, "job.json")
            with open(path, "w") as f:
                json.dump(job, f)
            nc, csv, report = (os.path.join(tmp, n) for n in ("out.ngc", "out.csv", "report.json"))
            before = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
            start = time.perf_counter()
            subprocess.run([binary, "plan", path, "--nc", nc, "--csv", csv, "--report", report], check=True)
            seconds = time.perf_counter() - start
            peak = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
            if peak < before:
                peak = before
            with open(report) as f:
                r = json.load(f)
            print(
                f"{r['points']:>10} points: peak RSS {peak / 1024:.1f} MiB, {seconds:.2f} s "
                f"({r['points'] / seconds / 1e6:.2f} M points/s), NC {os.path.getsize(nc) / 1e6:.0f} MB, "
                f"CSV {os.path.getsize(csv) / 1e6:.0f} MB"
            )
            for p in (nc, csv):
                os.remove(p)
        dynamics(binary, tmp)


def alone(command):
    """Runs `command`; its peak resident set, KiB (measured in a child of its own)."""
    probe = (
        "import resource, subprocess, sys; subprocess.run(sys.argv[1:], check=True, "
        "stdout=subprocess.DEVNULL); print(resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss)"
    )
    out = subprocess.run([sys.executable, "-c", probe, *command], check=True, capture_output=True)
    return int(out.stdout.split()[-1])


def dynamics(binary, tmp):
    """The dynamics rows (module docs)."""
    with open(os.path.join(ROOT, "crate", "jobs", "sinusoid-grid-fts.json")) as f:
        base = json.load(f)
    base["strategy"]["feed_mm_per_rev"] = 0.004
    base["strategy"]["sampling"] = {"type": "constant_angle", "points_per_rev": 1000}
    hcaa = {"type": "hcaa", "pv_tolerance_um": 0.01}
    kinds = {
        "automatic split": ({"type": "auto"}, None),
        "symmetric split": ({"type": "symmetric"}, None),
        "low-pass split 20 Hz": ({"type": "low_pass", "cutoff_hz": 20.0}, None),
        "machine limits, no split": (None, None),
        "automatic split, HCAA 0.01 um (a grid denser than the points)": ({"type": "auto"}, hcaa),
    }
    for name, (split, sampling) in kinds.items():
        job = json.loads(json.dumps(base))
        if split is None:
            del job["strategy"]["split"]
        else:
            job["strategy"]["split"] = split
        if sampling is not None:
            job["strategy"]["sampling"] = sampling
        path, nc, report = (os.path.join(tmp, n) for n in ("dyn.json", "dyn.ngc", "dyn-report.json"))
        with open(path, "w") as f:
            json.dump(job, f)
        start = time.perf_counter()
        peak = alone([binary, "plan", path, "--nc", nc, "--report", report])
        seconds = time.perf_counter() - start
        with open(report) as f:
            r = json.load(f)
        estimate = r["estimate"]["dynamics_memory_bytes"]
        samples = r["estimate"]["dynamics_samples"]
        print(
            f"dynamics, {name}: {r['points']} points, {samples} grid samples, peak RSS "
            f"{peak / 1024:.0f} MiB (estimate {estimate / 2**20:.0f} MiB), {seconds:.2f} s"
        )
        os.remove(nc)


if __name__ == "__main__":
    main()
