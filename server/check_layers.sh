#!/usr/bin/env bash
# check_layers.sh — the dependency graph of server/ and its rules:
#
#   1. no circle of #includes between files of server/;
#   2. with --objects DIR (a build's server/ folder): no circle of calls
#      between object files, from the symbols each one defines and uses (nm).
#      This sees what includes cannot: a header whose functions are defined
#      in another file (a callback declared by its caller), the way a circle
#      of calls hides;
#   3. in the daemon, dependencies run one way between its folders
#      (server/daemon/README.md): net -> clients -> sessions, gpu -> uploads,
#      and metrics/ below them all.
#      Neither includes nor calls may go against that (FORBIDDEN below);
#   4. with --objects: no variable a program can change (static or global,
#      in .data or .bss) in the daemon's folders: the daemon's state is made
#      at its top level (fluidcastd.c) and handed down.
#
# Prints the include graph ("from -> to", paths relative to server/) and, with
# --objects, the call graph between object files; -q prints only what fails.
# Exit status 0 when every rule holds, 1 otherwise, 2 on bad usage.
# Needs bash, awk, tsort and (for --objects) nm and objdump. Run by ctest as server_layers.
set -u

SERVER=$(cd "$(dirname "$0")" && pwd)
OBJECTS=""
QUIET=0
while [ $# -gt 0 ]; do
    case "$1" in
    --objects) OBJECTS=${2:-}; shift 2 || { echo "check_layers: --objects needs a folder" >&2; exit 2; } ;;
    -q) QUIET=1; shift ;;
    -h|--help) awk 'NR > 1 && /^#/ {sub(/^# ?/, ""); print; next} NR > 1 {exit}' "$0"; exit 0 ;;
    *) echo "check_layers: unknown argument '$1'" >&2; exit 2 ;;
    esac
done

# Daemon folders that must not depend on another: "from:to ...", paths under server/daemon/.
FORBIDDEN="sessions:clients sessions:net sessions:gpu
clients:net
gpu:clients gpu:sessions gpu:net
uploads:clients uploads:sessions uploads:net uploads:gpu
metrics:clients metrics:sessions metrics:net metrics:gpu metrics:uploads"

status=0
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

say() { [ "$QUIET" -eq 1 ] || printf '%s\n' "$@"; }

# The daemon folder a server/-relative path lies in ("" outside one).
layer_of() {
    case "$1" in
    daemon/*/*) local rest=${1#daemon/}; printf '%s' "${rest%%/*}" ;;
    *) printf '' ;;
    esac
}

# Edges "from to" on stdin: report each that breaks a FORBIDDEN rule.
check_rules() {
    local what=$1 from to lf lt rule bad=0
    while read -r from to; do
        lf=$(layer_of "$from")
        lt=$(layer_of "$to")
        [ -n "$lf" ] && [ -n "$lt" ] && [ "$lf" != "$lt" ] || continue
        for rule in $FORBIDDEN; do
            if [ "$rule" = "$lf:$lt" ]; then
                echo "FAIL: $what against the layers: $from -> $to (daemon/$lf/ must not depend on daemon/$lt/)"
                bad=1
            fi
        done
    done
    return $bad
}

# Edges "from to" in a file: report the circles tsort finds.
check_cycles() {
    local what=$1 edges=$2
    if ! tsort "$edges" >/dev/null 2>"$work/loops"; then
        echo "FAIL: a circle of $what:"
        grep -v 'input contains a loop' "$work/loops" | sed 's/^tsort: /    /'
        return 1
    fi
    return 0
}

# Relative to where the script was started from, before it moves to server/.
[ -z "$OBJECTS" ] || [ ! -d "$OBJECTS" ] || OBJECTS=$(cd "$OBJECTS" && pwd)

# ---- 1. Includes between files of server/ ----
# "x.h" is looked for next to the including file, then in server/daemon/ and
# server/ (the daemon's and the server libraries' include roots); includes
# that resolve outside server/ (proto/, system headers) are not part of the graph.
cd "$SERVER" || exit 2
find . \( -name '*.c' -o -name '*.h' -o -name '*.cpp' -o -name '*.hpp' \) -type f | sed 's#^\./##' | sort >"$work/files"
: >"$work/includes"
while read -r file; do
    dir=$(dirname "$file")
    sed -n 's/^[[:space:]]*#[[:space:]]*include[[:space:]]*"\([^"]*\)".*/\1/p' "$file" | while read -r name; do
        for root in "$dir" daemon .; do
            if [ -f "$root/$name" ]; then
                target=$(realpath -m --relative-to=. "$root/$name")
                echo "$file $target"
                break
            fi
        done
    done >>"$work/includes"
done <"$work/files"
# Every file is a node, even one that includes nothing.
{ cat "$work/includes"; awk '{print $1, $1}' "$work/files"; } >"$work/include_edges"

say "# include graph of server/ ($(wc -l <"$work/includes") includes between $(wc -l <"$work/files") files)"
[ "$QUIET" -eq 1 ] || awk '{print $1 " -> " $2}' "$work/includes"
check_cycles "includes" "$work/include_edges" || status=1
check_rules "include" <"$work/includes" || status=1

# ---- 2. Calls between object files ----
if [ -n "$OBJECTS" ]; then
    if [ ! -d "$OBJECTS" ]; then
        echo "FAIL: --objects $OBJECTS: no such folder (build first)"
        exit 1
    fi
    find "$OBJECTS" -name '*.o' -type f | sort >"$work/objects"
    : >"$work/variables"
    if [ ! -s "$work/objects" ]; then
        echo "FAIL: no object files under $OBJECTS (build first)"
        exit 1
    fi
    # "object type symbol" for every global symbol; objects named by their
    # source (daemon/clients/client.c), not CMake's CMakeFiles/T.dir path.
    # An object whose source is gone (moved, renamed) is a leftover of an
    # earlier build: not part of the program any more.
    while read -r obj; do
        name=$(realpath -m --relative-to="$OBJECTS" "$obj" | sed 's#CMakeFiles/[^/]*\.dir/##; s#__/#../#g; s#\.o$##')
        name=$(realpath -m --relative-to=. "$name")
        [ -f "$name" ] || continue
        nm -P -g "$obj" 2>/dev/null | awk -v o="$name" '{print o, $2, $1}'
        # Variables a program may change (.data, .bss, thread-local, common;
        # not .data.rel.ro, where constant tables of pointers lie).
        objdump -t "$obj" 2>/dev/null | awk -v o="$name" '/ O / {sec = $(NF - 2); name = $NF;
            if ((sec ~ /^\.t?(data|bss)/ && sec !~ /^\.data\.rel\.ro/) || sec == "*COM*")
                if (name !~ /^(__|\.)/) print o, name}' >>"$work/variables"
    done <"$work/objects" >"$work/symbols"
    # A strong definition (weak ones, C++ template copies, are everybody's) answers a use.
    awk '$2 ~ /^[TDBRCGS]$/ && !($3 in def) {def[$3] = $1; next}
         $2 == "U" {use[++n] = $1 " " $3}
         END {for (i = 1; i <= n; i++) {split(use[i], u, " "); if (u[2] in def && def[u[2]] != u[1]) print u[1], def[u[2]]}}' \
        "$work/symbols" | sort -u >"$work/calls"
    { cat "$work/calls"; awk '{print $1, $1}' "$work/symbols" | sort -u; } >"$work/call_edges"
    say "# call graph between object files ($(wc -l <"$work/calls") edges)"
    [ "$QUIET" -eq 1 ] || awk '{print $1 " -> " $2}' "$work/calls"
    check_cycles "calls between object files" "$work/call_edges" || status=1
    check_rules "call" <"$work/calls" || status=1
    # 4. The daemon's mutable global state lives at its top level only.
    if awk '$1 ~ /^daemon\/[^\/]+\//' "$work/variables" | grep -q .; then
        echo "FAIL: mutable global or static variables below the daemon's top level:"
        awk '$1 ~ /^daemon\/[^\/]+\// {print "    " $1 ": " $2}' "$work/variables"
        status=1
    fi
fi

if [ $status -eq 0 ]; then
    say "OK: no circles$([ -n "$OBJECTS" ] && echo ' of includes or calls'), daemon layers respected"
fi
exit $status
