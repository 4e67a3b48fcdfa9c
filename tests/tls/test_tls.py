#!/usr/bin/env python3
"""TLS on fluidcastd's TCP connections (issue 28), end to end: real
certificates made by `openssl` here (a CA, a server, a second server
certificate, one for another name, an expired one, a client), real daemons
(software GL), the fluidcast CLI, the Python binding and a TCP proxy.

What it asserts, each a property that could fail:
  - a render through TLS gives the same PNG bytes as one through the same
    daemon's Unix socket in clear;
  - each failure has its own exit status (cli_report.c) and the daemon goes on
    serving: unknown CA, name mismatch, expired certificate, a plaintext client
    on a TLS port, a TLS client on a plaintext port, mutual TLS without a
    client certificate;
  - a proxy between client and daemon sees neither the token, nor particle
    bytes, nor image bytes through TLS (and does see the token in clear, so
    the search itself works);
  - SIGHUP swaps the certificate: a new connection sees the new serial while a
    connection opened before keeps rendering;
  - 200 stalled handshakes do not stop a real client: it is served while all
    200 are still pending (the handshake-timeout counter still 0);
  - a stalled handshake is dropped and counted once its timeout passes.
No timing asserts: every wait is for an event, bounded only to end a hung test.

usage: test_tls.py FLUIDCASTD FLUIDCAST_CLI   (PYTHONPATH and FLUIDCAST_LIBRARY for the binding)
"""

import http.client
import os
import re
import shutil
import signal
import socket
import ssl
import struct
import subprocess
import sys
import tempfile
import threading
import time
import urllib.error
import urllib.request

DAEMON, CLI = sys.argv[1], sys.argv[2]
WORK = tempfile.mkdtemp(prefix="fc-tls-")
TOKEN = "tls-test-secret-0123456789abcdef"
# Exit statuses of the fluidcast command (client/cli/cli_report.h).
EXIT_UNKNOWN_CA, EXIT_NAME_MISMATCH, EXIT_EXPIRED = 8, 9, 10
EXIT_TLS_REQUIRED, EXIT_PLAINTEXT_PEER, EXIT_CLIENT_CERT = 11, 12, 13
failures = []
daemons = []


def check(condition, message):
    print(("ok   " if condition else "FAIL ") + message, flush=True)
    if not condition:
        failures.append(message)


def path(name):
    return os.path.join(WORK, name)


def openssl(*args):
    subprocess.run(["openssl", *args], check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)


# ---- certificates -------------------------------------------------------------

CA_CONFIG = """[ ca ]
default_ca = test_ca
[ test_ca ]
database = {work}/index.txt
new_certs_dir = {work}
serial = {work}/serial
default_md = sha256
policy = any_name
copy_extensions = copy
unique_subject = no
[ any_name ]
commonName = supplied
"""


def make_ca():
    openssl("req", "-x509", "-newkey", "ec", "-pkeyopt", "ec_paramgen_curve:P-256", "-nodes", "-keyout",
            path("ca.key"), "-out", path("ca.pem"), "-days", "2", "-subj", "/CN=fluidcast test CA")
    with open(path("ca.cnf"), "w") as f:
        f.write(CA_CONFIG.format(work=WORK))
    open(path("index.txt"), "w").close()
    with open(path("serial"), "w") as f:
        f.write("1000\n")


def issue(name, common_name, san, start="", end=""):
    """A certificate signed by the test CA; start/end ("YYYYMMDDHHMMSSZ") for one valid in the past."""
    openssl("req", "-newkey", "ec", "-pkeyopt", "ec_paramgen_curve:P-256", "-nodes", "-keyout", path(name + ".key"),
            "-out", path(name + ".csr"), "-subj", "/CN=" + common_name, "-addext", "subjectAltName=" + san)
    dates = ["-startdate", start, "-enddate", end] if start else ["-days", "1"]
    openssl("ca", "-batch", "-notext", "-config", path("ca.cnf"), "-cert", path("ca.pem"), "-keyfile", path("ca.key"),
            "-in", path(name + ".csr"), "-out", path(name + ".pem"), *dates)


def serial_of(pem):
    out = subprocess.run(["openssl", "x509", "-noout", "-serial", "-in", pem], check=True, capture_output=True, text=True)
    return out.stdout.strip().split("=", 1)[1].upper()


# ---- daemons ------------------------------------------------------------------

class Daemon:
    def __init__(self, name, *args):
        self.name = name
        self.port_file = path(name + ".port")
        self.log_path = path(name + ".log")
        self.log = open(self.log_path, "w")
        self.process = subprocess.Popen([DAEMON, "--gpu", "software", "--listen", "127.0.0.1:0", "--port-file",
                                         self.port_file, "--metrics-listen", "127.0.0.1:0", "--token-file",
                                         path("token"), *args], stdout=self.log, stderr=subprocess.STDOUT)
        daemons.append(self)

    def wait_ready(self):
        deadline = time.monotonic() + 120
        while time.monotonic() < deadline and not os.path.exists(self.port_file):
            if self.process.poll() is not None:
                raise SystemExit("%s exited: %s" % (self.name, open(self.log_path).read()))
            time.sleep(0.1)
        self.port = int(open(self.port_file).read())
        match = None
        while time.monotonic() < deadline and not match:
            match = re.search(r"(https?)://127\.0\.0\.1:(\d+)/metrics", open(self.log_path).read())
            time.sleep(0.05)
        self.metrics_scheme, self.metrics_port = match.group(1), int(match.group(2))

    def http_get(self, what):
        """GET what from the metrics endpoint: https (--metrics-tls) verified against the test CA."""
        context = ssl.create_default_context(cafile=path("ca.pem")) if self.metrics_scheme == "https" else None
        host = "localhost" if context else "127.0.0.1"
        url = "%s://%s:%d%s" % (self.metrics_scheme, host, self.metrics_port, what)
        return urllib.request.urlopen(url, timeout=30, context=context).read().decode()

    def metric(self, name):
        return float(re.search(r"^%s (\S+)$" % name, self.http_get("/metrics"), re.M).group(1))

    def stop(self):
        if self.process.poll() is None:
            self.process.send_signal(signal.SIGTERM)
            self.process.wait(timeout=60)
        self.log.close()


def cli(*args, server):
    """Runs a fluidcast command; (exit status, stderr)."""
    run = subprocess.run([CLI, *args, "--server", server, "--token-file", path("token"), "--connect-timeout", "60"],
                         capture_output=True, text=True, timeout=300)
    return run.returncode, run.stderr.strip()


def served(daemon):
    """The daemon still answers a TLS client."""
    return cli("info", "--tls-ca", path("ca.pem"), server="tls://localhost:%d" % daemon.port)[0] == 0


# ---- a TCP proxy that keeps what it forwards --------------------------------------

class Proxy:
    def __init__(self, target_port):
        self.target_port = target_port
        self.upstream = bytearray()     # client -> daemon
        self.downstream = bytearray()   # daemon -> client
        self.listener = socket.socket()
        self.listener.bind(("127.0.0.1", 0))
        self.listener.listen(8)
        self.port = self.listener.getsockname()[1]
        threading.Thread(target=self._accept, daemon=True).start()

    def _accept(self):
        while True:
            client, _ = self.listener.accept()
            server = socket.create_connection(("127.0.0.1", self.target_port))
            threading.Thread(target=self._pump, args=(client, server, self.upstream), daemon=True).start()
            threading.Thread(target=self._pump, args=(server, client, self.downstream), daemon=True).start()

    @staticmethod
    def _pump(src, dst, record):
        try:
            while True:
                data = src.recv(65536)
                if not data:
                    break
                record += data
                dst.sendall(data)
        except OSError:
            pass
        finally:
            for s in (src, dst):
                try:
                    s.shutdown(socket.SHUT_WR)
                except OSError:
                    pass


# ---- the tests ----------------------------------------------------------------

def write_particles():
    """A block of water as .f32 (x y z float32), on a fixed grid: no randomness."""
    points = []
    for i in range(24):
        for j in range(24):
            for k in range(12):
                points += [i * 0.04 + 0.013 * (j % 3), j * 0.04, k * 0.04 + 0.007 * (i % 5)]
    data = struct.pack("<%df" % len(points), *points)
    with open(path("water.f32"), "wb") as f:
        f.write(data)
    return data


def test_same_image(a, particles):
    plain = cli("snapshot", path("water.f32"), "-o", path("plain.png"), "--size", "320x240", "--eye", "2,-2,1.5",
                "--target", "0.5,0.5,0.2", server="unix:" + path("a.sock"))
    tls = cli("snapshot", path("water.f32"), "-o", path("tls.png"), "--size", "320x240", "--eye", "2,-2,1.5",
              "--target", "0.5,0.5,0.2", "--tls-ca", path("ca.pem"), server="tls://localhost:%d" % a.port)
    check(plain[0] == 0 and tls[0] == 0, "snapshots in clear (unix) and through TLS succeed: %s / %s" % (plain, tls))
    same = os.path.exists(path("tls.png")) and open(path("plain.png"), "rb").read() == open(path("tls.png"), "rb").read()
    check(same, "the image through TLS is byte for byte the one in clear")


def test_failures(a, b, c):
    cases = [
        ("unknown CA (no --tls-ca)", EXIT_UNKNOWN_CA, [], "tls://localhost:%d" % a.port),
        ("name mismatch (127.0.0.1 is not in the certificate)", EXIT_NAME_MISMATCH, ["--tls-ca", path("ca.pem")],
         "tls://127.0.0.1:%d" % a.port),
        ("plaintext client on a TLS port", EXIT_TLS_REQUIRED, [], "127.0.0.1:%d" % a.port),
        ("TLS client on a plaintext port", EXIT_PLAINTEXT_PEER, ["--tls-ca", path("ca.pem")],
         "tls://localhost:%d" % b.port),
        ("mutual TLS without a client certificate", EXIT_CLIENT_CERT, ["--tls-ca", path("ca.pem")],
         "tls://localhost:%d" % c.port),
    ]
    for what, expected, options, server in cases:
        status, stderr = cli("info", *options, server=server)
        check(status == expected, "%s: exit status %d (expected %d): %s" % (what, status, expected, stderr))
        check(served(a), "after '%s' the TLS daemon still serves" % what)
    mutual = ["--tls-ca", path("ca.pem"), "--tls-cert", path("client.pem"), "--tls-key", path("client.key")]
    status, stderr = cli("info", *mutual, server="tls://localhost:%d" % c.port)
    check(status == 0, "mutual TLS with the client certificate is served: %s" % stderr)
    # c admits 2 connections: with 2 held open a third is refused with ERROR LIMIT, told inside TLS.
    context = ssl.create_default_context(cafile=path("ca.pem"))
    context.load_cert_chain(path("client.pem"), path("client.key"))
    held = [context.wrap_socket(socket.create_connection(("127.0.0.1", c.port)), server_hostname="localhost")
            for _ in range(2)]
    status, stderr = cli("info", *mutual, server="tls://localhost:%d" % c.port)
    check(status == 5 and "maximum of 2 connections" in stderr,
          "beyond --max-connections a TLS client gets ERROR LIMIT: exit %d: %s" % (status, stderr))
    for s in held:
        s.close()


def test_proxy_sees_nothing(a, b, particles):
    sample_particles = particles[len(particles) // 2:len(particles) // 2 + 48]
    for daemon, tls in ((a, True), (b, False)):
        proxy = Proxy(daemon.port)
        options = ["--tls-ca", path("ca.pem")] if tls else []
        server = ("tls://localhost:%d" if tls else "127.0.0.1:%d") % proxy.port
        out = path("proxied-%s.png" % ("tls" if tls else "clear"))
        status, stderr = cli("snapshot", path("water.f32"), "-o", out, "--size", "320x240", *options, server=server)
        check(status == 0, "snapshot through the proxy (%s): %s" % ("TLS" if tls else "clear", stderr))
        image = open(out, "rb").read() if status == 0 else b"\0" * 4096
        sample_image = image[len(image) // 2:len(image) // 2 + 48]
        seen = (TOKEN.encode() in proxy.upstream, sample_particles in proxy.upstream, sample_image in proxy.downstream)
        if tls:
            check(seen == (False, False, False), "through TLS the proxy sees no token, particles or image: %s" % (seen,))
        else:
            check(seen == (True, True, True), "in clear the proxy does see token, particles and image (the search works)")


def new_connection_serial(port):
    context = ssl.create_default_context(cafile=path("ca.pem"))
    with socket.create_connection(("127.0.0.1", port)) as raw:
        with context.wrap_socket(raw, server_hostname="localhost") as tls:
            return tls.getpeercert()["serialNumber"].upper()


def test_reload(a):
    import numpy
    import fluidcast
    for kwargs, expected in (({}, fluidcast.Code.TLS_UNKNOWN_CA), ({"tls_ca": path("ca.pem"), "tls": False},
                                                                 fluidcast.Code.TLS_REQUIRED)):
        address = ("tls://localhost:%d" if "tls" not in kwargs else "127.0.0.1:%d") % a.port
        try:
            fluidcast.connect(address, token=TOKEN, connect_timeout=60, **kwargs).close()
            code = fluidcast.Code.OK
        except fluidcast.Error as e:
            code = e.code
        check(code == expected, "the binding reports %s as %s" % (address, code))
    first = serial_of(path("server.pem"))
    check(new_connection_serial(a.port) == first, "before SIGHUP the daemon shows the first certificate")
    client = fluidcast.connect("tls://localhost:%d" % a.port, token=TOKEN, tls_ca=path("ca.pem"), connect_timeout=60)
    positions = numpy.frombuffer(open(path("water.f32"), "rb").read(), dtype=numpy.float32).reshape(-1, 3)
    client.send_frame(positions)
    before = client.render()
    shutil.copy(path("server2.pem"), path("live.pem"))
    shutil.copy(path("server2.key"), path("live.key"))
    a.process.send_signal(signal.SIGHUP)
    second = serial_of(path("server2.pem"))
    seen, deadline = None, time.monotonic() + 60
    while seen != second and time.monotonic() < deadline:   # the reload is asynchronous to us
        seen = new_connection_serial(a.port)
    check(seen == second, "after SIGHUP a new connection sees the new serial %s (saw %s)" % (second, seen))
    client.send_frame(positions)
    check(client.render() == before, "the connection opened before SIGHUP goes on rendering")
    client.close()
    # An expired certificate, loaded the same way: clients refuse it with its own status.
    shutil.copy(path("expired.pem"), path("live.pem"))
    shutil.copy(path("expired.key"), path("live.key"))
    a.process.send_signal(signal.SIGHUP)
    expired = serial_of(path("expired.pem"))
    deadline = time.monotonic() + 60
    while time.monotonic() < deadline:
        try:
            new_connection_serial(a.port)
        except ssl.SSLCertVerificationError:
            break
    status, stderr = cli("info", "--tls-ca", path("ca.pem"), server="tls://localhost:%d" % a.port)
    check(status == EXIT_EXPIRED, "expired certificate (serial %s): exit status %d: %s" % (expired, status, stderr))
    shutil.copy(path("server.pem"), path("live.pem"))
    shutil.copy(path("server.key"), path("live.key"))
    a.process.send_signal(signal.SIGHUP)
    deadline = time.monotonic() + 60
    while time.monotonic() < deadline and not served(a):
        pass


def test_stalled_handshakes(a, c):
    stalled = []
    for _ in range(200):
        s = socket.create_connection(("127.0.0.1", a.port))
        s.sendall(b"\x16\x03\x01")   # the start of a TLS record, and then nothing
        stalled.append(s)
    check(served(a), "a real client is served while 200 handshakes stall")
    check(a.metric("fluidcast_tls_handshake_timeouts_total") == 0,
          "... and all 200 were still pending when it was (no handshake timed out yet)")
    for s in stalled:
        s.close()
    # c drops stalled handshakes after 300 ms: one is closed by the daemon and counted.
    s = socket.create_connection(("127.0.0.1", c.port))
    s.sendall(b"\x16\x03\x01")
    s.settimeout(120)
    try:
        closed = s.recv(1) == b""
    except ConnectionResetError:
        closed = True
    s.close()
    check(closed, "a stalled handshake is closed by the daemon")
    check(c.metric("fluidcast_tls_handshake_timeouts_total") >= 1, "... and counted in /metrics")


def test_metrics_tls(m):
    """--metrics-tls: /healthz and /metrics over HTTPS with the daemon's certificate; plain HTTP gets nothing."""
    check(m.metrics_scheme == "https", "with --metrics-tls the log names an https:// metrics endpoint")
    check(m.http_get("/healthz").strip() == "ok", "/healthz answers over HTTPS, the certificate verified")
    check("fluidcast_build_info" in m.http_get("/metrics"), "/metrics answers over HTTPS")
    try:
        urllib.request.urlopen("http://127.0.0.1:%d/healthz" % m.metrics_port, timeout=30).read()
        check(False, "plain HTTP to the HTTPS metrics endpoint is refused")
    except (urllib.error.URLError, ConnectionError, http.client.HTTPException):
        check(True, "plain HTTP to the HTTPS metrics endpoint is refused")


def main():
    with open(path("token"), "w") as f:
        f.write(TOKEN + "\n")
    make_ca()
    issue("server", "localhost", "DNS:localhost")
    issue("server2", "localhost", "DNS:localhost")
    issue("client", "fluidcast test client", "DNS:client.example")
    issue("expired", "localhost", "DNS:localhost", "20200101000000Z", "20200201000000Z")
    shutil.copy(path("server.pem"), path("live.pem"))
    shutil.copy(path("server.key"), path("live.key"))
    particles = write_particles()
    a = Daemon("a", "--tls-cert", path("live.pem"), "--tls-key", path("live.key"), "--unix", path("a.sock"),
               "--tls-handshake-timeout-ms", "600000")
    b = Daemon("b")
    c = Daemon("c", "--tls-cert", path("server.pem"), "--tls-key", path("server.key"), "--tls-client-ca",
               path("ca.pem"), "--tls-handshake-timeout-ms", "300", "--max-connections", "2")
    m = Daemon("m", "--tls-cert", path("server.pem"), "--tls-key", path("server.key"), "--metrics-tls")
    try:
        for d in (a, b, c, m):
            d.wait_ready()
        test_same_image(a, particles)
        test_failures(a, b, c)
        test_proxy_sees_nothing(a, b, particles)
        test_reload(a)
        test_stalled_handshakes(a, c)
        test_metrics_tls(m)
    finally:
        for d in daemons:
            d.stop()
    if failures:
        for d in daemons:
            print("---- %s log (tail)" % d.name)
            print("".join(open(d.log_path).readlines()[-30:]))
        print("%d check(s) failed" % len(failures))
        return 1
    shutil.rmtree(WORK, ignore_errors=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
