#ifndef scarp_materials_spectral_decomposition_h
#define scarp_materials_spectral_decomposition_h

#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>

#include <algorithm>
#include <array>
#include <cmath>

namespace scarp
{
  namespace materials
  {
    using namespace dealii;

    /**
     * @brief Eigenvalues (in descending order) and unit eigenvectors of a
     * symmetric 3x3 tensor, A = sum_i values[i] vectors[i] (x) vectors[i].
     *
     * Logarithmic strain and the principal-space return mapping both work on
     * this form; keeping it in a fixed-size struct keeps the hot path
     * allocation-free.
     */
    struct SpectralDecomposition
    {
      /// Eigenvalues, values[0] >= values[1] >= values[2].
      std::array<double, 3> values;
      /// Orthonormal eigenvectors matching @p values.
      std::array<Tensor<1, 3>, 3> vectors;
    };

    /**
     * @brief The in-plane 2x2 block of a plane tensor (xz = yz = 0) as
     * mean + scale (hs, bs; bs, -hs), with scale = max(|half|, |b|) and
     * rs = |(hs, bs)|, so that its eigenvalues are mean +- scale rs.
     *
     * Scaled because the off-diagonal of a nearly isotropic tensor can be
     * ~1e-160, whose square underflows. hs, bs and rs are NaN for scale = 0
     * (a diagonal block), which callers treat first.
     */
    struct PlaneBlock
    {
      double mean, half, b, scale, hs, bs, rs;

      explicit PlaneBlock(const SymmetricTensor<2, 3> &A)
        : mean(0.5 * (A[0][0] + A[1][1]))
        , half(0.5 * (A[0][0] - A[1][1]))
        , b(A[0][1])
        , scale(std::max(std::abs(half), std::abs(b)))
        , hs(half / scale)
        , bs(b / scale)
        , rs(std::sqrt(hs * hs + bs * bs))
      {
      }
    };

    /// Unit eigenvector (c, s) of the larger eigenvalue of the 2x2 block
    /// scale (hs, bs; bs, -hs) with rs = |(hs, bs)| > 0, without trig: of the
    /// two parallel candidates (hs + rs, bs) and (bs, rs - hs) the one
    /// without cancellation; c >= 0 as with atan2.
    inline void
    plane_unit_vector(const double hs,
                      const double bs,
                      const double rs,
                      double      &c,
                      double      &s)
    {
      // Both cases at once (rs + |hs| is rs + hs or rs - hs exactly), the
      // case picked by selects: the sign of hs varies from point to point,
      // and a branch on it was mispredicted about every other point.
      const bool   positive = hs >= 0.;
      const double a        = rs + std::abs(hs);
      const double n        = std::sqrt(2. * rs * a);
      const double c_num    = positive ? a : std::abs(bs);
      const double s_num    = positive ? bs : std::copysign(a, bs);
      c                     = c_num / n;
      s                     = s_num / n;
    }

    /// Spectral decomposition of a general symmetric 3x3 tensor (some
    /// off-diagonal of xz, yz nonzero) in the manner of Scherzinger and
    /// Dohrmann (2008): on the deviator scaled to its largest entry, the
    /// eigenvalue farthest from the other two from the invariants (the
    /// largest if the Lode angle is below pi/6, else the smallest), its
    /// eigenvector orthogonal to two orthonormalised rows of A - lambda I,
    /// and the remaining pair from the 2x2 block in the plane of those rows
    /// in closed form. Why not deal.II's eigenvectors(): its QL iteration
    /// costs about 350 ns, its hybrid method loses half the digits where
    /// eigenvalues nearly repeat (every Mohr-Coulomb edge); this one is
    /// backward stable to a few ulps of |A| for repeated eigenvalues too (the
    /// farthest eigenvalue has a gap of at least half the spread, and the
    /// pair is solved exactly), at about a fifth of the QL cost.
    inline SpectralDecomposition
    spectral_decomposition_general(const SymmetricTensor<2, 3> &A)
    {
      const double mean    = (A[0][0] + A[1][1] + A[2][2]) / 3.;
      double       s[3][3] = {{A[0][0] - mean, A[0][1], A[0][2]},
                              {A[0][1], A[1][1] - mean, A[1][2]},
                              {A[0][2], A[1][2], A[2][2] - mean}};
      // Scaled so that the squares below neither underflow nor overflow
      // (off-diagonals of 1e-160 were met in plane strain). scale > 0: some
      // off-diagonal is nonzero.
      double scale = 0.;
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = i; j < 3; ++j)
          scale = std::max(scale, std::abs(s[i][j]));
      const double inv_scale = 1. / scale;
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = 0; j < 3; ++j)
          s[i][j] *= inv_scale;
      const double J2 =
        0.5 * (s[0][0] * s[0][0] + s[1][1] * s[1][1] + s[2][2] * s[2][2]) +
        s[0][1] * s[0][1] + s[0][2] * s[0][2] + s[1][2] * s[1][2];
      const double J3 = s[0][0] * (s[1][1] * s[2][2] - s[1][2] * s[1][2]) -
                        s[0][1] * (s[0][1] * s[2][2] - s[1][2] * s[0][2]) +
                        s[0][2] * (s[0][1] * s[1][2] - s[1][1] * s[0][2]);
      const double ratio = 3. / J2;
      const double cos_3a =
        std::max(-1., std::min(1., 0.5 * J3 * ratio * std::sqrt(ratio)));
      const double     alpha         = std::acos(cos_3a) / 3.;
      const double     radius        = 2. * std::sqrt(J2 / 3.);
      constexpr double pi            = 3.14159265358979323846;
      const bool       largest_first = alpha < pi / 6.;
      const double     eta_1         = largest_first
                                         ? radius * std::cos(alpha)
                                         : radius * std::cos(alpha + 2. * pi / 3.);

      // Rows of s - eta_1 I: the longest, normalised, then the longer of the
      // other two orthogonalised against it; both are orthogonal to the
      // eigenvector of eta_1, which is their cross product.
      double r[3][3];
      double norm2[3];
      for (unsigned int i = 0; i < 3; ++i)
        {
          for (unsigned int j = 0; j < 3; ++j)
            r[i][j] = s[i][j] - (i == j ? eta_1 : 0.);
          norm2[i] = r[i][0] * r[i][0] + r[i][1] * r[i][1] + r[i][2] * r[i][2];
        }
      const unsigned int i0 = (norm2[0] >= norm2[1])
                                ? (norm2[0] >= norm2[2] ? 0 : 2)
                                : (norm2[1] >= norm2[2] ? 1 : 2);
      const unsigned int i1 = (i0 + 1) % 3, i2 = (i0 + 2) % 3;
      const double       inv0 = 1. / std::sqrt(norm2[i0]);
      Tensor<1, 3>       u1;
      for (unsigned int j = 0; j < 3; ++j)
        u1[j] = r[i0][j] * inv0;
      Tensor<1, 3> t1, t2;
      const double p1 = r[i1][0] * u1[0] + r[i1][1] * u1[1] + r[i1][2] * u1[2];
      const double p2 = r[i2][0] * u1[0] + r[i2][1] * u1[1] + r[i2][2] * u1[2];
      for (unsigned int j = 0; j < 3; ++j)
        {
          t1[j] = r[i1][j] - p1 * u1[j];
          t2[j] = r[i2][j] - p2 * u1[j];
        }
      const double       n1 = t1.norm_square(), n2 = t2.norm_square();
      const Tensor<1, 3> u2 =
        (n1 >= n2) ? t1 / std::sqrt(n1) : t2 / std::sqrt(n2);
      const Tensor<1, 3> v1 = cross_product_3d(u1, u2);

      // The pair in the plane of u1, u2: the 2x2 block of s there.
      Tensor<1, 3> su1, su2;
      for (unsigned int i = 0; i < 3; ++i)
        {
          su1[i] = s[i][0] * u1[0] + s[i][1] * u1[1] + s[i][2] * u1[2];
          su2[i] = s[i][0] * u2[0] + s[i][1] * u2[1] + s[i][2] * u2[2];
        }
      const double a11 = u1 * su1, a22 = u2 * su2,
                   a12  = 0.5 * (u1 * su2 + u2 * su1);
      const double half = 0.5 * (a11 - a22);
      const double mid  = 0.5 * (a11 + a22);
      const double big  = std::max(std::abs(half), std::abs(a12));
      double       c = 1., sn = 0., pair_radius = 0.;
      if (big > 0.)
        {
          const double hs = half / big, bs = a12 / big;
          const double rs = std::sqrt(hs * hs + bs * bs);
          pair_radius     = big * rs;
          plane_unit_vector(hs, bs, rs, c, sn);
        }
      const Tensor<1, 3> w_upper = c * u1 + sn * u2;
      const Tensor<1, 3> w_lower = c * u2 - sn * u1;
      const double       upper   = mid + pair_radius;
      const double       lower   = mid - pair_radius;

      SpectralDecomposition result;
      if (largest_first)
        {
          result.values  = {{eta_1, upper, lower}};
          result.vectors = {{v1, w_upper, w_lower}};
        }
      else
        {
          result.values  = {{upper, lower, eta_1}};
          result.vectors = {{w_upper, w_lower, v1}};
        }
      // eta_1 is the farthest of the three, but rounding may put it a hair
      // inside the pair when the three are about equally spaced.
      if (result.values[0] < result.values[1])
        {
          std::swap(result.values[0], result.values[1]);
          std::swap(result.vectors[0], result.vectors[1]);
        }
      if (result.values[1] < result.values[2])
        {
          std::swap(result.values[1], result.values[2]);
          std::swap(result.vectors[1], result.vectors[2]);
        }
      if (result.values[0] < result.values[1])
        {
          std::swap(result.values[0], result.values[1]);
          std::swap(result.vectors[0], result.vectors[1]);
        }
      for (double &v : result.values)
        v = v * scale + mean;
      return result;
    }

    /// The decomposition of a diagonal tensor from its diagonal: the values
    /// sorted in descending order by swaps (ties keep the order x, y, z),
    /// the vectors the axes.
    inline SpectralDecomposition
    sorted_diagonal(const std::array<double, 3> &diagonal)
    {
      SpectralDecomposition       result;
      std::array<unsigned int, 3> order = {{0, 1, 2}};
      if (diagonal[order[0]] < diagonal[order[1]])
        std::swap(order[0], order[1]);
      if (diagonal[order[1]] < diagonal[order[2]])
        std::swap(order[1], order[2]);
      if (diagonal[order[0]] < diagonal[order[1]])
        std::swap(order[0], order[1]);
      for (unsigned int i = 0; i < 3; ++i)
        {
          result.values[i]            = diagonal[order[i]];
          result.vectors[i]           = Tensor<1, 3>();
          result.vectors[i][order[i]] = 1.;
        }
      return result;
    }

    /// The decomposition of a plane tensor from its in-plane pair (upper >=
    /// lower, (c, s) the unit vector of upper) and its zz value: zz goes
    /// above, between or below the pair, ties as sorted_diagonal() would
    /// put them. Each entry is written once into @p result: picking
    /// whole vectors from a temporary array by index read back in 16-byte
    /// pieces what had been stored in 8-byte ones, a failed store-to-load
    /// forwarding per point (perf annotate of the elastic column); so did
    /// a returned value assigned to an array element (written to the
    /// stack, then copied), hence the output argument.
    inline void
    plane_pair_and_zz_into(const double           upper,
                           const double           lower,
                           const double           zz,
                           const double           c,
                           const double           s,
                           SpectralDecomposition &result)
    {
      // The slots by arithmetic on the comparisons, without branches (the
      // place of zz varies from point to point): zz above the pair goes to
      // 0, between to 1, at or below lower to 2 (upper >= lower).
      const unsigned int above_lower = lower < zz;
      const unsigned int above_upper = upper < zz;
      const unsigned int zz_slot     = 2 - above_lower - above_upper;
      const unsigned int upper_slot  = above_upper;
      const unsigned int lower_slot  = 1 + above_lower;
      result.values[upper_slot]      = upper;
      result.values[lower_slot]      = lower;
      result.values[zz_slot]         = zz;
      Tensor<1, 3> &v_upper          = result.vectors[upper_slot];
      Tensor<1, 3> &v_lower          = result.vectors[lower_slot];
      Tensor<1, 3> &v_zz             = result.vectors[zz_slot];
      v_upper[0]                     = c;
      v_upper[1]                     = s;
      v_upper[2]                     = 0.;
      v_lower[0]                     = -s;
      v_lower[1]                     = c;
      v_lower[2]                     = 0.;
      v_zz[0]                        = 0.;
      v_zz[1]                        = 0.;
      v_zz[2]                        = 1.;
    }

    /// plane_pair_and_zz_into() as a value.
    inline SpectralDecomposition
    plane_pair_and_zz(const double upper,
                      const double lower,
                      const double zz,
                      const double c,
                      const double s)
    {
      SpectralDecomposition result;
      plane_pair_and_zz_into(upper, lower, zz, c, s, result);
      return result;
    }

    /// Spectral decomposition of a diagonal tensor: its own, the diagonal
    /// sorted (this keeps the stress-free state exactly stress-free).
    inline SpectralDecomposition
    spectral_decomposition_diagonal(const SymmetricTensor<2, 3> &A)
    {
      return sorted_diagonal({{A[0][0], A[1][1], A[2][2]}});
    }

    /// Spectral decomposition of a plane tensor (xz = yz = 0, xy != 0):
    /// the in-plane 2x2 block in closed form (about ten times cheaper than
    /// an iterative 3x3 one, and exact for repeated eigenvalues), zz on its
    /// own. Plane strain keeps xz = yz = 0 exactly.
    inline SpectralDecomposition
    spectral_decomposition_plane(const SymmetricTensor<2, 3> &A)
    {
      // scale > 0 here, as b != 0.
      const PlaneBlock block(A);
      const double     radius = block.scale * block.rs;
      double           c, s;
      plane_unit_vector(block.hs, block.bs, block.rs, c, s);
      return plane_pair_and_zz(
        block.mean + radius, block.mean - radius, A[2][2], c, s);
    }

    /// Spectral decomposition of a symmetric 3x3 tensor (exact for
    /// diagonal tensors, closed form for plane ones, else
    /// spectral_decomposition_general(); accurate also for repeated
    /// eigenvalues, which occur on every Mohr-Coulomb edge). Each branch
    /// returns its own function's value: with a named result here and the
    /// general branch's returned beside it, the compiler built the result
    /// on the stack and copied it out in 16-byte pieces over 8-byte stores,
    /// a failed store-to-load forwarding per call (perf annotate of the
    /// main job: 8 % of this function's samples).
    inline SpectralDecomposition
    spectral_decomposition(const SymmetricTensor<2, 3> &A)
    {
      const double off =
        std::abs(A[0][1]) + std::abs(A[1][2]) + std::abs(A[0][2]);
      if (off == 0.)
        return spectral_decomposition_diagonal(A);
      if (A[0][2] == 0. && A[1][2] == 0.)
        return spectral_decomposition_plane(A);
      return spectral_decomposition_general(A);
    }

    /// compose(values, vectors) * scale written into @p out entry by entry:
    /// the same sums and product as `compose(values, vectors) / J` with
    /// scale = 1 / J (deal.II divides by multiplying with the inverse), but
    /// without the temporary on the stack that the compiler stored in
    /// 8-byte pieces and read back in 16-byte ones, a failed store-to-load
    /// forwarding per point (perf annotate: a third of the samples of
    /// LinearElastic::update on the elastic column).
    inline void
    compose_scaled_into(const std::array<double, 3>       &values,
                        const std::array<Tensor<1, 3>, 3> &vectors,
                        const double                       scale,
                        SymmetricTensor<2, 3>             &out)
    {
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = i; j < 3; ++j)
          {
            double a = 0.;
            for (unsigned int k = 0; k < 3; ++k)
              a += values[k] * vectors[k][i] * vectors[k][j];
            out[i][j] = a * scale;
          }
    }

    /// The symmetric tensor sum_i values[i] vectors[i] (x) vectors[i]
    /// (the sums of compose_scaled_into(), times 1: exactly them).
    inline SymmetricTensor<2, 3>
    compose(const std::array<double, 3>       &values,
            const std::array<Tensor<1, 3>, 3> &vectors)
    {
      SymmetricTensor<2, 3> A;
      compose_scaled_into(values, vectors, 1., A);
      return A;
    }

    /// Logarithm of a symmetric positive definite tensor.
    inline SymmetricTensor<2, 3>
    log_spd(const SymmetricTensor<2, 3> &A)
    {
      SpectralDecomposition s = spectral_decomposition(A);
      for (double &v : s.values)
        v = std::log(v);
      return compose(s.values, s.vectors);
    }

    /// factor times a symmetric tensor stored as six doubles (xx, yy, zz,
    /// xy, yz, xz), entry by entry (the products of factor * A).
    inline SymmetricTensor<2, 3>
    load_symmetric_scaled(const double *v, const double factor)
    {
      SymmetricTensor<2, 3> A;
      A[0][0] = v[0] * factor;
      A[1][1] = v[1] * factor;
      A[2][2] = v[2] * factor;
      A[0][1] = v[3] * factor;
      A[1][2] = v[4] * factor;
      A[0][2] = v[5] * factor;
      return A;
    }

    /// Read a symmetric tensor stored as six doubles (xx, yy, zz, xy, yz,
    /// xz), the layout used for tensors in the material state arrays.
    inline SymmetricTensor<2, 3>
    load_symmetric(const double *v)
    {
      SymmetricTensor<2, 3> A;
      A[0][0] = v[0];
      A[1][1] = v[1];
      A[2][2] = v[2];
      A[0][1] = v[3];
      A[1][2] = v[4];
      A[0][2] = v[5];
      return A;
    }

    /// Store a symmetric tensor as six doubles (xx, yy, zz, xy, yz, xz).
    inline void
    store_symmetric(const SymmetricTensor<2, 3> &A, double *v)
    {
      v[0] = A[0][0];
      v[1] = A[1][1];
      v[2] = A[2][2];
      v[3] = A[0][1];
      v[4] = A[1][2];
      v[5] = A[0][2];
    }
    /// Exponential of a general symmetric tensor by scaling and squaring
    /// with a Taylor polynomial whose degree follows the norm: exp(A) =
    /// exp(A / 2^s)^(2^s) with |A / 2^s| <= 1/4, the series cut where its
    /// remainder falls below 1e-17 (6 terms for an elastic strain of 1e-3,
    /// at most 12). Why not decompose and compose: deal.II's iterative 3x3
    /// eigenvectors() cost about 350 ns, the series 20-60 ns, and the
    /// Hencky predictor needs no eigenvectors of exp(2 eps_e), only the
    /// tensor. Accurate to a few ulps of |exp(A)| (the decomposition's
    /// accuracy too: neither resolves an eigenvalue far below |exp(A)| to
    /// its own relative precision).
    inline SymmetricTensor<2, 3>
    exp_symmetric_series(const SymmetricTensor<2, 3> &A)
    {
      // The largest absolute row sum bounds the spectral radius.
      double norm = 0.;
      for (unsigned int i = 0; i < 3; ++i)
        norm =
          std::max(norm,
                   std::abs(A[i][0]) + std::abs(A[i][1]) + std::abs(A[i][2]));
      // Scale by a power of two (exact) so that the norm is at most 1/4.
      int squarings = 0;
      if (norm > 0.25)
        {
          std::frexp(norm / 0.25, &squarings);
          if (std::ldexp(0.25, squarings - 1) >= norm)
            --squarings;
        }
      const double factor      = std::ldexp(1., -squarings);
      const double b[6]        = {A[0][0] * factor,
                                  A[1][1] * factor,
                                  A[2][2] * factor,
                                  A[0][1] * factor,
                                  A[1][2] * factor,
                                  A[0][2] * factor};
      const double scaled_norm = norm * factor;
      // Degree: the smallest m whose first omitted term, |B|^(m+1)/(m+1)!,
      // is below 1e-17 (the remainder is at most 4/3 of it for |B| <= 1/4,
      // and |exp(B)| >= exp(-1/4)).
      unsigned int omitted = 1;
      for (double term = scaled_norm; term > 1e-17 && omitted < 20;)
        {
          ++omitted;
          term *= scaled_norm / omitted;
        }
      const unsigned int degree = omitted - 1;
      // Horner: P = I + B P / k from k = m down to 1, P starting at I. P is a
      // polynomial in B, so B P is symmetric: its upper triangle suffices.
      // Entries as (xx, yy, zz, xy, yz, xz).
      double p[6] = {1., 1., 1., 0., 0., 0.};
      for (unsigned int k = degree; k >= 1; --k)
        {
          const double inv_k = 1. / k;
          const double q[6]  = {b[0] * p[0] + b[3] * p[3] + b[5] * p[5],
                                b[3] * p[3] + b[1] * p[1] + b[4] * p[4],
                                b[5] * p[5] + b[4] * p[4] + b[2] * p[2],
                                b[0] * p[3] + b[3] * p[1] + b[5] * p[4],
                                b[3] * p[5] + b[1] * p[4] + b[4] * p[2],
                                b[0] * p[5] + b[3] * p[4] + b[5] * p[2]};
          p[0]               = 1. + q[0] * inv_k;
          p[1]               = 1. + q[1] * inv_k;
          p[2]               = 1. + q[2] * inv_k;
          p[3]               = q[3] * inv_k;
          p[4]               = q[4] * inv_k;
          p[5]               = q[5] * inv_k;
        }
      // Undo the scaling: square s times.
      for (int k = 0; k < squarings; ++k)
        {
          const double q[6] = {p[0] * p[0] + p[3] * p[3] + p[5] * p[5],
                               p[3] * p[3] + p[1] * p[1] + p[4] * p[4],
                               p[5] * p[5] + p[4] * p[4] + p[2] * p[2],
                               p[0] * p[3] + p[3] * p[1] + p[5] * p[4],
                               p[3] * p[5] + p[1] * p[4] + p[4] * p[2],
                               p[0] * p[5] + p[3] * p[4] + p[5] * p[2]};
          std::copy(q, q + 6, p);
        }
      return load_symmetric(p);
    }

    /// The in-plane block (xx, yy, xy) of exp(A) for a plane tensor A, in
    /// closed form without eigenvectors: exp(A) = (e1 + e2)/2 I + (e1 -
    /// e2)/2 (A - m I)/r with e1,2 = exp(m +- r); e1 - e2 = exp(m - r)
    /// expm1(2 r) keeps the digits that the difference of the two
    /// exponentials loses when r is small. Shared by exp_symmetric() and
    /// the plane Hencky predictor, which needs no zz entry.
    inline void
    exp_plane_block(const SymmetricTensor<2, 3> &A,
                    double                      &xx,
                    double                      &yy,
                    double                      &xy)
    {
      const PlaneBlock block(A);
      if (block.scale == 0.)
        {
          xx = yy = std::exp(block.mean);
          xy      = 0.;
          return;
        }
      const double radius = block.scale * block.rs;
      const double lower  = std::exp(block.mean - radius);
      const double w      = 0.5 * lower * std::expm1(2. * radius);
      const double sum    = lower + w;
      xx                  = sum + w * (block.hs / block.rs);
      yy                  = sum - w * (block.hs / block.rs);
      xy                  = w * (block.bs / block.rs);
    }

    /// Exponential of a symmetric tensor (the result is SPD): plane tensors
    /// in closed form, others by exp_symmetric_series().
    inline SymmetricTensor<2, 3>
    exp_symmetric(const SymmetricTensor<2, 3> &A)
    {
      if (A[0][2] == 0. && A[1][2] == 0.)
        {
          // Plane strain: the in-plane block in closed form
          // (exp_plane_block()), half the cost of decompose-and-compose.
          SymmetricTensor<2, 3> E;
          E[2][2] = std::exp(A[2][2]);
          exp_plane_block(A, E[0][0], E[1][1], E[0][1]);
          return E;
        }
      return exp_symmetric_series(A);
    }

    /// compose(values, vectors) stored as six doubles (xx, yy, zz, xy, yz,
    /// xz) straight into @p v: the sums of compose(), without the temporary
    /// that store_symmetric() copied in 16-byte pieces from its 8-byte
    /// stores, a failed store-to-load forwarding per point (perf annotate of
    /// Chalk::update on the refined cliff).
    inline void
    store_composed(const std::array<double, 3>       &values,
                   const std::array<Tensor<1, 3>, 3> &vectors,
                   double                            *v)
    {
      constexpr unsigned int row[6] = {0, 1, 2, 0, 1, 0};
      constexpr unsigned int col[6] = {0, 1, 2, 1, 2, 2};
      for (unsigned int n = 0; n < 6; ++n)
        {
          double a = 0.;
          for (unsigned int k = 0; k < 3; ++k)
            a += values[k] * vectors[k][row[n]] * vectors[k][col[n]];
          v[n] = a;
        }
    }
  } // namespace materials
} // namespace scarp

#endif
