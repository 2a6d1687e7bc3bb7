#include <deal.II/base/bounding_box.h>
#include <deal.II/base/mpi.h>
#include <deal.II/numerics/rtree.h>

#include <scarp/grid/refinement_marker.h>

#include <array>

namespace scarp
{
  namespace grid
  {
    template <int dim>
    unsigned int
    RefinementMarker<dim>::mark(
      parallel::distributed::Triangulation<dim> &tria,
      const std::vector<typename Triangulation<dim>::active_cell_iterator>
                        &seeds,
      const double       buffer,
      const unsigned int max_level)
    {
      const MPI_Comm comm = tria.get_communicator();
      // Seed boxes as plain numbers (lower corner, upper corner).
      std::vector<std::array<double, 2 * dim>> local;
      local.reserve(seeds.size());
      for (const auto &cell : seeds)
        {
          std::array<double, 2 * dim> b;
          const Point<dim>            lo = cell->vertex(0);
          const Point<dim>            hi =
            cell->vertex(GeometryInfo<dim>::vertices_per_cell - 1);
          for (unsigned int d = 0; d < dim; ++d)
            {
              b[d]       = lo[d] - buffer;
              b[dim + d] = hi[d] + buffer;
            }
          local.push_back(b);
        }
      const auto gathered = Utilities::MPI::all_gather(comm, local);
      std::vector<BoundingBox<dim>> boxes;
      for (const auto &rank_boxes : gathered)
        for (const auto &b : rank_boxes)
          {
            Point<dim> lo, hi;
            for (unsigned int d = 0; d < dim; ++d)
              {
                lo[d] = b[d];
                hi[d] = b[dim + d];
              }
            boxes.emplace_back(std::make_pair(lo, hi));
          }
      unsigned int n_flagged = 0;
      if (!boxes.empty())
        {
          const auto                    tree = pack_rtree(boxes);
          std::vector<BoundingBox<dim>> hits;
          for (const auto &cell : tria.active_cell_iterators())
            if (cell->is_locally_owned() &&
                static_cast<unsigned int>(cell->level()) < max_level)
              {
                // Shrunk by a hair: touching a buffer box only at its edge
                // does not count (round-off would decide).
                Point<dim> lo = cell->vertex(0),
                           hi = cell->vertex(
                             GeometryInfo<dim>::vertices_per_cell - 1);
                const double eps = 1e-9 * (hi[0] - lo[0]);
                for (unsigned int d = 0; d < dim; ++d)
                  {
                    lo[d] += eps;
                    hi[d] -= eps;
                  }
                hits.clear();
                tree.query(boost::geometry::index::intersects(
                             BoundingBox<dim>(std::make_pair(lo, hi))),
                           std::back_inserter(hits));
                if (!hits.empty())
                  {
                    cell->set_refine_flag();
                    ++n_flagged;
                  }
              }
        }
      return Utilities::MPI::sum(n_flagged, comm);
    }

    template class RefinementMarker<2>;
    template class RefinementMarker<3>;
  } // namespace grid
} // namespace scarp
