# Compiles each GLSL shader at build time into a C++ header holding its SPIR-V as a
# uint32_t array (glslangValidator --vn), so the engine carries its shaders and no
# runtime path can go stale. A shader error fails the build, and so does SPIR-V that
# spirv-val rejects (glslang 11 emits invalid SPIR-V for some constructs without a word,
# e.g. a ?: between a buffer's struct and a local one). Every shader depends on
# every include, so editing a shared header recompiles them all.
#
# TRACING sources are compiled a second time with RB_NATIVE_RAY_QUERY into
# kSpirv_<name>_native: the same shader on the device's VK_KHR_ray_query instead of our
# compute BVH (shaders/include/rayquery.glsl).
function(raybudget_add_shaders target)
  cmake_parse_arguments(ARG "" "" "SOURCES;TRACING;INCLUDES" ${ARGN})
  set(out_dir "${CMAKE_CURRENT_BINARY_DIR}/spirv")
  file(MAKE_DIRECTORY "${out_dir}")
  set(headers)
  set(variants)
  foreach(src IN LISTS ARG_SOURCES ARG_TRACING)
    list(APPEND variants "${src}|")
  endforeach()
  foreach(src IN LISTS ARG_TRACING)
    list(APPEND variants "${src}|native")
  endforeach()
  foreach(variant IN LISTS variants)
    string(REPLACE "|" ";" parts "${variant}|")
    list(GET parts 0 src)
    list(GET parts 1 suffix)
    get_filename_component(name "${src}" NAME)
    string(REPLACE "." "_" var "${name}")
    set(defines)
    if(suffix)
      set(var "${var}_${suffix}")
      set(defines -DRB_NATIVE_RAY_QUERY)
    endif()
    set(out "${out_dir}/${var}.h")
    set(glslang ${GLSLANG_VALIDATOR} -V --target-env vulkan1.3 --quiet ${defines} -I${CMAKE_CURRENT_SOURCE_DIR})
    add_custom_command(
      OUTPUT "${out}"
      COMMAND ${glslang} -o "${out_dir}/${var}.spv" "${CMAKE_CURRENT_SOURCE_DIR}/${src}"
      COMMAND ${SPIRV_VAL} --target-env vulkan1.3 "${out_dir}/${var}.spv"
      COMMAND ${glslang} --vn kSpirv_${var} -o "${out}" "${CMAKE_CURRENT_SOURCE_DIR}/${src}"
      DEPENDS "${CMAKE_CURRENT_SOURCE_DIR}/${src}" ${ARG_INCLUDES}
      COMMENT "glslang ${name} ${suffix}"
      VERBATIM)
    list(APPEND headers "${out}")
  endforeach()
  add_custom_target(${target}_spirv DEPENDS ${headers})
  add_library(${target} INTERFACE)
  target_include_directories(${target} INTERFACE "$<BUILD_INTERFACE:${out_dir}>")
  add_dependencies(${target} ${target}_spirv)
endfunction()
