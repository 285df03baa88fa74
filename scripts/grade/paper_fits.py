#!/usr/bin/env python3
"""The paper's fitted formulas tabulated, as results for `verify grade` (CSV on standard output).

The formulas and parameters are the paper's (Popov, Li et al., "JKR adhesive normal contact of
annular, conical and spherical concave punches"), written here independently of the Rust code:

  flat annulus   gamma(eps)      = (1 - eps^m)^n,                 m = 2.915, n = 0.147    (3)
  cone           gamma_i(eps)    = (-ln eps)^n_i (a_i + b_i eps + c_i eps^2)              (8)
                 n1 = 0.874, a1 = 2.09, b1 = 0.54, c1 = 0.15
                 n2 = 0.945, a2 = 1.85, b2 = 0.45, c2 = 0.12                               (9)
  sphere         gamma_i(eps)    = a_i (1 - eps^m_i)^n_i                                  (10)
                 a1 = 3, m1 = 2.034, n1 = 0.91; a2 = 8/3, m2 = 2.015, n2 = 1.03           (11)

at eps = 0.05, 0.10, ..., 0.95 and 0.99 (the range of the paper's figures 4-6).

    python3 scripts/grade/paper_fits.py > verify/grade/paper-fits.csv
    verify grade --results verify/grade/paper-fits.csv --tol 0.03
"""

import math
import sys


def flat_annulus(eps):
    return (1.0 - eps**2.915) ** 0.147


def cone(eps, n, a, b, c):
    return (-math.log(eps)) ** n * (a + b * eps + c * eps * eps)


def sphere(eps, a, m, n):
    return a * (1.0 - eps**m) ** n


def main():
    if len(sys.argv) > 1:
        sys.exit("usage: python3 scripts/grade/paper_fits.py > FILE (no arguments)")
    points = [round(0.05 * k, 2) for k in range(1, 20)] + [0.99]
    out = sys.stdout
    out.write("# The paper's fits (3), (8)-(9), (10)-(11) at its points; scripts/grade/paper_fits.py\n")
    out.write("punch,eps,gamma,gamma1,gamma2,source\n")
    for eps in points:
        out.write(f"flat-annulus,{eps!r},{flat_annulus(eps)!r},,,paper eq. (3)\n")
    for eps in points:
        g1 = cone(eps, 0.874, 2.09, 0.54, 0.15)
        g2 = cone(eps, 0.945, 1.85, 0.45, 0.12)
        out.write(f"cone,{eps!r},,{g1!r},{g2!r},paper eqs. (8)-(9)\n")
    for eps in points:
        g1 = sphere(eps, 3.0, 2.034, 0.91)
        g2 = sphere(eps, 8.0 / 3.0, 2.015, 1.03)
        out.write(f"sphere,{eps!r},,{g1!r},{g2!r},paper eqs. (10)-(11)\n")


if __name__ == "__main__":
    main()
