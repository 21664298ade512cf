# SPDX-License-Identifier: BSD-3-Clause
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

# The installed plugin loads in ParaView and the installed Python package imports with
# plain vtkmodules (their RUNPATHs find the installed library).
if (PYTHON)
  execute_process(COMMAND "${CMAKE_COMMAND}" -E env "PYTHONPATH=${WORK_DIR}/prefix/lib/python3/dist-packages"
    "${PYTHON}" -c "from deformablesurface import vtkDeformableSurfaceFilter; vtkDeformableSurfaceFilter()"
    RESULT_VARIABLE rc)
  if (rc)
    message(FATAL_ERROR "the installed Python package does not import: ${rc}")
  endif ()
endif ()
if (PVPYTHON)
  execute_process(COMMAND "${PVPYTHON}" --force-offscreen-rendering -c
    "import paraview.simple as s; s.LoadPlugin('${WORK_DIR}/prefix/lib/paraview-5.11/plugins/DeformableSurface/DeformableSurface.so'); s.DeformableSurface(); s.ScaleSpaceGradient(); s.DelaunaySeedSurface()"
    RESULT_VARIABLE rc)
  if (rc)
    message(FATAL_ERROR "the installed plugin does not load in ParaView: ${rc}")
  endif ()
endif ()
