#ifndef scarp_scenes_shape_factory_h
#define scarp_scenes_shape_factory_h

#include <deal.II/base/parameter_handler.h>

#include <scarp/scenes/cliff_profile.h>
#include <scarp/scenes/shape.h>

#include <memory>

namespace scarp
{
  namespace scenes
  {
    /**
     * @brief Builds a Shape from the entries of the current subsection of a
     * scene file (for instance "subsection Body rock" or "subsection
     * Pre-damaged region crack").
     *
     * Entries: "Shape" (box|ball|polygon|cliff), "Box corners", "Centre",
     * "Radius", "Vertices" and the subsection "Cliff" (see CliffProfile).
     * All are declared in 2D and 3D, so that a scene file reads the same;
     * polygon and cliff are 2D only and create() rejects them in 3D.
     */
    template <int dim>
    class ShapeFactory
    {
    public:
      /// Declares the entries in the current subsection.
      static void
      declare_parameters(ParameterHandler &prm);

      /// Reads the entries of the current subsection and returns the shape;
      /// throws an ExcMessage naming the entry on bad input. For "cliff" the
      /// shape is the cliff body (CliffProfile::body()).
      static std::unique_ptr<Shape<dim>>
      create(ParameterHandler &prm);

      /// The cliff profile of the current subsection when "Shape = cliff"
      /// (for the tension crack, the toe and the diagnostics), nullptr
      /// otherwise. Throws in 3D if the shape is a cliff.
      static std::unique_ptr<CliffProfile>
      create_cliff_profile(ParameterHandler &prm);
    };
  } // namespace scenes
} // namespace scarp

#endif
