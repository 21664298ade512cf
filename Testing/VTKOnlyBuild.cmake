# SPDX-License-Identifier: BSD-3-Clause
# ctest driver: configure and build the project with DEFORMABLESURFACE_USE_PARAVIEW=OFF
# against ParaView's bundled VTK, then import the wrapped package with plain vtkmodules.
execute_process(COMMAND "${CMAKE_COMMAND}" -S "${SOURCE_DIR}" -B "${WORK_DIR}"
  -DDEFORMABLESURFACE_USE_PARAVIEW=OFF "-DVTK_DIR=${VTK_DIR}" -DBUILD_TESTING=OFF
  -DCMAKE_BUILD_TYPE=Release "-DPython3_EXECUTABLE=${PYTHON}"
  RESULT_VARIABLE rc)
if (rc)
  message(FATAL_ERROR "VTK-only configure failed: ${rc}")
endif ()
execute_process(COMMAND "${CMAKE_COMMAND}" --build "${WORK_DIR}" -j 2 RESULT_VARIABLE rc)
if (rc)
  message(FATAL_ERROR "VTK-only build failed: ${rc}")
endif ()
execute_process(COMMAND "${CMAKE_COMMAND}" -E env "PYTHONPATH=${WORK_DIR}/lib/python3/dist-packages"
  "${PYTHON}" -c "from deformablesurface import vtkImageScaleSpaceGradient; print(vtkImageScaleSpaceGradient().GetClassName())"
  RESULT_VARIABLE rc)
if (rc)
  message(FATAL_ERROR "VTK-only Python package does not import: ${rc}")
endif ()
