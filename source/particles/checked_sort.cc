#include <deal.II/base/bounding_box.h>
#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>

#include <deal.II/grid/grid_tools.h>

#include <scarp/particles/checked_sort.h>

#include <array>
#include <iomanip>
#include <limits>
#include <sstream>

namespace scarp
{
  namespace particles
  {
    template <int dim>
    void
    CheckedSort<dim>::sort(Particles::ParticleHandler<dim> &particles,
                           const Triangulation<dim>        &triangulation,
                           const unsigned int               mass_index,
                           const std::string               &when,
                           const MPI_Comm                   communicator)
    {
      // Every rank holds the whole coarse mesh: the same box everywhere.
      const BoundingBox<dim> box =
        GridTools::compute_bounding_box(triangulation);
      const auto inside = [&](const Point<dim> &x) {
        for (unsigned int d = 0; d < dim; ++d)
          {
            const double margin = 1e-10 * box.side_length(d);
            if (!(x[d] > box.lower_bound(d) + margin &&
                  x[d] < box.upper_bound(d) - margin))
              return false;
          }
        return true;
      };

      unsigned int n_lost = 0;
      double       mass   = 0.;
      Point<dim>   first;
      const auto   connection = particles.signals.particle_lost.connect(
        [&](const typename Particles::ParticleIterator<dim> &particle,
            const typename Triangulation<dim>::active_cell_iterator &) {
          if (!inside(particle->get_location()))
            return;
          if (n_lost == 0)
            first = particle->get_location();
          ++n_lost;
          if (mass_index != numbers::invalid_unsigned_int)
            mass += particle->get_properties()[mass_index];
        });
      particles.sort_particles_into_subdomains_and_cells();
      connection.disconnect();

      const unsigned int n_total = Utilities::MPI::sum(n_lost, communicator);
      if (n_total == 0)
        return;
      // Where the first loss was: from the lowest rank that lost a point.
      const unsigned int rank = Utilities::MPI::this_mpi_process(communicator);
      const unsigned int first_rank =
        Utilities::MPI::min(n_lost > 0
                              ? rank
                              : std::numeric_limits<unsigned int>::max(),
                            communicator);
      std::array<double, dim> where;
      for (unsigned int d = 0; d < dim; ++d)
        where[d] = first[d];
      where = Utilities::MPI::broadcast(communicator, where, first_rank);
      std::ostringstream message;
      message << std::setprecision(6) << n_total << " material point(s)";
      if (mass_index != numbers::invalid_unsigned_int)
        message << " with " << Utilities::MPI::sum(mass, communicator)
                << " kg (per metre in 2D)";
      message << " lost inside the mesh in the sort " << when
              << ": beyond the cells their rank owns or has as ghosts; the "
                 "first at (";
      for (unsigned int d = 0; d < dim; ++d)
        message << where[d] << (d + 1 < dim ? ", " : ")");
      message << ". A lost point is lost mass; the run stops.";
      AssertThrow(false, ExcMessage(message.str()));
    }

    template class CheckedSort<2>;
    template class CheckedSort<3>;
  } // namespace particles
} // namespace scarp
