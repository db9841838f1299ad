#!/usr/bin/env bash
# Fuzzes every file reader of cushion with libFuzzer (harnesses: tests/fuzz/fuzz_<name>.cpp).
#
#   tools/fuzz.sh [SECONDS_PER_HARNESS] [HARNESS...]
#       SECONDS_PER_HARNESS  default 600; 0 = build only
#       HARNESS              material protocol csv inp stl selectors campaign case deck (default: all)
#   environment: FUZZ_JOBS=1|2 harnesses run at once (default 1; the machine is shared, never more than 2)
#
# Configures and builds ./build-fuzz with clang (-DCUSHION_FUZZ=ON: libraries with
# -fsanitize=fuzzer-no-link,address,undefined, harnesses with -fsanitize=fuzzer,address,undefined), then runs
# each harness niced with -max_total_time, -timeout=10, -rss_limit_mb=2048 and a -max_len suited to the format.
# The seed corpus tests/fuzz/corpus/<harness>/ is copied into build-fuzz/corpus/<harness>/ (the work corpus;
# the source tree is never written). Crash, timeout and out-of-memory inputs go to build-fuzz/findings/<harness>/,
# the fuzzer's output to build-fuzz/logs/<harness>.log. Prints per harness the executions, exec/s and the
# findings; exits 1 if there is any finding (a crash, an exception other than cushion::InputError, a
# sanitizer report, a timeout, an out-of-memory or a leak), 2 on a usage error.
set -euo pipefail
cd "$(dirname "$0")/.."

ALL=(material protocol csv inp stl selectors campaign case deck)
SECONDS_PER=${1:-600}
if ! [[ "$SECONDS_PER" =~ ^[0-9]+$ ]]; then
  echo "usage: tools/fuzz.sh [SECONDS_PER_HARNESS] [HARNESS...] (harnesses: ${ALL[*]})" >&2
  exit 2
fi
shift || true
HARNESSES=("$@")
[ ${#HARNESSES[@]} -eq 0 ] && HARNESSES=("${ALL[@]}")
for h in "${HARNESSES[@]}"; do
  [[ " ${ALL[*]} " == *" $h "* ]] || { echo "tools/fuzz.sh: unknown harness '$h' (known: ${ALL[*]})" >&2; exit 2; }
done
JOBS=${FUZZ_JOBS:-1}
[[ "$JOBS" =~ ^[12]$ ]] || { echo "tools/fuzz.sh: FUZZ_JOBS must be 1 or 2" >&2; exit 2; }

max_len() {
  case "$1" in
    selectors) echo 256 ;;
    material | protocol | campaign | csv | stl) echo 4096 ;;
    inp | case | deck) echo 8192 ;;
  esac
}

B=build-fuzz
launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
CC=clang CXX=clang++ cmake -S . -B "$B" -DCUSHION_FUZZ=ON -DCUSHION_BUILD_TESTS=OFF \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g" "-DCMAKE_C_FLAGS_RELWITHDEBINFO=-O1 -g" \
  "${launcher[@]}" >/dev/null
targets=()
for h in "${HARNESSES[@]}"; do targets+=("fuzz_$h"); done
nice -n 10 cmake --build "$B" -j 2 --target "${targets[@]}"
[ "$SECONDS_PER" -eq 0 ] && exit 0

# The harnesses write each input to a per-process temporary file: on tmpfs when there is one (on this
# machine's /tmp disk a write costs ~2 ms, which capped the file-based harnesses at ~300 exec/s).
if [ -z "${TMPDIR:-}" ] && [ -d /dev/shm ] && [ -w /dev/shm ]; then export TMPDIR=/dev/shm; fi

run_one() {  # harness -> runs it, writes $B/logs/<h>.log
  local h=$1
  rm -rf "$B/corpus/$h"
  mkdir -p "$B/corpus/$h" "$B/findings/$h" "$B/logs"
  cp -r tests/fuzz/corpus/"$h"/. "$B/corpus/$h/" 2>/dev/null || true
  local dict=()
  [ -f "tests/fuzz/$h.dict" ] && dict=("-dict=tests/fuzz/$h.dict")
  # libFuzzer stops at the first finding; its exit code is kept in the log's last line.
  set +e
  ASAN_OPTIONS=detect_leaks=1:allocator_may_return_null=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
    nice -n 10 "$B/tests/fuzz/fuzz_$h" -max_total_time="$SECONDS_PER" -timeout=10 -rss_limit_mb=2048 \
    -max_len="$(max_len "$h")" -print_final_stats=1 -artifact_prefix="$B/findings/$h/" "${dict[@]}" \
    "$B/corpus/$h" >"$B/logs/$h.log" 2>&1
  echo "exit_code: $?" >>"$B/logs/$h.log"
  set -e
}

pids=()
for h in "${HARNESSES[@]}"; do
  run_one "$h" &
  pids+=($!)
  if [ ${#pids[@]} -ge "$JOBS" ]; then wait "${pids[0]}"; pids=("${pids[@]:1}"); fi
done
for p in "${pids[@]}"; do wait "$p"; done

status=0
printf '%-10s %12s %9s %8s %s\n' harness executions exec/s seconds findings
for h in "${HARNESSES[@]}"; do
  log="$B/logs/$h.log"
  runs=$(grep -oP 'stat::number_of_executed_units: *\K[0-9]+' "$log" | tail -1 || true)
  rate=$(grep -oP 'stat::average_exec_per_sec: *\K[0-9]+' "$log" | tail -1 || true)
  secs=$(grep -oP 'Done [0-9]+ runs in \K[0-9]+' "$log" | tail -1 || true)
  code=$(grep -oP '^exit_code: \K[0-9]+' "$log" | tail -1 || true)
  crashes=$(find "$B/findings/$h" -maxdepth 1 -type f \( -name 'crash-*' -o -name 'leak-*' \) | wc -l)
  timeouts=$(find "$B/findings/$h" -maxdepth 1 -type f -name 'timeout-*' | wc -l)
  ooms=$(find "$B/findings/$h" -maxdepth 1 -type f -name 'oom-*' | wc -l)
  reports=$(grep -cE 'ERROR: (AddressSanitizer|LeakSanitizer|UndefinedBehaviorSanitizer|libFuzzer)|runtime error:|FINDING:' "$log" || true)
  found="none"
  if [ "${code:-1}" != 0 ] || [ "$crashes" -gt 0 ] || [ "$timeouts" -gt 0 ] || [ "$ooms" -gt 0 ] || [ "$reports" -gt 0 ]; then
    found="crashes=$crashes timeouts=$timeouts ooms=$ooms sanitizer/exception reports=$reports (exit $code; $log)"
    status=1
  fi
  printf '%-10s %12s %9s %8s %s\n' "$h" "${runs:-?}" "${rate:-?}" "${secs:-?}" "$found"
done
[ $status -ne 0 ] && echo "findings kept in $B/findings/<harness>/; reproduce: $B/tests/fuzz/fuzz_<harness> <file>"
exit $status
