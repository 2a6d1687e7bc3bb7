#include <scarp/particles/property_layout.h>

namespace scarp
{
  namespace particles
  {
    template <int dim>
    void
    PropertyLayout<dim>::build(const bool                      apic,
                               const std::vector<std::string> &names)
    {
      unsigned int next = 0;
      mass              = next++;
      reference_volume  = next++;
      velocity          = next;
      next += dim;
      deformation_gradient = next;
      next += dim * dim;
      stress = next;
      next += 6;
      has_affine = apic;
      affine     = next;
      if (apic)
        next += dim * dim;
      reference_position = next;
      next += dim;
      material_id = next++;
      body_id     = next++;
      state       = next;
      n_state     = names.size();
      state_names = names;
      next += n_state;
      n = next;
    }


    template <int dim>
    std::vector<std::string>
    PropertyLayout<dim>::names() const
    {
      std::vector<std::string> result;
      result.push_back("mass");
      result.push_back("reference_volume");
      for (unsigned int d = 0; d < dim; ++d)
        result.push_back("velocity");
      for (unsigned int i = 0; i < dim; ++i)
        for (unsigned int j = 0; j < dim; ++j)
          result.push_back("F_" + std::to_string(i) + std::to_string(j));
      for (const char *s : {"stress_xx",
                            "stress_yy",
                            "stress_zz",
                            "stress_xy",
                            "stress_xz",
                            "stress_yz"})
        result.push_back(s);
      if (has_affine)
        for (unsigned int i = 0; i < dim; ++i)
          for (unsigned int j = 0; j < dim; ++j)
            result.push_back("C_" + std::to_string(i) + std::to_string(j));
      for (unsigned int d = 0; d < dim; ++d)
        result.push_back("reference_position");
      result.push_back("material_id");
      result.push_back("body_id");
      for (const auto &s : state_names)
        result.push_back(s);
      return result;
    }


    template <int dim>
    std::vector<DataComponentInterpretation::DataComponentInterpretation>
    PropertyLayout<dim>::interpretations() const
    {
      std::vector<DataComponentInterpretation::DataComponentInterpretation>
        result(n, DataComponentInterpretation::component_is_scalar);
      for (unsigned int d = 0; d < dim; ++d)
        {
          result[velocity + d] =
            DataComponentInterpretation::component_is_part_of_vector;
          result[reference_position + d] =
            DataComponentInterpretation::component_is_part_of_vector;
        }
      return result;
    }

    template class PropertyLayout<2>;
    template class PropertyLayout<3>;
  } // namespace particles
} // namespace scarp
