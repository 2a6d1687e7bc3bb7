#ifndef scarp_materials_neo_hookean_h
#define scarp_materials_neo_hookean_h

#include <scarp/materials/isotropic_elasticity.h>
#include <scarp/materials/material.h>

namespace scarp
{
  namespace materials
  {
    /**
     * @brief Compressible neo-Hookean hyperelasticity, a function of the
     * total deformation gradient F only:
     * P = mu (F - F^-T) + lambda ln J F^-T, sigma = P F^T / J,
     * psi = mu/2 (tr(F^T F) - 3) - mu ln J + lambda/2 (ln J)^2.
     *
     * The law of the Wallstedt & Guilkey (2008) manufactured solution
     * (verification item 7). No state; cannot start pre-stressed.
     */
    class NeoHookean : public Material
    {
    public:
      NeoHookean(const double density, const IsotropicElasticity &elasticity);

      double
      density() const override
      {
        return rho;
      }

      double
      p_wave_modulus() const override
      {
        return elasticity.p_wave_modulus();
      }

      unsigned int
      n_state_variables() const override
      {
        return 0;
      }

      std::vector<std::string>
      state_variable_names() const override
      {
        return {};
      }

      /// Only a zero initial stress is possible (the stress is a function
      /// of F, and F = I at the start); throws otherwise.
      void
      initialize_state(const SymmetricTensor<2, 3> &initial_stress,
                       double                      *state) const override;

      void
      update(const MaterialBatch &batch) const override;

      /// Cauchy stress for a deformation gradient F.
      SymmetricTensor<2, 3>
      cauchy_stress(const Tensor<2, 3> &F) const;

      /// Stored energy per reference volume for F.
      double
      stored_energy(const Tensor<2, 3> &F) const;

    private:
      const double              rho;
      const IsotropicElasticity elasticity;
    };
  } // namespace materials
} // namespace scarp

#endif
