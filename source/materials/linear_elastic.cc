#include <scarp/materials/hencky_strain.h>
#include <scarp/materials/linear_elastic.h>

namespace scarp
{
  namespace materials
  {
    LinearElastic::LinearElastic(const double               density,
                                 const IsotropicElasticity &elasticity)
      : rho(density)
      , elasticity(elasticity)
    {
      AssertThrow(density > 0.,
                  ExcMessage("Material: 'Density' must be > 0 kg/m^3."));
    }


    std::vector<std::string>
    LinearElastic::state_variable_names() const
    {
      return {"elastic_strain_xx",
              "elastic_strain_yy",
              "elastic_strain_zz",
              "elastic_strain_xy",
              "elastic_strain_yz",
              "elastic_strain_xz"};
    }


    void
    LinearElastic::initialize_state(const SymmetricTensor<2, 3> &initial_stress,
                                    double                      *state) const
    {
      store_symmetric(elasticity.strain(initial_stress), state);
    }


    void
    LinearElastic::update(const MaterialBatch &batch) const
    {
      SpectralDecomposition trial[hencky_chunk];
      for (unsigned int q = 0; q < batch.n; ++q)
        {
          double *const                state = batch.state[q];
          const SpectralDecomposition &e     = hencky_trial_strain_by_chunks(
            batch.delta_F, batch.state, batch.n, q, trial);
          const std::array<double, 3> tau =
            elasticity.principal_stress(e.values);
          const double J = determinant(batch.F[q]);
          store_composed(e.values, e.vectors, state);
          compose_scaled_into(tau, e.vectors, 1. / J, batch.stress[q]);
          if (batch.stored_energy != nullptr)
            batch.stored_energy[q] =
              0.5 * (tau[0] * e.values[0] + tau[1] * e.values[1] +
                     tau[2] * e.values[2]);
        }
    }
  } // namespace materials
} // namespace scarp
