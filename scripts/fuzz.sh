#!/usr/bin/env bash
# Builds the libFuzzer targets (fuzz/) with clang in build-fuzz/ and runs each for SECONDS (default 60),
# starting from the seed corpus in fuzz/corpus/<target>; new inputs go to build-fuzz/corpus/<target>, any
# crash, leak, timeout or sanitizer report to build-fuzz/artifacts/ and a non-zero exit.
# Usage: scripts/fuzz.sh [SECONDS] [TARGET ...]   (run ./scripts/setup.sh first: it installs clang)
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}
shift || true
targets=("$@")
if [ "${#targets[@]}" -eq 0 ]; then
  # Every fuzz/fuzz_NAME.cpp (the same folder CMakeLists.txt builds the targets from).
  for f in fuzz/fuzz_*.cpp; do t=${f#fuzz/fuzz_}; targets+=("${t%.cpp}"); done
fi

CC=clang CXX=clang++ cmake -S . -B build-fuzz -DSKINSPEC_FUZZ=ON -DSKINSPEC_BUILD_TESTS=OFF -DCMAKE_BUILD_TYPE=RelWithDebInfo > /dev/null
cmake --build build-fuzz -j 2 --target "${targets[@]/#/fuzz_}"

export LSAN_OPTIONS="suppressions=$PWD/tests/sanitizers/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
mkdir -p build-fuzz/artifacts
for t in "${targets[@]}"; do
  mkdir -p "build-fuzz/corpus/$t"
  echo "fuzz: $t for ${seconds} s"
  status=0
  "build-fuzz/fuzz_$t" "build-fuzz/corpus/$t" "fuzz/corpus/$t" -max_total_time="$seconds" -timeout=20 -rss_limit_mb=2048 \
    -artifact_prefix="build-fuzz/artifacts/$t-" -print_final_stats=1 > "build-fuzz/$t.log" 2>&1 || status=$?
  grep -E "^(#[0-9]+ +DONE|stat::number_of_executed_units|stat::new_units_added)" "build-fuzz/$t.log" || true
  if [ "$status" -ne 0 ]; then
    tail -n 40 "build-fuzz/$t.log"
    echo "fuzz: $t found a problem (build-fuzz/artifacts/$t-*, log build-fuzz/$t.log)"
    exit 1
  fi
done
