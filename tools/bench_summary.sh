# Sourced by the benchmark scripts (tools/bench_cube.sh, tools/bench_sitbar_solvers.sh): reads the summary
# `cushion run` prints (solver/analysis/analysis.cpp, format_summary) and the report of /usr/bin/time -v.
# read_summary SUMMARY_FILE TIME_FILE sets: elements dofs nnz asm_s asm_us nfact fact each method solves
# analyses increments iters total (wall s), cpu (user + system s), rss_mib (peak resident set).
read_summary() {
  local s="$1" t="$2"
  field() { sed -n "$1" "$s" | head -1; }
  elements=$(field 's/.*model: [0-9]* nodes, \([0-9]*\) elements.*/\1/p')
  dofs=$(field 's/.* \([0-9]*\) free dofs.*/\1/p')
  nnz=$(field 's/.* \([0-9]*\) nonzeros.*/\1/p')
  asm_s=$(field 's/.*element loops, \([0-9.]*\) s.*/\1/p')
  asm_us=$(field 's/.*, \([0-9.e+-]*\) us per element.*/\1/p')
  nfact=$(field 's/.*, \([0-9]*\) factorizations, .*/\1/p')
  fact=$(field 's/.*factorizations, \([0-9.]*\) s .*/\1/p')
  each=$(field 's/.*factorizations, [0-9.]* s (\([0-9.e+-]*\) s each).*/\1/p')
  method=$(field 's/.*linear solver: \([^,]*\), [0-9]* factorizations.*/\1/p')
  solves=$(field 's/.*, solves \([0-9.]*\) s.*/\1/p')
  analyses=$(field 's/.*, \([0-9]*\) symbolic analyses.*/\1/p')
  increments=$(field 's/.*steps, \([0-9]*\) increments.*/\1/p')
  iters=$(field 's/.*cut-backs, \([0-9]*\) Newton iterations.*/\1/p')
  total=$(field 's/.*wall time \([0-9.]*\) s.*/\1/p')
  rss_mib=$(( $(sed -n 's/.*Maximum resident set size (kbytes): \([0-9]*\).*/\1/p' "$t") / 1024 ))
  cpu=$(awk -F': ' '/User time|System time/ { t += $2 } END { printf "%.1f", t }' "$t")
}
