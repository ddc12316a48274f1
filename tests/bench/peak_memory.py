"""Peak memory of `spiralcam plan` (NC and CSV written to files) for 1 M and 10 M points.

Memory must stay flat: the planner streams, so the peak resident set should not grow with the
point count. Prints one line per size. Usage: python3 tests/bench/peak_memory.py [BINARY]
(default target/release/spiralcam; build it with `cargo build --release`).
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


if __name__ == "__main__":
    main()
