#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# with_xvfb.sh COMMAND...: runs COMMAND under a private Xvfb (24-bit screen) and stops it
# afterwards: the display of the demo and of the pvbatch_*.py rendering tests.
#
# Why not plain `xvfb-run -a`: on this kind of machine, under load, a pvbatch run now and
# then fails to open its display ("vtkXOpenGLRenderWindow: bad X server connection",
# XOpenDisplay returning NULL) although the server is alive and accepts other clients
# before and after. That is the test infrastructure failing, not the code under test, so
# such a run -- and only such a run -- is repeated with a fresh server, at most three times.
# Any other failure is reported as it is.
set -u
log=$(mktemp)
trap 'rm -f "$log"' EXIT

probe() {
  /usr/bin/python3 -c "import ctypes, sys
x = ctypes.CDLL('libX11.so.6')
x.XOpenDisplay.restype = ctypes.c_void_p
sys.exit(0 if x.XOpenDisplay(b':$1') else 1)" 2>/dev/null
}

run_once() {
  local display server ready rc
  for _ in 1 2 3 4 5 6 7 8; do
    display=$(( 200 + RANDOM % 700 ))
    if [ -e "/tmp/.X${display}-lock" ] || [ -e "/tmp/.X11-unix/X${display}" ]; then
      continue
    fi
    Xvfb ":${display}" -screen 0 1280x1024x24 -nolisten tcp >/dev/null 2>&1 &
    server=$!
    ready=0
    for _ in $(seq 1 100); do
      kill -0 "$server" 2>/dev/null || break
      if probe "$display"; then
        ready=1
        break
      fi
      sleep 0.1
    done
    if [ "$ready" = 1 ]; then
      DISPLAY=":${display}" "$@" >"$log" 2>&1
      rc=$?
      kill "$server" 2>/dev/null
      wait "$server" 2>/dev/null
      return "$rc"
    fi
    kill "$server" 2>/dev/null
    wait "$server" 2>/dev/null
  done
  echo "with_xvfb.sh: could not start an Xvfb server" >"$log"
  return 1
}

for attempt in 1 2 3; do
  run_once "$@"
  rc=$?
  if [ "$rc" -ne 0 ] && grep -q "bad X server connection" "$log" && [ "$attempt" -lt 3 ]; then
    echo "with_xvfb.sh: the display could not be opened (attempt $attempt); retrying with a new server" >&2
    continue
  fi
  cat "$log"
  exit "$rc"
done
