"""The machine dynamics and split of a long path, timed against the same program written without
them (issue 16: 28.4 M points within 1 GB and 20 s).

The job is `sinusoid-grid-fts.json` (800 revolutions, the automatic split against its machine)
at as many points a revolution as give about --points points (default 28 400 001); with
`--sampling hcaa`, HCAA at 0.01 µm on a feed that gives about as many points (2 077 105 at
1 µm a revolution, the count going as 1/feed), whose grid has about 1.8 samples a point. Each build
plans it twice a run, the program written to a file each time: once as it is (the path planned
into memory, analysed and split, then planned again and written with the slide's share and the
servo's word), once without the machine and the split (the path planned and written once, no
dynamics). The difference is what the dynamics cost. The peak resident set is that of the run
with them; the report's estimate of it and of their time are printed beside. With two builds
the runs alternate and their programs are compared byte for byte.

Usage: python3 tests/bench/dynamics.py [--points N] [--runs R] [--sampling hcaa] BINARY [OTHER_BINARY]
(build with `cargo build --release`; about 35 s a run of one build at 28.4 M points on the
2-vCPU build machine, and 2.4 GB of memory and 1.5 GB of disk for each program).
"""
import argparse
import filecmp
import json
import os
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

PROBE = (
    "import resource, subprocess, sys; subprocess.run(sys.argv[1:], check=True, "
    "stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL); "
    "print(resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss)"
)


def timed(command):
    """Runs `command` in a child of its own: (seconds, peak resident set in bytes)."""
    start = time.perf_counter()
    out = subprocess.run([sys.executable, "-c", PROBE, *command], check=True, capture_output=True)
    return time.perf_counter() - start, int(out.stdout.split()[-1]) * 1024


def jobs(tmp, points, sampling):
    """The job with the dynamics and the same without them, written to `tmp`: their paths."""
    with open(os.path.join(ROOT, "crate", "jobs", "sinusoid-grid-fts.json")) as f:
        job = json.load(f)
    if sampling == "hcaa":
        job["strategy"]["feed_mm_per_rev"] = 0.001 * 2_077_105 / points
        job["strategy"]["sampling"] = {"type": "hcaa", "pv_tolerance_um": 0.01}
    else:
        revolutions = job["part"]["diameter_mm"] / 2 / job["strategy"]["feed_mm_per_rev"]
        per_rev = max(1, round((points - 1) / revolutions))
        job["strategy"]["sampling"] = {"type": "constant_angle", "points_per_rev": per_rev}
    plain = json.loads(json.dumps(job))
    del plain["strategy"]["split"]
    plain["machine"] = {"spindle_rpm": job["machine"]["spindle_rpm"]}
    paths = []
    for name, j in (("dynamics", job), ("plain", plain)):
        path = os.path.join(tmp, f"{name}.json")
        with open(path, "w") as f:
            json.dump(j, f)
        paths.append(path)
    return paths


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--points", type=int, default=28_400_001)
    parser.add_argument("--runs", type=int, default=2)
    parser.add_argument("--sampling", choices=["constant_angle", "hcaa"], default="constant_angle")
    parser.add_argument("binaries", nargs="+")
    args = parser.parse_args()
    if len(args.binaries) > 2:
        parser.error("one or two builds")
    with tempfile.TemporaryDirectory() as tmp:
        with_dynamics, without = jobs(tmp, args.points, args.sampling)
        for run in range(args.runs):
            programs = []
            for k, binary in enumerate(args.binaries):
                nc, report = os.path.join(tmp, f"{k}.nc"), os.path.join(tmp, f"{k}.json")
                seconds, peak = timed([binary, "plan", with_dynamics, "--nc", nc, "--report", report])
                with open(report) as f:
                    r = json.load(f)
                plain_nc = os.path.join(tmp, "plain.nc")
                plain, _ = timed([binary, "plan", without, "--nc", plain_nc, "--report", report])
                os.remove(plain_nc)
                estimate = r["estimate"]
                print(
                    f"run {run + 1}, {os.path.basename(binary)}: {r['points']} points, "
                    f"with the dynamics {seconds:.2f} s, peak RSS {peak / 1e9:.2f} GB "
                    f"(estimated {estimate['dynamics_memory_bytes'] / 1e9:.2f} GB); without them "
                    f"{plain:.2f} s: the dynamics {seconds - plain:.2f} s "
                    f"(estimated {estimate['dynamics_seconds']:.2f} s)",
                    flush=True,
                )
                programs.append(nc)
            if len(programs) == 2:
                same = filecmp.cmp(programs[0], programs[1], shallow=False)
                print(f"run {run + 1}: programs {'byte-identical' if same else 'DIFFER'}", flush=True)
            for p in programs:
                os.remove(p)


if __name__ == "__main__":
    main()
