#!/usr/bin/env bash
# Independent check of cushion's contact + hyperfoam against CalculiX (Debian calculix-ccx):
# a rigid sphere (R = 100 mm) pressed 60 mm into the quarter 400 x 400 x 80 mm block, hyperfoam of
# cases/materials/paper_table3.json without Prony, base fixed, frictionless, same C3D8 mesh (one
# mesh.inp read by both programs). Prints the full-model indenter force of both at 20/40/60 mm and
# the wall-time ratio (both on one thread).
#
# usage: tools/calculix_indentation.sh [OUT_DIR] [-- options of tools/calculix/make_indentation.py]
#   OUT_DIR defaults to results/calculix_check; CUSHION (path of the cushion binary) defaults to
#   build/tools/cushion. Example of a finer mesh: tools/calculix_indentation.sh /tmp/cx -- --n 20 --nz 12
# The committed cases/calculix_check/ holds the default-mesh files this script writes.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(dirname "$here")"
out="${1:-$root/results/calculix_check}"
shift || true
[[ "${1:-}" == "--" ]] && shift
cushion="${CUSHION:-$root/build/tools/cushion}"
command -v ccx >/dev/null || { echo "calculix_indentation.sh: ccx not found (apt-get install calculix-ccx)" >&2; exit 2; }
[[ -x "$cushion" ]] || { echo "calculix_indentation.sh: cushion binary '$cushion' not found (set CUSHION=...)" >&2; exit 2; }

mkdir -p "$out"
python3 "$here/calculix/make_indentation.py" "$out" "$@"
cd "$out"
rm -rf cushion_out ccx_indentation.dat
seconds() { date +%s.%N; }

echo "CalculiX ($({ ccx -v 2>/dev/null || true; } | grep -o "Version [0-9.]*" | head -1)) ..."
t0=$(seconds)
OMP_NUM_THREADS=1 CCX_NPROC_STIFFNESS=1 NUMBER_OF_CPUS=1 ccx -i ccx_indentation > ccx.log 2>&1 ||
  { echo "CalculiX failed, see $out/ccx.log" >&2; exit 1; }
t1=$(seconds)
grep -q "forces (fx,fy,fz)" ccx_indentation.dat || { echo "CalculiX wrote no forces, see $out/ccx.log" >&2; exit 1; }

echo "cushion ..."
"$cushion" run case.json -o cushion_out --threads 1 --quiet > cushion.log 2>&1 ||
  { echo "cushion failed, see $out/cushion.log" >&2; exit 1; }
t2=$(seconds)
grep -E "summary|factorizations" cushion.log

python3 "$here/calculix/compare.py" ccx_indentation.dat cushion_out/contact_sphere.csv \
  "$(echo "$t1 - $t0" | bc)" "$(echo "$t2 - $t1" | bc)" 20 40 60 | tee comparison.txt
