# Run by `cmake --install` and cpack (an install(CODE) of fluidcast_install.cmake):
# writes the systemd units FC_UNIT_SOURCES into FC_UNIT_DIR with ExecStart at
# FC_UNIT_BINDIR/fluidcastd, both under CMAKE_INSTALL_PREFIX as this install
# has it (--prefix, cpack's /usr), not as configured. Relative dirs are under
# the prefix, absolute ones taken as they are; DESTDIR is honoured.
foreach(dir DIR BINDIR)
  if(IS_ABSOLUTE "${FC_UNIT_${dir}}")
    set(unit_full_${dir} "${FC_UNIT_${dir}}")
  else()
    set(unit_full_${dir} "${CMAKE_INSTALL_PREFIX}/${FC_UNIT_${dir}}")
  endif()
endforeach()
foreach(source IN LISTS FC_UNIT_SOURCES)
  get_filename_component(unit_name "${source}" NAME)
  file(READ "${source}" unit_text)
  string(REPLACE "/usr/bin/fluidcastd" "${unit_full_BINDIR}/fluidcastd" unit_text "${unit_text}")
  set(unit_path "${unit_full_DIR}/${unit_name}")
  message(STATUS "Installing: $ENV{DESTDIR}${unit_path}")
  file(WRITE "$ENV{DESTDIR}${unit_path}" "${unit_text}")
  list(APPEND CMAKE_INSTALL_MANIFEST_FILES "${unit_path}")
endforeach()
