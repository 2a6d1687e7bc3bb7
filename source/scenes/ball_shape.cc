#include <deal.II/base/exceptions.h>

#include <scarp/scenes/ball_shape.h>

#include <sstream>

namespace scarp
{
  namespace scenes
  {
    template <int dim>
    BallShape<dim>::BallShape(const Point<dim> &centre, const double radius)
      : ball_centre(centre)
      , ball_radius(radius)
    {
      std::ostringstream message;
      message << "Radius must be positive, got " << radius << ".";
      AssertThrow(radius > 0., ExcMessage(message.str()));
    }


    template <int dim>
    bool
    BallShape<dim>::contains(const Point<dim> &point) const
    {
      // Squared distances: no square root per point.
      return (point - ball_centre).norm_square() <= ball_radius * ball_radius;
    }


    template <int dim>
    BoundingBox<dim>
    BallShape<dim>::bounding_box() const
    {
      Point<dim> lower = ball_centre, upper = ball_centre;
      for (unsigned int d = 0; d < dim; ++d)
        {
          lower[d] -= ball_radius;
          upper[d] += ball_radius;
        }
      return BoundingBox<dim>(std::make_pair(lower, upper));
    }


    template <int dim>
    const Point<dim> &
    BallShape<dim>::centre() const
    {
      return ball_centre;
    }


    template <int dim>
    double
    BallShape<dim>::radius() const
    {
      return ball_radius;
    }


    template class BallShape<2>;
    template class BallShape<3>;
  } // namespace scenes
} // namespace scarp
