#!/usr/bin/env bash
# The sanitizer tier: pdmpm and the unit tests built with AddressSanitizer and
# UndefinedBehaviorSanitizer (-O1, any report aborts the test), then the unit label
# (the scene fuzzer and the checkpoint tests run the sanitized pdmpm). A unity build
# (16 sources per translation unit) because instrumented compiles dominate: on this
# project's 2-core machine a file-by-file build took 13.3 min, the unity build 6–7;
# the 272 unit tests 7–11 min. Part of ci/test.sh (and so of CI).
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build-sanitize}
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 \
  -DCMAKE_CXX_FLAGS="-fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined" \
  -DPDMPM_BUILD_BENCHMARKS=OFF -DCMAKE_UNITY_BUILD=ON -DCMAKE_UNITY_BUILD_BATCH_SIZE=16
cmake --build "$build" -j "$(nproc)" --target pdmpm unit_tests
cd "$build"
# The instrumented pdmpm runs ~12× slower: the tests' hang limits scale with it.
# The ParaView check (a third-party reader opening our files) runs in the release tier;
# here it would only add an X server started under the sanitized tests' load.
PDMPM_TEST_TIME_SCALE=10 ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
  ctest -L unit -E '^ParaView\.' -j "$(nproc)" --timeout 900 --output-on-failure
