#include <deal.II/base/mpi.h>

#include <scarp/base/rank_offset.h>
#include <scarp/particles/point_splitter.h>
#include <scarp/particles/pool_growth.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace scarp
{
  namespace particles
  {
    template <int dim>
    types::particle_index
    PointSplitter<dim>::split(
      Particles::ParticleHandler<dim> &particles,
      const PropertyLayout<dim>       &layout,
      const std::vector<unsigned int> &points_per_direction,
      const BoundingBox<dim>          &box,
      const MPI_Comm                   communicator,
      const bool                       current_volume)
    {
      constexpr unsigned int n_children = 1u << dim;
      struct Child
      {
        Point<dim>                                        location;
        typename Triangulation<dim>::active_cell_iterator cell;
        std::vector<double>                               properties;
      };
      std::vector<Child>    children;
      types::particle_index max_id = 0;
      for (auto &particle : particles)
        {
          max_id           = std::max(max_id, particle.get_id());
          double *const p  = particle.get_properties().data();
          const double  V0 = p[layout.reference_volume];
          // A compressed point still splits by V0 in a refined cell.
          const double V =
            current_volume
              ? std::max(V0,
                         V0 * std::abs(determinant(layout.get_matrix(
                                p, layout.deformation_gradient))))
              : V0;
          const double       side = dim == 2 ? std::sqrt(V) : std::cbrt(V);
          const auto         cell = particle.get_surrounding_cell();
          const double       h    = cell->vertex(1)[0] - cell->vertex(0)[0];
          const unsigned int n =
            points_per_direction[static_cast<unsigned int>(p[layout.body_id])];
          // Between the lattice side h/n of the cell and twice it.
          if (!(side > std::sqrt(2.) * h / n))
            continue;
          // By the current volume a point splits at most once below its
          // cell's share: children of a point dilated a thousandfold would
          // split again at every check, ever lighter (the cascade that
          // made a level-2 run unstable).
          if (current_volume && !(V0 >= 0.5 * std::pow(h / n, dim)))
            continue;
          const Point<dim>     x = particle.get_location();
          const Tensor<2, dim> F =
            layout.get_matrix(p, layout.deformation_gradient);
          const Tensor<2, dim> F_inv = invert(F);
          const Point<dim> X(layout.get_vector(p, layout.reference_position));
          // The children's offsets: by the reference volume at the centres
          // of the 2^dim sub-boxes of the axis-aligned box of side
          // V0^(1/dim) (GIMP's domain); by the current volume at F times
          // those of the reference box, so that they stay inside the
          // parallelogram the point has become. Both are kept inside the
          // mesh box.
          const double a =
            current_volume ? (dim == 2 ? std::sqrt(V0) : std::cbrt(V0)) : side;
          p[layout.mass] /= n_children;
          p[layout.reference_volume] /= n_children;
          const std::vector<double> parent(p, p + layout.n_properties());
          for (unsigned int c = 0; c < n_children; ++c)
            {
              Tensor<1, dim> offset;
              for (unsigned int d = 0; d < dim; ++d)
                offset[d] = ((c >> d) & 1u ? 0.25 : -0.25) * a;
              if (current_volume)
                offset = F * offset;
              // At most half-way to the nearer face of the box, the same
              // on both sides (the children keep the parent's centre), and
              // at most half the parent's cell: a child stays in that cell
              // or one touching it, which its rank owns or has as a ghost,
              // when the split goes by the current volume (F times the
              // offsets of a point stretched tenfold reaches several cells;
              // beyond the ghost layer the sort lost such children, and
              // their mass, without a word). A split by the reference
              // volume keeps the exact sub-boxes: a quarter of the side of
              // a point from a cell k levels coarser, h 2^(k-2) / n.
              for (unsigned int d = 0; d < dim; ++d)
                {
                  const double reach = std::min(
                    current_volume ? 0.5 * h
                                   : std::numeric_limits<double>::max(),
                    0.5 * std::max(0.,
                                   std::min(x[d] - box.lower_bound(d),
                                            box.upper_bound(d) - x[d])));
                  offset[d] = std::max(-reach, std::min(offset[d], reach));
                }
              const Tensor<1, dim> dX = F_inv * offset;
              if (c == 0)
                {
                  particle.set_location(x + offset);
                  layout.set_vector(p, layout.reference_position, X + dX);
                  continue;
                }
              Child child{x + offset, cell, parent};
              layout.set_vector(child.properties.data(),
                                layout.reference_position,
                                X + dX);
              children.push_back(std::move(child));
            }
        }

      // Ids: ranks take consecutive ranges above the largest id in use.
      max_id = Utilities::MPI::max(max_id, communicator);
      const types::particle_index n_local = children.size();
      const types::particle_index first   = rank_offset(n_local, communicator);
      types::particle_index       id      = max_id + 1 + first;
      PoolGrowth::reserve(particles, children.size());
      for (const Child &child : children)
        {
          // The reference location in the parent's cell (sorting moves a
          // child that lies in a neighbour).
          const Point<dim> x0 = child.cell->vertex(0);
          const double     h  = child.cell->vertex(1)[0] - x0[0];
          Point<dim>       xi;
          for (unsigned int d = 0; d < dim; ++d)
            xi[d] = (child.location[d] - x0[d]) / h;
          particles.insert_particle(child.location,
                                    xi,
                                    id++,
                                    child.cell,
                                    ArrayView<const double>(child.properties));
        }
      particles.update_cached_numbers();
      return Utilities::MPI::sum(n_local, communicator) / (n_children - 1);
    }

    template class PointSplitter<2>;
    template class PointSplitter<3>;
  } // namespace particles
} // namespace scarp
