#ifndef scarp_materials_isotropic_elasticity_h
#define scarp_materials_isotropic_elasticity_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/symmetric_tensor.h>

#include <array>

namespace scarp
{
  namespace materials
  {
    using namespace dealii;

    /**
     * @brief Isotropic linear elasticity D (Young's modulus E, Poisson's
     * ratio nu): stress = lambda tr(eps) I + 2 mu eps, its inverse and its
     * energy, for tensors and for principal values.
     *
     * With logarithmic strain and Kirchhoff stress this is the Hencky
     * hyperelastic law; the principal-value forms serve the return mapping.
     */
    class IsotropicElasticity
    {
    public:
      /// Default: E = 1 GPa, nu = 0.24 (Joss Bay chalk).
      IsotropicElasticity();

      /// E [Pa] > 0, -1 < nu < 0.5.
      IsotropicElasticity(const double youngs_modulus,
                          const double poisson_ratio);

      /// Declare `Young's modulus` and `Poisson's ratio` in the current
      /// subsection.
      static void
      declare_parameters(ParameterHandler &prm);

      /// Read the entries of declare_parameters() (current subsection).
      void
      parse_parameters(ParameterHandler &prm);

      double
      youngs_modulus() const
      {
        return E;
      }

      double
      poisson_ratio() const
      {
        return nu;
      }

      /// First Lame parameter lambda [Pa].
      double
      lambda() const
      {
        return lambda_;
      }

      /// Shear modulus mu [Pa].
      double
      shear_modulus() const
      {
        return mu;
      }

      /// Bulk modulus K = lambda + 2 mu / 3 [Pa].
      double
      bulk_modulus() const
      {
        return lambda_ + 2. * mu / 3.;
      }

      /// Constrained modulus M = lambda + 2 mu [Pa].
      double
      p_wave_modulus() const
      {
        return lambda_ + 2. * mu;
      }

      /// D : strain.
      SymmetricTensor<2, 3>
      stress(const SymmetricTensor<2, 3> &strain) const
      {
        return lambda_ * trace(strain) * unit_symmetric_tensor<3>() +
               2. * mu * strain;
      }

      /// D^-1 : stress.
      SymmetricTensor<2, 3>
      strain(const SymmetricTensor<2, 3> &stress) const
      {
        return (1. + nu) / E * stress -
               nu / E * trace(stress) * unit_symmetric_tensor<3>();
      }

      /// 1/2 strain : D : strain.
      double
      energy(const SymmetricTensor<2, 3> &strain) const
      {
        const double tr = trace(strain);
        return 0.5 * lambda_ * tr * tr + mu * (strain * strain);
      }

      /// D applied to principal strains.
      std::array<double, 3>
      principal_stress(const std::array<double, 3> &e) const
      {
        const double l = lambda_ * (e[0] + e[1] + e[2]);
        return {{l + 2. * mu * e[0], l + 2. * mu * e[1], l + 2. * mu * e[2]}};
      }

      /// D^-1 applied to principal stresses.
      std::array<double, 3>
      principal_strain(const std::array<double, 3> &s) const
      {
        const double t = nu / E * (s[0] + s[1] + s[2]);
        const double a = (1. + nu) / E;
        return {{a * s[0] - t, a * s[1] - t, a * s[2] - t}};
      }

    private:
      void
      compute_lame();

      double E;
      double nu;
      double lambda_;
      double mu;
    };
  } // namespace materials
} // namespace scarp

#endif
