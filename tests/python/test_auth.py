"""connect(token=...) against a daemon started with --token-file."""

import pytest

import fluidcast
from helpers import SIZE, Daemon, ball, look_at_ball, png_size


@pytest.fixture(scope="module")
def token_daemon(tmp_path_factory):
    token_file = tmp_path_factory.mktemp("token") / "token"
    token_file.write_text("s3cret-for-pytest\n")
    d = Daemon("--token-file", str(token_file))
    yield d
    status = d.stop()
    log = d.read_log()
    d.remove_files()
    assert status == 0, log


def test_token(token_daemon):
    for wrong in (None, "guess"):
        with pytest.raises(fluidcast.Error) as e:
            fluidcast.connect(token_daemon.address, token=wrong)
        assert e.value.code is fluidcast.Code.UNAUTHORIZED, wrong
    with fluidcast.connect(token_daemon.address, token="s3cret-for-pytest", reply_timeout=60) as c:
        c.send_frame(ball(500))
        look_at_ball(c)
        assert png_size(c.render()) == SIZE
