#!/usr/bin/env bash
# Runs the test suite under AddressSanitizer + UndefinedBehaviorSanitizer (gcc) in ./build-asan.
#
#   tools/sanitize.sh            the whole suite (every ctest; measured 2026-11-24: build 14 min, tests 2.3 h on 2 cores
#                                shared part of the time; the diagnose and fit tests dominate under ASan)
#   tools/sanitize.sh --readers  a named subset (not run by CI): the io, mesh and material libraries and their tests
#                                (every file reader, the fuzz-found regressions, the material laws; a few minutes)
#   extra arguments go to ctest (e.g. -R Inp, -L solver)
#
# Build: RelWithDebInfo (-O2 -g) with -fsanitize=address,undefined -fno-sanitize-recover=undefined
# -fno-omit-frame-pointer, for every library, test and the `cushion` program the CLI tests run. Sanitizer reports go
# to build-asan/sanitizer-logs/ (log_path), so a report is found even where a test expects a non-zero exit of the
# program it runs; any file there with an ASan/LSan ERROR or a UBSan runtime error fails the run. ASan's leak check is on. Prints the time taken; exit 0 only when
# every test passed and no report was written.
set -euo pipefail
cd "$(dirname "$0")/.."

subset=0
if [ "${1:-}" = "--readers" ]; then subset=1; shift; fi
BUILD=build-asan
LOGS="$PWD/$BUILD/sanitizer-logs"
start=$(date +%s)

launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
flags="-fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer"
cmake -S . -B "$BUILD" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS="$flags" "${launcher[@]}" \
      -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" \
      -DCMAKE_SHARED_LINKER_FLAGS="-fsanitize=address,undefined" >/dev/null
if [ $subset -eq 1 ]; then
  cmake --build "$BUILD" -j "$(nproc)" --target test_io test_mesh test_material
  set -- -L '^(io|mesh|material)$' "$@"
else
  cmake --build "$BUILD" -j "$(nproc)"
fi
built=$(date +%s)

rm -rf "$LOGS" && mkdir -p "$LOGS"
export ASAN_OPTIONS="log_path=$LOGS/asan:detect_leaks=1:strict_string_checks=1:detect_stack_use_after_return=1"
export UBSAN_OPTIONS="log_path=$LOGS/ubsan:print_stacktrace=1:halt_on_error=1"
status=0
# The PETSc tests (label petsc) start OpenMPI, which leaks at MPI_Finalize: they run apart, with OpenMPI's leaks
# suppressed (tools/lsan_openmpi.supp; slow unwinding so that the suppressions can match OpenMPI's frames).
ctest --test-dir "$BUILD" --output-on-failure -j "$(nproc)" -LE petsc "$@" || status=$?
if [ $subset -eq 0 ] && [ -n "$(ctest --test-dir "$BUILD" -N -L petsc "$@" | grep 'Test *#')" ]; then
  ASAN_OPTIONS="$ASAN_OPTIONS:fast_unwind_on_malloc=0" LSAN_OPTIONS="suppressions=$PWD/tools/lsan_openmpi.supp" \
    ctest --test-dir "$BUILD" --output-on-failure -j "$(nproc)" -L petsc "$@" || status=$?
fi
end=$(date +%s)

# A log file that holds only LeakSanitizer's "Suppressions used" statistics (the PETSc tests) is not a report.
report_files=$(grep -l -E "ERROR: |runtime error: " -r "$LOGS" || true)
reports=$(printf '%s' "$report_files" | grep -c . || true)
echo "sanitize: build $((built - start)) s, tests $((end - built)) s on $(nproc) cores (load now: $(cut -d' ' -f1-3 /proc/loadavg))"
if [ "$reports" -gt 0 ]; then
  echo "sanitize: $reports sanitizer report(s) in $LOGS:"
  printf '%s\n' "$report_files" | head -20
  head -40 "$(printf '%s\n' "$report_files" | head -1)"
  exit 1
fi
[ $status -eq 0 ] && echo "sanitize: all tests passed, no sanitizer report" || echo "sanitize: ctest failed ($status)"
exit $status
