# The installed package as a host sees it: installs the build into a fresh prefix, builds
# examples/minimal_host against that prefix alone (find_package(raybudget)), runs it with
# validation (it rasterises its own G-buffer and has raybudget record the frame into its
# command buffer), and checks its image against `raybudget render`'s for the same scene and
# settings.
file(REMOVE_RECURSE ${WORK})
function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err WORKING_DIRECTORY ${cwd})
  message("${out}${err}")
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}): ${ARGN}")
  endif()
endfunction()
set(cwd ${BINARY_DIR})
run(${CMAKE_COMMAND} --install ${BINARY_DIR} --prefix ${WORK}/prefix)
foreach(forbidden src vk passes select bvh)
  if(EXISTS ${WORK}/prefix/include/${forbidden})
    message(FATAL_ERROR "the package installs internal headers: include/${forbidden}")
  endif()
endforeach()
run(${CMAKE_COMMAND} -S ${SOURCE_DIR}/examples/minimal_host -B ${WORK}/host-build -G Ninja -DCMAKE_BUILD_TYPE=Release
    -DCMAKE_PREFIX_PATH=${WORK}/prefix -DCMAKE_CXX_COMPILER_LAUNCHER=${LAUNCHER})
run(${CMAKE_COMMAND} --build ${WORK}/host-build)
file(MAKE_DIRECTORY ${WORK}/run)
set(cwd ${WORK}/run)
run(${WORK}/host-build/minimal_host ${SCENE} --validation)
run(${RAYBUDGET} render ${SCENE} --policy all --frames 1 --width 320 --height 180 --out ${WORK}/cli)
# Identical on lavapipe; another driver may round the host's CPU-transformed vertices and our
# GPU-transformed ones differently, so a few pixels may differ slightly.
if(EXISTS ${PYTHON})
  run(${PYTHON} ${SOURCE_DIR}/tests/compare_images.py ${WORK}/run/minimal_host.png ${WORK}/cli/frame.png 8 0.005)
else()
  execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${WORK}/run/minimal_host.png ${WORK}/cli/frame.png RESULT_VARIABLE same)
  if(NOT same EQUAL 0)
    message(FATAL_ERROR "minimal_host.png differs from raybudget render's frame.png")
  endif()
  message("minimal_host.png equals raybudget render's frame.png")
endif()
