#!/usr/bin/env bash
# Benchmark (not a test): the cube_compression case (load 30 s, hold 2 s, unload 30 s, hyperfoam +
# Prony) on n^3 hex8 meshes of the quarter cube. Prints a markdown table of the figures `cushion run`
# reports plus the CPU time (user + system, all threads) and peak resident memory from
# /usr/bin/time -v and the machine load (1-minute load average before and after each run): on a
# shared machine wall times are only meaningful with the load; CPU time is less sensitive to it.
# Usage: tools/bench_cube.sh [CUSHION_BINARY] [n ...]     (default: build/tools/cushion, n = 10 20 40)
# Environment: OPENBLAS_NUM_THREADS (BLAS threads of the CHOLMOD factorization; 1 is faster on a
# loaded machine), BENCH_KEEP=DIR keeps each run's output and summary in DIR/out_n,
# BENCH_NEWTON=modified runs with "solver": {"newton": "modified"} (tangent reuse; default: full),
# BENCH_SOLVER=petsc chooses "linear_solver" (default auto: CHOLMOD), BENCH_PETSC_OPTIONS its "petsc_options",
# BENCH_NP=N runs under `mpirun -np N` (a distributed run; needs BENCH_SOLVER=petsc; peak RSS is then the
# largest process's).
# A long run: nice -n 10 tools/bench_cube.sh build/tools/cushion 40 > bench_40.md 2>&1 &
set -euo pipefail
# (the whole script is read before it runs: editing it during a long run is harmless)
main() {
  here="$(cd "$(dirname "$0")/.." && pwd)"
  . "$here/tools/bench_summary.sh"
  cushion="${1:-$here/build/tools/cushion}"
  shift || true
  if [ $# -gt 0 ]; then sizes=("$@"); else sizes=(10 20 40); fi
  [ -x /usr/bin/time ] || { echo "bench_cube.sh: /usr/bin/time is needed (Debian package 'time')" >&2; exit 1; }
  work="${BENCH_KEEP:-$(mktemp -d /tmp/cushion_bench_cube.XXXXXX)}"
  mkdir -p "$work"
  [ -n "${BENCH_KEEP:-}" ] || trap 'rm -rf "$work"' EXIT
  load() { cut -d' ' -f1 /proc/loadavg; }

  newton="${BENCH_NEWTON:-full}"
  solver="${BENCH_SOLVER:-auto}"
  np="${BENCH_NP:-1}"
  solver_keys="\"linear_solver\": \"$solver\", \"newton\": \"$newton\""
  [ "$solver" = petsc ] && solver_keys="$solver_keys, \"petsc_options\": \"${BENCH_PETSC_OPTIONS:-}\""
  launch=()
  [ "$np" -gt 1 ] && launch=(mpirun -q --oversubscribe -np "$np")
  [ "$np" -gt 1 ] && [ "$(id -u)" -eq 0 ] && launch+=(--allow-run-as-root)
  case "$newton" in full|modified) ;; *) echo "bench_cube.sh: BENCH_NEWTON must be full or modified, not '$newton'" >&2; exit 2;; esac
  echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'), OPENBLAS_NUM_THREADS=${OPENBLAS_NUM_THREADS:-unset}, Newton: $newton, linear solver: $solver ${BENCH_PETSC_OPTIONS:-}, processes: $np"
  echo
  echo "| mesh | elements | free dofs | nonzeros | linear solver | assembly us/element | factorizations | factorization s (each) | solves s | symbolic analyses | increments | Newton iterations | total s (wall) | CPU s | peak RSS MiB | load before/after |"
  echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
  for n in "${sizes[@]}"; do
    # The shipped case with its mesh replaced by n x n x n elements (paths made absolute).
    sed -e "s|\"elements\": \[4, 4, 8\]|\"elements\": [$n, $n, $n]|" \
        -e "s|\"../materials/paper_table3.json\"|\"$here/cases/materials/paper_table3.json\"|" \
        -e "s|\"solver\": {\"linear_solver\": \"auto\"}|\"solver\": {$solver_keys}|" \
        "$here/cases/cube_compression/case.json" > "$work/cube_$n.json"
    s="$work/summary_$n.txt"
    before=$(load)
    /usr/bin/time -v -o "$work/time_$n.txt" "${launch[@]}" "$cushion" run "$work/cube_$n.json" -o "$work/out_$n" --quiet --overwrite > "$s"
    after=$(load)
    read_summary "$s" "$work/time_$n.txt"
    printf '| %s^3 | %s | %s | %s | %s | %s | %s | %s (%s) | %s | %s | %s | %s | %s | %s | %d | %s / %s |\n' "$n" "$elements" \
      "$dofs" "$nnz" "$method" "$asm_us" "$nfact" "$fact" "$each" "$solves" "$analyses" "$increments" "$iters" "$total" "$cpu" \
      "$rss_mib" "$before" "$after"
  done
}
main "$@"
exit
