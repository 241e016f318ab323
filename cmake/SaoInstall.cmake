# `cmake --install` gives a config package: find_package(sao CONFIG) defines sao::core (static, with
# the generated effect sao::effect), sao::gl and sao::vulkan (shared, when built) — the same names
# as the in-tree aliases, so a project builds unchanged against the source tree or the package.
#
#   <prefix>/include/sao/*.h, sao/gl/effect.h, sao/vulkan/effect.h, sao_effect.h (generated)
#   <prefix>/lib/libsao_core.a, libsao_effect.a, libsao_gl.so*, libsao_vulkan.so*
#   <prefix>/lib/cmake/sao/saoConfig.cmake, saoConfigVersion.cmake, saoTargets*.cmake
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

# The version lives twice: project(VERSION) for the package and sao/version.h for the code, whose
# SAO_VERSION create() compares with the library's. They must agree.
file(STRINGS ${PROJECT_SOURCE_DIR}/backends/core/include/sao/version.h sao_version_lines
     REGEX "^#define SAO_VERSION_(MAJOR|MINOR|PATCH) ")
foreach(part MAJOR MINOR PATCH)
  string(REGEX MATCH "SAO_VERSION_${part} ([0-9]+)" _ "${sao_version_lines}")
  if(NOT CMAKE_MATCH_1 STREQUAL PROJECT_VERSION_${part})
    message(FATAL_ERROR "sao/version.h says SAO_VERSION_${part} ${CMAKE_MATCH_1}, project() says "
                        "${PROJECT_VERSION_${part}}: keep them equal")
  endif()
endforeach()

set(sao_install_cmakedir ${CMAKE_INSTALL_LIBDIR}/cmake/sao)
set(sao_export_targets sao_core sao_effect)
set_target_properties(sao_core PROPERTIES EXPORT_NAME core)
set_target_properties(sao_effect PROPERTIES EXPORT_NAME effect)
target_include_directories(sao_core PUBLIC $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
target_include_directories(sao_effect PUBLIC $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/backends/core/include/sao DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
        FILES_MATCHING PATTERN "*.h")
install(FILES ${PROJECT_BINARY_DIR}/effect/sao_effect/sao_effect.h DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})

set(sao_package_has_gl OFF)
if(TARGET sao_gl)
  set(sao_package_has_gl ON)
  list(APPEND sao_export_targets sao_gl)
  set_target_properties(sao_gl PROPERTIES EXPORT_NAME gl)
  target_include_directories(sao_gl PUBLIC $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  install(FILES ${PROJECT_SOURCE_DIR}/backends/gl/include/sao/gl/effect.h
          DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/sao/gl)
endif()

set(sao_package_has_vulkan OFF)
if(TARGET sao_vulkan)
  set(sao_package_has_vulkan ON)
  list(APPEND sao_export_targets sao_vulkan)
  set_target_properties(sao_vulkan PROPERTIES EXPORT_NAME vulkan VERSION ${PROJECT_VERSION}
                                              SOVERSION ${PROJECT_VERSION_MAJOR})
  target_include_directories(sao_vulkan PUBLIC $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  install(FILES ${PROJECT_SOURCE_DIR}/backends/vulkan/include/sao/vulkan/effect.h
          DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/sao/vulkan)
endif()

install(TARGETS ${sao_export_targets} EXPORT saoTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
        RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(EXPORT saoTargets NAMESPACE sao:: DESTINATION ${sao_install_cmakedir})

configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/saoConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/saoConfig.cmake
                              INSTALL_DESTINATION ${sao_install_cmakedir})
# 0.x: a minor version may break the API (and the header/library check in create() says so).
write_basic_package_version_file(${PROJECT_BINARY_DIR}/saoConfigVersion.cmake
                                 VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/saoConfig.cmake ${PROJECT_BINARY_DIR}/saoConfigVersion.cmake
        DESTINATION ${sao_install_cmakedir})
