// SPDX-License-Identifier: BSD-3-Clause
// Scores a segmentation of one object against its reference mask, the same way for our
// filter's surface and for the threshold a user would try instead: distances both
// ways between the surface and the reference boundary (the mask's 0.5 iso-surface), Dice of the
// voxels inside the surface against the mask, the volume ratio, the share of the enclosed
// volume outside the mask, the surface's SelfIntersections (its field data) and its vertices
// outside the image. Distances are in world units (mm); volumes are voxel counts on the image's
// grid (a voxel is inside when its centre is). ParaView 5.11's VTK has neither ImagingStencil
// nor ImagingMorphological: the voxelisation and the connected component are done here.
#ifndef ObjectScore_h
#define ObjectScore_h

#include "vtkCellArray.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkFlyingEdges3D.h"
#include "vtkImageConstantPad.h"
#include "vtkImageData.h"
#include "vtkImageThreshold.h"
#include "vtkMatrix3x3.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkStaticCellLocator.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <functional>
#include <vector>

namespace dsobjects
{
/// The numbers of one segmentation (distances in world units). SelfIntersections is -1 when
/// the surface does not say (an iso-surface).
struct ObjectScore
{
  double Seconds = 0;
  long long Vertices = 0;
  double SurfaceMean = 0, SurfaceP95 = 0;     ///< surface vertices -> reference boundary
  double ReferenceMean = 0, ReferenceP95 = 0; ///< reference boundary points -> surface
  double Dice = 0, VolumeRatio = 0, OutsideShare = 0;
  int SelfIntersections = -1;
  long long VerticesOutside = 0;
};

/// A reference mask: 1 where keep(label value, voxel index) holds, on the label's grid.
inline std::vector<unsigned char> MaskOf(
  vtkImageData* label, const std::function<bool(double, vtkIdType)>& keep)
{
  vtkDataArray* a = label->GetPointData()->GetScalars();
  std::vector<unsigned char> mask(static_cast<size_t>(a->GetNumberOfTuples()), 0);
  for (vtkIdType v = 0; v < a->GetNumberOfTuples(); ++v)
    mask[v] = keep(a->GetComponent(v, 0), v) ? 1 : 0;
  return mask;
}

/// The boundary of a 0/1 mask on grid's geometry: its 0.5 iso-surface, the grid padded by one
/// voxel of 0 so a mask touching the border still gives a closed surface.
inline vtkSmartPointer<vtkPolyData> MaskBoundary(
  const std::vector<unsigned char>& mask, vtkImageData* grid)
{
  vtkNew<vtkImageData> image;
  image->CopyStructure(grid);
  vtkNew<vtkUnsignedCharArray> a;
  a->SetName("Mask");
  a->SetNumberOfTuples(static_cast<vtkIdType>(mask.size()));
  std::copy(mask.begin(), mask.end(), a->GetPointer(0));
  image->GetPointData()->SetScalars(a);
  int e[6];
  grid->GetExtent(e);
  vtkNew<vtkImageConstantPad> pad;
  pad->SetInputData(image);
  pad->SetOutputWholeExtent(e[0] - 1, e[1] + 1, e[2] - 1, e[3] + 1, e[4] - 1, e[5] + 1);
  pad->SetConstant(0);
  vtkNew<vtkFlyingEdges3D> iso;
  iso->SetInputConnection(pad->GetOutputPort());
  iso->SetValue(0, 0.5);
  iso->ComputeNormalsOff();
  iso->ComputeGradientsOff();
  iso->ComputeScalarsOff();
  iso->Update();
  return iso->GetOutput();
}

/// The crossings of each grid column (i, j) along z with the surface's triangles. The columns
/// are shifted by a hundred-thousandth of a voxel so none passes exactly through a vertex or
/// an edge of the triangle grid of an iso-surface.
inline std::vector<std::vector<double>> ColumnCrossings(vtkPolyData* surface, vtkImageData* grid)
{
  int n[3];
  double o[3], s[3];
  grid->GetDimensions(n);
  grid->GetOrigin(o);
  grid->GetSpacing(s);
  const double ox = o[0] + 1.1e-5 * s[0], oy = o[1] + 1.7e-5 * s[1];
  std::vector<std::vector<double>> crossings(static_cast<size_t>(n[0]) * n[1]);
  vtkCellArray* polys = surface->GetPolys();
  vtkIdType npts;
  const vtkIdType* ids;
  double p[3][3];
  for (polys->InitTraversal(); polys->GetNextCell(npts, ids);)
  {
    if (npts != 3)
      continue;
    for (int k = 0; k < 3; ++k)
      surface->GetPoint(ids[k], p[k]);
    const double det =
      (p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[2][0] - p[0][0]) * (p[1][1] - p[0][1]);
    if (det == 0)
      continue; // seen edge-on from z: no column crosses it
    const double x0 = std::min({ p[0][0], p[1][0], p[2][0] }),
                 x1 = std::max({ p[0][0], p[1][0], p[2][0] });
    const double y0 = std::min({ p[0][1], p[1][1], p[2][1] }),
                 y1 = std::max({ p[0][1], p[1][1], p[2][1] });
    const int i0 = std::max(0, static_cast<int>(std::ceil((x0 - ox) / s[0])));
    const int i1 = std::min(n[0] - 1, static_cast<int>(std::floor((x1 - ox) / s[0])));
    const int j0 = std::max(0, static_cast<int>(std::ceil((y0 - oy) / s[1])));
    const int j1 = std::min(n[1] - 1, static_cast<int>(std::floor((y1 - oy) / s[1])));
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i)
      {
        const double x = ox + i * s[0], y = oy + j * s[1];
        // Barycentric coordinates of the column in the projected triangle.
        const double u =
          ((x - p[0][0]) * (p[2][1] - p[0][1]) - (p[2][0] - p[0][0]) * (y - p[0][1])) / det;
        const double v =
          ((p[1][0] - p[0][0]) * (y - p[0][1]) - (x - p[0][0]) * (p[1][1] - p[0][1])) / det;
        if (u < 0 || v < 0 || u + v > 1)
          continue;
        crossings[static_cast<size_t>(j) * n[0] + i].push_back(
          p[0][2] + u * (p[1][2] - p[0][2]) + v * (p[2][2] - p[0][2]));
      }
  }
  return crossings;
}

/// The voxels (of grid) whose centres lie inside the closed surface: along each column, between
/// the 1st and 2nd crossing, the 3rd and 4th, ... (even-odd rule).
inline std::vector<unsigned char> SurfaceInterior(vtkPolyData* surface, vtkImageData* grid)
{
  int n[3];
  double o[3], s[3];
  grid->GetDimensions(n);
  grid->GetOrigin(o);
  grid->GetSpacing(s);
  std::vector<unsigned char> inside(static_cast<size_t>(n[0]) * n[1] * n[2], 0);
  std::vector<std::vector<double>> crossings = ColumnCrossings(surface, grid);
  for (size_t column = 0; column < crossings.size(); ++column)
  {
    std::vector<double>& z = crossings[column];
    std::sort(z.begin(), z.end());
    for (size_t c = 0; c + 1 < z.size(); c += 2)
    {
      const int k0 = std::max(0, static_cast<int>(std::ceil((z[c] - o[2]) / s[2])));
      const int k1 = std::min(n[2] - 1, static_cast<int>(std::floor((z[c + 1] - o[2]) / s[2])));
      for (int k = k0; k <= k1; ++k)
        inside[static_cast<size_t>(k) * n[0] * n[1] + column] = 1;
    }
  }
  return inside;
}

/// The distance of every stride-th point of from to the triangles of to; of at most MaxSamples
/// points evenly spread over from's list (a leaked iso-surface has millions of points far from
/// the reference, where each locator query is slow; the statistics do not need them all).
constexpr vtkIdType MaxSamples = 50000;
inline std::vector<double> Distances(vtkPolyData* from, vtkPolyData* to, vtkIdType stride = 1)
{
  stride = std::max(stride, (from->GetNumberOfPoints() + MaxSamples - 1) / MaxSamples);
  std::vector<double> d;
  if (to->GetNumberOfCells() == 0)
    return d;
  vtkNew<vtkStaticCellLocator> locator;
  locator->SetDataSet(to);
  locator->BuildLocator();
  double p[3], closest[3], d2;
  vtkIdType cell;
  int sub;
  for (vtkIdType i = 0; i < from->GetNumberOfPoints(); i += stride)
  {
    from->GetPoint(i, p);
    locator->FindClosestPoint(p, closest, cell, sub, d2);
    d.push_back(std::sqrt(d2));
  }
  return d;
}

inline void MeanP95(std::vector<double> d, double& mean, double& p95)
{
  if (d.empty())
  {
    mean = p95 = 1e9; // nothing to measure: worse than any goal
    return;
  }
  double sum = 0;
  for (double x : d)
    sum += x;
  mean = sum / d.size();
  const size_t k = std::min(d.size() - 1, static_cast<size_t>(0.95 * d.size()));
  std::nth_element(d.begin(), d.begin() + k, d.end());
  p95 = d[k];
}

inline long long PointsOutside(vtkPolyData* surface, vtkImageData* image)
{
  double b[6], p[3];
  image->GetBounds(b);
  long long n = 0;
  for (vtkIdType i = 0; i < surface->GetNumberOfPoints(); ++i)
  {
    surface->GetPoint(i, p);
    bool out = false;
    for (int a = 0; a < 3; ++a)
      out = out || p[a] < b[2 * a] - 1e-6 || p[a] > b[2 * a + 1] + 1e-6;
    n += out ? 1 : 0;
  }
  return n;
}

/// Scores a surface and the voxels it encloses (inside) against the reference mask and its
/// boundary. referenceStride: every how many reference boundary points are measured.
inline ObjectScore Score(vtkPolyData* surface, const std::vector<unsigned char>& inside,
  const std::vector<unsigned char>& reference, vtkPolyData* referenceBoundary, vtkImageData* image,
  vtkIdType referenceStride = 1)
{
  ObjectScore s;
  s.Vertices = surface->GetNumberOfPoints();
  MeanP95(Distances(surface, referenceBoundary), s.SurfaceMean, s.SurfaceP95);
  MeanP95(Distances(referenceBoundary, surface, referenceStride), s.ReferenceMean, s.ReferenceP95);
  long long in = 0, ref = 0, both = 0;
  for (size_t v = 0; v < reference.size() && v < inside.size(); ++v)
  {
    in += inside[v];
    ref += reference[v];
    both += inside[v] & reference[v];
  }
  s.Dice = in + ref > 0 ? 2.0 * both / double(in + ref) : 0.0;
  s.VolumeRatio = ref > 0 ? double(in) / ref : 0.0;
  s.OutsideShare = in > 0 ? double(in - both) / in : 0.0;
  if (vtkDataArray* si = surface->GetFieldData()->GetArray("SelfIntersections"))
    s.SelfIntersections = static_cast<int>(si->GetTuple1(0));
  s.VerticesOutside = PointsOutside(surface, image);
  return s;
}

/// The 6-connected component of mask that holds voxel seed (empty when seed is not in it).
inline std::vector<unsigned char> Component(
  const std::vector<unsigned char>& mask, const int n[3], vtkIdType seed)
{
  std::vector<unsigned char> component(mask.size(), 0);
  if (seed < 0 || !mask[seed])
    return component;
  const vtkIdType step[3] = { 1, n[0], static_cast<vtkIdType>(n[0]) * n[1] };
  std::vector<vtkIdType> front = { seed };
  component[seed] = 1;
  while (!front.empty())
  {
    const vtkIdType v = front.back();
    front.pop_back();
    const int ijk[3] = { static_cast<int>(v % n[0]), static_cast<int>((v / n[0]) % n[1]),
      static_cast<int>(v / step[2]) };
    for (int a = 0; a < 3; ++a)
      for (int sign = -1; sign <= 1; sign += 2)
      {
        const int c = ijk[a] + sign;
        const vtkIdType w = v + sign * step[a];
        if (c >= 0 && c < n[a] && mask[w] && !component[w])
        {
          component[w] = 1;
          front.push_back(w);
        }
      }
  }
  return component;
}

/// The alternative a user would pick (a connected threshold, as region-growing tools offer):
/// the voxels in [lo, hi] (vtkImageThreshold), the 6-connected component of them that holds the
/// click, and its boundary as the surface, timed together.
struct ThresholdResult
{
  std::vector<unsigned char> Inside;
  vtkSmartPointer<vtkPolyData> Surface;
  double Seconds = 0;
};

inline ThresholdResult ThresholdComponent(
  vtkImageData* image, double lo, double hi, const std::array<double, 3>& click)
{
  ThresholdResult r;
  const auto t0 = std::chrono::steady_clock::now();
  vtkNew<vtkImageThreshold> threshold;
  threshold->SetInputData(image);
  threshold->ThresholdBetween(lo, hi);
  threshold->SetInValue(1);
  threshold->SetOutValue(0);
  threshold->SetOutputScalarTypeToUnsignedChar();
  threshold->Update();
  vtkDataArray* a = threshold->GetOutput()->GetPointData()->GetScalars();
  std::vector<unsigned char> in(static_cast<size_t>(a->GetNumberOfTuples()));
  for (vtkIdType v = 0; v < a->GetNumberOfTuples(); ++v)
    in[v] = a->GetComponent(v, 0) > 0 ? 1 : 0;
  int n[3];
  image->GetDimensions(n);
  r.Inside = Component(in, n, image->FindPoint(click[0], click[1], click[2]));
  r.Surface = MaskBoundary(r.Inside, image);
  r.Seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

/// True when the image has no rotation (the stencil and the iso-surfaces assume axis-aligned
/// grids; the phantoms and Colin27 are).
inline bool AxisAligned(vtkImageData* image)
{
  vtkMatrix3x3* m = image->GetDirectionMatrix();
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      if (std::abs(m->GetElement(r, c) - (r == c ? 1.0 : 0.0)) > 1e-9)
        return false;
  return true;
}
} // namespace dsobjects

#endif
