# SPDX-License-Identifier: BSD-3-Clause
# CTest driver: install the project into a scratch prefix, then configure, build and run the
# consumer project against that install tree (find_package(camfollower)).
# Inputs: BUILD_DIR (the project's build tree), SOURCE_DIR (the consumer sources), WORK_DIR,
# SANITIZE (the sanitizers the package was built with, empty for none: the consumer is built with them too),
# PRECOMPILED (camfollower::precompiled installed: also check that a misaligned unit cannot link it).
file(REMOVE_RECURSE "${WORK_DIR}")
execute_process(COMMAND "${CMAKE_COMMAND}" --install "${BUILD_DIR}" --prefix "${WORK_DIR}/prefix"
                RESULT_VARIABLE rc)
if(rc)
  message(FATAL_ERROR "install failed: ${rc}")
endif()
set(flags "")
if(SANITIZE)
  set(flags "-DCMAKE_CXX_FLAGS=-fsanitize=${SANITIZE},float-cast-overflow"
            "-DCMAKE_EXE_LINKER_FLAGS=-fsanitize=${SANITIZE},float-cast-overflow")
endif()
execute_process(COMMAND "${CMAKE_COMMAND}" -S "${SOURCE_DIR}" -B "${WORK_DIR}/build"
                        "-DCMAKE_PREFIX_PATH=${WORK_DIR}/prefix" ${flags} RESULT_VARIABLE rc)
if(rc)
  message(FATAL_ERROR "consumer configure failed: ${rc}")
endif()
execute_process(COMMAND "${CMAKE_COMMAND}" --build "${WORK_DIR}/build" RESULT_VARIABLE rc)
if(rc)
  message(FATAL_ERROR "consumer build failed: ${rc}")
endif()
execute_process(COMMAND "${WORK_DIR}/build/consumer" RESULT_VARIABLE rc)
if(rc)
  message(FATAL_ERROR "consumer run failed: ${rc}")
endif()
if(PRECOMPILED)
  execute_process(COMMAND "${CMAKE_COMMAND}" --build "${WORK_DIR}/build" --target misaligned
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc OR NOT "${out}${err}" MATCHES "camfollower_precompiled_eigen_alignment_0")
    message(FATAL_ERROR "a unit with another Eigen alignment than the precompiled library linked, or failed "
                        "for another reason (${rc}):\n${out}${err}")
  endif()
endif()
