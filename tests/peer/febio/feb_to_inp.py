#!/usr/bin/env python3
"""Writes the mesh of an FEBio 4.0 input file (.feb) as an ABAQUS mesh (.inp) that `cushion run` reads.

    python3 feb_to_inp.py PROBLEM.feb OUT.inp [--domain PART ...]

Kept: the nodes used by the chosen solid domains (default: every hex8 domain), their hex8 elements (FEBio's
hex8 node order is ABAQUS C3D8's), every <NodeSet> restricted to the kept nodes, and every <Surface> as a node
set of its facet nodes. Node ids are FEBio's. Coordinates are written with 17 significant digits.
Units: FEBio problems are dimensionless; the case files read lengths as mm (see README.md in this folder).
"""
import argparse
import sys
import xml.etree.ElementTree as ET


def id_list(text):
    return [int(tok) for tok in text.replace(",", " ").split()]


def read_feb(path, domains):
    mesh = ET.parse(path).getroot().find("Mesh")
    nodes = {}
    for block in mesh.findall("Nodes"):
        for node in block.findall("node"):
            nodes[int(node.get("id"))] = [float(v) for v in node.text.split(",")]
    elements = []
    for block in mesh.findall("Elements"):
        if block.get("type") != "hex8" or (domains and block.get("name") not in domains):
            continue
        for elem in block.findall("elem"):
            elements.append((int(elem.get("id")), id_list(elem.text)))
    used = sorted({n for _, conn in elements for n in conn})
    sets = {}
    for nset in mesh.findall("NodeSet"):
        sets[nset.get("name")] = id_list(nset.text)
    for surf in mesh.findall("Surface"):
        sets[surf.get("name")] = sorted({n for facet in surf for n in id_list(facet.text)})
    keep = set(used)
    sets = {name: [n for n in ids if n in keep] for name, ids in sets.items()}
    return {n: nodes[n] for n in used}, elements, {k: v for k, v in sets.items() if v}


def inp_name(name):
    return name.replace(" ", "_")


def write_inp(out, nodes, elements, sets, source):
    lines = [f"** mesh of {source} (FEBio TestSuite, MIT licence), written by feb_to_inp.py", "*NODE"]
    lines += [f"{n}, {x!r}, {y!r}, {z!r}" for n, (x, y, z) in sorted(nodes.items())]
    lines.append("*ELEMENT, TYPE=C3D8, ELSET=SOLID")
    lines += [f"{e}, " + ", ".join(str(n) for n in conn) for e, conn in elements]
    for name, ids in sets.items():
        lines.append(f"*NSET, NSET={inp_name(name)}")
        lines += [", ".join(str(n) for n in ids[i:i + 8]) for i in range(0, len(ids), 8)]
    with open(out, "w") as f:
        f.write("\n".join(lines) + "\n")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("feb")
    parser.add_argument("inp")
    parser.add_argument("--domain", action="append", default=[], help="keep only these <Elements name=...>")
    args = parser.parse_args()
    nodes, elements, sets = read_feb(args.feb, args.domain)
    if not elements:
        sys.exit(f"feb_to_inp: {args.feb}: no hex8 elements kept")
    write_inp(args.inp, nodes, elements, sets, args.feb.split("/")[-1])
    print(f"{args.inp}: {len(nodes)} nodes, {len(elements)} hex8, sets: {', '.join(sets)}")


if __name__ == "__main__":
    main()
