#!/usr/bin/env bash
# Benchmark (not a test): the cube_compression case (load 30 s, hold 2 s, unload 30 s, hyperfoam +
# Prony) on n^3 hex8 meshes of the quarter cube. Prints a markdown table of the figures `cushion run`
# reports plus the CPU time (user + system, all threads) and peak resident memory from
# /usr/bin/time -v and the machine load (1-minute load average before and after each run): on a
# shared machine wall times are only meaningful with the load; CPU time is less sensitive to it.
# Usage: tools/bench_cube.sh [CUSHION_BINARY] [n ...]     (default: build/tools/cushion, n = 10 20 40)
# Environment: OPENBLAS_NUM_THREADS (BLAS threads of the CHOLMOD factorization; 1 is faster on a
# loaded machine), BENCH_KEEP=DIR keeps each run's output and summary in DIR/out_n,
# BENCH_NEWTON=modified runs with "solver": {"newton": "modified"} (tangent reuse; default: full).
# A long run: nice -n 10 tools/bench_cube.sh build/tools/cushion 40 > bench_40.md 2>&1 &
set -euo pipefail
# (the whole script is read before it runs: editing it during a long run is harmless)
main() {
  here="$(cd "$(dirname "$0")/.." && pwd)"
  cushion="${1:-$here/build/tools/cushion}"
  shift || true
  if [ $# -gt 0 ]; then sizes=("$@"); else sizes=(10 20 40); fi
  [ -x /usr/bin/time ] || { echo "bench_cube.sh: /usr/bin/time is needed (Debian package 'time')" >&2; exit 1; }
  work="${BENCH_KEEP:-$(mktemp -d /tmp/cushion_bench_cube.XXXXXX)}"
  mkdir -p "$work"
  [ -n "${BENCH_KEEP:-}" ] || trap 'rm -rf "$work"' EXIT
  load() { cut -d' ' -f1 /proc/loadavg; }

  newton="${BENCH_NEWTON:-full}"
  case "$newton" in full|modified) ;; *) echo "bench_cube.sh: BENCH_NEWTON must be full or modified, not '$newton'" >&2; exit 2;; esac
  echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'), OPENBLAS_NUM_THREADS=${OPENBLAS_NUM_THREADS:-unset}, Newton: $newton"
  echo
  echo "| mesh | elements | free dofs | nonzeros | assembly us/element | factorizations | factorization s (each) | symbolic analyses | increments | Newton iterations | total s (wall) | CPU s | peak RSS MiB | load before/after |"
  echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
  for n in "${sizes[@]}"; do
    # The shipped case with its mesh replaced by n x n x n elements (paths made absolute).
    sed -e "s|\"elements\": \[4, 4, 8\]|\"elements\": [$n, $n, $n]|" \
        -e "s|\"../materials/paper_table3.json\"|\"$here/cases/materials/paper_table3.json\"|" \
        -e "s|\"solver\": {\"linear_solver\": \"auto\"}|\"solver\": {\"linear_solver\": \"auto\", \"newton\": \"$newton\"}|" \
        "$here/cases/cube_compression/case.json" > "$work/cube_$n.json"
    s="$work/summary_$n.txt"
    before=$(load)
    /usr/bin/time -v -o "$work/time_$n.txt" "$cushion" run "$work/cube_$n.json" -o "$work/out_$n" --quiet --overwrite > "$s"
    after=$(load)
    field() { sed -n "$1" "$s" | head -1; }
    elements=$(field 's/.*model: [0-9]* nodes, \([0-9]*\) elements.*/\1/p')
    dofs=$(field 's/.* \([0-9]*\) free dofs.*/\1/p')
    nnz=$(field 's/.* \([0-9]*\) nonzeros.*/\1/p')
    asm=$(field 's/.*, \([0-9.e+-]*\) us per element.*/\1/p')
    nfact=$(field 's/.*, \([0-9]*\) factorizations, .*/\1/p')
    fact=$(field 's/.*factorizations, \([0-9.]*\) s .*/\1/p')
    each=$(field 's/.*factorizations, [0-9.]* s (\([0-9.e+-]*\) s each).*/\1/p')
    analyses=$(field 's/.*, \([0-9]*\) symbolic analyses.*/\1/p')
    increments=$(field 's/.*steps, \([0-9]*\) increments.*/\1/p')
    iters=$(field 's/.*cut-backs, \([0-9]*\) Newton iterations.*/\1/p')
    total=$(field 's/.*wall time \([0-9.]*\) s.*/\1/p')
    rss_kb=$(sed -n 's/.*Maximum resident set size (kbytes): \([0-9]*\).*/\1/p' "$work/time_$n.txt")
    cpu=$(awk -F': ' '/User time|System time/ { t += $2 } END { printf "%.1f", t }' "$work/time_$n.txt")
    printf '| %s^3 | %s | %s | %s | %s | %s | %s (%s) | %s | %s | %s | %s | %s | %d | %s / %s |\n' "$n" "$elements" \
      "$dofs" "$nnz" "$asm" "$nfact" "$fact" "$each" "$analyses" "$increments" "$iters" "$total" "$cpu" \
      $((rss_kb / 1024)) "$before" "$after"
  done
}
main "$@"
exit
