"""The ctypes mirror against the C headers: every struct's size, alignment and
every field's offset and size, every enumerator's value, every constant, as a C
program compiled here from the headers prints them; and nothing the headers
declare is left unmirrored. A header change not made in fluidcast/_capi.py or
fluidcast/_enums.py fails here instead of corrupting memory."""

import ctypes
import os
import re
import shutil
import subprocess

import pytest

import fluidcast
from fluidcast import _capi, _enums

from helpers import REPO

HEADERS = [os.path.join(REPO, "proto", "fluidcast_types.h"), os.path.join(REPO, "proto", "fc_settings.h"),
           os.path.join(REPO, "proto", "fc_surface_mesh.h"), os.path.join(REPO, "client", "lib", "fluidcast.h")]
INCLUDE_DIRS = [os.path.join(REPO, "proto"), os.path.join(REPO, "client", "lib")]


def _header_text():
    text = "\n".join(open(h).read() for h in HEADERS)
    text = re.sub(r"/\*.*?\*/", "", text, flags=re.S)
    return re.sub(r"//[^\n]*", "", text)


def _c_program():
    lines = ["#include <stddef.h>", "#include <stdio.h>", '#include "fluidcast.h"', "int main(void) {"]
    for cls in _capi.STRUCTS:
        t = cls._c_name_
        lines.append('printf("struct %s %%zu %%zu\\n", sizeof(%s), _Alignof(%s));' % (t, t, t))
        for name, _ in cls._fields_:
            lines.append('printf("field %s.%s %%zu %%zu\\n", offsetof(%s, %s), sizeof(((%s *)0)->%s));'
                         % (t, name, t, name, t, name))
    for enum_type in _enums.C_TYPES:
        for member in enum_type:
            c = _enums.c_name(member)
            lines.append('printf("value %s %%lld\\n", (long long)%s);' % (c, c))
    for c, value in _enums.C_CONSTANTS.items():
        if isinstance(value, str):
            lines.append('printf("string %s %%s\\n", %s);' % (c, c))
        else:
            lines.append('printf("value %s %%lld\\n", (long long)(%s));' % (c, c))
    lines += ["return 0;", "}"]
    return "\n".join(lines) + "\n"


@pytest.fixture(scope="module")
def c_layout(tmp_path_factory):
    """What the compiled program prints: {("struct", name): (size, align), ("field", "t.f"): (offset, size),
    ("value", NAME): value} (a string constant's value as text)."""
    cc = os.environ.get("FC_TEST_CC") or shutil.which("cc") or shutil.which("gcc")
    if not cc:
        pytest.fail("no C compiler: set FC_TEST_CC")
    work = tmp_path_factory.mktemp("layout")
    source, exe = work / "layout.c", work / "layout"
    source.write_text(_c_program())
    flags = ["-std=c11", "-Wall", "-Werror"] + ["-I" + d for d in INCLUDE_DIRS]
    build = subprocess.run([cc, *flags, str(source), "-o", str(exe)], capture_output=True, text=True)
    assert build.returncode == 0, "the layout program does not compile against the headers " \
                                  "(a field or enumerator renamed or removed?):\n" + build.stderr
    out = subprocess.run([str(exe)], capture_output=True, text=True, check=True).stdout
    layout = {}
    for line in out.splitlines():
        kind, name, *numbers = line.split()
        if kind == "string":   # a string constant (no spaces): kept as text
            layout[("value", name)] = tuple(numbers)
        else:
            layout[(kind, name)] = tuple(int(n) for n in numbers)
    return layout


@pytest.mark.parametrize("cls", _capi.STRUCTS, ids=lambda c: c._c_name_)
def test_struct_size_alignment_and_fields(c_layout, cls):
    t = cls._c_name_
    assert (ctypes.sizeof(cls), ctypes.alignment(cls)) == c_layout[("struct", t)], \
        "%s: ctypes (size, alignment) differ from C's: a field added to the header?" % t
    for name, _ in cls._fields_:
        field = getattr(cls, name)
        assert (field.offset, field.size) == c_layout[("field", t + "." + name)], "%s.%s" % (t, name)


def test_enum_values_and_constants(c_layout):
    for enum_type in _enums.C_TYPES:
        for member in enum_type:
            assert c_layout[("value", _enums.c_name(member))] == (int(member),), _enums.c_name(member)
    for name, value in _enums.C_CONSTANTS.items():
        assert c_layout[("value", name)] == (value,), name


def test_every_header_struct_enum_and_define_is_mirrored():
    text = _header_text()
    structs = set(re.findall(r"typedef\s+struct\s+(\w+)\s*\{", text))
    assert structs == {cls._c_name_ for cls in _capi.STRUCTS}
    enums = dict(re.findall(r"typedef\s+enum\s+(\w+)\s*\{(.*?)\}", text, flags=re.S))
    mirrored = {c: e for e, c in _enums.C_TYPES.items()}
    assert set(enums) == set(mirrored), "enums in the headers vs fluidcast._enums.C_TYPES"
    for c_type, body in enums.items():
        names = set(re.findall(r"^\s*(FC_\w+)", body, flags=re.M)) - set(_enums.C_CONSTANTS)
        assert names == {_enums.c_name(m) for m in mirrored[c_type]}, c_type
    defines = set(re.findall(r"#define\s+(FC_\w+)\s", text))
    assert defines <= set(_enums.C_CONSTANTS), "unmirrored #defines: %s" % (defines - set(_enums.C_CONSTANTS))


def test_every_declared_function_has_a_prototype():
    text = _header_text()
    declared = set(re.findall(r"\b(fc_\w+)\s*\(", text))
    assert declared == set(_capi._PROTOTYPES)
