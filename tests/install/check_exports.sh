#!/usr/bin/env bash
# The ABI of an installed libfluidcast.so is exactly the functions its installed
# headers declare (docs/abi.md): every symbol the library defines in its dynamic
# symbol table is a function declared in INCLUDEDIR/fluidcast/*.h, and every
# function declared there is exported, as a function (nm type T).
# The declarations come from the compiler itself (GCC's -aux-info lists every
# function prototype a translation unit sees, with the file it came from), so
# macros, attributes and declarations spread over lines cannot fool the check.
#
# usage: check_exports.sh LIBFLUIDCAST.so INCLUDEDIR CC WORK_DIR
set -euo pipefail
[ $# -eq 4 ] || { echo "usage: $0 LIBFLUIDCAST.so INCLUDEDIR CC WORK_DIR" >&2; exit 2; }
LIB=$1 INC=$2/fluidcast CC=$3 WORK=$4
fail() { echo "FAIL: $*" >&2; exit 1; }
[ -d "$INC" ] || fail "no $INC"
mkdir -p "$WORK"

# Every installed header, included by one translation unit.
headers=$(cd "$INC" && ls -- *.h)
[ -n "$headers" ] || fail "no headers in $INC"
for h in $headers; do printf '#include "%s"\n' "$h"; done > "$WORK/all_headers.c"
"$CC" -std=c11 -I"$INC" -fsyntax-only -aux-info "$WORK/aux.txt" "$WORK/all_headers.c" ||
    fail "$CC cannot list the headers' prototypes (-aux-info needs GCC)"
# Lines look like: /* DIR/fc_frame.h:32:NC */ extern fc_code fc_frame_alloc (fc_frame *, ...);
# Only the installed headers' lines count (not libc's); the name is the word before the first " (".
grep -F "/* $INC/" "$WORK/aux.txt" | sed -E 's/^[^*]*\*\/ *//; s/ \(.*//; s/.*[ *]//' | sort -u \
    > "$WORK/declared.txt"
[ -s "$WORK/declared.txt" ] || fail "no function declared in $INC"

# What the library exports: everything it defines in .dynsym (functions T, data D/B/R, ...).
nm -D --defined-only "$LIB" | awk '{print $2, $3}' | sort -k2 > "$WORK/exported_typed.txt"
awk '{print $2}' "$WORK/exported_typed.txt" | sort -u > "$WORK/exported.txt"
awk '$1 == "T" {print $2}' "$WORK/exported_typed.txt" | sort -u > "$WORK/exported_functions.txt"

status=0
undeclared=$(comm -23 "$WORK/exported.txt" "$WORK/declared.txt")
if [ -n "$undeclared" ]; then
    echo "FAIL: $LIB exports $(echo "$undeclared" | wc -l) symbol(s) no installed header declares:" >&2
    echo "$undeclared" | sed 's/^/    /' >&2
    status=1
fi
missing=$(comm -23 "$WORK/declared.txt" "$WORK/exported_functions.txt")
if [ -n "$missing" ]; then
    echo "FAIL: $(echo "$missing" | wc -l) function(s) declared in $INC are not exported functions of $LIB:" >&2
    echo "$missing" | sed 's/^/    /' >&2
    status=1
fi
[ $status -eq 0 ] && echo "exports: $(wc -l < "$WORK/exported.txt") symbols, the $(wc -l < "$WORK/declared.txt") functions of $INC"
exit $status
