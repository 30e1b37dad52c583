# Find SuiteSparse (Debian 12 ships 5.12 without a CMake package configuration).
# Provides SuiteSparse::SuiteSparse (CHOLMOD, UMFPACK, AMD, COLAMD, CAMD, CCOLAMD, config).
find_path(SuiteSparse_INCLUDE_DIR cholmod.h PATH_SUFFIXES suitesparse)
set(_ss_components umfpack cholmod amd colamd camd ccolamd suitesparseconfig)
set(SuiteSparse_LIBRARIES "")
foreach(_c IN LISTS _ss_components)
  find_library(SuiteSparse_${_c}_LIBRARY NAMES ${_c})
  mark_as_advanced(SuiteSparse_${_c}_LIBRARY)
  if(SuiteSparse_${_c}_LIBRARY)
    list(APPEND SuiteSparse_LIBRARIES ${SuiteSparse_${_c}_LIBRARY})
  else()
    set(SuiteSparse_${_c}_LIBRARY_MISSING TRUE)
  endif()
endforeach()

include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(SuiteSparse
  REQUIRED_VARS SuiteSparse_INCLUDE_DIR SuiteSparse_cholmod_LIBRARY SuiteSparse_umfpack_LIBRARY
                SuiteSparse_suitesparseconfig_LIBRARY)

if(SuiteSparse_FOUND AND NOT TARGET SuiteSparse::SuiteSparse)
  add_library(SuiteSparse::SuiteSparse INTERFACE IMPORTED)
  set_target_properties(SuiteSparse::SuiteSparse PROPERTIES
    INTERFACE_INCLUDE_DIRECTORIES "${SuiteSparse_INCLUDE_DIR}"
    INTERFACE_LINK_LIBRARIES "${SuiteSparse_LIBRARIES}")
endif()
mark_as_advanced(SuiteSparse_INCLUDE_DIR)
