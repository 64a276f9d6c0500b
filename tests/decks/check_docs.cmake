# Fails when docs/styles.md differs from `slender --markdown-styles`.
execute_process(COMMAND "${SLENDER}" --markdown-styles OUTPUT_VARIABLE now RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "slender --markdown-styles failed")
endif()
file(READ "${DOC}" committed)
if(NOT now STREQUAL committed)
  message(FATAL_ERROR "docs/styles.md is stale: run  build/slender --markdown-styles > docs/styles.md")
endif()
