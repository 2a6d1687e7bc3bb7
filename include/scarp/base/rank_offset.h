#ifndef scarp_base_rank_offset_h
#define scarp_base_rank_offset_h

#include <deal.II/base/mpi.h>
#include <deal.II/particles/property_pool.h>

namespace scarp
{
  using namespace dealii;

  /// The sum of @p n_local over the ranks below this one (0 on rank 0):
  /// where this rank's range starts when each rank numbers @p n_local
  /// new items (points, ids) consecutively. deal.II 9.4 has no
  /// Utilities::MPI::partial_and_total_sum yet.
  inline types::particle_index
  rank_offset(const types::particle_index n_local, const MPI_Comm communicator)
  {
    types::particle_index offset = 0;
    MPI_Exscan(&n_local,
               &offset,
               1,
               Utilities::MPI::mpi_type_id_for_type<types::particle_index>,
               MPI_SUM,
               communicator);
    // MPI leaves the result on rank 0 undefined.
    if (Utilities::MPI::this_mpi_process(communicator) == 0)
      offset = 0;
    return offset;
  }
} // namespace scarp

#endif
