#!/usr/bin/env bash
# container.build_deps: the Containerfile's build stage installs every Debian
# package the build requires, i.e. each package fc_require_pkg names in the
# CMakeLists.txt files (the message "apt-get install PKG" tells a user). CI
# builds the image from a .deb, not from source, so without this check a new
# dependency would leave `docker build -f deploy/container/Containerfile .`
# broken unnoticed. Needs no engine.
#   usage: container_build_deps.sh SOURCE_DIR
source "$(dirname "$0")/lib.sh"
[ $# -eq 1 ] || fail "usage: $0 SOURCE_DIR"
SRC=$1
# The Debian package argument of each fc_require_pkg(VAR module "debian packages") call.
required=$(cd "$SRC" && git ls-files 2> /dev/null '*CMakeLists.txt' || find . -name CMakeLists.txt -not -path './build*')
packages=$(cd "$SRC" && for f in $required; do tr '\n' ' ' < "$f"; echo; done |
    grep -o 'fc_require_pkg([^)]*)' | grep -v 'fc_require_pkg(var ' |
    sed -E 's/.*"([^"]*)"[ ]*\)$/\1/; t; s/.*[ (]([^ ()]*)[ ]*\)$/\1/' | tr ' ' '\n' | sed '/^$/d' | sort -u)
[ -n "$packages" ] || fail "no fc_require_pkg calls found under $SRC"
echo "required: $(echo $packages)"
# The build stage's apt-get install list: from "FROM ... AS build" to the next FROM.
stage=$(sed -n '/^FROM .* AS build$/,/^FROM /p' "$SRC/deploy/container/Containerfile")
missing=""
for p in $packages; do
    printf '%s\n' "$stage" | tr ' \\' '\n\n' | matches -x -- "$p" || missing="$missing $p"
done
[ -z "$missing" ] || fail "deploy/container/Containerfile's build stage lacks:$missing"
echo "PASS"
