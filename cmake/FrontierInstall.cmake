# cmake/FrontierInstall.cmake: `cmake --install build --prefix P` (docs/library.md).
#
#   P/bin/frontier                      the command-line program
#   P/lib/libfrontier_{core,collision,io,render,run}.a (or .so with -DBUILD_SHARED_LIBS=ON)
#   P/include/frontier/<folder>/*.h     the public headers and every project header they include
#   P/lib/cmake/Frontier/               FrontierConfig.cmake, FrontierConfigVersion.cmake and the
#                                       exported targets Frontier::frontier (all five libraries),
#                                       Frontier::core, Frontier::collision, Frontier::io,
#                                       Frontier::render, Frontier::run
#
# The include directory of the installed targets is P/include/frontier, so a program spells the
# headers as the project does ("core/simulator.h").
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(FRONTIER_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/Frontier)
set(FRONTIER_INSTALL_INCLUDEDIR ${CMAKE_INSTALL_INCLUDEDIR}/frontier)

# The headers a program includes. Installing copies them with every header of the project they
# include, followed at install time (cmake/InstallPublicHeaders.cmake), so an installed header never
# includes one that was not installed.
set(FRONTIER_PUBLIC_HEADERS
  core/model.h
  core/state.h
  core/simulator.h
  core/time_function.h
  core/contact.h
  collision/contacts.h
  io/scene.h
  io/trajectory.h
  io/atomic_file.h
  render/renderer.h
  run/scene_loading.h
  run/simulation.h
  run/names.h)

# Frontier::frontier: the five libraries together (the `frontier` executable's name is taken in
# this tree, hence frontier_library).
add_library(frontier_library INTERFACE)
set_target_properties(frontier_library PROPERTIES EXPORT_NAME frontier)
target_link_libraries(frontier_library INTERFACE frontier_core frontier_collision frontier_io frontier_render
  frontier_run)
foreach(part core collision io render run)
  set_target_properties(frontier_${part} PROPERTIES EXPORT_NAME ${part})
endforeach()
# The public headers are C++20 (std::span).
target_compile_features(frontier_core INTERFACE cxx_std_20)
if(FRONTIER_SANITIZE)
  # Objects built with -fsanitize need the sanitizers' runtime wherever they are linked.
  target_link_options(frontier_core INTERFACE -fsanitize=address,undefined)
endif()

install(TARGETS frontier RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(TARGETS frontier_core frontier_collision frontier_io frontier_render frontier_run frontier_library
  EXPORT FrontierTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
  RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR}
  INCLUDES DESTINATION ${FRONTIER_INSTALL_INCLUDEDIR})
install(CODE "
  set(FRONTIER_SOURCE_DIR \"${PROJECT_SOURCE_DIR}\")
  set(FRONTIER_PUBLIC_HEADERS \"${FRONTIER_PUBLIC_HEADERS}\")
  set(FRONTIER_INSTALL_INCLUDEDIR \"${FRONTIER_INSTALL_INCLUDEDIR}\")")
install(SCRIPT ${PROJECT_SOURCE_DIR}/cmake/InstallPublicHeaders.cmake)

install(EXPORT FrontierTargets NAMESPACE Frontier:: DESTINATION ${FRONTIER_INSTALL_CMAKEDIR})
# Static libraries carry their private dependencies into every program that links them, so the
# package config must find those too; shared ones need only Eigen (in the public headers).
get_target_property(FRONTIER_LIBRARY_TYPE frontier_core TYPE)
if(FRONTIER_LIBRARY_TYPE STREQUAL "STATIC_LIBRARY")
  set(FRONTIER_STATIC_LIBRARIES ON)
else()
  set(FRONTIER_STATIC_LIBRARIES OFF)
endif()
if(sdformat12_FOUND)
  set(FRONTIER_WITH_SDFORMAT ON)
else()
  set(FRONTIER_WITH_SDFORMAT OFF)
endif()
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/FrontierConfig.cmake.in
  ${PROJECT_BINARY_DIR}/FrontierConfig.cmake
  INSTALL_DESTINATION ${FRONTIER_INSTALL_CMAKEDIR}
  NO_SET_AND_CHECK_MACRO NO_CHECK_REQUIRED_COMPONENTS_MACRO)
# 0.x: a minor version may change the API.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/FrontierConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/FrontierConfig.cmake ${PROJECT_BINARY_DIR}/FrontierConfigVersion.cmake
  DESTINATION ${FRONTIER_INSTALL_CMAKEDIR})
