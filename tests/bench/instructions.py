"""Instructions a point of a planned program, counted by callgrind: a figure that does not drift
with the shared machine's speed (its wall and CPU times vary by about 20 % within the hour, so a
change of a few per cent cannot be told from the noise by timing alone).

Plans `plan_numpy.py`'s asphere and paper 004 lens array (one-way compensation, ISO NC to
/dev/null) under `valgrind --tool=callgrind` twice: over the whole part and at four times the
feed (the same points a turn, a quarter of the turns), and prints the instructions of a point as
the difference between the two runs divided by the difference in points (the job's set-up, the
same in both, drops out), then the functions that execute the most instructions a point in the larger
run (their own instructions, not those of the functions they call).

    python3 tests/bench/instructions.py [BINARY [OTHER]] [--points N] [--per-rev P] [--top K]

BINARY defaults to target/release/spiralcam (`cargo build --release -p spiralcam`); with OTHER
both are counted, row by row. P is the points a turn (default 5 680, the 28.4 M-point jobs':
the compensation's warm start depends on the angle between points, so a coarser turn counts
other work), N about the points of the whole part (default 568 001: 100 turns; rounded to a
multiple of four turns), K the number of functions listed (default 12). Installs valgrind with
apt where it is missing. Each run takes about 50 times the planner's own time.
"""

import json
import os
import re
import shutil
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from plan_numpy import ROOT, job  # noqa: E402


def ensure_valgrind():
    if shutil.which("valgrind"):
        return
    sudo = [] if os.geteuid() == 0 else ["sudo"]
    print("valgrind is missing: installing it with apt", file=sys.stderr)
    subprocess.run(sudo + ["apt-get", "install", "-y", "-q", "valgrind"], check=True)


def count(binary, job_path, tmp):
    """(total instructions, {function: own instructions}) of planning `job_path`."""
    out = os.path.join(tmp, "callgrind.out")
    subprocess.run(
        ["valgrind", "--tool=callgrind", f"--callgrind-out-file={out}", binary, "plan",
         job_path, "--nc", "/dev/null", "--max-points", "1e9"],
        check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
    )
    text = subprocess.run(["callgrind_annotate", out], check=True, capture_output=True,
                          text=True).stdout
    total = int(re.search(r"^([\d,]+) \S* *PROGRAM TOTALS", text, re.M).group(1).replace(",", ""))
    functions = {}
    for m in re.finditer(r"^ *([\d,]+) \([ \d.]+%\)  [^:]*:(.+?) \[", text, re.M):
        functions[m.group(2)] = int(m.group(1).replace(",", ""))
    return total, functions


def main():
    args = sys.argv[1:]
    points, per_rev, top, binaries = 568_001, 5_680, 12, []
    while args:
        flag = args.pop(0)
        if flag == "--points":
            points = int(args.pop(0))
        elif flag == "--per-rev":
            per_rev = int(args.pop(0))
        elif flag == "--top":
            top = int(args.pop(0))
        else:
            binaries.append(flag)
    binaries = binaries or [os.path.join(ROOT, "target", "release", "spiralcam")]
    # Whole turns, a multiple of four, so that the run at four times the feed has a quarter.
    turns = max(4, round((points - 1) / per_rev / 4) * 4)
    points = turns * per_rev + 1
    ensure_valgrind()
    with tempfile.TemporaryDirectory() as tmp:
        for kind in ["asphere", "lens_array"]:
            whole = job(kind, points)
            whole["strategy"]["feed_mm_per_rev"] = 5.0 / turns
            whole["strategy"]["sampling"]["points_per_rev"] = per_rev
            small = per_rev * (turns // 4) + 1
            paths = {}
            for n, feed in [(points, 1.0), (small, 4.0)]:
                j = json.loads(json.dumps(whole))
                j["strategy"]["feed_mm_per_rev"] *= feed
                paths[n] = os.path.join(tmp, f"{kind}_{n}.json")
                with open(paths[n], "w") as f:
                    json.dump(j, f)
            for binary in binaries:
                lo, _ = count(binary, paths[small], tmp)
                hi, functions = count(binary, paths[points], tmp)
                per_point = (hi - lo) / (points - small)
                print(f"{kind:11s} {os.path.basename(binary)}: {per_point:7.0f} instructions a point "
                      f"({hi / 1e6:.0f} M at {points} points, {lo / 1e6:.0f} M at {small})")
                for name, n in sorted(functions.items(), key=lambda f: -f[1])[:top]:
                    print(f"    {n / points:6.0f}  {name}")


if __name__ == "__main__":
    main()
