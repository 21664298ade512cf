// SPDX-License-Identifier: BSD-3-Clause
#include "dsRegionValues.h"

#include "vtkSMPTools.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <vector>

namespace dsurf
{
namespace
{

/// A float's key in the order of the values (-0 as +0): a value's bits, the sign flipped for
/// positive values and all bits for negative ones.
std::uint32_t OrderKey(float value)
{
  std::uint32_t u;
  const float v = value == 0.0f ? 0.0f : value;
  std::memcpy(&u, &v, sizeof u);
  return (u & 0x80000000u) ? ~u : (u | 0x80000000u);
}

float KeyValue(std::uint32_t key)
{
  const std::uint32_t u = (key & 0x80000000u) ? (key & 0x7fffffffu) : ~key;
  float v;
  std::memcpy(&v, &u, sizeof v);
  return v;
}

/// Values a chunk of the parallel loops below holds.
constexpr std::size_t ChunkValues = 1 << 20;

/// The counts of the values whose OrderKey has `prefix` in its `known` bits, by the `digits`
/// values of its bits from `shift` on, counted chunk by chunk in parallel (in the caller's SMP
/// scope) and added in the chunks' order.
std::vector<double> DigitHistogram(const std::vector<float>& values, int shift, int digits,
  std::uint32_t known, std::uint32_t prefix)
{
  const std::size_t chunks = (values.size() + ChunkValues - 1) / ChunkValues;
  std::vector<std::vector<double>> counts(chunks, std::vector<double>(digits, 0.0));
  vtkSMPTools::For(0, static_cast<vtkIdType>(chunks), 1,
    [&](vtkIdType first, vtkIdType last)
    {
      for (vtkIdType c = first; c < last; ++c)
      {
        const std::size_t end =
          std::min(values.size(), static_cast<std::size_t>(c + 1) * ChunkValues);
        for (std::size_t i = static_cast<std::size_t>(c) * ChunkValues; i < end; ++i)
        {
          const std::uint32_t key = OrderKey(values[i]);
          if ((key & known) == prefix)
          {
            counts[c][(key >> shift) & (digits - 1)] += 1.0;
          }
        }
      }
    });
  std::vector<double> histogram(digits, 0.0);
  for (const std::vector<double>& h : counts)
  {
    for (int d = 0; d < digits; ++d)
    {
      histogram[d] += h[d];
    }
  }
  return histogram;
}
} // namespace

long long CountOfAll(const std::vector<float>& values, const PieceReductions& reduce)
{
  std::vector<double> n{ static_cast<double>(values.size()) };
  reduce.Sum(n);
  return static_cast<long long>(n[0]);
}

double Quantile(const SharedValues& all, double q, const PieceReductions& reduce)
{
  const long long n = all.Count;
  long long k = std::min(n - 1, static_cast<long long>(q * (n - 1) + 0.5));
  std::uint32_t prefix = 0, known = 0; // the key's bits found so far, and which
  for (const int shift : { 21, 10, 0 })
  {
    const int digits = shift == 0 ? 1 << 10 : 1 << 11;
    std::vector<double> histogram = DigitHistogram(all.Values, shift, digits, known, prefix);
    reduce.Sum(histogram);
    int d = 0;
    for (; d + 1 < digits && k >= static_cast<long long>(histogram[d]); ++d)
    {
      k -= static_cast<long long>(histogram[d]);
    }
    prefix |= static_cast<std::uint32_t>(d) << shift;
    known |= static_cast<std::uint32_t>(digits - 1) << shift;
  }
  return KeyValue(prefix);
}
} // namespace dsurf
