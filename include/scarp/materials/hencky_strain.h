#ifndef scarp_materials_hencky_strain_h
#define scarp_materials_hencky_strain_h

#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>

#include <scarp/materials/spectral_decomposition.h>

#include <cmath>

namespace scarp
{
  namespace materials
  {
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
      // exp of the in-plane block, as exp_symmetric() computes it.
      double b_n[2][2];
      exp_plane_block(two_eps_e_n, b_n[0][0], b_n[1][1], b_n[0][1]);
      b_n[1][0] = b_n[0][1];
      double Fb[2][2];
      for (unsigned int i = 0; i < 2; ++i)
        for (unsigned int k = 0; k < 2; ++k)
          Fb[i][k] = delta_F[i][0] * b_n[0][k] + delta_F[i][1] * b_n[1][k];
      SymmetricTensor<2, 3> b_trial;
      for (unsigned int i = 0; i < 2; ++i)
        for (unsigned int j = i; j < 2; ++j)
          b_trial[i][j] = Fb[i][0] * delta_F[j][0] + Fb[i][1] * delta_F[j][1];
      const double zz = 0.5 * two_eps_e_n[2][2];
      // Diagonal: sorted as spectral_decomposition_diagonal() sorts, on
      // the strains.
      if (b_trial[0][1] == 0.)
        return sorted_diagonal(
          {{0.5 * std::log(b_trial[0][0]), 0.5 * std::log(b_trial[1][1]), zz}});
      // The in-plane pair as spectral_decomposition_plane() finds it, zz
      // placed among the strains as it places it among the stretches.
      const PlaneBlock trial(b_trial);
      const double     radius = trial.scale * trial.rs;
      double           c, s;
      plane_unit_vector(trial.hs, trial.bs, trial.rs, c, s);
      return plane_pair_and_zz(0.5 * std::log(trial.mean + radius),
                               0.5 * std::log(trial.mean - radius),
                               zz,
                               c,
                               s);
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
      if (two_eps_e_n[0][2] == 0. && two_eps_e_n[1][2] == 0. &&
          delta_F[0][2] == 0. && delta_F[1][2] == 0. && delta_F[2][0] == 0. &&
          delta_F[2][1] == 0. && delta_F[2][2] == 1.)
        return hencky_trial_strain_plane(delta_F, two_eps_e_n);
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
  } // namespace materials
} // namespace scarp

#endif
