"""The settings' table (fc_settings.h) walked entry by entry against what is
made from it outside C: the binding's FcSettings fields and keywords, and the
help of every command that renders. A setting added to the table must show up
in each of them without another edit."""

import os
import subprocess

import pytest

import fluidcast
from fluidcast import _capi

CLI = os.environ.get("FLUIDCAST_CLI")
RENDERING_COMMANDS = ("snapshot", "render", "stream", "view")


def _table():
    table = _capi.settings_table()
    assert table, "the library's settings table is empty"
    return table


def test_every_entry_is_a_field_at_its_offset():
    fields = {name: getattr(_capi.FcSettings, name) for name, _ in _capi.FcSettings._fields_}
    for spec in _table():
        name = spec.name.decode()
        assert name in fields, name
        assert fields[name].offset == spec.offset, name
        assert fields[name].size == 4 * spec.count, name
    assert len(fields) == len(_table())


def test_every_entry_is_a_keyword_with_the_tables_default():
    defaults = fluidcast.default_settings()
    assert tuple(defaults) == fluidcast.SETTING_NAMES
    for spec in _table():
        name = spec.name.decode()
        value = defaults[name]
        values = value if isinstance(value, tuple) else (value,)
        assert [float(v) for v in values] == pytest.approx(list(spec.initial)[:spec.count]), name


@pytest.mark.skipif(not CLI, reason="FLUIDCAST_CLI names no fluidcast executable")
@pytest.mark.parametrize("command", RENDERING_COMMANDS)
def test_every_option_is_in_the_help(command):
    out = subprocess.run([CLI, command, "--help"], capture_output=True, text=True, check=True).stdout
    for spec in _table():
        option = spec.option.decode()
        assert "  %s " % option in out, "%s --help lacks %s" % (command, option)
