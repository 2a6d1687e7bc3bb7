#ifndef scarp_materials_linear_elastic_h
#define scarp_materials_linear_elastic_h

#include <scarp/materials/isotropic_elasticity.h>
#include <scarp/materials/material.h>

namespace scarp
{
  namespace materials
  {
    /**
     * @brief Hencky (logarithmic strain) hyperelasticity: Kirchhoff stress
     * tau = D : eps_e with eps_e = 1/2 ln b_e, updated incrementally by
     * b_e_trial = dF exp(2 eps_e) dF^T; Cauchy stress tau / J.
     *
     * Linear in the logarithmic strain, so it reduces to linear elasticity
     * for small strains, and it is exactly objective under large rotations
     * (no stress rate). State: eps_e (6 values: xx, yy, zz, xy, yz, xz).
     * Stored energy 1/2 eps_e : D : eps_e per reference volume.
     */
    class LinearElastic : public Material
    {
    public:
      LinearElastic(const double               density,
                    const IsotropicElasticity &elasticity);

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
        return 6;
      }

      std::vector<std::string>
      state_variable_names() const override;

      /// eps_e = D^-1 : sigma (small strain, F = I so tau = sigma).
      void
      initialize_state(const SymmetricTensor<2, 3> &initial_stress,
                       double                      *state) const override;

      void
      update(const MaterialBatch &batch) const override;

      const IsotropicElasticity &
      get_elasticity() const
      {
        return elasticity;
      }

    private:
      const double              rho;
      const IsotropicElasticity elasticity;
    };
  } // namespace materials
} // namespace scarp

#endif
