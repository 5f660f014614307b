# cmake -DPROGRAM=soiqd -DOUTPUT=soiqd.8 -P usage_to_man.cmake: soiqd(8) from `soiqd --help`
# (server/app/server_config.cpp server_usage()), so the page says exactly what the program does:
# its paragraphs as the DESCRIPTION, each option as a tagged paragraph, the exit codes.
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
# The help's parts: "usage: ..." line, description paragraph, "Options:" block, exit codes.
string(FIND "${usage}" "\nOptions:\n" options_at)
string(FIND "${usage}" "\nExit codes:" exits_at)
if(options_at EQUAL -1 OR exits_at EQUAL -1)
  message(FATAL_ERROR "${PROGRAM} --help lacks its Options: or Exit codes: part")
endif()
string(SUBSTRING "${usage}" 0 ${options_at} head)
math(EXPR options_from "${options_at} + 10")
math(EXPR options_length "${exits_at} - ${options_from}")
string(SUBSTRING "${usage}" ${options_from} ${options_length} options)
string(SUBSTRING "${usage}" ${exits_at} -1 exits)
string(REGEX REPLACE "^usage: [^\n]*\n\n" "" description "${head}")
# An option line ("  --flag VALUE") starts a tagged paragraph; its indented lines are the text.
string(REGEX REPLACE "(^|\n)  (\\\\-[^\n]*)" "\\1.TP\n.B \\2" options "${options}")
string(REGEX REPLACE "\n      " "\n" options "${options}")
string(REPLACE "\ndefault: " "\n.br\ndefault: " options "${options}")
string(REPLACE "\nExit codes: " "" exits "${exits}")
file(WRITE ${OUTPUT}.part
  ".TH SOIQD 8 \"\" \"soiq\" \"System Administration\"\n"
  ".SH NAME\nsoiqd \\- the soiq server: stores structures and images, computes features, answers queries\n"
  ".SH SYNOPSIS\n.B soiqd\n[\\fIOPTION\\fR]...\n"
  ".SH DESCRIPTION\n${description}\n"
  ".SH OPTIONS\n${options}\n"
  ".SH EXIT STATUS\n${exits}"
  ".SH SEE ALSO\n\\fBsoiq\\fR(1)\n")
file(RENAME ${OUTPUT}.part ${OUTPUT})
