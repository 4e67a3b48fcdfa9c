# A Debian package of everything `cmake --install` puts in place:
#     cmake -S . -B build -DCMAKE_INSTALL_PREFIX=/usr && cmake --build build
#     (cd build && cpack -G DEB)      ->  fluidcast_<version>_<arch>.deb
#     sudo apt-get install ./build/fluidcast_*.deb
# One package (daemon, CLI, library, headers, pkg-config and CMake files).
# Depends comes from dpkg-shlibdeps (dpkg-dev) over the packed binaries.
# Included last in the top-level CMakeLists.txt; tests/install builds and checks it.
set(CPACK_PACKAGE_NAME fluidcast)
set(CPACK_PACKAGE_VENDOR "fluidcast")
set(CPACK_PACKAGE_CONTACT "fluidcast maintainers <maintainers@users.noreply.h-seed-463078b5.example>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "remote renderer for particle fluids: fluidcastd, fluidcast CLI, libfluidcast")
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_RESOURCE_FILE_README ${PROJECT_SOURCE_DIR}/README.md)
set(CPACK_STRIP_FILES ON)
set(CPACK_GENERATOR DEB)
set(CPACK_SOURCE_GENERATOR "")
# Debian packages install under /usr, whatever prefix `cmake --install` was
# configured for: every installed path is relative to the prefix (the .pc and
# the CMake package find it from where they lie, the systemd units are written
# at install time), so the package is right from any build. With
# -DCMAKE_INSTALL_PREFIX=/usr the library goes to Debian's multiarch directory
# (lib/x86_64-linux-gnu); from another prefix's build, to /usr/lib.
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)

set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_MAINTAINER "${CPACK_PACKAGE_CONTACT}")
set(CPACK_DEBIAN_PACKAGE_SECTION graphics)
set(CPACK_DEBIAN_PACKAGE_PRIORITY optional)
# The synopsis is CPACK_PACKAGE_DESCRIPTION_SUMMARY; this is the long description.
set(CPACK_DEBIAN_PACKAGE_DESCRIPTION "fluidcastd renders particle simulations (screen-space fluid rendering through
EGL on a GPU, or Mesa's llvmpipe without one) for clients on the network.
Simulation codes push frames with libfluidcast; the fluidcast command renders
particle files and sequences to images and videos, streams and watches sessions.
Includes the headers, libfluidcast.a, fluidcast.pc and the CMake package
(find_package(fluidcast)) to build against the library.")
# Depends: dpkg-shlibdeps over the binaries; libfluidcast.so.0 is in this package.
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_GENERATE_SHLIBS ON)
# libfluidcast.so.0, which fluidcast needs, is in this package rather than on the system.
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS_PRIVATE_DIRS ${CMAKE_BINARY_DIR}/lib)
# libepoxy opens libEGL.so.1 and the GL library, libOpenGL.so.0 (else libGL.so.1),
# at run time (dlopen), so dpkg-shlibdeps sees neither; without the GL one
# fluidcastd aborts at start (found by the container test on a minimal Debian).
set(CPACK_DEBIAN_PACKAGE_DEPENDS "libegl1, libopengl0 | libgl1")
# EGL finds Mesa (llvmpipe, or a GPU's driver) through libglvnd's vendor files.
# fluidcast snapshot --legend draws its text with DejaVu Sans (FC_LEGEND_FONT, client/cli).
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS "libegl-mesa0, libgl1-mesa-dri, fonts-dejavu-core")
if(EXISTS ${PROJECT_SOURCE_DIR}/python/fluidcast/__init__.py)
  # The Python package (ctypes over libfluidcast.so.0) and its arrays.
  string(APPEND CPACK_DEBIAN_PACKAGE_RECOMMENDS ", python3, python3-numpy")
endif()
set(CPACK_DEBIAN_PACKAGE_SUGGESTS "libzstd-dev, libssl-dev")
if(NOT CMAKE_INSTALL_PREFIX STREQUAL "/usr")
  message(STATUS "cpack -G DEB packs under /usr with the library in /usr/${CMAKE_INSTALL_LIBDIR}: configure "
                 "with -DCMAKE_INSTALL_PREFIX=/usr for Debian's multiarch library directory")
endif()
include(CPack)
