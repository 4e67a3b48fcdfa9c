#!/usr/bin/env bash
# check_layers.sh — the dependency graph of proto/, client/ and server/ and its rules:
#
#   1. no circle of #includes between files;
#   2. with --objects BUILD (the build's top folder): no circle of calls
#      between object files, from the symbols each one defines and uses (nm).
#      This sees what includes cannot: a header whose functions are defined
#      in another file (a callback declared by its caller), the way a circle
#      of calls hides;
#   3. between the trees, dependencies run one way: client/ and server/ may
#      use proto/; proto/ uses neither, and client/ and server/ never use each
#      other (TREES_ALLOWED below). Neither includes nor calls may go against it;
#   4. in the daemon, dependencies run one way between its folders
#      (server/daemon/README.md): net -> conversations -> sessions, gpu -> uploads,
#      and metrics/ below them all (DAEMON_FORBIDDEN below);
#   5. with --objects: no variable a program can change (static or global,
#      in .data or .bss) in the daemon's folders: the daemon's state is made
#      at its top level (fluidcastd.c) and handed down.
#
# Usage: check_layers.sh [-q] [--objects BUILD] [TREE...]
# TREEs are folders of the source (default: proto client server); with --objects
# the object files under BUILD/TREE are read. Prints the include graph ("from ->
# to", paths from the source's top) and, with --objects, the call graph between
# object files; -q prints only what fails.
# Exit status 0 when every rule holds, 1 otherwise, 2 on bad usage.
# Needs bash, awk, tsort and (for --objects) nm and objdump. Run by ctest as layers.
set -u

SOURCE=$(cd "$(dirname "$0")/../.." && pwd)
OBJECTS=""
QUIET=0
TREES=""
while [ $# -gt 0 ]; do
    case "$1" in
    --objects) OBJECTS=${2:-}; shift 2 || { echo "check_layers: --objects needs a folder" >&2; exit 2; } ;;
    -q) QUIET=1; shift ;;
    -h|--help) awk 'NR > 1 && /^#/ {sub(/^# ?/, ""); print; next} NR > 1 {exit}' "$0"; exit 0 ;;
    -*) echo "check_layers: unknown argument '$1'" >&2; exit 2 ;;
    *) TREES="$TREES ${1%/}"; shift ;;
    esac
done
TREES=${TREES# }
[ -n "$TREES" ] || TREES="proto client server"

# Trees that may depend on another: "from:to ...".
TREES_ALLOWED="client:proto server:proto"

# Daemon folders that must not depend on another: "from:to ...", paths under server/daemon/.
DAEMON_FORBIDDEN="sessions:conversations sessions:net sessions:gpu
conversations:net
gpu:conversations gpu:sessions gpu:net
uploads:conversations uploads:sessions uploads:net uploads:gpu
metrics:conversations metrics:sessions metrics:net metrics:gpu metrics:uploads
web:conversations web:sessions web:gpu web:uploads"

status=0
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

say() { [ "$QUIET" -eq 1 ] || printf '%s\n' "$@"; }

# Relative to where the script was started from, before it moves to the source's top.
[ -z "$OBJECTS" ] || [ ! -d "$OBJECTS" ] || OBJECTS=$(cd "$OBJECTS" && pwd)
cd "$SOURCE" || exit 2
for tree in $TREES; do
    [ -d "$tree" ] || { echo "check_layers: no folder $tree in $SOURCE" >&2; exit 2; }
done

# Edges "from to" on stdin: report each that goes between trees against
# TREES_ALLOWED or between daemon folders against DAEMON_FORBIDDEN.
check_rules() {
    awk -v what="$1" -v allowed="$TREES_ALLOWED" -v forbidden="$DAEMON_FORBIDDEN" '
        # The daemon folder a path lies in ("" outside one).
        function daemon_layer(path) {
            if (path !~ /^server\/daemon\/[^\/]+\//) return ""
            sub(/^server\/daemon\//, "", path); sub(/\/.*/, "", path); return path
        }
        BEGIN {
            n = split(allowed, a, /[[:space:]]+/); for (i = 1; i <= n; i++) tree_ok[a[i]] = 1
            n = split(forbidden, f, /[[:space:]]+/); for (i = 1; i <= n; i++) layer_bad[f[i]] = 1
        }
        {
            tf = $1; sub(/\/.*/, "", tf); tt = $2; sub(/\/.*/, "", tt)
            if (tf != tt && !((tf ":" tt) in tree_ok)) {
                print "FAIL: " what " against the layers: " $1 " -> " $2 " (" tf "/ must not depend on " tt "/)"; bad = 1
            }
            lf = daemon_layer($1); lt = daemon_layer($2)
            if (lf != "" && lt != "" && ((lf ":" lt) in layer_bad)) {
                print "FAIL: " what " against the layers: " $1 " -> " $2 " (daemon/" lf "/ must not depend on daemon/" lt "/)"; bad = 1
            }
        }
        END { exit bad }'
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

# ---- 1. Includes between files ----
# "x.h" is looked for next to the including file, then as the end of a path
# in the including file's tree, then in proto/ (every tree's include
# directories hold its own folders and proto's), then in the other trees
# (which rule 3 then refuses). Includes found nowhere (system headers, a
# library's) are not part of the graph.
# shellcheck disable=SC2086
find $TREES \( -name '*.c' -o -name '*.h' -o -name '*.cpp' -o -name '*.hpp' \) -type f | sort >"$work/files"
tr '\n' '\0' <"$work/files" | xargs -0 grep -H '^[[:space:]]*#[[:space:]]*include[[:space:]]*"' |
    sed -n 's/^\([^:]*\):[[:space:]]*#[[:space:]]*include[[:space:]]*"\([^"]*\)".*/\1 \2/p' >"$work/quoted"
awk '
    # a/b/../c -> a/c, a/./b -> a/b
    function normal(path,    n, part, out, i, k) {
        n = split(path, part, "/"); k = 0
        for (i = 1; i <= n; i++) {
            if (part[i] == "." || part[i] == "") continue
            if (part[i] == ".." && k > 0 && out[k] != "..") { k--; continue }
            out[++k] = part[i]
        }
        path = ""
        for (i = 1; i <= k; i++) path = path (i > 1 ? "/" : "") out[i]
        return path
    }
    function tree(path) { sub(/\/.*/, "", path); return path }
    # The one file of `in_tree` whose path ends in /name ("" when none or several).
    function ending(name, in_tree,    f, found, count) {
        count = 0
        for (f in is_file)
            if (tree(f) == in_tree && (f == in_tree "/" name || substr(f, length(f) - length(name)) == "/" name)) {
                found = f; count++
            }
        if (count > 1) ambiguous[name " in " in_tree "/"] = 1
        return count == 1 ? found : ""
    }
    NR == FNR { is_file[$1] = 1; trees[tree($1)] = 1; next }
    {
        file = $1; name = $2; dir = file; sub(/\/[^\/]*$/, "", dir)
        target = normal(dir "/" name)
        if (!(target in is_file)) target = ending(name, tree(file))
        if (target == "" && ("proto" in trees)) target = ending(name, "proto")
        for (t in trees) if (target == "" && t != tree(file) && t != "proto") target = ending(name, t)
        if (target != "") print file, target
    }
    END { for (a in ambiguous) print "check_layers: include \"" a "\" names several files: not followed" > "/dev/stderr" }
' "$work/files" "$work/quoted" | sort -u >"$work/includes"
# Every file is a node, even one that includes nothing.
{ cat "$work/includes"; awk '{print $1, $1}' "$work/files"; } >"$work/include_edges"

say "# include graph of $TREES ($(wc -l <"$work/includes") includes between $(wc -l <"$work/files") files)"
[ "$QUIET" -eq 1 ] || awk '{print $1 " -> " $2}' "$work/includes"
check_cycles "includes" "$work/include_edges" || status=1
check_rules "include" <"$work/includes" || status=1

# ---- 2. Calls between object files ----
if [ -n "$OBJECTS" ]; then
    if [ ! -d "$OBJECTS" ]; then
        echo "FAIL: --objects $OBJECTS: no such folder (build first)"
        exit 1
    fi
    for tree in $TREES; do
        [ ! -d "$OBJECTS/$tree" ] || find "$OBJECTS/$tree" -name '*.o' -type f
    done | sort >"$work/objects"
    if [ ! -s "$work/objects" ]; then
        echo "FAIL: no object files for $TREES under $OBJECTS (build first)"
        exit 1
    fi
    # Objects named by their source (server/daemon/net/connection.c), not by
    # CMake's CMakeFiles/T.dir path ("__/" stands for "../" there). An object
    # whose source is gone (moved, renamed) is a leftover of an earlier build:
    # not part of the program any more.
    sed "s#^$OBJECTS/##; s#CMakeFiles/[^/]*\\.dir/##; s#__/#../#g; s#\\.o\$##" "$work/objects" |
        tr '\n' '\0' | xargs -0 realpath -m --relative-to=. | paste -d ' ' "$work/objects" - |
        while read -r obj name; do [ ! -f "$name" ] || echo "$obj $name"; done >"$work/sources"
    # "source type symbol" for every global symbol.
    awk '{print $1}' "$work/sources" | tr '\n' '\0' | xargs -0 nm -A -P -g 2>/dev/null |
        awk 'NR == FNR {source[$1 ":"] = $2; next} $1 in source {print source[$1], $3, $2}' \
            "$work/sources" - >"$work/symbols"
    # Variables a program may change (.data, .bss, thread-local, common;
    # not .data.rel.ro, where constant tables of pointers lie).
    awk '{print $1}' "$work/sources" | tr '\n' '\0' | xargs -0 objdump -t 2>/dev/null |
        awk 'NR == FNR {source[$1] = $2; next}
             /:[[:space:]]+file format / {o = source[substr($1, 1, length($1) - 1)]; next}
             / O / && o != "" {sec = $(NF - 2); name = $NF
                 if ((sec ~ /^\.t?(data|bss)/ && sec !~ /^\.data\.rel\.ro/) || sec == "*COM*")
                     if (name !~ /^(__|\.)/) print o, name}' "$work/sources" - >"$work/variables"
    # A strong definition (weak ones, C++ template copies, are everybody's)
    # answers a use. A symbol defined in several sources (a program's own
    # version of a library's function) may answer it from any of them.
    awk '$2 ~ /^[TDBRCGS]$/ {if (!(($3, $1) in seen)) {seen[$3, $1] = 1; def[$3] = def[$3] " " $1}; next}
         $2 == "U" {use[++n] = $1 " " $3}
         END {for (i = 1; i <= n; i++) {
                  split(use[i], u, " ")
                  if (!(u[2] in def)) continue
                  k = split(def[u[2]], d, " ")
                  for (j = 1; j <= k; j++) if (d[j] != u[1]) print u[1], d[j]
              }}' \
        "$work/symbols" | sort -u >"$work/calls"
    { cat "$work/calls"; awk '{print $1, $1}' "$work/symbols" | sort -u; } >"$work/call_edges"
    say "# call graph between object files ($(wc -l <"$work/calls") edges)"
    [ "$QUIET" -eq 1 ] || awk '{print $1 " -> " $2}' "$work/calls"
    check_cycles "calls between object files" "$work/call_edges" || status=1
    check_rules "call" <"$work/calls" || status=1
    # 5. The daemon's mutable global state lives at its top level only.
    if awk '$1 ~ /^server\/daemon\/[^\/]+\//' "$work/variables" | grep -q .; then
        echo "FAIL: mutable global or static variables below the daemon's top level:"
        awk '$1 ~ /^server\/daemon\/[^\/]+\// {print "    " $1 ": " $2}' "$work/variables"
        status=1
    fi
fi

if [ $status -eq 0 ]; then
    say "OK: no circles$([ -n "$OBJECTS" ] && echo ' of includes or calls') in $TREES, layers respected"
fi
exit $status
