#ifndef scarp_scenes_shape_h
#define scarp_scenes_shape_h

#include <deal.II/base/bounding_box.h>
#include <deal.II/base/point.h>

namespace scarp
{
  namespace scenes
  {
    using namespace dealii;

    /**
     * @brief A region of space: answers whether a point lies inside it.
     *
     * Shapes describe where a body is seeded with particles and which
     * particles start damaged. They are used once, at set-up, so a virtual
     * call per point is acceptable here (it is not in the time step).
     */
    template <int dim>
    class Shape
    {
    public:
      virtual ~Shape() = default;

      /// Whether @p point lies inside the shape. Each implementation
      /// documents its convention for points on the boundary.
      virtual bool
      contains(const Point<dim> &point) const = 0;

      /// An axis-aligned box that contains the whole shape, for instance to
      /// skip cells that cannot hold any of its particles.
      virtual BoundingBox<dim>
      bounding_box() const = 0;
    };
  } // namespace scenes
} // namespace scarp

#endif
