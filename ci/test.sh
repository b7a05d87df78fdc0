#!/usr/bin/env bash
# The README's second command: install dependencies, build (Release), run the
# unit tests and the fast verification gates, then check the report renders.
set -euo pipefail
cd "$(dirname "$0")/.."
ci/install_deps.sh
cmake --preset release
cmake --build --preset release -j "$(nproc)"
rm -rf build/results
ctest --preset fast -j "$(nproc)" --timeout 900
/usr/bin/python3 -m unittest discover -s reports/tests -q
/usr/bin/python3 reports/make_report.py --allow-missing
