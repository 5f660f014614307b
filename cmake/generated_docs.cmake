# What the build makes from the programs themselves, so that it cannot drift from them: soiq's bash
# completion and man page from its command table (`soiq completion bash`, `soiq man`), and soiqd's
# man page from `soiqd --help`. Written to ${PROJECT_BINARY_DIR}/completion and /man after the
# programs are built, and installed to share/bash-completion/completions and share/man/man1, man8.
set(SOIQ_COMPLETION ${PROJECT_BINARY_DIR}/completion/soiq)
set(SOIQ_MAN1 ${PROJECT_BINARY_DIR}/man/soiq.1)
set(SOIQD_MAN8 ${PROJECT_BINARY_DIR}/man/soiqd.8)
add_custom_command(
  OUTPUT ${SOIQ_COMPLETION} ${SOIQ_MAN1}
  COMMAND ${CMAKE_COMMAND} -DPROGRAM=$<TARGET_FILE:soiq> -DARGUMENTS=completion\;bash -DOUTPUT=${SOIQ_COMPLETION}
          -P ${PROJECT_SOURCE_DIR}/cmake/program_output.cmake
  COMMAND ${CMAKE_COMMAND} -DPROGRAM=$<TARGET_FILE:soiq> -DARGUMENTS=man -DOUTPUT=${SOIQ_MAN1}
          -P ${PROJECT_SOURCE_DIR}/cmake/program_output.cmake
  DEPENDS soiq ${PROJECT_SOURCE_DIR}/cmake/program_output.cmake
  COMMENT "soiq: bash completion and soiq(1) from the command table"
  VERBATIM)
add_custom_command(
  OUTPUT ${SOIQD_MAN8}
  COMMAND ${CMAKE_COMMAND} -DPROGRAM=$<TARGET_FILE:soiqd> -DOUTPUT=${SOIQD_MAN8}
          -P ${PROJECT_SOURCE_DIR}/cmake/usage_to_man.cmake
  DEPENDS soiqd ${PROJECT_SOURCE_DIR}/cmake/usage_to_man.cmake
  COMMENT "soiqd: soiqd(8) from soiqd --help"
  VERBATIM)
add_custom_target(soiq_generated_docs ALL DEPENDS ${SOIQ_COMPLETION} ${SOIQ_MAN1} ${SOIQD_MAN8})

install(FILES ${SOIQ_COMPLETION} DESTINATION ${CMAKE_INSTALL_DATADIR}/bash-completion/completions)
install(FILES ${SOIQ_MAN1} DESTINATION ${CMAKE_INSTALL_MANDIR}/man1)
install(FILES ${SOIQD_MAN8} DESTINATION ${CMAKE_INSTALL_MANDIR}/man8)
