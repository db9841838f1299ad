#!/usr/bin/env bash
# Benchmark (not a test): one linear solve with the tangent of the quarter cube (n^3 hex8, 20 %
# compressed; tests/bench/quarter_cube.hpp) by CHOLMOD LL^T, PETSc CG + GAMG (rigid-body near-null
# space; the default of "linear_solver": "petsc") and PETSc + MUMPS Cholesky, each in its own process
# under /usr/bin/time -v. Prints a markdown table: free dofs, nonzeros, setup (analysis + factorization,
# or preconditioner setup) and solve wall times, the process's wall time and peak resident memory,
# the Krylov iterations and the relative residual |K x - b| / |b|. A solver that fails or runs out of
# memory gets a row saying so; the next sizes still run.
# Usage: tools/bench_linear.sh [BENCH_LINEAR_BINARY] [n ...]
#        (default: build/tests/bench_linear, n = 10 20 40 69; 69^3 hex8 is about 1 M free dofs)
# Environment: BENCH_SOLVERS="cholmod gamg mumps" (the solvers to run, in order), BENCH_PETSC_OPTIONS (added
# to the PETSc solvers' options, e.g. "-mg_levels_ksp_type chebyshev -mg_levels_pc_type jacobi"),
# OPENBLAS_NUM_THREADS.
# A long run: nice -n 10 tools/bench_linear.sh build/tests/bench_linear 10 20 40 69 > bench_linear.md 2>&1 &
set -euo pipefail
main() {
  here="$(cd "$(dirname "$0")/.." && pwd)"
  bench="${1:-$here/build/tests/bench_linear}"
  shift || true
  if [ $# -gt 0 ]; then sizes=("$@"); else sizes=(10 20 40 69); fi
  read -r -a solvers <<< "${BENCH_SOLVERS:-cholmod gamg mumps}"
  [ -x /usr/bin/time ] || { echo "bench_linear.sh: /usr/bin/time is needed (Debian package 'time')" >&2; exit 1; }
  [ -x "$bench" ] || { echo "bench_linear.sh: $bench not found (a build with PETSc: target bench_linear)" >&2; exit 1; }
  work="$(mktemp -d /tmp/cushion_bench_linear.XXXXXX)"
  trap 'rm -rf "$work"' EXIT

  echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'), $(free -g | awk '/Mem:/ {print $2}') GiB, OPENBLAS_NUM_THREADS=${OPENBLAS_NUM_THREADS:-unset}, PETSc options '${BENCH_PETSC_OPTIONS:-}', load $(cut -d' ' -f1 /proc/loadavg)"
  echo
  echo "| mesh | free dofs | nonzeros | solver | setup s | solve s | process wall s | peak RSS MiB | Krylov iterations | residual |"
  echo "|---|---|---|---|---|---|---|---|---|---|"
  for n in "${sizes[@]}"; do
    for s in "${solvers[@]}"; do
      out="$work/out_${s}_$n.txt"
      tv="$work/time_${s}_$n.txt"
      if ! /usr/bin/time -v -o "$tv" "$bench" "$s" "$n" "${BENCH_PETSC_OPTIONS:-}" > "$out" 2>&1; then
        printf '| %s^3 | | | %s | failed: %s | | | | | |\n' "$n" "$s" "$(tail -1 "$out" | tr '|' '/')"
        continue
      fi
      field() { sed -n "s/.* $1=\([^ ]*\).*/\1/p" "$out" | head -1; }
      iterations=$(sed -n 's/.*report="ksp [a-z]*: \([0-9]*\) iterations.*/\1/p' "$out")
      rss_kb=$(sed -n 's/.*Maximum resident set size (kbytes): \([0-9]*\).*/\1/p' "$tv")
      wall=$(sed -n 's/.*Elapsed (wall clock) time (h:mm:ss or m:ss): \(.*\)/\1/p' "$tv")
      printf '| %s^3 | %s | %s | %s | %s | %s | %s | %d | %s | %s |\n' "$n" "$(field dofs)" "$(field nnz)" "$s" \
        "$(field setup_s)" "$(field solve_s)" "$wall" $((rss_kb / 1024)) "${iterations:--}" "$(field residual)"
    done
  done
}
main "$@"
