#!/usr/bin/env python3
"""Writes the hyperfoam-only sphere indentation of the cushion-vs-CalculiX check.

One mesh file (ABAQUS .inp, C3D8, read by both codes), the cushion case and material files, and
the CalculiX deck. Units: mm, N, MPa. Geometry: quarter of the paper's 400 x 400 x 80 mm block
(x, y in [0, 200], z in [0, 80]), symmetry planes x = 0 and y = 0, base z = 0 fixed, frictionless
rigid sphere of radius R centred on the z axis touching the top face at the start, pressed
`depth` mm down. Contact: node-to-surface, frictionless; cushion: analytic sphere, augmented
Lagrangian to `tolerance` mm; CalculiX: faceted rigid sphere (vertices on the sphere, 2 degree
facets), penalty *SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR with slope `penalty` MPa/mm (stiffer
slopes stop converging in CalculiX, see shared/notes/calculix.md).

usage: make_indentation.py OUT_DIR [--n 14 --nz 8 --ratio 2.5 --radius 100 --depth 60
                                    --steps 30 --penalty 0.1]
"""
import argparse
import json
import math
import os

# Hyperfoam of cases/materials/paper_table3.json (no Prony): (mu [kPa], alpha, nu).
TERMS = [(10.0, 10.0, 0.0), (0.1, -2.0, 0.0), (0.5, 3.0, 0.0)]
L, H = 200.0, 80.0


def graded(n, ratio, length):
    """n + 1 coordinates on [0, length], finest at 0, h_last / h_first = ratio (geometric)."""
    q = ratio ** (1.0 / (n - 1)) if n > 1 else 1.0
    h = [q ** i for i in range(n)]
    s = sum(h)
    x = [0.0]
    for hi in h:
        x.append(x[-1] + length * hi / s)
    x[-1] = length
    return x


def write_mesh(path, n, nz, ratio):
    xs = graded(n, ratio, L)
    zs = [H * k / nz for k in range(nz + 1)]
    nid = lambda i, j, k: 1 + i + (n + 1) * (j + (n + 1) * k)
    with open(path, "w") as f:
        f.write("** quarter block 200 x 200 x 80 mm, C3D8, written by tools/calculix/make_indentation.py\n*NODE\n")
        for k in range(nz + 1):
            for j in range(n + 1):
                for i in range(n + 1):
                    f.write(f"{nid(i, j, k)}, {xs[i]:.12g}, {xs[j]:.12g}, {zs[k]:.12g}\n")
        f.write("*ELEMENT, TYPE=C3D8, ELSET=FOAM\n")
        e = 0
        top = []
        for k in range(nz):
            for j in range(n):
                for i in range(n):
                    e += 1
                    c = [nid(i, j, k), nid(i + 1, j, k), nid(i + 1, j + 1, k), nid(i, j + 1, k)]
                    c += [a + (n + 1) ** 2 for a in c]
                    f.write(f"{e}, " + ", ".join(map(str, c)) + "\n")
                    if k == nz - 1:
                        top.append(e)
        f.write("*ELSET, ELSET=FOAM_TOP\n")
        for i in range(0, len(top), 16):
            f.write(", ".join(map(str, top[i:i + 16])) + "\n")
    return (n + 1) ** 2 * (nz + 1), e


def sphere_indenter(path, first_node, first_elem, radius, centre_z, m=40, theta_max_deg=80.0, t=5.0):
    """Rigid quarter sphere cap as one layer of C3D8 (nodes 1-4 on the sphere, 5-8 inside it): face S1 faces the foam."""
    theta_max = math.radians(theta_max_deg)
    ids = {}
    lines = ["*NODE"]
    node = first_node
    for layer, r in enumerate((radius, radius - t)):
        for j in range(m + 1):
            for i in range(m + 1):
                s = max(i, j) / m
                phi = math.atan2(j, i) if (i or j) else 0.0
                th = s * theta_max
                rho, z = r * math.sin(th), centre_z - r * math.cos(th)
                ids[layer, i, j] = node
                lines.append(f"{node}, {rho * math.cos(phi):.12g}, {rho * math.sin(phi):.12g}, {z:.12g}")
                node += 1
    ref, rot = node, node + 1
    lines.append(f"{ref}, 0, 0, {centre_z:.12g}")
    lines.append(f"{rot}, 0, 0, {centre_z:.12g}")
    lines.append("*ELEMENT, TYPE=C3D8, ELSET=INDENTER")
    e = first_elem
    for j in range(m):
        for i in range(m):
            c = [ids[0, i, j], ids[0, i + 1, j], ids[0, i + 1, j + 1], ids[0, i, j + 1]]
            c += [ids[1, i, j], ids[1, i + 1, j], ids[1, i + 1, j + 1], ids[1, i, j + 1]]
            lines.append(f"{e}, " + ", ".join(map(str, c)))
            e += 1
    lines += [f"*NSET, NSET=NREF\n{ref}", f"*NSET, NSET=NROT\n{rot}"]
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")
    return ref, rot


def main():
    p = argparse.ArgumentParser()
    p.add_argument("out")
    p.add_argument("--n", type=int, default=14)
    p.add_argument("--nz", type=int, default=8)
    p.add_argument("--ratio", type=float, default=2.5)
    p.add_argument("--radius", type=float, default=100.0)
    p.add_argument("--depth", type=float, default=60.0)
    p.add_argument("--steps", type=int, default=30)
    p.add_argument("--penalty", type=float, default=0.1)
    p.add_argument("--tolerance", type=float, default=0.05)
    a = p.parse_args()
    os.makedirs(a.out, exist_ok=True)
    nodes, elems = write_mesh(os.path.join(a.out, "mesh.inp"), a.n, a.nz, a.ratio)
    zc = H + a.radius
    ref, rot = sphere_indenter(os.path.join(a.out, "ccx_indenter.inp"), nodes + 1, elems + 1, a.radius, zc)

    material = {"name": "paper_table3_hyperfoam_only",
                "description": "Hyperfoam of cases/materials/paper_table3.json without the Prony series "
                               "(static comparison with CalculiX).",
                "density_kg_m3": 65,
                "hyperfoam": {"terms": [{"mu_kPa": m, "alpha": al, "nu": nu} for m, al, nu in TERMS]}}
    with open(os.path.join(a.out, "material.json"), "w") as f:
        json.dump(material, f, indent=2)
        f.write("\n")
    dt = 1.0 / a.steps
    case = {
        "description": f"Cushion side of tools/calculix_indentation.sh: rigid sphere R = {a.radius:g} mm pressed "
                       f"{a.depth:g} mm into the quarter 400 x 400 x 80 mm block, hyperfoam only (static), "
                       f"base fixed, frictionless contact (augmented Lagrangian, penetration <= {a.tolerance:g} mm).",
        "mesh": {"inp": "mesh.inp"},
        "material": {"file": "material.json"},
        "sets": {"sym_x": "x == 0", "sym_y": "y == 0", "base": "z == 0", "top": f"z == {H:g}"},
        "steps": [{
            "name": "press", "type": "static", "time_period_s": 1,
            "increment": {"initial_s": dt, "min_s": dt / 1000, "max_s": dt, "max_increments": 10 * a.steps},
            "boundary": [{"set": "sym_x", "type": "symmetry_x"}, {"set": "sym_y", "type": "symmetry_y"},
                         {"set": "base", "type": "fixed"}],
            "contact": [{"name": "sphere", "set": "top",
                         "indenter": {"type": "sphere", "centre_mm": [0, 0, zc], "radius_mm": a.radius},
                         "motion_mm": [0, 0, -a.depth], "penalty_MPa_per_mm": a.penalty,
                         "tolerance_mm": a.tolerance, "force_factor": 4}],
            "output": {"frames_every_s": 1.0 / 3, "history": [{"set": "base", "quantities": ["RF3"]}]}}],
    }
    with open(os.path.join(a.out, "case.json"), "w") as f:
        json.dump(case, f, indent=2)
        f.write("\n")

    mu = [m * 1e-3 for m, _, _ in TERMS]  # MPa
    hf = f"{mu[0]:g}, {TERMS[0][1]:g}, {mu[1]:g}, {TERMS[1][1]:g}, {mu[2]:g}, {TERMS[2][1]:g}, " \
         f"{TERMS[0][2]:g}, {TERMS[1][2]:g}\n{TERMS[2][2]:g}"
    deck = f"""** CalculiX side of tools/calculix_indentation.sh (written by tools/calculix/make_indentation.py)
** units mm, N, MPa, t/mm^3
*INCLUDE, INPUT=mesh.inp
*INCLUDE, INPUT=ccx_indenter.inp
*NSET, NSET=SYMX
{"".join(f"{1 + (a.n + 1) * j + (a.n + 1) ** 2 * k},{chr(10)}" for k in range(a.nz + 1) for j in range(a.n + 1))}
*NSET, NSET=SYMY
{"".join(f"{1 + i + (a.n + 1) ** 2 * k},{chr(10)}" for k in range(a.nz + 1) for i in range(a.n + 1))}
*NSET, NSET=BASE
{"".join(f"{1 + i},{chr(10)}" for i in range((a.n + 1) ** 2))}
*MATERIAL, NAME=FOAM
*HYPERFOAM, N=3
{hf}
*DENSITY
6.5e-11
*MATERIAL, NAME=STEEL
*ELASTIC
210000, 0.3
*SOLID SECTION, ELSET=FOAM, MATERIAL=FOAM
*SOLID SECTION, ELSET=INDENTER, MATERIAL=STEEL
*RIGID BODY, ELSET=INDENTER, REF NODE={ref}, ROT NODE={rot}
*SURFACE, NAME=SFOAM, TYPE=ELEMENT
FOAM_TOP, S2
*SURFACE, NAME=SIND, TYPE=ELEMENT
INDENTER, S1
*SURFACE INTERACTION, NAME=FRICTIONLESS
*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR
{a.penalty:g}, 1e-9, 1e-3
*CONTACT PAIR, INTERACTION=FRICTIONLESS, TYPE=NODE TO SURFACE
SFOAM, SIND
*BOUNDARY
SYMX, 1, 1
SYMY, 2, 2
BASE, 1, 3
{ref}, 1, 2
{rot}, 1, 3
*TIME POINTS, NAME=TP
{chr(10).join(f"{(k + 1) * dt:.9g}," for k in range(a.steps))}
*STEP, NLGEOM, INC=10000
*STATIC
{dt / 4:.9g}, 1.0, {dt * 1e-4:.9g}, {dt:.9g}
*CONTROLS, PARAMETERS=TIME INCREMENTATION
20, 30, 9, 200, 10, 4, , 5
*CONTROLS, PARAMETERS=FIELD, FIELD=DISPLACEMENT
0.005, 0.01, , 0.2
*BOUNDARY
{ref}, 3, 3, {-a.depth:g}
*NODE PRINT, NSET=NREF, TIME POINTS=TP
U, RF
*END STEP
"""
    with open(os.path.join(a.out, "ccx_indentation.inp"), "w") as f:
        f.write(deck)


if __name__ == "__main__":
    main()
