# `cmake --install` gives a config package: find_package(sao CONFIG COMPONENTS ...) defines sao::core
# (static, with the generated effect sao::effect), sao::io (static, EXR/PNG files), sao::cpu (static,
# the CPU reference, to test an engine's own port against), sao::gl, sao::gles and sao::vulkan
# (shared, when built) — the same names as the in-tree aliases, so a project builds
# unchanged against the source tree or the package.
#
#   <prefix>/include/sao/*.h, sao/cpu/*.h, sao/gl/effect.h, sao/vulkan/effect.h, sao_effect.h (generated)
#   <prefix>/lib/libsao_core.a, libsao_effect.a, libsao_io.a, libsao_cpu.a, libsao_gl.so*, libsao_vulkan.so*
#   <prefix>/lib/cmake/sao/saoConfig.cmake, saoConfigVersion.cmake, sao_<component>_targets*.cmake
#   <prefix>/share/sao/shaders/: every compiled pass variant as GLSL 4.30, SPIR-V, HLSL (SM 5.0 and
#   6.0: .sm50.hlsl, .sm60.hlsl) and, where it exists there, GLSL ES 3.10 (.es310.glsl), and
#   sao_passes.json describing them and each target's layout (sao_SHADER_DIR), for an engine that
#   runs the passes itself
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

# One export set a component, so that saoConfig.cmake loads (and finds the dependencies of) only
# the components asked for: a GL-only consumer needs neither OpenEXR, stb nor Vulkan installed.
#   component  targets                exported name   dependencies the consumer must have
#   core       sao_core, sao_effect   sao::core       none
#   io         sao_io                 sao::io         OpenEXR (CONFIG), stb (pkg-config)
#   cpu        sao_cpu                sao::cpu        Threads
#   gl         sao_gl                 sao::gl         none (GL comes from the caller's loader)
#   gles       sao_gles               sao::gles       none (OpenGL ES 3.1, from the caller's loader)
#   vulkan     sao_vulkan             sao::vulkan     Vulkan (Vulkan::Headers)
set(sao_package_components core)
# What `cmake --install` needs built, and nothing else: `cmake --build build --target
# sao_installed_libraries` (CI's release stage builds it, not the samples and tests).
add_custom_target(sao_installed_libraries)
# sao_export_component(COMPONENT TARGET [TARGET...]): exports the targets as sao::<EXPORT_NAME>.
function(sao_export_component component)
  add_dependencies(sao_installed_libraries ${ARGN})
  foreach(target IN LISTS ARGN)
    target_include_directories(${target} PUBLIC $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  endforeach()
  install(TARGETS ${ARGN} EXPORT sao_${component}_targets
          ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
          LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
          RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
  install(EXPORT sao_${component}_targets NAMESPACE sao:: FILE sao_${component}_targets.cmake
          DESTINATION ${sao_install_cmakedir})
endfunction()

set_target_properties(sao_core PROPERTIES EXPORT_NAME core)
set_target_properties(sao_effect PROPERTIES EXPORT_NAME effect)
sao_export_component(core sao_core sao_effect)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/backends/core/include/sao DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
        FILES_MATCHING PATTERN "*.h")
install(FILES ${PROJECT_BINARY_DIR}/effect/sao_effect/sao_effect.h DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
set(sao_install_shaderdir ${CMAKE_INSTALL_DATADIR}/sao/shaders)
install(DIRECTORY ${PROJECT_BINARY_DIR}/effect/sao_effect/ DESTINATION ${sao_install_shaderdir}
        FILES_MATCHING PATTERN "*.glsl" PATTERN "*.spv" PATTERN "*.hlsl" PATTERN "sao_passes.json")

if(TARGET sao_io)
  list(APPEND sao_package_components io)
  set_target_properties(sao_io PROPERTIES EXPORT_NAME io)
  sao_export_component(io sao_io)
  install(FILES ${PROJECT_SOURCE_DIR}/backends/io/include/sao/io.h DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/sao)
endif()

# The CPU reference, the oracle an engine tests its own executor against (the effect's C++ passes are
# compiled into it: nothing of effect/cpu/ is installed).
if(TARGET sao_cpu)
  list(APPEND sao_package_components cpu)
  set_target_properties(sao_cpu PROPERTIES EXPORT_NAME cpu)
  sao_export_component(cpu sao_cpu)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/backends/cpu/include/sao/cpu DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/sao
          FILES_MATCHING PATTERN "*.h")
endif()

if(TARGET sao_gl)
  list(APPEND sao_package_components gl)
  set_target_properties(sao_gl PROPERTIES EXPORT_NAME gl)
  sao_export_component(gl sao_gl)
  install(FILES ${PROJECT_SOURCE_DIR}/backends/gl/include/sao/gl/effect.h
                ${PROJECT_SOURCE_DIR}/backends/gl/include/sao/gl/effect_common.h
                ${PROJECT_SOURCE_DIR}/backends/gl/include/sao/gl/effect_api.inl
          DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/sao/gl)
endif()

# The OpenGL ES 3.1 backend: the GL backend's API in namespace sao::gles (the same API header,
# included under that name) and the GLSL ES 3.10 blobs; a consumer may take it alone.
if(TARGET sao_gles)
  list(APPEND sao_package_components gles)
  set_target_properties(sao_gles PROPERTIES EXPORT_NAME gles)
  sao_export_component(gles sao_gles)
  install(FILES ${PROJECT_SOURCE_DIR}/backends/gl/include/sao/gl/effect_common.h
                ${PROJECT_SOURCE_DIR}/backends/gl/include/sao/gl/effect_api.inl
          DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/sao/gl)
  install(FILES ${PROJECT_SOURCE_DIR}/backends/gl/include/sao/gles/effect.h
          DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/sao/gles)
endif()

if(TARGET sao_vulkan)
  list(APPEND sao_package_components vulkan)
  set_target_properties(sao_vulkan PROPERTIES EXPORT_NAME vulkan VERSION ${PROJECT_VERSION}
                                              SOVERSION ${PROJECT_VERSION_MAJOR})
  sao_export_component(vulkan sao_vulkan)
  install(FILES ${PROJECT_SOURCE_DIR}/backends/vulkan/include/sao/vulkan/effect.h
          DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/sao/vulkan)
endif()

configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/saoConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/saoConfig.cmake
                              INSTALL_DESTINATION ${sao_install_cmakedir}
                              PATH_VARS sao_install_shaderdir)
# 0.x: a minor version may break the API (and the header/library check in create() says so).
write_basic_package_version_file(${PROJECT_BINARY_DIR}/saoConfigVersion.cmake
                                 VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/saoConfig.cmake ${PROJECT_BINARY_DIR}/saoConfigVersion.cmake
        DESTINATION ${sao_install_cmakedir})
