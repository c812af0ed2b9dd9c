// Exact line integrals of the reconstructed field g along rays: the ground
// truth of every accuracy number in the project.
//
// Tent kernel: g is the trilinear interpolation of the voxel values on the
// grid padded with one layer of zeros, so along a ray it is a cubic
// polynomial inside each cell, which Simpson's rule integrates exactly.
// Box kernel: g is constant on the cube of each voxel. Cells are walked with
// the Amanatides-Woo traversal.
#ifndef mcxRayIntegrator_h
#define mcxRayIntegrator_h

#include "mcxSampleGenerator.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace mcx
{

class RayIntegrator
{
public:
  /// values: nx*ny*nz voxel values of g (x fastest).
  RayIntegrator(const double* values, const int dims[3], Kernel kernel)
    : Reconstruction(kernel)
    , Shift(kernel == Kernel::Tent ? 1.0 : 0.5)
  {
    const int pad = kernel == Kernel::Tent ? 1 : 0;
    for (int a = 0; a < 3; ++a)
    {
      this->Dims[a] = dims[a] + 2 * pad;
      // Cell c covers [c, c + 1] in shifted coordinates q: for the tent,
      // q = p + 1 and cell corners are padded lattice points; for the box,
      // q = p + 0.5 and cell c is the cube of voxel c.
      this->Cells[a] = kernel == Kernel::Tent ? dims[a] + 1 : dims[a];
    }
    const std::size_t n = static_cast<std::size_t>(this->Dims[0]) * this->Dims[1] * this->Dims[2];
    this->Values.assign(n, 0.0);
    for (int k = 0; k < dims[2]; ++k)
    {
      for (int j = 0; j < dims[1]; ++j)
      {
        const double* src = values + (static_cast<std::size_t>(k) * dims[1] + j) * dims[0];
        double* dst = this->Values.data() + this->Index(pad, j + pad, k + pad);
        std::copy(src, src + dims[0], dst);
      }
    }
  }

  /// Integral of g(p0 + t d) dt over t in [tmin, tmax], p0 and d in voxel
  /// coordinates (tmin, tmax may be infinite).
  double Integrate(const double p0[3], const double d[3], double tmin, double tmax) const
  {
    double q0[3];
    for (int a = 0; a < 3; ++a)
    {
      q0[a] = p0[a] + this->Shift;
      // Clip to the support box [0, Cells[a]].
      if (d[a] == 0.0)
      {
        if (!(q0[a] > 0.0 && q0[a] < this->Cells[a]))
        {
          return 0.0;
        }
        continue;
      }
      double t0 = (0.0 - q0[a]) / d[a];
      double t1 = (this->Cells[a] - q0[a]) / d[a];
      if (t0 > t1)
      {
        std::swap(t0, t1);
      }
      tmin = std::max(tmin, t0);
      tmax = std::min(tmax, t1);
    }
    if (!(tmin < tmax))
    {
      return 0.0;
    }

    int cell[3];
    int step[3];
    double tNext[3];
    double tDelta[3];
    for (int a = 0; a < 3; ++a)
    {
      const double q = q0[a] + tmin * d[a];
      int c = static_cast<int>(std::floor(q));
      if (d[a] < 0 && q == c)
      {
        --c;
      }
      cell[a] = std::max(0, std::min(this->Cells[a] - 1, c));
      if (d[a] > 0)
      {
        step[a] = 1;
        tNext[a] = (cell[a] + 1 - q0[a]) / d[a];
        tDelta[a] = 1.0 / d[a];
      }
      else if (d[a] < 0)
      {
        step[a] = -1;
        tNext[a] = (cell[a] - q0[a]) / d[a];
        tDelta[a] = -1.0 / d[a];
      }
      else
      {
        step[a] = 0;
        tNext[a] = std::numeric_limits<double>::infinity();
        tDelta[a] = std::numeric_limits<double>::infinity();
      }
    }

    double sum = 0.0;
    double t = tmin;
    while (t < tmax)
    {
      const double tExit = std::min(tmax, std::min(tNext[0], std::min(tNext[1], tNext[2])));
      if (tExit > t)
      {
        sum += this->CellIntegral(cell, q0, d, t, tExit);
      }
      t = tExit;
      bool inside = true;
      for (int a = 0; a < 3; ++a)
      {
        if (tNext[a] <= tExit)
        {
          cell[a] += step[a];
          tNext[a] += tDelta[a];
          inside = inside && cell[a] >= 0 && cell[a] < this->Cells[a];
        }
      }
      if (!inside)
      {
        break;
      }
    }
    return sum;
  }

private:
  std::size_t Index(int i, int j, int k) const
  {
    return (static_cast<std::size_t>(k) * this->Dims[1] + j) * this->Dims[0] + i;
  }

  double Trilinear(const int cell[3], const double q[3]) const
  {
    const double fx = q[0] - cell[0], fy = q[1] - cell[1], fz = q[2] - cell[2];
    const std::size_t i = this->Index(cell[0], cell[1], cell[2]);
    const std::size_t sy = static_cast<std::size_t>(this->Dims[0]);
    const std::size_t sz = sy * this->Dims[1];
    const double* v = this->Values.data();
    const double c00 = v[i] + fx * (v[i + 1] - v[i]);
    const double c10 = v[i + sy] + fx * (v[i + sy + 1] - v[i + sy]);
    const double c01 = v[i + sz] + fx * (v[i + sz + 1] - v[i + sz]);
    const double c11 = v[i + sy + sz] + fx * (v[i + sy + sz + 1] - v[i + sy + sz]);
    const double c0 = c00 + fy * (c10 - c00);
    const double c1 = c01 + fy * (c11 - c01);
    return c0 + fz * (c1 - c0);
  }

  double CellIntegral(
    const int cell[3], const double q0[3], const double d[3], double t0, double t1) const
  {
    if (this->Reconstruction == Kernel::Box)
    {
      return this->Values[this->Index(cell[0], cell[1], cell[2])] * (t1 - t0);
    }
    const double tm = 0.5 * (t0 + t1);
    double qa[3], qm[3], qb[3];
    for (int a = 0; a < 3; ++a)
    {
      qa[a] = q0[a] + t0 * d[a];
      qm[a] = q0[a] + tm * d[a];
      qb[a] = q0[a] + t1 * d[a];
    }
    return (t1 - t0) / 6.0 *
      (this->Trilinear(cell, qa) + 4.0 * this->Trilinear(cell, qm) + this->Trilinear(cell, qb));
  }

  Kernel Reconstruction;
  double Shift;
  int Dims[3];
  int Cells[3];
  std::vector<double> Values;
};

} // namespace mcx

#endif
