#!/usr/bin/env python3
"""Reference values of Forbes' Q polynomials for spiralcam's tests (tests/tests/surface_forbes.rs).

Writes tests/golden/qpoly_reference.json: the bare radial polynomials Q(x), x = u², and dQ/dx at
a few x in [0, 1.2], for

- Qbfs_n (Forbes 2007, "Shape specification for axially symmetric optical surfaces", Opt.
  Express 15, 5218), n = 0 ... 6;
- Qcon_n (same paper), n = 0 ... 6;
- Q_n^m of the freeform set (Forbes 2012, "Characterizing the shape of freeform optics", Opt.
  Express 20, 2483), m = 1 ... 4, n = 0 ... 6 (m = 0 is Qbfs).

They are computed here from the definitions alone, by exact Gram-Schmidt in rational arithmetic
(Python's fractions), not from Forbes' recurrences that spiralcam implements:

- Qbfs: u²(1 − u²)·Q_n(u²) orthonormal under <f, g> = (2/π)∫₀¹ f'(u)g'(u) du/√(1 − u²);
- Q^m: u^m cos(mθ)·Q_n^m(u²) orthonormal under the mean over θ of the same weighted integral of
  ∇f·∇g, i.e. (2/π)∫₀¹ ½[F'G' + m²FG/u²] du/√(1 − u²) for the radial parts F = u^m·Q(u²);
- Qcon: orthogonal under ∫₀¹ x⁴·Q_m·Q_n dx (u⁴Q(u²) orthogonal in sag over the disc), with
  Q_n(1) = 1 (the Jacobi polynomials P_n^(0,4)(2x − 1)).

Every integrand is an even polynomial in u, so with the moments (2/π)∫₀¹ u^2k du/√(1 − u²) =
(2k − 1)!!/(2k)!! the inner products are exact rationals; only the final normalisation takes a
square root. Signs follow Forbes: the coefficient of xⁿ in Q_n has the sign (−1)ⁿ.

The script then checks the values against prysm (PyPI, G. Brandon Dube's implementation of
Forbes' recurrences; prysm 0.21.1 fails for m = 1, so that column is checked only for m ≠ 1),
against scipy's Jacobi polynomials for Qcon, and prints the largest differences; it stops if any
exceeds 1e-12.

Regenerate (needs network once, for the virtual environment):

    python3 tests/bench/qpoly_reference.py

numpy, scipy and prysm are installed on first use into /tmp/spiralcam-qpoly-venv, in which the
script then runs itself.
"""

import json
import math
import os
import subprocess
import sys
from fractions import Fraction

VENV = "/tmp/spiralcam-qpoly-venv"
OUT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "golden", "qpoly_reference.json")
X = [0.0, 0.05, 0.2, 0.37, 0.5, 0.64, 0.81, 0.95, 1.0, 1.2]
N_MAX = 6
M_MAX = 4


def ensure_packages():
    try:
        import numpy  # noqa: F401
        import prysm  # noqa: F401
        import scipy  # noqa: F401
    except ImportError:
        python = os.path.join(VENV, "bin", "python")
        if os.environ.get("SPIRALCAM_IN_VENV"):
            sys.exit("numpy/scipy/prysm missing even in " + VENV)
        if not os.path.exists(python):
            subprocess.check_call([sys.executable, "-m", "venv", VENV])
            subprocess.check_call([python, "-m", "pip", "install", "--quiet", "numpy", "scipy", "prysm"])
        env = dict(os.environ, SPIRALCAM_IN_VENV="1")
        os.execve(python, [python] + sys.argv, env)


# Polynomials are dicts {power: Fraction}.


def mul(a, b):
    out = {}
    for i, x in a.items():
        for j, y in b.items():
            out[i + j] = out.get(i + j, 0) + x * y
    return {k: v for k, v in out.items() if v != 0}


def add(a, b, scale=1):
    out = dict(a)
    for k, v in b.items():
        out[k] = out.get(k, 0) + scale * v
    return {k: v for k, v in out.items() if v != 0}


def deriv(a):
    return {k - 1: k * v for k, v in a.items() if k > 0}


def chebyshev_moment(k):
    """(2/π)∫₀¹ u^k du/√(1 − u²) for even k: (k − 1)!!/k!!."""
    assert k % 2 == 0
    m = Fraction(1)
    for j in range(1, k, 2):
        m *= Fraction(j, j + 1)
    return m


def weighted(p):
    """(2/π)∫₀¹ p(u) du/√(1 − u²) for an even polynomial p."""
    return sum(v * chebyshev_moment(k) for k, v in p.items())


def in_u(q, shift):
    """u^shift · q(u²) as a polynomial in u, q given in x = u²."""
    return {2 * k + shift: v for k, v in q.items()}


def inner_bfs(q1, q2):
    """Slope inner product of u²(1 − u²)q(u²)."""
    env = {2: Fraction(1), 4: Fraction(-1)}
    f = deriv(mul(env, in_u(q1, 0)))
    g = deriv(mul(env, in_u(q2, 0)))
    return weighted(mul(f, g))


def inner_freeform(m):
    def inner(q1, q2):
        f, g = in_u(q1, m), in_u(q2, m)
        radial = mul(deriv(f), deriv(g))
        # m²·F·G/u²: F·G has the factor u^(2m), m ≥ 1.
        fg = mul(f, g)
        angular = {k - 2: m * m * v for k, v in fg.items()}
        return weighted(add(radial, angular)) / 2

    return inner


def inner_con(q1, q2):
    """∫₀¹ x⁴ q1 q2 dx."""
    p = mul({4: Fraction(1)}, mul(q1, q2))
    return sum(v / (k + 1) for k, v in p.items())


def gram_schmidt(inner, n_max):
    """Orthogonal polynomials in x (rational, leading coefficient 1 on xⁿ) and their norms²."""
    basis, norms = [], []
    for n in range(n_max + 1):
        v = {n: Fraction(1)}
        for b, nb in zip(basis, norms):
            v = add(v, b, -inner({n: Fraction(1)}, b) / nb)
        basis.append(v)
        norms.append(inner(v, v))
    return basis, norms


def evaluate(q, x):
    return float(sum(v * Fraction(x) ** k for k, v in q.items()))


def table(polys, scales):
    rows = []
    for n, (q, s) in enumerate(zip(polys, scales)):
        dq = deriv(q)
        rows.append({
            "n": n,
            "q": [s * evaluate(q, x) for x in X],
            "dq_dx": [s * evaluate(dq, x) for x in X],
        })
    return rows


def orthonormal(inner):
    polys, norms = gram_schmidt(inner, N_MAX)
    scales = [(-1) ** n / math.sqrt(nrm) for n, nrm in enumerate(norms)]
    return polys, scales


def main():
    ensure_packages()
    import numpy as np
    from prysm.polynomials import qpoly
    from scipy.special import eval_jacobi

    out = {"x": X, "generator": "tests/bench/qpoly_reference.py"}
    worst = {}

    polys, scales = orthonormal(inner_bfs)
    out["qbfs"] = table(polys, scales)
    polys, norms = gram_schmidt(inner_con, N_MAX)
    # Q_n(1) = 1.
    out["qcon"] = table(polys, [1 / evaluate(q, 1.0) for q in polys])
    out["q2d"] = []
    for m in range(1, M_MAX + 1):
        polys, scales = orthonormal(inner_freeform(m))
        for row in table(polys, scales):
            out["q2d"].append({"m": m, **row})

    # Cross-checks against prysm and scipy (at u > 0, where prysm's prefixes do not vanish).
    def note(key, a, b):
        worst[key] = max(worst.get(key, 0.0), abs(a - b) / max(1.0, abs(b)))

    for row in out["qbfs"]:
        for x, q in zip(X, row["q"]):
            if 0 < x < 1:
                u = math.sqrt(x)
                note("qbfs vs prysm", q * x * (1 - x), float(qpoly.Qbfs(row["n"], np.array(u))))
    for row in out["qcon"]:
        for x, q in zip(X, row["q"]):
            note("qcon vs scipy jacobi(0,4)", q, float(eval_jacobi(row["n"], 0, 4, 2 * x - 1)))
            if x > 0:
                u = math.sqrt(x)
                note("qcon vs prysm", q * x * x, float(qpoly.Qcon(row["n"], np.array(u))))
    for row in out["q2d"]:
        m = row["m"]
        if m == 1:
            continue
        for x, q in zip(X, row["q"]):
            if x > 0:
                u = math.sqrt(x)
                note("q2d vs prysm (m 2..4)", q * u**m, float(qpoly.Q2d(row["n"], m, np.array(u), np.array(0.0))))
    out["checks"] = worst
    for k, v in worst.items():
        print(f"{k}: largest relative difference {v:.2e}")
    if any(v > 1e-12 for v in worst.values()):
        sys.exit("reference and independent implementation disagree")
    with open(OUT, "w") as f:
        json.dump(out, f, indent=1)
        f.write("\n")
    print("wrote", os.path.normpath(OUT))


if __name__ == "__main__":
    main()
