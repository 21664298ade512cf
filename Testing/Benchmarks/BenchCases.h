// SPDX-License-Identifier: BSD-3-Clause
// What the object benchmarks (BenchObjects, BenchSeveralObjects) share: reading a NIfTI volume,
// checking that a label volume lies on its image's grid, and choosing cases by name.
#ifndef BenchCases_h
#define BenchCases_h

#include "../Cxx/ObjectScore.h"

#include "vtkDSNIFTIImageReader.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkSmartPointer.h"

#include <cmath>
#include <string>
#include <vector>

namespace dsobjects
{
inline vtkSmartPointer<vtkImageData> ReadNifti(const std::string& path)
{
  vtkNew<vtkDSNIFTIImageReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->ShallowCopy(reader->GetOutput());
  return image;
}

/// The same voxels in the same place, axis-aligned (a label volume drawn on its image).
inline bool SameGrid(vtkImageData* a, vtkImageData* b)
{
  int da[3], db[3];
  a->GetDimensions(da);
  b->GetDimensions(db);
  double oa[3], ob[3], sa[3], sb[3];
  a->GetOrigin(oa);
  b->GetOrigin(ob);
  a->GetSpacing(sa);
  b->GetSpacing(sb);
  for (int k = 0; k < 3; ++k)
    if (da[k] != db[k] || std::abs(oa[k] - ob[k]) > 1e-6 || std::abs(sa[k] - sb[k]) > 1e-6)
      return false;
  return AxisAligned(a) && AxisAligned(b);
}

/// Whether the case `name` is asked for: no filters, or one that is part of the name.
inline bool Wanted(const std::vector<std::string>& filters, const std::string& name)
{
  if (filters.empty())
    return true;
  for (const std::string& f : filters)
    if (name.find(f) != std::string::npos)
      return true;
  return false;
}
} // namespace dsobjects

#endif
