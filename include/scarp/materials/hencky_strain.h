#ifndef scarp_materials_hencky_strain_h
#define scarp_materials_hencky_strain_h

#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>

#include <scarp/materials/spectral_decomposition.h>

#include <algorithm>
#include <cmath>
#include <new>

namespace scarp
{
  namespace materials
  {
    /// Whether a step is plane strain for the predictor: 2 eps_e_n and dF
    /// without xz, yz, zx, zy entries, and dF_zz = 1.
    inline bool
    is_plane_strain_step(const Tensor<2, 3>          &delta_F,
                         const SymmetricTensor<2, 3> &two_eps_e_n)
    {
      return two_eps_e_n[0][2] == 0. && two_eps_e_n[1][2] == 0. &&
             delta_F[0][2] == 0. && delta_F[1][2] == 0. &&
             delta_F[2][0] == 0. && delta_F[2][1] == 0. && delta_F[2][2] == 1.;
    }

    /// b_trial = dF exp(2 eps_e_n) dF^T of plane strain, its in-plane
    /// block (xx, yy, xy): the first stage of hencky_trial_strain_plane().
    inline void
    plane_trial_b(const Tensor<2, 3>          &delta_F,
                  const SymmetricTensor<2, 3> &two_eps_e_n,
                  double                      &xx,
                  double                      &yy,
                  double                      &xy)
    {
      // exp of the in-plane block, as exp_symmetric() computes it.
      double b_n[2][2];
      exp_plane_block(two_eps_e_n, b_n[0][0], b_n[1][1], b_n[0][1]);
      b_n[1][0] = b_n[0][1];
      double Fb[2][2];
      for (unsigned int i = 0; i < 2; ++i)
        for (unsigned int k = 0; k < 2; ++k)
          Fb[i][k] = delta_F[i][0] * b_n[0][k] + delta_F[i][1] * b_n[1][k];
      xx = Fb[0][0] * delta_F[0][0] + Fb[0][1] * delta_F[0][1];
      yy = Fb[1][0] * delta_F[1][0] + Fb[1][1] * delta_F[1][1];
      xy = Fb[0][0] * delta_F[1][0] + Fb[0][1] * delta_F[1][1];
    }

    /// The in-plane principal stretches of b_trial (upper >= lower) and the
    /// unit vector (c, s) of upper, as spectral_decomposition_plane() finds
    /// them; xy != 0. The second stage of hencky_trial_strain_plane().
    inline void
    plane_trial_pair(const double xx,
                     const double yy,
                     const double xy,
                     double      &upper,
                     double      &lower,
                     double      &c,
                     double      &s)
    {
      SymmetricTensor<2, 3> b_trial;
      b_trial[0][0] = xx;
      b_trial[1][1] = yy;
      b_trial[0][1] = xy;
      const PlaneBlock trial(b_trial);
      const double     radius = trial.scale * trial.rs;
      plane_unit_vector(trial.hs, trial.bs, trial.rs, c, s);
      upper = trial.mean + radius;
      lower = trial.mean - radius;
    }

    /// The Hencky predictor of plane strain (two_eps_e_n and delta_F
    /// without xz, yz, zx, zy entries, delta_F[2][2] = 1): only the
    /// in-plane block goes through exp and log, and the out-of-plane
    /// strain is eps_e_n's zz itself, since b_trial_zz = exp(2 eps_zz).
    /// Why: ln(exp(2 eps_zz)) / 2 cost an exp and a log per point and
    /// step (a third of the transcendental calls of the predictor), and
    /// its round trip lost digits: exp(2 eps) rounds to 1e-16 absolute,
    /// which is 5e-13 of an eps of 1e-4. The in-plane block's sums, its
    /// decomposition and its order among the principal strains are those
    /// of the general path (the order compared in strains instead of
    /// stretches, which is the same order but for exact ties after
    /// rounding, where either is right).
    inline SpectralDecomposition
    hencky_trial_strain_plane(const Tensor<2, 3>          &delta_F,
                              const SymmetricTensor<2, 3> &two_eps_e_n)
    {
      double xx, yy, xy;
      plane_trial_b(delta_F, two_eps_e_n, xx, yy, xy);
      const double zz = 0.5 * two_eps_e_n[2][2];
      // Diagonal: sorted as spectral_decomposition_diagonal() sorts, on
      // the strains.
      if (xy == 0.)
        return sorted_diagonal({{0.5 * std::log(xx), 0.5 * std::log(yy), zz}});
      // The in-plane pair as spectral_decomposition_plane() finds it, zz
      // placed among the strains as it places it among the stretches.
      double upper, lower, c, s;
      plane_trial_pair(xx, yy, xy, upper, lower, c, s);
      return plane_pair_and_zz(
        0.5 * std::log(upper), 0.5 * std::log(lower), zz, c, s);
    }

    /// b_trial = dF exp(2 eps_e_n) dF^T for any dF and eps_e_n: the first
    /// stage of hencky_trial_strain_of()'s general path.
    inline SymmetricTensor<2, 3>
    general_trial_b(const Tensor<2, 3>          &delta_F,
                    const SymmetricTensor<2, 3> &two_eps_e_n)
    {
      const SymmetricTensor<2, 3> b_n = exp_symmetric(two_eps_e_n);
      SymmetricTensor<2, 3>       b_trial;
      if (b_n[0][2] == 0. && b_n[1][2] == 0. && delta_F[0][2] == 0. &&
          delta_F[1][2] == 0. && delta_F[2][0] == 0. && delta_F[2][1] == 0.)
        {
          // Plane strain: the in-plane block and zz only; the same sums as
          // the general product below without its zero terms, so the same
          // numbers.
          double Fb[2][2];
          for (unsigned int i = 0; i < 2; ++i)
            for (unsigned int k = 0; k < 2; ++k)
              Fb[i][k] = delta_F[i][0] * b_n[0][k] + delta_F[i][1] * b_n[1][k];
          for (unsigned int i = 0; i < 2; ++i)
            for (unsigned int j = i; j < 2; ++j)
              b_trial[i][j] =
                Fb[i][0] * delta_F[j][0] + Fb[i][1] * delta_F[j][1];
          b_trial[2][2] = delta_F[2][2] * b_n[2][2] * delta_F[2][2];
        }
      else
        {
          // dF b_n dF^T, symmetric by construction; build it symmetrically.
          const Tensor<2, 3> Fb = delta_F * Tensor<2, 3>(b_n);
          for (unsigned int i = 0; i < 3; ++i)
            for (unsigned int j = i; j < 3; ++j)
              {
                double v = 0.;
                for (unsigned int k = 0; k < 3; ++k)
                  v += Fb[i][k] * delta_F[j][k];
                b_trial[i][j] = v;
              }
        }
      return b_trial;
    }

    /**
     * Elastic predictor in logarithmic (Hencky) strain, given 2 eps_e_n:
     * b_e_trial = dF exp(2 eps_e_n) dF^T and eps_e_trial = 1/2 ln b_e_trial,
     * returned in spectral form (principal logarithmic strains in
     * descending order and their directions).
     *
     * Why this form: a rigid rotation dF = R gives b_e_trial = R b_e R^T,
     * so the principal strains are unchanged and the directions rotate
     * exactly; no objective stress rate is needed.
     */
    inline SpectralDecomposition
    hencky_trial_strain_of(const Tensor<2, 3>          &delta_F,
                           const SymmetricTensor<2, 3> &two_eps_e_n)
    {
      if (is_plane_strain_step(delta_F, two_eps_e_n))
        return hencky_trial_strain_plane(delta_F, two_eps_e_n);
      const SymmetricTensor<2, 3> b_trial =
        general_trial_b(delta_F, two_eps_e_n);
      SpectralDecomposition s = spectral_decomposition(b_trial);
      for (double &v : s.values)
        v = 0.5 * std::log(v);
      return s;
    }

    /// The Hencky predictor of eps_e_n stored as six doubles (xx, yy, zz, xy,
    /// yz, xz) in a material state: 2 eps_e_n is built from the stored
    /// entries one by one (the same products). Why: a tensor loaded from
    /// the state entry by entry and then doubled in 16-byte pieces stalled
    /// on a failed store-to-load forwarding per point (perf annotate).
    inline SpectralDecomposition
    hencky_trial_strain(const Tensor<2, 3> &delta_F, const double *eps_e_n)
    {
      return hencky_trial_strain_of(delta_F,
                                    load_symmetric_scaled(eps_e_n, 2.));
    }

    /// The most points hencky_trial_strains() takes at once.
    constexpr unsigned int hencky_chunk = 8;

    /// The Hencky predictors of n <= hencky_chunk points (eps_e_n[k] as in
    /// hencky_trial_strain()) into trial[0, n), stage by stage over the
    /// points: the exponentials and products of all, then all the
    /// decompositions (in-plane, or 3x3 for points that are not plane
    /// strain), then all the logarithms. Why: one
    /// predictor is a chain of dependent roots, divisions and libm calls
    /// too long for the processor to overlap with the next point's; by
    /// stages the chains of neighbouring points run side by side (the
    /// short refined cliff's constitutive update 126 -> 94 ns per point,
    /// doc/performance/constitutive_update.md). The same operations per
    /// point as hencky_trial_strain(): the same numbers.
    inline void
    hencky_trial_strains(const Tensor<2, 3>    *delta_F,
                         const double *const   *eps_e_n,
                         const unsigned int     n,
                         SpectralDecomposition *trial)
    {
      SymmetricTensor<2, 3> two_eps[hencky_chunk];
      bool                  plane[hencky_chunk];
      double xx[hencky_chunk], yy[hencky_chunk], xy[hencky_chunk];
      for (unsigned int k = 0; k < n; ++k)
        {
          two_eps[k] = load_symmetric_scaled(eps_e_n[k], 2.);
          plane[k]   = is_plane_strain_step(delta_F[k], two_eps[k]);
        }
      SymmetricTensor<2, 3> b_general[hencky_chunk];
      for (unsigned int k = 0; k < n; ++k)
        if (plane[k])
          plane_trial_b(delta_F[k], two_eps[k], xx[k], yy[k], xy[k]);
        else
          b_general[k] = general_trial_b(delta_F[k], two_eps[k]);
      double upper[hencky_chunk], lower[hencky_chunk], c[hencky_chunk],
        s[hencky_chunk];
      for (unsigned int k = 0; k < n; ++k)
        if (!plane[k])
          // Built in place (a prvalue initialises the object; assigned,
          // it would go through a temporary on the stack).
          new (&trial[k])
            SpectralDecomposition(spectral_decomposition(b_general[k]));
        else if (xy[k] != 0.)
          plane_trial_pair(xx[k], yy[k], xy[k], upper[k], lower[k], c[k], s[k]);
      for (unsigned int k = 0; k < n; ++k)
        {
          const double zz = 0.5 * two_eps[k][2][2];
          if (!plane[k])
            for (double &v : trial[k].values)
              v = 0.5 * std::log(v);
          else if (xy[k] == 0.)
            trial[k] = sorted_diagonal(
              {{0.5 * std::log(xx[k]), 0.5 * std::log(yy[k]), zz}});
          else
            plane_pair_and_zz_into(0.5 * std::log(upper[k]),
                                   0.5 * std::log(lower[k]),
                                   zz,
                                   c[k],
                                   s[k],
                                   trial[k]);
        }
    }

    /// The trial decomposition of point q of a batch (delta_F[0, n),
    /// eps_e_n[0, n)) out of @p trial, which holds q's chunk: at the
    /// first point of each chunk the chunk's predictors are computed
    /// (hencky_trial_strains()). Call it for q = 0, 1, ..., n - 1 in
    /// order.
    inline SpectralDecomposition &
    hencky_trial_strain_by_chunks(const Tensor<2, 3>  *delta_F,
                                  const double *const *eps_e_n,
                                  const unsigned int   n,
                                  const unsigned int   q,
                                  SpectralDecomposition (&trial)[hencky_chunk])
    {
      if (q % hencky_chunk == 0)
        hencky_trial_strains(delta_F + q,
                             eps_e_n + q,
                             std::min(hencky_chunk, n - q),
                             trial);
      return trial[q % hencky_chunk];
    }
  } // namespace materials
} // namespace scarp

#endif
