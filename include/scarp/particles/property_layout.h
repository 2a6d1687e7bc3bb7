#ifndef scarp_particles_property_layout_h
#define scarp_particles_property_layout_h

#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>
#include <deal.II/numerics/data_component_interpretation.h>

#include <string>
#include <vector>

namespace scarp
{
  namespace particles
  {
    using namespace dealii;

    /**
     * @brief Where each quantity of a material point sits in the flat array
     * of doubles that deal.II's ParticleHandler stores per particle.
     *
     * The layout is assembled from what the scene switches on: the affine
     * velocity matrix only with APIC, material state only as long as the
     * longest state of the scene's materials (an elastic scene carries no
     * damage history).
     */
    template <int dim>
    class PropertyLayout
    {
    public:
      /// Build the layout. @p apic adds the affine matrix C; @p state_names
      /// are the state variables of the material with the longest state.
      void
      build(const bool apic, const std::vector<std::string> &state_names);

      unsigned int
      n_properties() const
      {
        return n;
      }

      /// Offsets of the fields.
      unsigned int mass = 0, reference_volume = 0, velocity = 0,
                   deformation_gradient = 0, stress = 0, affine = 0,
                   reference_position = 0, material_id = 0, body_id = 0,
                   state = 0;
      unsigned int n_state = 0;
      bool         has_affine = false;

      /// Names for output (vector fields share one name).
      std::vector<std::string>
      names() const;
      std::vector<DataComponentInterpretation::DataComponentInterpretation>
      interpretations() const;

      /// Accessors on a property array.
      static Tensor<1, dim>
      get_vector(const double *p, const unsigned int offset)
      {
        Tensor<1, dim> v;
        for (unsigned int d = 0; d < dim; ++d)
          v[d] = p[offset + d];
        return v;
      }
      static void
      set_vector(double *p, const unsigned int offset, const Tensor<1, dim> &v)
      {
        for (unsigned int d = 0; d < dim; ++d)
          p[offset + d] = v[d];
      }
      static Tensor<2, dim>
      get_matrix(const double *p, const unsigned int offset)
      {
        Tensor<2, dim> m;
        for (unsigned int i = 0; i < dim; ++i)
          for (unsigned int j = 0; j < dim; ++j)
            m[i][j] = p[offset + i * dim + j];
        return m;
      }
      static void
      set_matrix(double *p, const unsigned int offset, const Tensor<2, dim> &m)
      {
        for (unsigned int i = 0; i < dim; ++i)
          for (unsigned int j = 0; j < dim; ++j)
            p[offset + i * dim + j] = m[i][j];
      }
      /// Stress is stored as xx, yy, zz, xy, xz, yz (deal.II's unrolled
      /// order of SymmetricTensor<2,3>).
      static SymmetricTensor<2, 3>
      get_stress(const double *p, const unsigned int offset)
      {
        SymmetricTensor<2, 3> s;
        for (unsigned int k = 0; k < 6; ++k)
          s.access_raw_entry(k) = p[offset + k];
        return s;
      }
      static void
      set_stress(double                      *p,
                 const unsigned int           offset,
                 const SymmetricTensor<2, 3> &s)
      {
        for (unsigned int k = 0; k < 6; ++k)
          p[offset + k] = s.access_raw_entry(k);
      }

    private:
      unsigned int             n = 0;
      std::vector<std::string> state_names;
    };
  } // namespace particles
} // namespace scarp

#endif
