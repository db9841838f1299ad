#!/usr/bin/env python3
"""Force table of the cushion-vs-CalculiX indentation check.

usage: compare.py CCX_DAT CUSHION_CONTACT_CSV CCX_SECONDS CUSHION_SECONDS [DEPTHS_MM...]
CCX_DAT: the .dat file of the deck from make_indentation.py (*NODE PRINT of U, RF of the indenter's
reference node, quarter model); CUSHION_CONTACT_CSV: contact_sphere.csv (forces already x4).
Prints depth, both full-model forces [N], their relative difference and the wall-time ratio.
"""
import csv
import sys


def ccx_curve(path):
    """(depth [mm], full-model force [N]) pairs from the reference node's U3 and RF3 blocks."""
    depth, force, block = [], [], None
    for line in open(path):
        words = line.split()
        if line.strip().startswith("displacements"):
            block = "u"
        elif line.strip().startswith("forces"):
            block = "f"
        elif len(words) == 4 and block:
            value = float(words[3])
            (depth if block == "u" else force).append(-value if block == "u" else -4.0 * value)
            block = None
    return [(0.0, 0.0)] + list(zip(depth, force))


def cushion_curve(path):
    rows = csv.DictReader(line for line in open(path) if not line.startswith("#"))
    name = None
    curve = []
    for r in rows:
        if name is None:
            name = next(k for k in r if k.endswith(".U3_mm")).split(".")[0]
        curve.append((-float(r[name + ".U3_mm"]), -float(r[name + ".F3_N"])))
    return curve


def at(curve, d):
    """Linear interpolation of the force at depth d (None beyond the curve)."""
    for (d0, f0), (d1, f1) in zip(curve, curve[1:]):
        if d0 <= d <= d1 and d1 > d0:
            return f0 + (f1 - f0) * (d - d0) / (d1 - d0)
    return None


def main():
    ccx, cushion = ccx_curve(sys.argv[1]), cushion_curve(sys.argv[2])
    t_ccx, t_cushion = float(sys.argv[3]), float(sys.argv[4])
    depths = [float(x) for x in sys.argv[5:]] or [20.0, 40.0, 60.0]
    print(f"{'depth_mm':>9} {'cushion_N':>11} {'calculix_N':>11} {'difference_%':>13}")
    for d in depths:
        a, b = at(cushion, d), at(ccx, d)
        if a is None or b is None:
            print(f"{d:9.1f} {'-' if a is None else f'{a:11.2f}':>11} {'-' if b is None else f'{b:11.2f}':>11}"
                  "   (depth not reached)")
            continue
        print(f"{d:9.1f} {a:11.2f} {b:11.2f} {100.0 * (a - b) / b:13.2f}")
    print(f"wall time: cushion {t_cushion:.1f} s, CalculiX {t_ccx:.1f} s, ratio cushion/CalculiX "
          f"{t_cushion / t_ccx:.2f}")


if __name__ == "__main__":
    main()
