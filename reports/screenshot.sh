#!/usr/bin/env bash
# Renders the report page with headless Chromium to a PNG, to look at it without a browser.
#   reports/screenshot.sh [PAGE.html] [OUT.png]     (defaults: build/report/index.html, build/report/screenshot.png)
#   WINDOW=1400,6000 reports/screenshot.sh ...      (width,height in CSS pixels; default 1400,3000)
# Chromium runs offline: no network features, a throwaway profile, and the page itself loads nothing.
set -euo pipefail

page="${1:-build/report/index.html}"
out="${2:-build/report/screenshot.png}"
window="${WINDOW:-1400,3000}"
chromium="${CHROMIUM:-/usr/bin/chromium}"

if [ ! -f "$page" ]; then
  echo "screenshot.sh: page $page not found (run reports/make_report.py first)" >&2
  exit 1
fi
if [ ! -x "$chromium" ]; then
  echo "screenshot.sh: $chromium not found (Debian package: chromium)" >&2
  exit 1
fi

profile="$(mktemp -d)"
trap 'rm -rf "$profile"' EXIT
mkdir -p "$(dirname "$out")"
page_abs="$(realpath "$page")"
out_abs="$(realpath -m "$out")"

"$chromium" --headless --no-sandbox --disable-gpu --disable-quic --no-first-run \
  --disable-background-networking --disable-component-update --disable-sync \
  --hide-scrollbars --user-data-dir="$profile" \
  --screenshot="$out_abs" --window-size="$window" "file://$page_abs" 2>"$profile/chromium.log" || {
  echo "screenshot.sh: chromium failed; its log:" >&2
  cat "$profile/chromium.log" >&2
  exit 1
}
[ -s "$out_abs" ] || { echo "screenshot.sh: no screenshot written" >&2; exit 1; }
echo "$out"
