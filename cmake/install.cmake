# `cmake --install BUILD [--prefix P]`: the programs soiq and soiqd, and the C++ client library as a
# CMake package, so another project can write
#
#   find_package(soiq REQUIRED)
#   target_link_libraries(app PRIVATE soiq::client)
#
# The client library is three static archives (soiq_client, soiq_proto: the generated API,
# soiq_core_base: soiq's Status and Result) with the headers they need, under include/soiq with the
# paths the sources use ("client/soiq_client.h", "soiq/v1/soiq.grpc.pb.h", "core/base/status.h").
include(CMakePackageConfigHelpers)

install(TARGETS soiq soiqd soiq-admin RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})

# soiq_warnings only rides along: static archives list their private link dependencies.
install(TARGETS soiq_client soiq_proto soiq_core_base soiq_warnings
        EXPORT soiqTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
set_target_properties(soiq_client PROPERTIES EXPORT_NAME client)
add_library(soiq::client ALIAS soiq_client)

set(SOIQ_INCLUDE_DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/soiq)
install(FILES client/soiq_client.h client/retry.h DESTINATION ${SOIQ_INCLUDE_DESTINATION}/client)
install(FILES core/base/status.h DESTINATION ${SOIQ_INCLUDE_DESTINATION}/core/base)
install(DIRECTORY ${PROJECT_BINARY_DIR}/proto/gen/ DESTINATION ${SOIQ_INCLUDE_DESTINATION}
        FILES_MATCHING PATTERN "*.pb.h")

set(SOIQ_CMAKE_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/soiq)
install(EXPORT soiqTargets NAMESPACE soiq:: DESTINATION ${SOIQ_CMAKE_DESTINATION})
configure_package_config_file(cmake/soiqConfig.cmake.in ${PROJECT_BINARY_DIR}/soiqConfig.cmake
                              INSTALL_DESTINATION ${SOIQ_CMAKE_DESTINATION})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/soiqConfigVersion.cmake COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/soiqConfig.cmake ${PROJECT_BINARY_DIR}/soiqConfigVersion.cmake
        DESTINATION ${SOIQ_CMAKE_DESTINATION})
