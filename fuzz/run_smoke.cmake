# The ctest smoke run of one fuzz target: a fixed number of executions from its seed corpus, with a
# fixed random seed so the run is the same every time.  New inputs land in WORK_DIR (cleared first).
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}/corpus" "${WORK_DIR}/artifacts")
execute_process(COMMAND "${FUZZER}" -runs=${RUNS} -seed=1 -timeout=60 -rss_limit_mb=2048 -dict=${DICT}
                        -artifact_prefix=${WORK_DIR}/artifacts/ "${WORK_DIR}/corpus" "${SEEDS}"
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
string(REGEX MATCH "Done [0-9]+ runs in [0-9]+ second" done "${err}")
if(NOT rc EQUAL 0)
  string(LENGTH "${err}" n)
  if(n GREATER 6000)
    math(EXPR from "${n} - 6000")
    string(SUBSTRING "${err}" ${from} -1 err)
  endif()
  message(FATAL_ERROR "fuzz target failed (${rc}); the input is in ${WORK_DIR}/artifacts/\n…${err}")
endif()
message(STATUS "${done}")
