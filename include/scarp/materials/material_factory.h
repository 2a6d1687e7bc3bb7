#ifndef scarp_materials_material_factory_h
#define scarp_materials_material_factory_h

#include <deal.II/base/parameter_handler.h>

#include <scarp/materials/material.h>

#include <memory>

namespace scarp
{
  namespace materials
  {
    /**
     * @brief Declares the parameters of a material and creates the model
     * selected by `Model` from them.
     *
     * Entries (in the current subsection, which the caller enters, e.g.
     * `subsection Material chalk`): `Model`, `Density`, and subsections
     * `Elasticity`, `Mohr-Coulomb`, `Damage`. All models share the same
     * entries so that a scene can switch models by one line; entries a
     * model does not use are ignored. Defaults: Joss Bay chalk.
     */
    class MaterialFactory
    {
    public:
      static void
      declare_parameters(ParameterHandler &prm);

      /// Create the model from the entries of the current subsection.
      /// Throws ExcMessage naming the entry for impossible values.
      static std::unique_ptr<Material>
      create(ParameterHandler &prm);
    };
  } // namespace materials
} // namespace scarp

#endif
