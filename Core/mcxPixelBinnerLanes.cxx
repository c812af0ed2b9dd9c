// PixelBinner::LocatePoints on SIMD lanes: Google Highway compiles the
// kernel once per instruction set (scalar to AVX-512 on x86) and picks the
// widest the CPU has at run time. Every lane does the scalar Locate's
// operations in its order, and additions, multiplications, divisions and
// square roots are correctly rounded on every instruction set, so the
// results are those of PixelBinner::Locate bit for bit (the project
// compiles with -ffp-contract=off: no fused multiply-add on one path that
// the other lacks).
#include "mcxPixelBinner.h"

#include <algorithm>

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "mcxPixelBinnerLanes.cxx"
#include <hwy/foreach_target.h> // IWYU pragma: keep
#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace mcx
{
namespace HWY_NAMESPACE
{
namespace hn = hwy::HWY_NAMESPACE;

// One row of the binner's affine map at points (x, y, z): ((m0 x + m1 y) + m2 z) + offset.
template <class D, class V>
HWY_INLINE V Affine(D d, const double* row, double offset, V x, V y, V z)
{
  V sum = hn::Add(hn::Mul(hn::Set(d, row[0]), x), hn::Mul(hn::Set(d, row[1]), y));
  sum = hn::Add(sum, hn::Mul(hn::Set(d, row[2]), z));
  return hn::Add(sum, hn::Set(d, offset));
}

void LocateLanes(const PixelBinner::Map& map, const double* x, const double* y, const double* z,
  std::size_t n, double* fx, double* fy, double* f, std::uint8_t* located, double* inverseDepth)
{
  const hn::ScalableTag<double> d;
  const std::size_t lanes = hn::Lanes(d);
  HWY_ALIGN double flags[hn::MaxLanes(d)];
  for (std::size_t i = 0; i < n; i += lanes)
  {
    const std::size_t count = std::min(lanes, n - i);
    // A partial last vector: loaded in full from the caller's padding
    // (LocatePoints asks for arrays of a multiple of MaximumLanes).
    const auto px = hn::LoadU(d, x + i);
    const auto py = hn::LoadU(d, y + i);
    const auto pz = hn::LoadU(d, z + i);
    decltype(hn::Zero(d)) u, v, weight, inverse = hn::Zero(d);
    auto inFront = hn::Eq(hn::Zero(d), hn::Zero(d)); // all true
    if (!map.Perspective)
    {
      u = Affine(d, map.Rows, map.PixelOffset[0], px, py, pz);
      v = Affine(d, map.Rows + 3, map.PixelOffset[1], px, py, pz);
      weight = hn::Set(d, 1.0);
    }
    else
    {
      const auto a = Affine(d, map.Rows, map.Offset[0], px, py, pz);
      const auto b = Affine(d, map.Rows + 3, map.Offset[1], px, py, pz);
      const auto depth = Affine(d, map.Rows + 6, map.Offset[2], px, py, pz);
      inFront = hn::Ge(depth, hn::Set(d, map.Near)); // false for NaN, as !(z >= Near)
      inverse = hn::Div(hn::Set(d, 1.0), depth);
      u = hn::Add(hn::Mul(hn::Mul(a, inverse), hn::Set(d, map.PixelScale[0])),
        hn::Set(d, map.PixelOffset[0]));
      v = hn::Add(hn::Mul(hn::Mul(b, inverse), hn::Set(d, map.PixelScale[1])),
        hn::Set(d, map.PixelOffset[1]));
      const auto squares = hn::Add(hn::Add(hn::Mul(a, a), hn::Mul(b, b)), hn::Mul(depth, depth));
      weight =
        hn::Mul(hn::Mul(hn::Mul(hn::Mul(hn::Set(d, map.FocalSquared), hn::Sqrt(squares)), inverse),
                  inverse),
          inverse);
    }
    // Finite: |value| below infinity (false for NaN and both infinities).
    const auto infinity = hn::Set(d, HUGE_VAL);
    const auto finite = hn::And(hn::Lt(hn::Abs(u), infinity), hn::Lt(hn::Abs(v), infinity));
    hn::Store(hn::IfThenElseZero(hn::And(inFront, finite), hn::Set(d, 1.0)), d, flags);
    HWY_ALIGN double us[hn::MaxLanes(d)], vs[hn::MaxLanes(d)], ws[hn::MaxLanes(d)],
      inverses[hn::MaxLanes(d)];
    hn::Store(u, d, us);
    hn::Store(v, d, vs);
    hn::Store(weight, d, ws);
    hn::Store(inverse, d, inverses);
    for (std::size_t l = 0; l < count; ++l)
    {
      fx[i + l] = us[l];
      fy[i + l] = vs[l];
      f[i + l] = ws[l];
      located[i + l] = flags[l] != 0.0 ? 1 : 0;
    }
    if (inverseDepth)
    {
      std::copy(inverses, inverses + count, inverseDepth + i);
    }
  }
}
} // namespace HWY_NAMESPACE
} // namespace mcx
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace mcx
{
HWY_EXPORT(LocateLanes);

void PixelBinner::LocatePoints(const double* x, const double* y, const double* z, std::size_t n,
  double* fx, double* fy, double* f, std::uint8_t* located, double* inverseDepth) const
{
  HWY_DYNAMIC_DISPATCH(LocateLanes)(this->Lanes, x, y, z, n, fx, fy, f, located, inverseDepth);
}

const char* PixelBinner::LanesInstructionSet()
{
  // The target HWY_DYNAMIC_DISPATCH calls: the best one supported and compiled.
  const std::int64_t best = hwy::SupportedTargets() & HWY_TARGETS;
  return hwy::TargetName(best & -best);
}
} // namespace mcx
#endif
