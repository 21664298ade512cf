# SPDX-License-Identifier: BSD-3-Clause
# Included from the build-tree copy of vtk.module (see the top-level CMakeLists.txt):
# paths here are absolute so the module can be built from any binary directory.
set(_ds_filters_dir "${DeformableSurface_SOURCE_DIR}/Filters")

# The VTK algorithms (thin wrappers), one class per file.
file(GLOB _ds_classes CONFIGURE_DEPENDS "${_ds_filters_dir}/vtk*.cxx")
list(TRANSFORM _ds_classes REPLACE "\\.cxx$" "")

# The algorithm core: plain C++, no pipeline types (vtkSMPTools and vtkIdType are used), unit-testable.
file(GLOB _ds_core_sources CONFIGURE_DEPENDS "${_ds_filters_dir}/Core/*.cxx")
file(GLOB _ds_core_headers CONFIGURE_DEPENDS "${_ds_filters_dir}/Core/*.h")
# The wrappers' bridge from VTK data to the core (dsVTKImage: image checks, geometry, the values in their own type).
file(GLOB _ds_bridge_sources CONFIGURE_DEPENDS "${_ds_filters_dir}/ds*.cxx")
file(GLOB _ds_bridge_headers CONFIGURE_DEPENDS "${_ds_filters_dir}/ds*.h")
list(APPEND _ds_core_sources ${_ds_bridge_sources})
list(APPEND _ds_core_headers ${_ds_bridge_headers})

# The DICOM reader and its core are built only on GDCM (top-level DEFORMABLESURFACE_USE_GDCM).
if (NOT DEFORMABLESURFACE_HAVE_GDCM)
  list(FILTER _ds_classes EXCLUDE REGEX "vtkDSDICOM[^/]*$")
  list(FILTER _ds_core_sources EXCLUDE REGEX "/dsDicom[^/]*$")
  list(FILTER _ds_core_headers EXCLUDE REGEX "/dsDicom[^/]*$")
endif ()

vtk_module_add_module(DeformableSurface::Filters
  CLASSES         ${_ds_classes}
  SOURCES         ${_ds_core_sources}
  PRIVATE_HEADERS ${_ds_core_headers})
# dsNiftiHeader reads gzipped NIfTI headers and streams with the zlib VTK's NIfTI reader uses.
vtk_module_link(DeformableSurface::Filters PRIVATE VTK::zlib)
vtk_module_include(DeformableSurface::Filters
  PUBLIC
    "$<BUILD_INTERFACE:${_ds_filters_dir}>"
    "$<BUILD_INTERFACE:${_ds_filters_dir}/Core>")
if (DEFORMABLESURFACE_HAVE_GDCM)
  # Private: the module's public headers name no GDCM type. gdcmMSFF brings gdcmDSED, gdcmCommon.
  vtk_module_link(DeformableSurface::Filters PRIVATE gdcmMSFF)
  vtk_module_include(DeformableSurface::Filters PRIVATE ${GDCM_INCLUDE_DIRS})
endif ()

# The sweep calls small functions of this library per vertex (the force and image samples, the
# fan normal, the umbrellas). An exported function of a shared library is called through the PLT,
# and within its own file is not inlined, unless it cannot be interposed: these options bind the
# library's calls to its own functions directly (its exported interface is unchanged).
if(CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang" AND NOT APPLE AND NOT WIN32)
  vtk_module_compile_options(DeformableSurface::Filters PRIVATE -fno-semantic-interposition)
  vtk_module_link_options(DeformableSurface::Filters PRIVATE -Wl,-Bsymbolic-functions)
endif()
