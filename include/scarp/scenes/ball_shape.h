#ifndef scarp_scenes_ball_shape_h
#define scarp_scenes_ball_shape_h

#include <scarp/scenes/shape.h>

namespace scarp
{
  namespace scenes
  {
    /**
     * @brief A disk (2D) or ball (3D): the closed set |x - centre| <= radius.
     */
    template <int dim>
    class BallShape : public Shape<dim>
    {
    public:
      /// Throws unless @p radius is positive.
      BallShape(const Point<dim> &centre, const double radius);

      bool
      contains(const Point<dim> &point) const override;

      BoundingBox<dim>
      bounding_box() const override;

      const Point<dim> &
      centre() const;

      double
      radius() const;

    private:
      Point<dim> ball_centre;
      double     ball_radius;
    };
  } // namespace scenes
} // namespace scarp

#endif
