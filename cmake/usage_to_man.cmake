# cmake -DPROGRAM=soiqd -DOUTPUT=soiqd.8 -P usage_to_man.cmake: soiqd(8) from `soiqd --help`
# (server/app/server_config.cpp server_usage()), its text kept as written (.nf), so the page says
# exactly what the program does.
get_filename_component(folder ${OUTPUT} DIRECTORY)
file(MAKE_DIRECTORY ${folder})
execute_process(COMMAND ${PROGRAM} --help OUTPUT_VARIABLE usage RESULT_VARIABLE status)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "${PROGRAM} --help exited ${status}")
endif()
# roff: a backslash is \e, a hyphen \- (searchable options), a line starting with . or ' is text.
string(REPLACE "\\" "\\e" usage "${usage}")
string(REPLACE "-" "\\-" usage "${usage}")
string(REGEX REPLACE "(^|\n)([.'])" "\\1\\\\&\\2" usage "${usage}")
file(WRITE ${OUTPUT}.part
  ".TH SOIQD 8 \"\" \"soiq\" \"System Administration\"\n"
  ".SH NAME\nsoiqd \\- the soiq server: stores structures and images, computes features, answers queries\n"
  ".SH SYNOPSIS\n.B soiqd\n[\\fIOPTION\\fR]...\n"
  ".SH DESCRIPTION\n"
  "\\fBsoiqd\\fR serves the soiq gRPC API (package soiq.v1) and the standard health service; "
  "\\fBsoiq\\fR(1) is its client.\n"
  ".SH OPTIONS\n.nf\n${usage}.fi\n"
  ".SH SEE ALSO\n\\fBsoiq\\fR(1)\n")
file(RENAME ${OUTPUT}.part ${OUTPUT})
