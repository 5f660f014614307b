# FindNifti2: libnifti2 (NIfTI-1 and -2 reading and writing) and its znz compression layer, as the
# imported target Nifti2::nifti2. Debian 12's own package config (NIFTIConfig.cmake) cannot be used:
# its NIFTI::znz points at /usr/lib/libznz.so.3.0.0, while the package installs the library under
# the multiarch directory (/usr/lib/x86_64-linux-gnu), so find_package(NIFTI CONFIG) fails.
find_path(Nifti2_INCLUDE_DIR nifti2_io.h PATH_SUFFIXES nifti)
find_library(Nifti2_LIBRARY nifti2)
find_library(Nifti2_ZNZ_LIBRARY znz)
include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(Nifti2 REQUIRED_VARS Nifti2_LIBRARY Nifti2_ZNZ_LIBRARY Nifti2_INCLUDE_DIR)
mark_as_advanced(Nifti2_INCLUDE_DIR Nifti2_LIBRARY Nifti2_ZNZ_LIBRARY)
if(Nifti2_FOUND AND NOT TARGET Nifti2::nifti2)
  add_library(Nifti2::znz UNKNOWN IMPORTED)
  set_target_properties(Nifti2::znz PROPERTIES IMPORTED_LOCATION "${Nifti2_ZNZ_LIBRARY}"
                                               INTERFACE_INCLUDE_DIRECTORIES "${Nifti2_INCLUDE_DIR}")
  add_library(Nifti2::nifti2 UNKNOWN IMPORTED)
  set_target_properties(Nifti2::nifti2 PROPERTIES IMPORTED_LOCATION "${Nifti2_LIBRARY}"
                                                  INTERFACE_INCLUDE_DIRECTORIES "${Nifti2_INCLUDE_DIR}"
                                                  INTERFACE_LINK_LIBRARIES "Nifti2::znz;ZLIB::ZLIB;m")
endif()
