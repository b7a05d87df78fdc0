#!/usr/bin/env bash
# pvpython with its own virtual X server: verification/tools/pvpython_headless.sh SCRIPT ARGS…
# xvfb-run -a races for one display number when called concurrently, and under load a
# fresh Xvfb can refuse its first client ("bad X server connection") although its
# socket exists: here the display is ours, and a refused connection is retried
# (at most three times) — that failure is the X server's start, not the fields'.
set -u
display=$((200 + $$ % 700))
while [ -e "/tmp/.X${display}-lock" ]; do display=$((display + 1)); done
Xvfb ":${display}" -screen 0 1024x768x24 -nolisten tcp >/dev/null 2>&1 &
server=$!
output=$(mktemp)
trap 'kill "$server" 2>/dev/null; wait "$server" 2>/dev/null; rm -f "$output"' EXIT
for _ in $(seq 100); do
  [ -e "/tmp/.X11-unix/X${display}" ] && break
  sleep 0.1
done
for attempt in 1 2 3; do
  DISPLAY=":${display}" pvpython "$@" >"$output" 2>&1
  status=$?
  if [ "$status" -eq 0 ] || ! grep -q "bad X server connection" "$output"; then break; fi
  echo "pvpython_headless: attempt ${attempt}: the X server refused the connection; retrying" >&2
  sleep 2
done
cat "$output"
exit "$status"
