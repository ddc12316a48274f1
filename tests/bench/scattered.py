"""The scattered example planned to files, timed: `spiralcam plan crate/jobs/scattered-lens-array.json
--nc … --report …` (65 025 data points, 180 001 path points, paper 004's RBF with the L1 kernel),
wall time, CPU time (user + system) and peak resident set per run.

Give a second binary to compare two builds side by side: their runs alternate (this shared
machine's load drifts), and their programs are compared byte for byte. Usage:
python3 tests/bench/scattered.py [BINARY [OTHER]] [--runs N] [--job JOB]
(default target/release/spiralcam, 2 runs each; build it with `cargo build --release`).
"""
import argparse
import filecmp
import os
import resource
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
PROBE = (
    "import resource, subprocess, sys; subprocess.run(sys.argv[1:], check=True, "
    "stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL); "
    "u = resource.getrusage(resource.RUSAGE_CHILDREN); print(u.ru_utime + u.ru_stime, u.ru_maxrss)"
)


def run(binary, job, nc, report):
    """Plans `job` with `binary` in a child of its own: (wall s, CPU s, peak RSS MiB)."""
    start = time.perf_counter()
    out = subprocess.run(
        [sys.executable, "-c", PROBE, binary, "plan", job, "--nc", nc, "--report", report],
        check=True,
        capture_output=True,
        text=True,
    )
    wall = time.perf_counter() - start
    cpu, peak_kib = out.stdout.split()
    return wall, float(cpu), int(peak_kib) / 1024


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("binaries", nargs="*")
    parser.add_argument("--runs", type=int, default=2)
    parser.add_argument("--job", default=os.path.join(ROOT, "crate", "jobs", "scattered-lens-array.json"))
    args = parser.parse_args()
    binaries = args.binaries or [os.path.join(ROOT, "target", "release", "spiralcam")]
    if len(binaries) > 2:
        parser.error("at most two binaries")
    with tempfile.TemporaryDirectory() as tmp:
        programs = [os.path.join(tmp, f"{i}.ngc") for i in range(len(binaries))]
        for k in range(args.runs):
            for i, binary in enumerate(binaries):
                report = os.path.join(tmp, f"{i}.json")
                wall, cpu, peak = run(binary, args.job, programs[i], report)
                print(f"{binary}: run {k + 1}: {wall:.2f} s [CPU {cpu:.2f} s], peak RSS {peak:.0f} MiB")
        if len(binaries) == 2:
            same = filecmp.cmp(programs[0], programs[1], shallow=False)
            print("programs byte-identical" if same else "PROGRAMS DIFFER")


if __name__ == "__main__":
    main()
