#include <deal.II/base/mpi.h>

#include <scarp/base/rank_offset.h>
#include <scarp/particles/body_seeder.h>
#include <scarp/particles/pool_growth.h>

namespace scarp
{
  namespace particles
  {
    template <int dim>
    types::particle_index
    BodySeeder<dim>::seed(const parallel::distributed::Triangulation<dim> &tria,
                          Particles::ParticleHandler<dim> &handler,
                          const BoundingBox<dim>          &region_box,
                          const std::function<bool(const Point<dim> &)> &inside,
                          const unsigned int          per_direction,
                          const types::particle_index first_id,
                          const Initializer          &initialize)
    {
      // Reference positions of the lattice inside one cell.
      std::vector<Point<dim>> lattice;
      const unsigned int      n_points = Utilities::pow(per_direction, dim);
      for (unsigned int k = 0; k < n_points; ++k)
        {
          Point<dim>   xi;
          unsigned int rest = k;
          for (unsigned int d = 0; d < dim; ++d)
            {
              xi[d] = (rest % per_direction + 0.5) / per_direction;
              rest /= per_direction;
            }
          lattice.push_back(xi);
        }

      // First pass: which points are inside, to number them globally.
      struct NewPoint
      {
        typename Triangulation<dim>::active_cell_iterator cell;
        Point<dim>                                        x, xi;
        double                                            volume;
      };
      std::vector<NewPoint> points;
      for (const auto &cell : tria.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            const BoundingBox<dim> cell_box = cell->bounding_box();
            if (cell_box.get_neighbor_type(region_box) ==
                NeighborType::not_neighbors)
              continue;
            const Point<dim> x0     = cell_box.get_boundary_points().first;
            const double     h      = cell_box.side_length(0);
            const double     volume = cell->measure() / n_points;
            for (const Point<dim> &xi : lattice)
              {
                const Point<dim> x = x0 + h * xi;
                if (inside(x))
                  points.push_back({cell, x, xi, volume});
              }
          }

      const types::particle_index n_local = points.size();
      const types::particle_index offset =
        rank_offset(n_local, tria.get_communicator());

      std::vector<double> properties(handler.n_properties_per_particle());
      PoolGrowth::reserve(handler, points.size());
      for (types::particle_index k = 0; k < n_local; ++k)
        {
          std::fill(properties.begin(), properties.end(), 0.);
          initialize(points[k].x, points[k].volume, properties.data());
          handler.insert_particle(points[k].x,
                                  points[k].xi,
                                  first_id + offset + k,
                                  points[k].cell,
                                  make_array_view(properties));
        }
      handler.update_cached_numbers();
      return Utilities::MPI::sum(n_local, tria.get_communicator());
    }

    template class BodySeeder<2>;
    template class BodySeeder<3>;
  } // namespace particles
} // namespace scarp
