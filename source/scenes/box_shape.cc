#include <deal.II/base/exceptions.h>

#include <scarp/scenes/box_shape.h>

#include <algorithm>
#include <sstream>

namespace scarp
{
  namespace scenes
  {
    template <int dim>
    BoxShape<dim>::BoxShape(const Point<dim> &corner_a,
                            const Point<dim> &corner_b)
    {
      for (unsigned int d = 0; d < dim; ++d)
        {
          lower[d] = std::min(corner_a[d], corner_b[d]);
          upper[d] = std::max(corner_a[d], corner_b[d]);
          if (!(upper[d] > lower[d]))
            {
              std::ostringstream message;
              message << "Box corners: the box (" << corner_a << ") - ("
                      << corner_b << ") has zero extent in direction " << d
                      << ".";
              AssertThrow(false, ExcMessage(message.str()));
            }
        }
    }


    template <int dim>
    bool
    BoxShape<dim>::contains(const Point<dim> &point) const
    {
      for (unsigned int d = 0; d < dim; ++d)
        if (point[d] < lower[d] || !(point[d] < upper[d]))
          return false;
      return true;
    }


    template <int dim>
    BoundingBox<dim>
    BoxShape<dim>::bounding_box() const
    {
      return BoundingBox<dim>(std::make_pair(lower, upper));
    }


    template <int dim>
    const Point<dim> &
    BoxShape<dim>::lower_corner() const
    {
      return lower;
    }


    template <int dim>
    const Point<dim> &
    BoxShape<dim>::upper_corner() const
    {
      return upper;
    }


    template <int dim>
    double
    BoxShape<dim>::measure() const
    {
      double result = 1.;
      for (unsigned int d = 0; d < dim; ++d)
        result *= upper[d] - lower[d];
      return result;
    }


    template class BoxShape<2>;
    template class BoxShape<3>;
  } // namespace scenes
} // namespace scarp
