# SPDX-License-Identifier: BSD-3-Clause
# Imported targets camfollower::klu and camfollower::cholmod for SuiteSparse's KLU and CHOLMOD (the
# sparse backend, solver/sparse_newton.hpp), and camfollower::spectra's include path. SuiteSparse 7
# ships CMake packages (SuiteSparse::KLU, SuiteSparse::CHOLMOD); older ones (Debian 12's 5.12) only
# headers and libraries, found here by name.
include_guard(GLOBAL)

find_package(KLU CONFIG QUIET)
find_package(CHOLMOD CONFIG QUIET)
if(TARGET SuiteSparse::KLU AND TARGET SuiteSparse::CHOLMOD)
  add_library(camfollower::klu INTERFACE IMPORTED)
  target_link_libraries(camfollower::klu INTERFACE SuiteSparse::KLU)
  add_library(camfollower::cholmod INTERFACE IMPORTED)
  target_link_libraries(camfollower::cholmod INTERFACE SuiteSparse::CHOLMOD)
else()
  find_path(CAMFOLLOWER_SUITESPARSE_INCLUDE_DIR klu.h PATH_SUFFIXES suitesparse)
  foreach(lib klu btf amd colamd cholmod suitesparseconfig)
    find_library(CAMFOLLOWER_SUITESPARSE_${lib} NAMES ${lib})
    if(NOT CAMFOLLOWER_SUITESPARSE_${lib} OR NOT CAMFOLLOWER_SUITESPARSE_INCLUDE_DIR)
      message(FATAL_ERROR "SuiteSparse (${lib}) not found: install it (Debian/Ubuntu: libsuitesparse-dev)")
    endif()
  endforeach()
  add_library(camfollower::klu INTERFACE IMPORTED)
  target_include_directories(camfollower::klu INTERFACE ${CAMFOLLOWER_SUITESPARSE_INCLUDE_DIR})
  target_link_libraries(camfollower::klu INTERFACE ${CAMFOLLOWER_SUITESPARSE_klu} ${CAMFOLLOWER_SUITESPARSE_btf}
                        ${CAMFOLLOWER_SUITESPARSE_amd} ${CAMFOLLOWER_SUITESPARSE_colamd} ${CAMFOLLOWER_SUITESPARSE_suitesparseconfig})
  add_library(camfollower::cholmod INTERFACE IMPORTED)
  target_include_directories(camfollower::cholmod INTERFACE ${CAMFOLLOWER_SUITESPARSE_INCLUDE_DIR})
  target_link_libraries(camfollower::cholmod INTERFACE ${CAMFOLLOWER_SUITESPARSE_cholmod} ${CAMFOLLOWER_SUITESPARSE_suitesparseconfig})
endif()

find_package(Spectra 1.0 CONFIG QUIET)
if(TARGET Spectra::Spectra)
  add_library(camfollower::spectra INTERFACE IMPORTED)
  target_link_libraries(camfollower::spectra INTERFACE Spectra::Spectra)
else()
  find_path(CAMFOLLOWER_SPECTRA_INCLUDE_DIR Spectra/SymEigsShiftSolver.h)
  if(NOT CAMFOLLOWER_SPECTRA_INCLUDE_DIR)
    message(FATAL_ERROR "Spectra not found: install it (Debian/Ubuntu: libspectra-dev)")
  endif()
  add_library(camfollower::spectra INTERFACE IMPORTED)
  target_include_directories(camfollower::spectra INTERFACE ${CAMFOLLOWER_SPECTRA_INCLUDE_DIR})
endif()
