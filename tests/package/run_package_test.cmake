# Installs the already-built project into a scratch prefix, then configures, builds and runs a
# small consumer that finds it with find_package(inbetween).  Fails on any step's failure.
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")
function(run_step)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "step failed (${rc}): ${ARGN}\n${out}\n${err}")
  endif()
  set(step_output "${out}" PARENT_SCOPE)
endfunction()
run_step(${CMAKE_COMMAND} --install "${BINARY_DIR}" --prefix "${WORK_DIR}/prefix")
run_step(${CMAKE_COMMAND} -S "${SOURCE_DIR}/tests/package/consumer" -B "${WORK_DIR}/build"
         -DCMAKE_PREFIX_PATH=${WORK_DIR}/prefix -DCMAKE_BUILD_TYPE=Release
         # The consumer is built with the same flags as the installed archives (sanitizers included).
         "-DCMAKE_CXX_FLAGS=${CONSUMER_CXX_FLAGS}"
         # and the same compiler (the asan preset's archives are clang's, with its sanitizer runtime).
         "-DCMAKE_CXX_COMPILER=${CONSUMER_CXX_COMPILER}")
run_step(${CMAKE_COMMAND} --build "${WORK_DIR}/build")
run_step("${WORK_DIR}/build/consumer")
if(NOT step_output MATCHES "consumer ok")
  message(FATAL_ERROR "consumer printed: ${step_output}")
endif()
message(STATUS "installed package consumed: ${step_output}")
# The Python module, when it was built and installed: importable from the installed folder alone.
set(python_package "${WORK_DIR}/prefix/lib/python3/dist-packages")
if(EXISTS "${python_package}/inbetween/__init__.py" AND EXISTS /usr/bin/python3)
  run_step(${CMAKE_COMMAND} -E env "PYTHONPATH=${python_package}" /usr/bin/python3 -c
           "import inbetween\nassert len(inbetween.euler_sequences()) == 24\nprint('python ok')")
  message(STATUS "installed Python module imported: ${step_output}")
endif()
