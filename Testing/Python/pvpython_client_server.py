# SPDX-License-Identifier: BSD-3-Clause
# Client-server, as a ParaView user runs it against a remote machine: a pvserver on a free
# loopback port, pvpython connected to it with Connect("localhost", port), the plugin loaded on
# both sides (the server executes the filters, the client needs the proxy definitions), the
# README's pipeline (OpenDataFile, Box, DeformableSurface) run on the server on a ball phantom in
# three file formats, the surfaces fetched to the client and checked (on the ball, closed
# 2-manifold, inputs unchanged); then the server is stopped and no process is left behind.
import os
import socket
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from paraview import simple  # noqa: E402

import readme_pipeline as rp  # noqa: E402

PLUGIN = os.environ["DS_PLUGIN"]


def free_port():
    """A loopback TCP port nobody listens on now."""
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def start_server(port, log_path):
    """pvserver on port; returns the process once its log says it accepts connections.
    (Not a probe connection: pvserver serves one client, and a probe would be it.)"""
    log = open(log_path, "w")
    server = subprocess.Popen(["pvserver", "--server-port=%d" % port, "--force-offscreen-rendering"],
                              stdout=log, stderr=subprocess.STDOUT)
    deadline = time.time() + 60
    while time.time() < deadline:
        if server.poll() is not None:
            raise SystemExit("FAILED: pvserver exited with %d before accepting connections" % server.returncode)
        with open(log_path) as f:
            if "Accepting connection" in f.read():
                return server
        time.sleep(0.2)
    server.kill()
    raise SystemExit("FAILED: pvserver did not accept connections on port %d within 60 s" % port)


def stop_server(server, connection):
    """Disconnect, then stop the server and make sure its process is gone. (pvserver 5.11 here
    does not exit by itself while this client process lives on, so it gets SIGTERM; the client
    then logs one "Broken pipe" as it closes the dead socket on exit.)"""
    from paraview import servermanager
    if connection is not None:
        servermanager.Disconnect(connection)
    try:
        server.wait(timeout=5)
    except subprocess.TimeoutExpired:
        server.terminate()
        server.wait(timeout=10)
    return server.returncode


out = os.path.join(os.environ.get("DS_TEST_OUTPUT", "."), "client_server")
os.makedirs(out, exist_ok=True)
port = free_port()
server = start_server(port, os.path.join(out, "pvserver.log"))
failures = []
connection = None
try:
    connection = simple.Connect("localhost", port)
    if connection is None or not connection.IsRemote():
        raise SystemExit("FAILED: no remote connection to localhost:%d" % port)
    simple.LoadPlugin(PLUGIN, remote=True, ns=rp.__dict__)   # the server executes the filters
    simple.LoadPlugin(PLUGIN, remote=False, ns=rp.__dict__)  # the client knows the proxies
    for name, (scalars, n, mean) in sorted(rp.run_all(out).items()):
        print("%-9s on the server: %5d points, mean |d| %.3f voxel" % (name, n, mean))
        if n == 0 or not mean <= rp.TOLERANCE:
            failures.append("%s: %d points, mean |d| %.3f (allowed %.2f)" % (name, n, mean, rp.TOLERANCE))
finally:
    code = stop_server(server, connection)
print("pvserver on port %d exited with %s" % (port, code))
if server.poll() is None:
    failures.append("pvserver still running after the disconnect")
for f in failures:
    print("FAILED:", f)
sys.exit(1 if failures else 0)
