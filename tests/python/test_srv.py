"""'srv:' addresses and sessions through the binding: a real DNS server
(dnsmasq on a loopback port, records for the test daemon and a dead target)
that $FLUIDCAST_DNS_SERVER points libfluidcast at. Skipped without dnsmasq
(deploy/setup.sh installs it)."""

import os
import shutil
import signal
import socket
import struct
import subprocess
import time

import pytest

import fluidcast

NAME = "_fluidcast._tcp.py.test"
DNSMASQ = shutil.which("dnsmasq") or next((p for p in ("/usr/sbin/dnsmasq",) if os.path.exists(p)), None)


def _srv_query(name):
    labels = b"".join(bytes([len(part)]) + part.encode() for part in name.split("."))
    return struct.pack(">HHHHHH", 0x5eed, 0x0100, 1, 0, 0, 0) + labels + b"\0" + struct.pack(">HH", 33, 1)


def _answers(port, name):
    with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as s:
        s.settimeout(0.2)
        try:
            s.sendto(_srv_query(name), ("127.0.0.1", port))
            reply = s.recv(4096)
        except OSError:
            return False
    return reply[:2] == b"\x5e\xed" and struct.unpack(">H", reply[6:8])[0] > 0   # an answer record


def _free_udp_port():
    """A port the kernel finds free on 127.0.0.1 now, rather than a random guess; dnsmasq binds it next,
    and if something took it meanwhile, the caller tries another."""
    with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


class Dnsmasq:
    """dnsmasq serving only ``records`` on 127.0.0.1 and a free port; stopped by its pid."""

    def __init__(self, directory, records):
        for _ in range(5):
            self.port = _free_udp_port()
            config = directory / "dnsmasq.conf"
            config.write_text("port=%d\nlisten-address=127.0.0.1\nbind-interfaces\nno-resolv\nno-hosts\nno-poll\n%s\n"
                              % (self.port, "\n".join(records)))
            self.log = open(directory / "dnsmasq.log", "ab")
            self.process = subprocess.Popen([DNSMASQ, "--keep-in-foreground", "--log-facility=-", "--pid-file",
                                             "--user=root", "--conf-file=%s" % config],
                                            stdout=self.log, stderr=subprocess.STDOUT)
            deadline = time.monotonic() + 10
            while time.monotonic() < deadline and self.process.poll() is None:
                if _answers(self.port, NAME):
                    return
                time.sleep(0.05)
            self.stop()     # the port was taken, or it never answered: another port
        raise RuntimeError("dnsmasq did not start; see %s" % (directory / "dnsmasq.log"))

    def stop(self):
        if self.process.poll() is None:
            self.process.send_signal(signal.SIGTERM)
            self.process.wait(timeout=10)
        self.log.close()


@pytest.fixture
def dns(daemon, tmp_path, monkeypatch):
    if not DNSMASQ:
        pytest.skip("dnsmasq is not installed (deploy/setup.sh installs it)")
    port = int(daemon.address.rsplit(":", 1)[1])
    # The daemon and a target nobody listens on (port 1), equal priority and
    # weight: whichever comes first for a session, the client ends up on the daemon.
    server = Dnsmasq(tmp_path, ["srv-host=%s,localhost,%d,0,10" % (NAME, port),
                                "srv-host=%s,localhost,1,0,10" % NAME,
                                "srv-host=_fluidcast._tcp.nothing.test"])
    monkeypatch.setenv("FLUIDCAST_DNS_SERVER", "127.0.0.1:%d" % server.port)
    yield port
    server.stop()


def test_producer_and_viewer_of_a_session_meet_through_srv(dns):
    with fluidcast.connect("srv:" + NAME, session="dam", reply_timeout=60) as producer, \
            fluidcast.connect("srv:" + NAME, session="dam", reply_timeout=60) as viewer:
        for c in (producer, viewer):
            assert c.address == "srv:" + NAME and c.session == "dam"
            assert c.daemon == "localhost:%d" % dns
        producer.publish("dam")
        viewer.subscribe("dam", format="png", size=(64, 48))
        assert [s.name for s in viewer.list_sessions()] == ["dam"]


def test_srv_without_a_session(dns):
    with fluidcast.connect("srv:" + NAME) as c:
        assert c.session is None and c.daemon == "localhost:%d" % dns


def test_srv_errors(dns, monkeypatch):
    with pytest.raises(fluidcast.Error) as e:
        fluidcast.connect("srv:_fluidcast._tcp.nothing.test", session="dam", connect_timeout=5)
    assert e.value.code is fluidcast.Code.CONNECT
    monkeypatch.setenv("FLUIDCAST_DNS_SERVER", "not-an-address")
    with pytest.raises(fluidcast.Error) as e:
        fluidcast.connect("srv:" + NAME, session="dam")
    assert e.value.code is fluidcast.Code.USAGE and "FLUIDCAST_DNS_SERVER" in e.value.message
