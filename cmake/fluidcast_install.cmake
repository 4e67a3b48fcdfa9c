# What `cmake --install` puts beside the targets' own install() rules (the
# binaries in client/cli and server/daemon, the libraries and headers in
# client/lib): the pkg-config file, the CMake package config, the SpaceMouse
# udev rule and, when it exists, the Python package. Included at the end of the
# top-level CMakeLists.txt, after every target is defined. tests/install checks
# the result, and cmake/fluidcast_packaging.cmake packs it into a .deb.
include(CMakePackageConfigHelpers)

# Where find_package looks: <prefix>/<libdir>/cmake/fluidcast.
set(FLUIDCAST_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/fluidcast)
set(FLUIDCAST_UDEV_RULES_DIR lib/udev/rules.d CACHE STRING
    "where the udev rule is installed, relative to the prefix (udev reads /usr/lib/udev/rules.d)")
set(FLUIDCAST_PYTHON_DIR lib/python3/dist-packages CACHE STRING
    "where the Python package is installed, relative to the prefix (Debian's path for python3)")

# pkg-config: fluidcast.pc, relocatable: its prefix is found from where the file
# is (${pcfiledir}, <prefix>/<libdir>/pkgconfig), so `cmake --install --prefix
# DIR`, a DESTDIR staging tree moved elsewhere and the .deb (packed under /usr
# whatever prefix was configured) all give a .pc that names their own files.
# Only an absolute CMAKE_INSTALL_LIBDIR/INCLUDEDIR stays absolute.
if(IS_ABSOLUTE "${CMAKE_INSTALL_LIBDIR}")
  set(FC_PC_PREFIX "${CMAKE_INSTALL_PREFIX}")
else()
  file(RELATIVE_PATH pc_to_prefix "/prefix/${CMAKE_INSTALL_LIBDIR}/pkgconfig" "/prefix")
  string(REGEX REPLACE "/$" "" pc_to_prefix "${pc_to_prefix}")
  set(FC_PC_PREFIX "\${pcfiledir}/${pc_to_prefix}")
endif()
foreach(dir LIBDIR INCLUDEDIR)
  if(IS_ABSOLUTE "${CMAKE_INSTALL_${dir}}")
    set(FC_PC_${dir} "${CMAKE_INSTALL_${dir}}")
  else()
    set(FC_PC_${dir} "\${prefix}/${CMAKE_INSTALL_${dir}}")
  endif()
endforeach()
configure_file(${CMAKE_CURRENT_LIST_DIR}/fluidcast.pc.in ${CMAKE_BINARY_DIR}/fluidcast.pc @ONLY)
install(FILES ${CMAKE_BINARY_DIR}/fluidcast.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)

# CMake: find_package(fluidcast) -> fluidcast::fluidcast, fluidcast::fluidcast_static
install(EXPORT fluidcastTargets NAMESPACE fluidcast:: DESTINATION ${FLUIDCAST_CMAKE_DIR})
configure_package_config_file(${CMAKE_CURRENT_LIST_DIR}/fluidcastConfig.cmake.in
  ${CMAKE_BINARY_DIR}/fluidcastConfig.cmake
  INSTALL_DESTINATION ${FLUIDCAST_CMAKE_DIR}
  PATH_VARS CMAKE_INSTALL_INCLUDEDIR)
write_basic_package_version_file(${CMAKE_BINARY_DIR}/fluidcastConfigVersion.cmake
  COMPATIBILITY SameMajorVersion)
install(FILES ${CMAKE_BINARY_DIR}/fluidcastConfig.cmake ${CMAKE_BINARY_DIR}/fluidcastConfigVersion.cmake
  DESTINATION ${FLUIDCAST_CMAKE_DIR})

# The SpaceMouse rule (TAG+="uaccess"): udev applies it on the next plug-in.
install(FILES ${PROJECT_SOURCE_DIR}/deploy/udev/70-fluidcast-spacemouse.rules
  DESTINATION ${FLUIDCAST_UDEV_RULES_DIR})

# The systemd units (deploy/systemd), their ExecStart pointed at where
# fluidcastd is installed (the files say /usr/bin/fluidcastd, Debian's place).
# Written at install time (fluidcast_install_units.cmake), under the prefix of
# that install: `cmake --install --prefix DIR` and the .deb (/usr) get their own.
set(FLUIDCAST_SYSTEMD_UNIT_DIR lib/systemd/system CACHE STRING
    "where the systemd units are installed, relative to the prefix (systemd reads /usr/lib/systemd/system)")
set(unit_sources "")
foreach(unit fluidcastd.service fluidcastd.socket fluidcastd@.service)
  list(APPEND unit_sources ${PROJECT_SOURCE_DIR}/deploy/systemd/${unit})
endforeach()
install(CODE "
  set(FC_UNIT_SOURCES \"${unit_sources}\")
  set(FC_UNIT_DIR \"${FLUIDCAST_SYSTEMD_UNIT_DIR}\")
  set(FC_UNIT_BINDIR \"${CMAKE_INSTALL_BINDIR}\")
  include(\"${CMAKE_CURRENT_LIST_DIR}/fluidcast_install_units.cmake\")")

# The Python package, once python/fluidcast exists (reconfigure to pick it up).
if(EXISTS ${PROJECT_SOURCE_DIR}/python/fluidcast/__init__.py)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/python/fluidcast DESTINATION ${FLUIDCAST_PYTHON_DIR}
    PATTERN "__pycache__" EXCLUDE PATTERN "*.pyc" EXCLUDE PATTERN "tests" EXCLUDE)
endif()
