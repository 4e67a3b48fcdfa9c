#!/usr/bin/env bash
# tests/install: what `cmake --install` and `cpack -G DEB` deliver, used the way
# a user outside the tree uses them (deploy/README.md, "Install").
#   1. cmake --install into DESTDIR=WORK/root; the binaries, libfluidcast.so with
#      its SONAME links, libfluidcast.a, the headers, fluidcast.pc, the CMake
#      package and the udev rule are there; libfluidcast.so exports exactly the
#      functions the installed headers declare (check_exports.sh); every header
#      compiles alone.
#   2. A consumer (tests/install/consumer) and examples/producer.c build against
#      that tree only, shared and static, with pkg-config and with find_package;
#      the consumer also against `cmake --install --prefix WORK/moved`, a prefix
#      given at install time only (the .pc and the CMake package are relocatable).
#   3. fluidcastd from the tree renders for each of them (a PNG each); the installed
#      fluidcast draws a legend, writes an .mp4 and runs `view` through its modules
#      (<libdir>/fluidcast).
#   4. cpack -G DEB: under /usr whatever the configured prefix; name, Depends (the
#      modules' libraries too), files; dpkg -x and run what it holds (the CLI's
#      modules included), a consumer built with its .pc, its exports; and
#      apt-get's simulation resolves its Depends on this system.
# Never installs anything onto this machine.
#
# usage: test_install.sh BUILD_DIR SOURCE_DIR WORK_DIR CMAKE CPACK CC PREFIX BINDIR LIBDIR INCLUDEDIR VERSION
set -euo pipefail
[ $# -eq 11 ] || { echo "usage: $0 BUILD SOURCE WORK CMAKE CPACK CC PREFIX BINDIR LIBDIR INCLUDEDIR VERSION" >&2; exit 2; }
BUILD=$1 SRC=$2 WORK=$3 CMAKE=$4 CPACK=$5 CC=$6 PREFIX=$7 BINDIR=$8 LIBDIR=$9 INCLUDEDIR=${10} VERSION=${11}
# under PREFIX DIR: DIR under PREFIX, unless DIR is absolute (CMAKE_INSTALL_<dir>'s rule).
under() { case $2 in /*) echo "$2" ;; *) echo "$1/$2" ;; esac; }
BINDIR_REL=$BINDIR LIBDIR_REL=$LIBDIR INCLUDEDIR_REL=$INCLUDEDIR
BINDIR=$(under "$PREFIX" "$BINDIR_REL") LIBDIR=$(under "$PREFIX" "$LIBDIR_REL") INCLUDEDIR=$(under "$PREFIX" "$INCLUDEDIR_REL")
# The .deb installs under /usr whatever prefix was configured (cmake/fluidcast_packaging.cmake).
DEB_BINDIR=$(under /usr "$BINDIR_REL") DEB_LIBDIR=$(under /usr "$LIBDIR_REL")
DEB_INCLUDEDIR=$(under /usr "$INCLUDEDIR_REL")
SOMAJOR=${VERSION%%.*}

step() { echo "== $(date +%T) $*"; }
fail() { echo "FAIL: $*" >&2; exit 1; }
need_file() { [ -f "$1" ] || fail "missing $1"; }
# grep -q at the end of a pipe may stop reading early and fail the pipe (pipefail): read it all.
matches() { grep "$@" > /dev/null; }

DAEMON_PID=""
stop_daemon() {
    if [ -n "$DAEMON_PID" ]; then
        kill "$DAEMON_PID" 2>/dev/null || true
        wait "$DAEMON_PID" 2>/dev/null || true
        DAEMON_PID=""
    fi
}
trap stop_daemon EXIT

rm -rf "$WORK"
mkdir -p "$WORK"
ROOT=$WORK/root

step "cmake --install $BUILD (DESTDIR=$ROOT)"
DESTDIR=$ROOT "$CMAKE" --install "$BUILD" > "$WORK/install.log"
R=$ROOT
for f in "$R$BINDIR/fluidcastd" "$R$BINDIR/fluidcast"; do
    [ -x "$f" ] || fail "missing executable $f"
done
need_file "$R$LIBDIR/libfluidcast.so.$VERSION"
[ "$(readlink "$R$LIBDIR/libfluidcast.so.$SOMAJOR")" = "libfluidcast.so.$VERSION" ] ||
    fail "libfluidcast.so.$SOMAJOR is not a link to libfluidcast.so.$VERSION"
[ "$(readlink "$R$LIBDIR/libfluidcast.so")" = "libfluidcast.so.$SOMAJOR" ] ||
    fail "libfluidcast.so is not a link to libfluidcast.so.$SOMAJOR"
readelf -d "$R$LIBDIR/libfluidcast.so.$VERSION" | matches "SONAME.*\[libfluidcast.so.$SOMAJOR\]" ||
    fail "libfluidcast's SONAME is not libfluidcast.so.$SOMAJOR"
need_file "$R$LIBDIR/libfluidcast.a"
HEADERS="fluidcast.h fluidcast_types.h fc_error.h fc_frame.h fc_api.h"
for h in $HEADERS; do need_file "$R$INCLUDEDIR/fluidcast/$h"; done
need_file "$R$LIBDIR/pkgconfig/fluidcast.pc"
# Relocatable: the prefix is where the .pc is, not the configured one (else --prefix DIR and the .deb break).
# shellcheck disable=SC2016  # a literal ${pcfiledir}
matches '^prefix=${pcfiledir}/' < "$R$LIBDIR/pkgconfig/fluidcast.pc" ||
    fail "fluidcast.pc's prefix is not relative to \${pcfiledir}: $(grep '^prefix=' "$R$LIBDIR/pkgconfig/fluidcast.pc")"
for f in fluidcastConfig.cmake fluidcastConfigVersion.cmake fluidcastTargets.cmake; do
    need_file "$R$LIBDIR/cmake/fluidcast/$f"
done
need_file "$R$PREFIX/lib/udev/rules.d/70-fluidcast-spacemouse.rules"
# The CLI's modules (client/cli/cli_module.h): OpenImageIO, libav, SDL2 and libhdf5, loaded only by the commands
# that use them.
MODULES="fluidcast-image.so fluidcast-video.so fluidcast-view.so fluidcast-hdf5.so"
for m in $MODULES; do need_file "$R$LIBDIR/fluidcast/$m"; done
if readelf -d "$R$BINDIR/fluidcast" | grep NEEDED | matches -e libOpenImageIO -e libav -e libSDL2 -e libhdf5; then
    fail "the installed fluidcast links OpenImageIO, libav, SDL2 or libhdf5 itself"
fi
for u in fluidcastd.service fluidcastd.socket fluidcastd@.service; do
    need_file "$R$PREFIX/lib/systemd/system/$u"
    matches "^ExecStart=$BINDIR/fluidcastd " < "$R$PREFIX/lib/systemd/system/$u" || [ "$u" = fluidcastd.socket ] ||
        fail "$u does not run $BINDIR/fluidcastd"
done
# The Python package, when this build was configured with python/fluidcast present.
PYPKG=""
if grep -rqs "python/fluidcast" "$BUILD/cmake_install.cmake"; then
    PYPKG=$R$PREFIX/lib/python3/dist-packages/fluidcast
    need_file "$PYPKG/__init__.py"
fi
# Nothing installed may point back into the build or source tree.
if grep -rlF -e "$BUILD" -e "$SRC/" "$R$LIBDIR/pkgconfig" "$R$LIBDIR/cmake" "$R$INCLUDEDIR/fluidcast"; then
    fail "installed files name the build or source tree"
fi
for f in "$R$BINDIR/fluidcastd" "$R$BINDIR/fluidcast" "$R$LIBDIR/libfluidcast.so.$VERSION" \
         "$R$LIBDIR/fluidcast/fluidcast-image.so" "$R$LIBDIR/fluidcast/fluidcast-video.so" \
         "$R$LIBDIR/fluidcast/fluidcast-view.so" "$R$LIBDIR/fluidcast/fluidcast-hdf5.so"; do
    if readelf -d "$f" | grep -E 'RPATH|RUNPATH' | matches -F "$BUILD"; then fail "$f keeps the build tree's RPATH"; fi
done
# The static library holds the protocol functions its headers declare (the shared
# library's exports are checked against the headers below, check_exports.sh).
# (Listed to a file first: grep -q ending a pipe early fails it under pipefail.)
nm --defined-only "$R$LIBDIR/libfluidcast.a" > "$WORK/nm-static.txt" 2>/dev/null
for sym in fc_frame_alloc fc_frame_estimate_radius fc_camera_frame_bounds fc_settings_default fc_code_name \
           fc_client_connect fc_client_upload_frame; do
    grep -qw "T $sym" "$WORK/nm-static.txt" || fail "libfluidcast.a lacks $sym"
done

step "libfluidcast.so exports exactly the functions the installed headers declare"
bash "$SRC/tests/install/check_exports.sh" "$R$LIBDIR/libfluidcast.so.$VERSION" "$R$INCLUDEDIR" "$CC" "$WORK/exports" ||
    fail "libfluidcast.so's exports are not its documented API (docs/abi.md)"

step "each installed header compiles with only the installed headers"
for h in $HEADERS; do
    printf '#include "%s"\n#include "%s"\nint main(void) { return 0; }\n' "$h" "$h" > "$WORK/header_$h.c"
    "$CC" -std=c11 -Wall -Wextra -Werror -pedantic -I"$R$INCLUDEDIR/fluidcast" -fsyntax-only "$WORK/header_$h.c" ||
        fail "$h does not compile on its own"
done

EX=$SRC/examples
CONSUMER=$SRC/tests/install/consumer
step "build with pkg-config (PKG_CONFIG_SYSROOT_DIR=$R)"
pc() {
    PKG_CONFIG_PATH="$R$LIBDIR/pkgconfig" PKG_CONFIG_SYSROOT_DIR="$R" \
        PKG_CONFIG_ALLOW_SYSTEM_CFLAGS=1 PKG_CONFIG_ALLOW_SYSTEM_LIBS=1 pkg-config "$@"
}
[ "$(pc --modversion fluidcast)" = "$VERSION" ] || fail "pkg-config --modversion fluidcast is not $VERSION"
CFLAGS_FC=$(pc --cflags fluidcast)
LIBS_FC=$(pc --libs fluidcast)
LIBS_STATIC=$(pc --static --libs fluidcast)
echo "cflags: $CFLAGS_FC"; echo "libs: $LIBS_FC"; echo "static libs: $LIBS_STATIC"
case " $LIBS_STATIC " in *" -lzstd "*) ;; *) fail "pkg-config --static --libs lacks -lzstd" ;; esac
# shellcheck disable=SC2086
{
    "$CC" -std=c11 -Wall -Wextra -Werror -D_POSIX_C_SOURCE=200809L $CFLAGS_FC -o "$WORK/consumer_pc_shared" \
          "$CONSUMER/consumer.c" $LIBS_FC -lm
    "$CC" -std=c11 -Wall -Wextra -Werror -D_POSIX_C_SOURCE=200809L $CFLAGS_FC -o "$WORK/producer_pc_shared" \
          "$EX/producer.c" "$EX/sloshing_block.c" $LIBS_FC -lm
    # The archive itself where the .pc says -lfluidcast; its private libraries from Libs.private.
    "$CC" -std=c11 -Wall -Wextra -Werror -D_POSIX_C_SOURCE=200809L $CFLAGS_FC -o "$WORK/consumer_pc_static" \
          "$CONSUMER/consumer.c" ${LIBS_STATIC/-lfluidcast/-l:libfluidcast.a}
}
readelf -d "$WORK/consumer_pc_shared" | matches "NEEDED.*libfluidcast.so.$SOMAJOR" || fail "consumer_pc_shared does not need libfluidcast.so.$SOMAJOR"
if readelf -d "$WORK/consumer_pc_static" | matches "NEEDED.*libfluidcast"; then fail "consumer_pc_static needs libfluidcast.so"; fi

step "build with CMake (find_package(fluidcast), CMAKE_PREFIX_PATH=$R$PREFIX)"
"$CMAKE" -S "$CONSUMER" -B "$WORK/cmake-consumer" -DCMAKE_C_COMPILER="$CC" -DCMAKE_PREFIX_PATH="$R$PREFIX" \
         -DFC_EXAMPLES_DIR="$EX" -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF > "$WORK/cmake-consumer.log" ||
    { cat "$WORK/cmake-consumer.log"; fail "the consumer project does not configure"; }
grep -q "fluidcast_DIR:PATH=$R$LIBDIR/cmake/fluidcast" "$WORK/cmake-consumer/CMakeCache.txt" ||
    fail "find_package(fluidcast) did not find the installed tree: $(grep fluidcast_DIR "$WORK/cmake-consumer/CMakeCache.txt")"
"$CMAKE" --build "$WORK/cmake-consumer" -j2 > "$WORK/cmake-build.log" ||
    { cat "$WORK/cmake-build.log"; fail "the consumer project does not build"; }
CB=$WORK/cmake-consumer
readelf -d "$CB/consumer_shared" | matches "NEEDED.*libfluidcast.so.$SOMAJOR" || fail "consumer_shared does not need libfluidcast.so"
if readelf -d "$CB/consumer_static" | matches "NEEDED.*libfluidcast"; then fail "consumer_static needs libfluidcast.so"; fi

MOVED=$WORK/moved
step "cmake --install $BUILD --prefix $MOVED: pkg-config and find_package there"
# Another prefix than the configured one, given at install time: the .pc, the CMake package and the
# systemd units must name this prefix's files (PKG_CONFIG_PATH alone, no sysroot).
"$CMAKE" --install "$BUILD" --prefix "$MOVED" > "$WORK/install-moved.log"
M_BINDIR=$(under "$MOVED" "$BINDIR_REL") M_LIBDIR=$(under "$MOVED" "$LIBDIR_REL")
matches "^ExecStart=$M_BINDIR/fluidcastd " < "$MOVED/lib/systemd/system/fluidcastd.service" ||
    fail "the units under $MOVED do not run $M_BINDIR/fluidcastd: $(grep ExecStart "$MOVED/lib/systemd/system/fluidcastd.service")"
# shellcheck disable=SC2046
"$CC" -std=c11 -Wall -Wextra -Werror -D_POSIX_C_SOURCE=200809L -o "$WORK/consumer_moved_pc" "$CONSUMER/consumer.c" \
      $(PKG_CONFIG_PATH="$M_LIBDIR/pkgconfig" pkg-config --cflags --libs fluidcast) -lm ||
    fail "the consumer does not build with pkg-config against $MOVED"
"$CMAKE" -S "$CONSUMER" -B "$WORK/cmake-moved" -DCMAKE_C_COMPILER="$CC" -DCMAKE_PREFIX_PATH="$MOVED" \
         -DFC_EXAMPLES_DIR="$EX" -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF > "$WORK/cmake-moved.log" ||
    { cat "$WORK/cmake-moved.log"; fail "the consumer project does not configure against $MOVED"; }
grep -q "fluidcast_DIR:PATH=$M_LIBDIR/cmake/fluidcast" "$WORK/cmake-moved/CMakeCache.txt" ||
    fail "find_package(fluidcast) did not find $MOVED: $(grep fluidcast_DIR "$WORK/cmake-moved/CMakeCache.txt")"
"$CMAKE" --build "$WORK/cmake-moved" --target consumer_shared > "$WORK/cmake-moved-build.log" ||
    { cat "$WORK/cmake-moved-build.log"; fail "the consumer does not build with find_package against $MOVED"; }

# Starts DAEMON (a fluidcastd) on a free loopback port; sets ADDR.
start_daemon() {
    local daemon=$1 libdir=$2 portfile=$WORK/port.$RANDOM
    (cd "$WORK" && exec env LD_LIBRARY_PATH="$libdir" "$daemon" --listen 127.0.0.1:0 --port-file "$portfile" \
        --gpu software --log-level warn) &
    DAEMON_PID=$!
    for _ in $(seq 1 300); do
        [ -s "$portfile" ] && break
        kill -0 "$DAEMON_PID" 2>/dev/null || fail "$daemon exited before announcing its port"
        sleep 0.1
    done
    [ -s "$portfile" ] || fail "$daemon did not announce its port within 30 s"
    ADDR=127.0.0.1:$(cat "$portfile")
}
check_png() {
    [ "$(head -c 8 "$1" | od -An -tx1 | tr -d ' \n')" = 89504e470d0a1a0a ] || fail "$1 is not a PNG"
}

step "render through the installed fluidcastd"
start_daemon "$R$BINDIR/fluidcastd" "$R$LIBDIR"
echo "daemon at $ADDR (pid $DAEMON_PID)"
for prog in "$WORK/consumer_pc_shared" "$WORK/consumer_pc_static" "$CB/consumer_shared" "$CB/consumer_static"; do
    LD_LIBRARY_PATH="$R$LIBDIR" "$prog" "$ADDR" "$prog.png" || fail "$prog did not render"
    check_png "$prog.png"
done
for prog in "$WORK/producer_pc_shared" "$CB/producer_shared" "$CB/producer_static"; do
    LD_LIBRARY_PATH="$R$LIBDIR" "$prog" "$ADDR" "install-$(basename "$prog")" 3 || fail "$prog failed"
done
for prog in "$WORK/consumer_moved_pc" "$WORK/cmake-moved/consumer_shared"; do
    LD_LIBRARY_PATH="$M_LIBDIR" "$prog" "$ADDR" "$prog.png" || fail "$prog did not render"
    check_png "$prog.png"
done
LD_LIBRARY_PATH="$R$LIBDIR" "$R$BINDIR/fluidcast" info --server "$ADDR" > "$WORK/info.txt" ||
    fail "the installed fluidcast info failed"
# A small ball of particles, some moving, for the commands that need the modules.
{
    echo "x,y,z,vx,vy,vz"
    for i in $(seq -4 4); do for j in $(seq -4 4); do for k in $(seq -4 4); do
        [ $((i * i + j * j + k * k)) -le 16 ] && echo "0.$((i + 5)),0.$((j + 5)),0.$((k + 5)),0,0,$(((i + 4) % 3))"
    done; done; done
} > "$WORK/ball.csv"
# The installed fluidcast finds its modules next to itself (bin/ -> <libdir>/fluidcast).
check_modules() {   # FLUIDCAST EXTRA_LD_LIBRARY_PATH TAG
    LD_LIBRARY_PATH="$2" "$1" snapshot "$WORK/ball.csv" -o "$WORK/legend-$3.png" --server "$ADDR" --size 96x64 \
        --color-by speed --range 0:2 --legend > "$WORK/legend-$3.txt" 2>&1 ||
        { cat "$WORK/legend-$3.txt"; fail "$1 snapshot --legend failed (fluidcast-image.so)"; }
    matches "^legend: columns" < "$WORK/legend-$3.txt" || fail "$1 drew no legend"
    check_png "$WORK/legend-$3.png"
    LD_LIBRARY_PATH="$2" "$1" render "$WORK/ball.csv" "$WORK/ball.csv" -o "$WORK/video-$3.mp4" --server "$ADDR" \
        --size 96x64 > "$WORK/video-$3.txt" 2>&1 ||
        { cat "$WORK/video-$3.txt"; fail "$1 render to .mp4 failed (fluidcast-video.so)"; }
    [ "$(head -c 8 "$WORK/video-$3.mp4" | tail -c 4)" = ftyp ] || fail "$WORK/video-$3.mp4 is not an MP4"
    LD_LIBRARY_PATH="$2" "$1" view --help > "$WORK/view-$3.txt" 2>&1 ||
        { cat "$WORK/view-$3.txt"; fail "$1 view --help failed (fluidcast-view.so)"; }
    matches "^usage: fluidcast view" < "$WORK/view-$3.txt" || fail "$1 view --help printed no usage"
    # An HDF5 file through fluidcast-hdf5.so, when tests/readers' h5py fixtures were made in this build.
    local h5=$BUILD/tests/readers/hdf5_fixtures/swift_f32.h5
    if [ -f "$h5" ]; then
        LD_LIBRARY_PATH="$2" "$1" snapshot "$h5" -o "$WORK/hdf5-$3.png" --server "$ADDR" --size 96x64 --up z \
            > "$WORK/hdf5-$3.txt" 2>&1 || { cat "$WORK/hdf5-$3.txt"; fail "$1 snapshot of $h5 failed (fluidcast-hdf5.so)"; }
        check_png "$WORK/hdf5-$3.png"
    else
        echo "no HDF5 fixtures in $BUILD (h5py): the installed HDF5 module is not run"
    fi
}
check_modules "$R$BINDIR/fluidcast" "$R$LIBDIR" installed
stop_daemon
if [ -n "$PYPKG" ]; then
    step "the installed Python package"
    if python3 -c "import numpy" 2>/dev/null; then
        FLUIDCAST_LIBRARY="$R$LIBDIR/libfluidcast.so.$SOMAJOR" PYTHONPATH="$(dirname "$PYPKG")" python3 -c \
            "import fluidcast, sys; assert fluidcast.__file__.startswith(sys.argv[1]), fluidcast.__file__" "$PYPKG" ||
            fail "the installed Python package does not import"
    else
        echo "no numpy here: compiling it only"
        python3 -c "import py_compile, sys; [py_compile.compile(f, doraise=True) for f in sys.argv[1:]]" \
            "$PYPKG"/*.py || fail "the installed Python package does not compile"
        rm -rf "$PYPKG/__pycache__"
    fi
fi

step "cpack -G DEB"
ARCH=$(dpkg --print-architecture)
DEB=$WORK/pkg/fluidcast_${VERSION}_$ARCH.deb
# As `cd build && cpack -G DEB` does, except for cpack's first step, the "preinstall"
# target (make all over the whole tree): the suite's build is complete, and a
# test must not rebuild or relink binaries that other tests are running. A
# generator without a preinstall target (Ninja; only its name is used) skips it.
(cd "$WORK" && "$CPACK" -G DEB --config "$BUILD/CPackConfig.cmake" -B "$WORK/pkg" -D CPACK_CMAKE_GENERATOR=Ninja \
    > "$WORK/cpack.log" 2>&1) ||
    { cat "$WORK/cpack.log"; fail "cpack -G DEB failed"; }
need_file "$DEB"
dpkg-deb -I "$DEB" > "$WORK/deb-info.txt"
cat "$WORK/deb-info.txt"
for field in Package Version Architecture Maintainer Section Description Depends; do
    grep -q "^ $field: ." "$WORK/deb-info.txt" || fail "the .deb has no $field"
done
# What the CLI's modules load must be there too (the daemon needs most of it as well; libhdf5 only
# fluidcast-hdf5.so links, so its presence shows that dpkg-shlibdeps read the modules).
for dep in libc6 libzstd1 libegl1 libopenimageio2.4 libavformat59 libsdl2-2.0-0 libhdf5-103-1; do
    grep "^ Depends:" "$WORK/deb-info.txt" | matches -w "$dep" || fail "Depends lacks $dep"
done
dpkg-deb -c "$DEB" | awk '{print $6}' > "$WORK/deb-files.txt"
for f in "$DEB_BINDIR/fluidcastd" "$DEB_BINDIR/fluidcast" "$DEB_LIBDIR/libfluidcast.so.$VERSION" "$DEB_LIBDIR/libfluidcast.so.$SOMAJOR" \
         "$DEB_LIBDIR/libfluidcast.so" "$DEB_LIBDIR/libfluidcast.a" "$DEB_INCLUDEDIR/fluidcast/fluidcast.h" \
         "$DEB_INCLUDEDIR/fluidcast/fluidcast_types.h" "$DEB_LIBDIR/pkgconfig/fluidcast.pc" \
         "$DEB_LIBDIR/cmake/fluidcast/fluidcastConfig.cmake" "/usr/lib/udev/rules.d/70-fluidcast-spacemouse.rules" \
         "$DEB_LIBDIR/fluidcast/fluidcast-image.so" "$DEB_LIBDIR/fluidcast/fluidcast-video.so" \
         "$DEB_LIBDIR/fluidcast/fluidcast-view.so" "$DEB_LIBDIR/fluidcast/fluidcast-hdf5.so"; do
    grep -qx "\.$f" "$WORK/deb-files.txt" || fail "the .deb lacks $f"
done

step "dpkg -x the .deb and run what it holds"
X=$WORK/extracted
dpkg -x "$DEB" "$X"
LD_LIBRARY_PATH="$X$DEB_LIBDIR" "$X$DEB_BINDIR/fluidcast" --version | tee "$WORK/version.txt"
grep -q "$VERSION" "$WORK/version.txt" || fail "fluidcast --version does not say $VERSION"
LD_LIBRARY_PATH="$X$DEB_LIBDIR" "$X$DEB_BINDIR/fluidcastd" --help | matches -- "--port-file" || fail "fluidcastd --help"
start_daemon "$X$DEB_BINDIR/fluidcastd" "$X$DEB_LIBDIR"
LD_LIBRARY_PATH="$X$DEB_LIBDIR" "$CB/consumer_shared" "$ADDR" "$WORK/from_deb.png" || fail "no render from the .deb's daemon and library"
check_png "$WORK/from_deb.png"
# The .deb's own .pc (where pkg-config finds it once installed: its prefix is /usr) and exports.
PC_DEB=$X$DEB_LIBDIR/pkgconfig
[ "$(PKG_CONFIG_PATH="$PC_DEB" pkg-config --variable=prefix fluidcast)" -ef "$X/usr" ] ||
    fail "the .deb's fluidcast.pc has prefix $(PKG_CONFIG_PATH="$PC_DEB" pkg-config --variable=prefix fluidcast)"
# shellcheck disable=SC2046
"$CC" -std=c11 -Wall -Wextra -Werror -D_POSIX_C_SOURCE=200809L -o "$WORK/consumer_deb_pc" "$CONSUMER/consumer.c" \
      $(PKG_CONFIG_PATH="$PC_DEB" pkg-config --cflags --libs fluidcast) -lm || fail "no build with the .deb's .pc"
LD_LIBRARY_PATH="$X$DEB_LIBDIR" "$WORK/consumer_deb_pc" "$ADDR" "$WORK/consumer_deb_pc.png" ||
    fail "the consumer built with the .deb's .pc did not render"
bash "$SRC/tests/install/check_exports.sh" "$X$DEB_LIBDIR/libfluidcast.so.$VERSION" "$X$DEB_INCLUDEDIR" "$CC" \
    "$WORK/exports-deb" || fail "the .deb's libfluidcast.so exports are not its documented API"
matches "^ExecStart=/usr/bin/fluidcastd " < "$X/usr/lib/systemd/system/fluidcastd.service" ||
    fail "the .deb's fluidcastd.service does not run /usr/bin/fluidcastd"
check_modules "$X$DEB_BINDIR/fluidcast" "$X$DEB_LIBDIR" deb
stop_daemon

if command -v apt-get > /dev/null; then
    step "apt-get install --simulate ./$(basename "$DEB")"
    # Simulation only, without the dpkg lock: nothing is installed here.
    if apt-get install --simulate -o Debug::NoLocking=1 "$DEB" > "$WORK/apt.txt" 2>&1; then
        grep -E "^(Inst|Conf) fluidcast " "$WORK/apt.txt" || fail "apt-get would not install fluidcast: $(cat "$WORK/apt.txt")"
    else
        cat "$WORK/apt.txt"
        fail "apt-get cannot resolve the .deb's dependencies"
    fi
fi
echo "PASS"
