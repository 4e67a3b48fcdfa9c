#!/usr/bin/env python3
"""Every option that `fluidcast COMMAND --help` and `fluidcastd --help` print
is documented in docs/*.md, so a new option cannot go undocumented.
Usage: check_doc_options.py REPO_ROOT FLUIDCAST FLUIDCASTD. Exit 1 listing
each option no page names."""
import pathlib
import re
import subprocess
import sys

COMMANDS = ["snapshot", "render", "stream", "watch", "info", "view", "spacemouse"]
OPTION = re.compile(r"(?<![\w-])--[a-z][a-z0-9-]*")


def help_text(argv):
    # --help exits 0 and writes to stdout; stderr joins it in case a command prints there.
    result = subprocess.run(argv + ["--help"], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, check=True)
    return result.stdout.decode("utf-8", "replace")


def main():
    root, fluidcast, fluidcastd = pathlib.Path(sys.argv[1]), sys.argv[2], sys.argv[3]
    docs = "\n".join(page.read_text(encoding="utf-8") for page in sorted((root / "docs").glob("*.md")))
    documented = set(OPTION.findall(docs))
    helps = [("fluidcast", help_text([fluidcast]))]
    helps += [(f"fluidcast {command}", help_text([fluidcast, command])) for command in COMMANDS]
    helps.append(("fluidcastd", help_text([fluidcastd])))
    missing = []
    for program, text in helps:
        for option in sorted(set(OPTION.findall(text)) - documented):
            missing.append(f"{program} {option}: in --help but in no docs/*.md page")
    for line in missing:
        print(line)
    print(f"{len(helps)} --help texts checked, {len(missing)} options undocumented")
    return 1 if missing else 0


if __name__ == "__main__":
    sys.exit(main())
