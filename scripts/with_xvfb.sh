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
dfile=$(mktemp)
xlog=$(mktemp)
alive=unknown
display=none
trap 'rm -f "$log" "$dfile" "$xlog"' EXIT

probe() {
  /usr/bin/python3 -c "import ctypes, sys
x = ctypes.CDLL('libX11.so.6')
x.XOpenDisplay.restype = ctypes.c_void_p
sys.exit(0 if x.XOpenDisplay(b':$1') else 1)" 2>/dev/null
}

run_once() {
  local server ready rc
  # -displayfd: the server takes the first free display itself (its lock file is made
  # atomically) and writes the number once it accepts clients; choosing a number here and
  # checking its lock file left a window in which two runs could share one server.
  : >"$dfile"
  Xvfb -displayfd 3 -screen 0 1280x1024x24 -nolisten tcp 3>"$dfile" >"$xlog" 2>&1 &
  server=$!
  ready=0
  for _ in $(seq 1 100); do
    kill -0 "$server" 2>/dev/null || break
    display=$(head -n 1 "$dfile" 2>/dev/null)
    if [ -n "$display" ] && probe "$display"; then
      ready=1
      break
    fi
    sleep 0.1
  done
  if [ "$ready" != 1 ]; then
    kill "$server" 2>/dev/null
    wait "$server" 2>/dev/null
    { echo "with_xvfb.sh: could not start an Xvfb server"; cat "$xlog"; } >"$log"
    return 1
  fi
  DISPLAY=":${display}" "$@" >"$log" 2>&1
  rc=$?
  # For the retry message: whether the server outlived the command.
  if kill -0 "$server" 2>/dev/null; then alive=yes; else alive=no; fi
  kill "$server" 2>/dev/null
  wait "$server" 2>/dev/null
  return "$rc"
}

for attempt in 1 2 3; do
  run_once "$@"
  rc=$?
  if [ "$rc" -ne 0 ] && grep -q "bad X server connection" "$log" && [ "$attempt" -lt 3 ]; then
    echo "with_xvfb.sh: the display :$display could not be opened (attempt $attempt; the server" \
      "was alive after the command: $alive); retrying with a new server" >&2
    sed 's/^/with_xvfb.sh: Xvfb: /' "$xlog" >&2
    continue
  fi
  cat "$log"
  exit "$rc"
done
