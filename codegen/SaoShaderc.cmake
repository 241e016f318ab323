# sao_generate_effect(<target> EFFECT <entry.glsl> NAME <stem>)
# Runs sao-shaderc at build time and makes <target>, a static library holding the generated
# C++ glue and the embedded GLSL/SPIR-V blobs. Editing any included GLSL file rebuilds (depfile).
function(sao_generate_effect target)
  cmake_parse_arguments(ARG "" "EFFECT;NAME" "" ${ARGN})
  set(out_dir ${CMAKE_CURRENT_BINARY_DIR}/${target})
  set(header ${out_dir}/${ARG_NAME}_effect.h)
  set(source ${out_dir}/${ARG_NAME}_effect.cpp)
  add_custom_command(
    OUTPUT ${header} ${source}
    COMMAND sao-shaderc ${ARG_EFFECT} -o ${out_dir} --depfile ${out_dir}/${ARG_NAME}.d
    DEPENDS sao-shaderc ${ARG_EFFECT}
    DEPFILE ${out_dir}/${ARG_NAME}.d
    COMMENT "sao-shaderc: generating shaders and glue for ${ARG_EFFECT}"
    VERBATIM)
  add_library(${target} STATIC ${source} ${header})
  target_include_directories(${target} PUBLIC $<BUILD_INTERFACE:${out_dir}>)
  target_compile_features(${target} PUBLIC cxx_std_20)
endfunction()
