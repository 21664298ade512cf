# ctest driver: install the build into a scratch prefix, then configure, build and
# run Examples/CxxApp against it with find_package(DeformableSurface).
# -D BUILD_DIR=... -D SOURCE_DIR=... -D WORK_DIR=...
file(REMOVE_RECURSE "${WORK_DIR}")
execute_process(COMMAND "${CMAKE_COMMAND}" --install "${BUILD_DIR}" --prefix "${WORK_DIR}/prefix"
  RESULT_VARIABLE rc OUTPUT_QUIET)
if (rc)
  message(FATAL_ERROR "cmake --install failed: ${rc}")
endif ()
execute_process(COMMAND "${CMAKE_COMMAND}" -S "${SOURCE_DIR}/Examples/CxxApp" -B "${WORK_DIR}/app"
  "-DCMAKE_PREFIX_PATH=${WORK_DIR}/prefix" -DCMAKE_BUILD_TYPE=Release
  RESULT_VARIABLE rc)
if (rc)
  message(FATAL_ERROR "configuring the app against the installed package failed: ${rc}")
endif ()
execute_process(COMMAND "${CMAKE_COMMAND}" --build "${WORK_DIR}/app" RESULT_VARIABLE rc)
if (rc)
  message(FATAL_ERROR "building the app failed: ${rc}")
endif ()
execute_process(COMMAND "${WORK_DIR}/app/ds_app" RESULT_VARIABLE rc)
if (rc)
  message(FATAL_ERROR "the app failed: ${rc}")
endif ()
