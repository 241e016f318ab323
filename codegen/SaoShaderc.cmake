# sao_generate_effect(<target> EFFECT <entry.glsl> NAME <stem> [CPU_PASSES <header>] [SPIRV_FROM_HLSL 50|60])
# Runs sao-shaderc at build time and makes <target>, a static library holding the generated
# C++ glue and the embedded GLSL/SPIR-V blobs, and <target>_gles, the GLSL ES 3.10 blobs (for the
# GLES backend only). Editing any included GLSL file rebuilds (depfile). SPIRV_FROM_HLSL embeds the
# SPIR-V compiled back from that shader model's HLSL (the HLSL round trip's test). The tool is
# ${sao_shaderc_tool} (codegen/CMakeLists.txt: sao-shaderc, or SAO_HOST_SHADERC).
# CPU_PASSES names the header with the effect's C++ passes (it defines sao::cpu::runEffectPass,
# e.g. effect/cpu/passes.h): the target then carries SAO_CPU_PASSES_HEADER="<absolute path>" and
# the header's folder, which the CPU reference compiled against the effect includes. Build tree
# only: sao_cpu is not installed, and the package must not point into the source tree.
function(sao_generate_effect target)
  cmake_parse_arguments(ARG "" "EFFECT;NAME;CPU_PASSES;SPIRV_FROM_HLSL" "" ${ARGN})
  set(out_dir ${CMAKE_CURRENT_BINARY_DIR}/${target})
  set(header ${out_dir}/${ARG_NAME}_effect.h)
  set(source ${out_dir}/${ARG_NAME}_effect.cpp)
  set(gles_source ${out_dir}/${ARG_NAME}_effect_gles.cpp)
  set(extra)
  if(ARG_SPIRV_FROM_HLSL)
    set(extra --spirv-from-hlsl ${ARG_SPIRV_FROM_HLSL})
  endif()
  add_custom_command(
    OUTPUT ${header} ${source} ${gles_source}
    COMMAND ${sao_shaderc_tool} ${ARG_EFFECT} -o ${out_dir} --depfile ${out_dir}/${ARG_NAME}.d ${extra}
    DEPENDS ${sao_shaderc_tool} ${ARG_EFFECT}
    DEPFILE ${out_dir}/${ARG_NAME}.d
    COMMENT "sao-shaderc: generating shaders and glue for ${ARG_EFFECT}"
    VERBATIM)
  add_library(${target} STATIC ${source} ${header})
  target_include_directories(${target} PUBLIC $<BUILD_INTERFACE:${out_dir}>)
  target_compile_features(${target} PUBLIC cxx_std_20)
  add_library(${target}_gles STATIC ${gles_source})
  target_link_libraries(${target}_gles PUBLIC ${target})
  if(ARG_CPU_PASSES)
    get_filename_component(cpu_passes "${ARG_CPU_PASSES}" ABSOLUTE)
    if(NOT EXISTS "${cpu_passes}")
      message(FATAL_ERROR "sao_generate_effect(${target}): CPU_PASSES ${cpu_passes} does not exist")
    endif()
    get_filename_component(cpu_passes_dir "${cpu_passes}" DIRECTORY)
    target_compile_definitions(${target} PUBLIC "$<BUILD_INTERFACE:SAO_CPU_PASSES_HEADER=\"${cpu_passes}\">")
    target_include_directories(${target} PUBLIC $<BUILD_INTERFACE:${cpu_passes_dir}>)
  endif()
endfunction()
