# Runs one deck and checks its exit code and output.
#   -DSLENDER=path -DDECK=path -DWORKDIR=dir -DEXPECT_RC=n [-DEXPECT_REGEX=re]
#   [-DARGS="-v;a=1"] [-DNO_NAN_FILES="f1;f2"]
file(REMOVE_RECURSE "${WORKDIR}")
file(MAKE_DIRECTORY "${WORKDIR}")
execute_process(COMMAND "${SLENDER}" "${DECK}" ${ARGS}
                WORKING_DIRECTORY "${WORKDIR}"
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${out}${err}")
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
