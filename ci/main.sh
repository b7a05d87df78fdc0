#!/usr/bin/env bash
# The README's first command: install dependencies, build, run the verification
# suite (unit tests and fast gates), write the HTML report and print its path.
# FULL=1 also runs the paper-resolution (`full`) gates.
set -euo pipefail
cd "$(dirname "$0")/.."
ci/install_deps.sh
cmake --preset release
cmake --build --preset release -j "$(nproc)"
labels="unit|fast"
[ "${FULL:-0}" = "1" ] && labels="unit|fast|full"
status=0
rm -rf build/results  # gates from an earlier run must not leak into this report
ctest --test-dir build -L "$labels" -j "$(nproc)" --output-on-failure || status=$?
/usr/bin/python3 reports/make_report.py --allow-missing || status=$?
echo "report: $(pwd)/build/report/index.html"
exit $status
