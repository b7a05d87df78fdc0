#!/usr/bin/env bash
# The README's second command: install dependencies, build (Release), run the
# unit tests and the fast verification gates, check the report renders, then the
# sanitizer tier (ci/sanitize.sh: ASan + UBSan build of pdmpm and the unit tests).
set -euo pipefail
cd "$(dirname "$0")/.."
ci/install_deps.sh
cmake --preset release
cmake --build --preset release -j "$(nproc)"
rm -rf build/results
ctest --preset fast -j "$(nproc)" --timeout 900
/usr/bin/python3 -m unittest discover -s reports/tests -q
/usr/bin/python3 reports/make_report.py --allow-missing
ci/sanitize.sh build-sanitize
