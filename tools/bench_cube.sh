#!/usr/bin/env bash
# Benchmark (not a test): the cube_compression case (load 30 s, hold 2 s, unload 30 s, hyperfoam +
# Prony) on n^3 hex8 meshes of the quarter cube; prints the figures `cushion run` reports.
# Usage: tools/bench_cube.sh [CUSHION_BINARY] [n ...]     (default: build/tools/cushion, n = 10 20 40)
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
cushion="${1:-$here/build/tools/cushion}"
shift || true
if [ $# -gt 0 ]; then sizes=("$@"); else sizes=(10 20 40); fi
work="$(mktemp -d /tmp/cushion_bench_cube.XXXXXX)"
trap 'rm -rf "$work"' EXIT
echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')"
printf '%-6s %8s %10s %12s %10s %10s %8s %8s %10s %10s %9s\n' mesh elements dofs nonzeros "asm_us/el" "fact_s" n_fact iters "total_s" "wall_s" "peak_MiB"
for n in "${sizes[@]}"; do
  # The shipped case with its mesh replaced by n x n x n elements (paths made absolute).
  sed -e "s|\"elements\": \[4, 4, 8\]|\"elements\": [$n, $n, $n]|" \
      -e "s|\"../materials/paper_table3.json\"|\"$here/cases/materials/paper_table3.json\"|" \
      "$here/cases/cube_compression/case.json" > "$work/cube_$n.json"
  start=$(date +%s%N)
  "$cushion" run "$work/cube_$n.json" -o "$work/out_$n" --quiet > "$work/summary_$n.txt"
  wall=$(awk -v a="$start" -v b="$(date +%s%N)" 'BEGIN { print (b - a) / 1e9 }')
  s="$work/summary_$n.txt"
  elements=$(sed -n 's/.*model: [0-9]* nodes, \([0-9]*\) elements.*/\1/p' "$s")
  dofs=$(sed -n 's/.* \([0-9]*\) free dofs.*/\1/p' "$s")
  nnz=$(sed -n 's/.* \([0-9]*\) nonzeros.*/\1/p' "$s")
  asm=$(sed -n 's/.*, \([0-9.e+-]*\) us per element.*/\1/p' "$s")
  nfact=$(sed -n 's/.*, \([0-9]*\) factorizations, .*/\1/p' "$s")
  fact=$(sed -n 's/.*factorizations, \([0-9.]*\) s .*/\1/p' "$s")
  iters=$(sed -n 's/.*cut-backs, \([0-9]*\) Newton iterations.*/\1/p' "$s")
  total=$(sed -n 's/.*wall time \([0-9.]*\) s.*/\1/p' "$s")
  peak=$(sed -n 's/.*peak memory: \([0-9.]*\) MiB.*/\1/p' "$s")
  printf '%-6s %8s %10s %12s %10s %10s %8s %8s %10s %10.2f %9s\n' "${n}^3" "$elements" "$dofs" "$nnz" "$asm" "$fact" "$nfact" "$iters" "$total" "$wall" "$peak"
done
