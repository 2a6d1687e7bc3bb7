#include <scarp/materials/hencky_strain.h>
#include <scarp/materials/mohr_coulomb.h>

#include <cmath>

namespace scarp
{
  namespace materials
  {
    MohrCoulomb::MohrCoulomb(const double                         density,
                             const IsotropicElasticity           &elasticity,
                             const MohrCoulombReturn::Parameters &strength)
      : rho(density)
      , elasticity(elasticity)
      , mohr_coulomb(elasticity, strength)
    {
      AssertThrow(density > 0.,
                  ExcMessage("Material: 'Density' must be > 0 kg/m^3."));
    }


    std::vector<std::string>
    MohrCoulomb::state_variable_names() const
    {
      return {"elastic_strain_xx",
              "elastic_strain_yy",
              "elastic_strain_zz",
              "elastic_strain_xy",
              "elastic_strain_yz",
              "elastic_strain_xz",
              "plastic_strain",
              "plastic_dissipation"};
    }


    void
    MohrCoulomb::initialize_state(const SymmetricTensor<2, 3> &initial_stress,
                                  double                      *state) const
    {
      store_symmetric(elasticity.strain(initial_stress), state);
      state[plastic_strain]      = 0.;
      state[plastic_dissipation] = 0.;
    }


    void
    MohrCoulomb::update(const MaterialBatch &batch) const
    {
      SpectralDecomposition trial[hencky_chunk];
      for (unsigned int q = 0; q < batch.n; ++q)
        {
          double *const          state = batch.state[q];
          SpectralDecomposition &e     = hencky_trial_strain_by_chunks(
            batch.delta_F, batch.state, batch.n, q, trial);
          std::array<double, 3> tau = elasticity.principal_stress(e.values);
          if (batch.inelastic.plasticity &&
              mohr_coulomb.return_stress(tau) !=
                MohrCoulombReturn::Region::elastic)
            {
              // Principal plastic strain increment: trial minus corrected
              // elastic strain (same principal directions).
              const std::array<double, 3> eps =
                elasticity.principal_strain(tau);
              double dissipation = 0., norm2 = 0.;
              for (unsigned int i = 0; i < 3; ++i)
                {
                  const double dep = e.values[i] - eps[i];
                  dissipation += tau[i] * dep;
                  norm2 += dep * dep;
                  e.values[i] = eps[i];
                }
              state[plastic_strain] += std::sqrt(2. / 3. * norm2);
              state[plastic_dissipation] += dissipation;
            }
          store_composed(e.values, e.vectors, state + elastic_strain);
          compose_scaled_into(tau,
                              e.vectors,
                              1. / determinant(batch.F[q]),
                              batch.stress[q]);
          if (batch.stored_energy != nullptr)
            batch.stored_energy[q] =
              0.5 * (tau[0] * e.values[0] + tau[1] * e.values[1] +
                     tau[2] * e.values[2]);
        }
    }
  } // namespace materials
} // namespace scarp
