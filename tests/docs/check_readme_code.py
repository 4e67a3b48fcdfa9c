#!/usr/bin/env python3
"""The README's code still compiles against today's headers: its C block, put
in a function whose parameters are the particles (n, xyz) it uses, is compiled
with -Wall -Wextra -Werror; its Python blocks are parsed.
Usage: check_readme_code.py REPO_ROOT CC. Exit 1 naming the block that fails."""
import pathlib
import re
import subprocess
import sys
import tempfile

WRAPPER = """#include <stdio.h>
{includes}
int readme_example(size_t n, float *xyz);
int readme_example(size_t n, float *xyz)
{{
{body}
    return 0;
}}
"""


def blocks(text, language):
    return re.findall(r"^```" + language + r"\n(.*?)^```", text, re.S | re.M)


def check_c(block, root, cc):
    lines = block.splitlines()
    includes = "\n".join(line for line in lines if line.startswith("#include"))
    body = "\n".join(line for line in lines if not line.startswith("#include"))
    with tempfile.TemporaryDirectory() as scratch:
        source = pathlib.Path(scratch) / "readme_example.c"
        source.write_text(WRAPPER.format(includes=includes, body=body), encoding="utf-8")
        result = subprocess.run([cc, "-std=c11", "-Wall", "-Wextra", "-Werror", "-fsyntax-only",
                                 "-I", str(root / "client" / "lib"), "-I", str(root / "proto"), str(source)],
                                stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
    return result.returncode == 0, result.stdout.decode("utf-8", "replace")


def main():
    root, cc = pathlib.Path(sys.argv[1]), sys.argv[2]
    readme = (root / "README.md").read_text(encoding="utf-8")
    c_blocks, python_blocks = blocks(readme, "c"), blocks(readme, "python")
    failures = 0
    if not c_blocks or not python_blocks:
        print("README.md has no ```c or no ```python block: the quick tour lost its examples")
        failures += 1
    for number, block in enumerate(c_blocks, 1):
        ok, output = check_c(block, root, cc)
        if not ok:
            print(f"README.md C block {number} does not compile:\n{output}")
            failures += 1
    for number, block in enumerate(python_blocks, 1):
        try:
            compile(block, f"README.md python block {number}", "exec")
        except SyntaxError as error:
            print(f"README.md Python block {number}: {error}")
            failures += 1
    print(f"{len(c_blocks)} C and {len(python_blocks)} Python blocks checked, {failures} failures")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
