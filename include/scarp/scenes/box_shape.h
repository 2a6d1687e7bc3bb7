#ifndef scarp_scenes_box_shape_h
#define scarp_scenes_box_shape_h

#include <scarp/scenes/shape.h>

namespace scarp
{
  namespace scenes
  {
    /**
     * @brief An axis-aligned box (a rectangle in 2D), given by two opposite
     * corners in any order.
     *
     * The box is half open, [lower, upper) in every direction: boxes that
     * tile space then split a set of points without double counting, and a
     * box one cell wide holds exactly one cell's worth of a regular particle
     * lattice (this matters for the one-cell-wide tension crack).
     */
    template <int dim>
    class BoxShape : public Shape<dim>
    {
    public:
      /// Throws if the box has zero extent in some direction.
      BoxShape(const Point<dim> &corner_a, const Point<dim> &corner_b);

      bool
      contains(const Point<dim> &point) const override;

      BoundingBox<dim>
      bounding_box() const override;

      /// The corner with the smallest coordinates.
      const Point<dim> &
      lower_corner() const;

      /// The corner with the largest coordinates.
      const Point<dim> &
      upper_corner() const;

      /// Area (2D) or volume (3D).
      double
      measure() const;

    private:
      Point<dim> lower;
      Point<dim> upper;
    };
  } // namespace scenes
} // namespace scarp

#endif
