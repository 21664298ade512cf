// SPDX-License-Identifier: BSD-3-Clause
// What the Colin27 object cases share (TestColin27Objects, BenchObjects, BenchSeveralObjects):
// reading a NIfTI volume of mricron-data, checking that a label volume lies on its image's grid,
// and reading the clicks committed in Examples/ (chosen on the image, docs/RESULTS.md).
#ifndef Colin27Cases_h
#define Colin27Cases_h

#include "ObjectScore.h"

#include "vtkDSNIFTIImageReader.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkSmartPointer.h"

#include <array>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace dsobjects
{
/// Colin27's T1 below this is CSF: the AAL labels of the deep nuclei take in 14-18 % of it from
/// the ventricles beside them, so their references leave it out (docs/RESULTS.md).
constexpr double Colin27CSFBelow = 60.0;
/// The README's click range for the brain, read off the image (docs/RESULTS.md).
constexpr double Colin27BrainRange[2] = { 62.0, 130.0 };
/// The seed sphere of a caudate click (mm): the default 5 mm reaches past a caudate's head.
constexpr double CaudateSeedRadius = 3.0;
/// Every how many points of the brain mask's boundary (355 000) are measured: ~45 000 give the
/// same statistics.
constexpr int BrainBoundaryStride = 8;

/// Voxels of `t1` (Colin27) that are not CSF (Colin27CSFBelow).
inline bool NotCSF(vtkDataArray* t1, vtkIdType v)
{
  return t1->GetComponent(v, 0) >= Colin27CSFBelow;
}

/// Where Debian's mricron-data puts Colin27 (ch2), its brain mask (ch2bet) and the AAL labels.
inline const std::string& MricronTemplates()
{
  static const std::string dir = "/usr/share/mricron/templates/";
  return dir;
}

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

/// AAL label `label` of `aal` without its CSF in `t1` (NotCSF).
inline std::vector<unsigned char> NucleusWithoutCSF(vtkImageData* aal, vtkImageData* t1, int label)
{
  vtkDataArray* values = t1->GetPointData()->GetScalars();
  return MaskOf(
    aal, [values, label](double l, vtkIdType v) { return l == label && NotCSF(values, v); });
}

/// The clicks of a CSV with the header x,y,z (and, with `ids`, a fourth column ObjectId).
inline std::vector<std::array<double, 3>> ReadClicks(
  const std::string& path, std::vector<int>* ids = nullptr)
{
  std::vector<std::array<double, 3>> clicks;
  std::ifstream in(path);
  std::string line;
  std::getline(in, line); // the header
  while (std::getline(in, line))
  {
    std::array<double, 3> p;
    int id = 0;
    char comma;
    std::istringstream row(line);
    if (row >> p[0] >> comma >> p[1] >> comma >> p[2] && (!ids || row >> comma >> id))
    {
      clicks.push_back(p);
      if (ids)
        ids->push_back(id);
    }
  }
  return clicks;
}
} // namespace dsobjects

#endif
