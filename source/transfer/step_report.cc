#include <deal.II/base/mpi.h>

#include <scarp/transfer/step_report.h>

#include <cmath>
#include <sstream>
#include <vector>

namespace scarp
{
  namespace transfer
  {
    void
    StepReport::reduce(MPI_Comm communicator)
    {
      std::vector<double> sums = {kinetic_energy,
                                  gravitational_energy,
                                  stored_energy,
                                  internal_work,
                                  damping_dissipation,
                                  boundary_dissipation,
                                  transfer_dissipation,
                                  body_force_work,
                                  removed_kinetic_energy,
                                  removed_gravitational_energy,
                                  mass,
                                  plastic_dissipation,
                                  damage_dissipation,
                                  damaged_volume,
                                  n_points,
                                  momentum[0],
                                  momentum[1],
                                  momentum[2],
                                  angular_momentum[0],
                                  angular_momentum[1],
                                  angular_momentum[2],
                                  n_not_finite,
                                  n_inverted,
                                  n_outside,
                                  n_too_fast,
                                  n_changed_cell,
                                  n_removed_stretched};
      Utilities::MPI::sum(sums, communicator, sums);
      unsigned int k = 0;
      for (double *x : {&kinetic_energy,
                        &gravitational_energy,
                        &stored_energy,
                        &internal_work,
                        &damping_dissipation,
                        &boundary_dissipation,
                        &transfer_dissipation,
                        &body_force_work,
                        &removed_kinetic_energy,
                        &removed_gravitational_energy,
                        &mass,
                        &plastic_dissipation,
                        &damage_dissipation,
                        &damaged_volume,
                        &n_points,
                        &momentum[0],
                        &momentum[1],
                        &momentum[2],
                        &angular_momentum[0],
                        &angular_momentum[1],
                        &angular_momentum[2],
                        &n_not_finite,
                        &n_inverted,
                        &n_outside,
                        &n_too_fast,
                        &n_changed_cell,
                        &n_removed_stretched})
        *x = sums[k++];
      // Ranks accumulate the squared speed (no root per point).
      std::vector<double> maxima = {max_speed, max_damage};
      Utilities::MPI::max(maxima, communicator, maxima);
      max_speed  = std::sqrt(maxima[0]);
      max_damage = maxima[1];
      if (n_failures() > 0)
        {
          const unsigned int my_rank =
            Utilities::MPI::this_mpi_process(communicator);
          const unsigned int first =
            Utilities::MPI::min(has_offender ? my_rank : ~0u, communicator);
          MPI_Bcast(offender.data(), 3, MPI_DOUBLE, first, communicator);
          has_offender = true;
        }
    }


    std::string
    StepReport::failure_message() const
    {
      if (n_failures() == 0)
        return "";
      std::ostringstream s;
      if (n_not_finite > 0)
        s << n_not_finite
          << " material point(s) have a NaN or infinite velocity, "
             "deformation gradient or stress. ";
      if (n_inverted > 0)
        s << n_inverted
          << " material point(s) have an inverted or collapsed volume "
             "(J <= 0). ";
      if (n_too_fast > 0)
        s << n_too_fast
          << " material point(s) moved more than a cell in one step. ";
      if (n_outside > 0)
        s << n_outside << " material point(s) left the background mesh. ";
      s << "First one near (" << offender[0] << ", " << offender[1] << ", "
        << offender[2] << ").";
      return s.str();
    }
  } // namespace transfer
} // namespace scarp
