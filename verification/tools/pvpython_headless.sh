#!/usr/bin/env bash
# pvpython with its own virtual X server: verification/tools/pvpython_headless.sh SCRIPT ARGS…
# xvfb-run -a races for one display number when called concurrently, and under load a
# fresh Xvfb can be slow to accept clients, or lose its display to another server started
# at the same moment. So each attempt (at most three) starts its own Xvfb on a free
# display, waits until that server answers a client (xdpyinfo from x11-utils, up to
# 30 s), and runs pvpython only then; a refused connection is retried with a new
# server — that failure is the X server's start, not the fields'.
set -u
# Whether the server on display $1 accepts a client (without xdpyinfo: its socket exists).
answers() {
  if command -v xdpyinfo >/dev/null; then
    DISPLAY="$1" xdpyinfo >/dev/null 2>&1
  else
    [ -e "/tmp/.X11-unix/X${1#:}" ]
  fi
}
output=$(mktemp)
server=
stop_server() {
  if [ -n "$server" ]; then
    kill "$server" 2>/dev/null
    wait "$server" 2>/dev/null
  fi
  server=
}
trap 'stop_server; rm -f "$output"' EXIT
display=$((200 + $$ % 700))
status=1
for attempt in 1 2 3; do
  while [ -e "/tmp/.X${display}-lock" ] || [ -e "/tmp/.X11-unix/X${display}" ]; do display=$((display + 1)); done
  Xvfb ":${display}" -screen 0 1024x768x24 -nolisten tcp >/dev/null 2>&1 &
  server=$!
  ready=no
  for _ in $(seq 300); do
    kill -0 "$server" 2>/dev/null || break  # lost the display to another server
    if answers ":${display}"; then
      ready=yes
      break
    fi
    sleep 0.1
  done
  if [ "$ready" = yes ]; then
    DISPLAY=":${display}" pvpython "$@" >"$output" 2>&1
    status=$?
    if [ "$status" -eq 0 ] || ! grep -q "bad X server connection" "$output"; then break; fi
    echo "pvpython_headless: attempt ${attempt}: the X server refused the connection; retrying" >&2
  else
    echo "pvpython_headless: attempt ${attempt}: Xvfb on :${display} did not start; retrying" >&2
    echo "pvpython_headless: no X server could be started" >"$output"
  fi
  stop_server
  display=$((display + 1))
  sleep 1
done
cat "$output"
exit "$status"
