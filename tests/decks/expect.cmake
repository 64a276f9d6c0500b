# Runs one deck and checks its exit code and output.
#   -DSLENDER=path -DDECK=path -DWORKDIR=dir -DEXPECT_RC=n [-DEXPECT_REGEX=re]
#   [-DARGS="-v;a=1"] [-DNO_NAN_FILES="f1;f2"]
#   [-DRESUME_ARGS="-v;resume=1"]: run the deck a second time in the same folder (an
#     interrupted run continued); the exit code and regex then apply to that run
#   [-DEXPECT_ROWS="file;n"]: the file has a header line and n data lines
file(REMOVE_RECURSE "${WORKDIR}")
file(MAKE_DIRECTORY "${WORKDIR}")
execute_process(COMMAND "${SLENDER}" "${DECK}" ${ARGS}
                WORKING_DIRECTORY "${WORKDIR}"
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${out}${err}")
if(DEFINED RESUME_ARGS AND NOT "${RESUME_ARGS}" STREQUAL "")
  if(NOT "${rc}" STREQUAL "0")
    message(FATAL_ERROR "the run to be resumed ended with exit code ${rc}")
  endif()
  execute_process(COMMAND "${SLENDER}" "${DECK}" ${RESUME_ARGS}
                  WORKING_DIRECTORY "${WORKDIR}"
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  message("resumed:\n${out}${err}")
endif()
if(NOT "${rc}" STREQUAL "${EXPECT_RC}")
  message(FATAL_ERROR "exit code ${rc}, expected ${EXPECT_RC}")
endif()
if(DEFINED EXPECT_REGEX AND NOT "${out}${err}" MATCHES "${EXPECT_REGEX}")
  message(FATAL_ERROR "output does not match: ${EXPECT_REGEX}")
endif()
foreach(f IN LISTS NO_NAN_FILES)
  if(NOT EXISTS "${WORKDIR}/${f}")
    message(FATAL_ERROR "expected output file ${f} is missing")
  endif()
  file(READ "${WORKDIR}/${f}" content)
  string(TOLOWER "${content}" content)
  if(content MATCHES "nan|inf")
    message(FATAL_ERROR "${f} contains nan or inf")
  endif()
endforeach()
if(DEFINED EXPECT_ROWS AND NOT "${EXPECT_ROWS}" STREQUAL "")
  list(GET EXPECT_ROWS 0 rows_file)
  list(GET EXPECT_ROWS 1 rows_n)
  file(STRINGS "${WORKDIR}/${rows_file}" lines)
  list(LENGTH lines n)
  math(EXPR n "${n} - 1")
  if(NOT n EQUAL rows_n)
    message(FATAL_ERROR "${rows_file} has ${n} data lines, expected ${rows_n}")
  endif()
endif()
