# cmake -DPROGRAM=P -DARGUMENTS="a;b" -DOUTPUT=F -P program_output.cmake: F is what `P a b` prints
# on stdout; the build fails when P exits non-zero, so nothing half-written is installed.
get_filename_component(folder ${OUTPUT} DIRECTORY)
file(MAKE_DIRECTORY ${folder})
execute_process(COMMAND ${PROGRAM} ${ARGUMENTS} OUTPUT_FILE ${OUTPUT}.part RESULT_VARIABLE status)
if(NOT status EQUAL 0)
  file(REMOVE ${OUTPUT}.part)
  message(FATAL_ERROR "${PROGRAM} ${ARGUMENTS} exited ${status}")
endif()
file(RENAME ${OUTPUT}.part ${OUTPUT})
