#ifndef scarp_materials_mohr_coulomb_h
#define scarp_materials_mohr_coulomb_h

#include <scarp/materials/isotropic_elasticity.h>
#include <scarp/materials/material.h>
#include <scarp/materials/mohr_coulomb_return.h>

namespace scarp
{
  namespace materials
  {
    /**
     * @brief Hencky elasticity with perfectly plastic Mohr-Coulomb flow
     * (non-associated through the dilation angle), returned in principal
     * Kirchhoff stress space by MohrCoulombReturn.
     *
     * State: eps_e (6), equivalent plastic strain, cumulative plastic
     * dissipation per reference volume (sum of tau : d eps_p, backward
     * Euler with the corrected stress).
     */
    class MohrCoulomb : public Material
    {
    public:
      /// Layout of the state array of a point.
      enum StateIndex : unsigned int
      {
        elastic_strain      = 0, ///< 6 values: xx, yy, zz, xy, yz, xz
        plastic_strain      = 6, ///< sum of sqrt(2/3 d eps_p : d eps_p)
        plastic_dissipation = 7, ///< [J/m^3]
        n_state             = 8
      };

      MohrCoulomb(const double                         density,
                  const IsotropicElasticity           &elasticity,
                  const MohrCoulombReturn::Parameters &strength);

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
        return n_state;
      }

      std::vector<std::string>
      state_variable_names() const override;

      /// eps_e = D^-1 : sigma; the stress is not checked against the yield
      /// surface (the first update returns it if needed).
      void
      initialize_state(const SymmetricTensor<2, 3> &initial_stress,
                       double                      *state) const override;

      /// Without batch.inelastic.plasticity pure Hencky elasticity (gravity
      /// loading stage).
      void
      update(const MaterialBatch &batch) const override;

      bool
      has_plasticity() const override
      {
        return true;
      }

      DissipatedEnergy
      dissipated_energy(const double *state) const override
      {
        return {state[plastic_dissipation], 0.};
      }

      const MohrCoulombReturn &
      get_return_mapping() const
      {
        return mohr_coulomb;
      }

      const IsotropicElasticity &
      get_elasticity() const
      {
        return elasticity;
      }

    private:
      const double              rho;
      const IsotropicElasticity elasticity;
      const MohrCoulombReturn   mohr_coulomb;
    };
  } // namespace materials
} // namespace scarp

#endif
