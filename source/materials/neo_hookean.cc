#include <scarp/materials/neo_hookean.h>

#include <cmath>

namespace scarp
{
  namespace materials
  {
    NeoHookean::NeoHookean(const double               density,
                           const IsotropicElasticity &elasticity)
      : rho(density)
      , elasticity(elasticity)
    {
      AssertThrow(density > 0.,
                  ExcMessage("Material: 'Density' must be > 0 kg/m^3."));
    }


    void
    NeoHookean::initialize_state(const SymmetricTensor<2, 3> &initial_stress,
                                 double *) const
    {
      AssertThrow(initial_stress.norm() == 0.,
                  ExcMessage("The neo-Hookean material is a function of the "
                             "total deformation and cannot start with a "
                             "non-zero initial stress."));
    }


    SymmetricTensor<2, 3>
    NeoHookean::cauchy_stress(const Tensor<2, 3> &F) const
    {
      // sigma = P F^T / J = (mu (F F^T - I) + lambda ln J I) / J: symmetric
      // by construction, so build it from b = F F^T directly.
      const double                J  = determinant(F);
      const double                mu = elasticity.shear_modulus();
      const SymmetricTensor<2, 3> b  = symmetrize(F * transpose(F));
      return (mu * (b - unit_symmetric_tensor<3>()) +
              elasticity.lambda() * std::log(J) * unit_symmetric_tensor<3>()) /
             J;
    }


    double
    NeoHookean::stored_energy(const Tensor<2, 3> &F) const
    {
      const double lnJ = std::log(determinant(F));
      const double mu  = elasticity.shear_modulus();
      return 0.5 * mu * (scalar_product(F, F) - 3.) - mu * lnJ +
             0.5 * elasticity.lambda() * lnJ * lnJ;
    }


    void
    NeoHookean::update(const MaterialBatch &batch) const
    {
      for (unsigned int q = 0; q < batch.n; ++q)
        {
          batch.stress[q] = cauchy_stress(batch.F[q]);
          if (batch.stored_energy != nullptr)
            batch.stored_energy[q] = stored_energy(batch.F[q]);
        }
    }
  } // namespace materials
} // namespace scarp
