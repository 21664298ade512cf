#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Installs the Debian 12 packages the project needs to build, test and run its demo.
# Idempotent and quick when everything is there: apt runs only for missing packages.
# --with-itk (opt-in, not for CI): also ITK, which only BenchAccuracy's comparison column uses
# (scripts/benchmark.sh Accuracy passes it); the module never depends on ITK.
set -euo pipefail

packages=(
  # toolchain (clang-format: the Format.check test)
  cmake g++ make clang-format
  # the sanitizer and fuzzing stages of scripts/test.sh (clang++ with libFuzzer and the
  # ASan/UBSan runtimes)
  clang libclang-rt-14-dev
  # ParaView 5.11 with its bundled VTK 9.2 (do NOT add libvtk9-dev/python3-vtk9: they remove python3-paraview)
  paraview paraview-dev python3-paraview libopenmpi-dev
  # XML_DOCUMENTATION ON (the GUI help pages)
  qttools5-dev qtxmlpatterns5-dev-tools libqt5svg5-dev
  # Qt5 OpenGL's CMake config, which ParaView's VTK looks for (without it a configure warning)
  libqt5opengl5-dev
  # third-party headers/config that ParaView's bundled VTK asks find_package() for
  libdouble-conversion-dev liblz4-dev liblzma-dev libexpat1-dev libjsoncpp-dev libutfcpp-dev
  libpugixml-dev libeigen3-dev libglew-dev libfreetype-dev libpng-dev libjpeg-dev libtiff-dev
  zlib1g-dev libxml2-dev libgl2ps-dev libfontconfig-dev libtheora-dev libogg-dev
  # the DICOM series reader (GDCM's core libraries: JPEG 2000 through OpenJPEG, JPEG-LS through
  # CharLS); without it the module builds without the reader
  libgdcm-dev
  # screenshots without a display
  xvfb xauth
  # real volumes: Colin27 T1 brain MRI (and its brain mask)
  mricron-data
  # a second real head no one tuned on: ITK's KmeansTest T1 with its skull-stripped reference
  insighttoolkit5-examples
  # a real head CT (InVesalius's example project), and SciPy for scoring and benchmarks
  invesalius-examples python3-scipy
)
if [ "${1:-}" = "--with-itk" ]; then
  packages+=(libinsighttoolkit5-dev)
fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

SUDO=""
if [ "$(id -u)" -ne 0 ]; then
  SUDO="sudo"
fi
echo "Installing: ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
