#!/usr/bin/env bash
# The test suite under AddressSanitizer + UndefinedBehaviorSanitizer (docs/STABILITY.md), in build-asan/.
# Run after ./scripts/setup.sh (which installs the packages). Any sanitizer report fails its test.
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build-asan -DSKINSPEC_SANITIZE=ON -DSKINSPEC_BENCH=OFF -DCMAKE_BUILD_TYPE=RelWithDebInfo > /dev/null
cmake --build build-asan -j 2
# A failed test runs once more: LeakSanitizer's exit scan itself crashes now and then ("Tracer caught signal 11",
# about one test in 500 per run, always one that wrote images through OpenImageIO; docs/STABILITY.md). A sanitizer
# report from our code comes back on the second run and still fails.
ctest --test-dir build-asan --output-on-failure -j 2 --timeout 900 --repeat until-pass:2
