# cmake/InstallPublicHeaders.cmake: run by `cmake --install` (cmake/FrontierInstall.cmake). Copies
# FRONTIER_PUBLIC_HEADERS (paths relative to FRONTIER_SOURCE_DIR) and, recursively, every header
# of the project they include ("folder/name.h"; <...> includes are other packages') to
# CMAKE_INSTALL_PREFIX/FRONTIER_INSTALL_INCLUDEDIR, keeping the folders.
cmake_policy(VERSION 3.20) # include() scopes it to this file
set(_fh_pending ${FRONTIER_PUBLIC_HEADERS})
set(_fh_found "")
while(_fh_pending)
  list(POP_FRONT _fh_pending _fh_header)
  if(_fh_header IN_LIST _fh_found)
    continue()
  endif()
  if(NOT EXISTS "${FRONTIER_SOURCE_DIR}/${_fh_header}")
    message(FATAL_ERROR "a public header includes \"${_fh_header}\", which is not in ${FRONTIER_SOURCE_DIR}")
  endif()
  list(APPEND _fh_found ${_fh_header})
  file(STRINGS "${FRONTIER_SOURCE_DIR}/${_fh_header}" _fh_includes REGEX "^[ \t]*#[ \t]*include[ \t]*\"")
  foreach(_fh_line IN LISTS _fh_includes)
    string(REGEX REPLACE "^[ \t]*#[ \t]*include[ \t]*\"([^\"]+)\".*$" "\\1" _fh_included "${_fh_line}")
    list(APPEND _fh_pending ${_fh_included})
  endforeach()
endwhile()
list(SORT _fh_found)
foreach(_fh_header IN LISTS _fh_found)
  get_filename_component(_fh_folder "${_fh_header}" DIRECTORY)
  file(INSTALL DESTINATION "${CMAKE_INSTALL_PREFIX}/${FRONTIER_INSTALL_INCLUDEDIR}/${_fh_folder}"
    TYPE FILE FILES "${FRONTIER_SOURCE_DIR}/${_fh_header}")
endforeach()
