// Writes the same points twice: with deal.II's Particles::DataOut (one piece
// per rank) into reference/, and with ParticleVtuWriter in chunks of 64
// points (several pieces per file) into chunked/. The script
// particle_vtu_writer.sh then reads both back and requires the same files,
// the same points and the same values (tools/read_particles.py).
//
// Two outputs: index 7 with points in every cell (about 512 per rank on 2
// ranks: 8 pieces), index 8 with points only below y = 0.5, which leaves the
// second of 2 ranks without any (its file must still be a valid, empty
// piece). The properties: a scalar, a vector and a tensor, so that the
// vector and tensor ranges of the PVTU record are checked too.
#include <deal.II/base/mpi.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/fe/mapping_q1.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/particles/data_out.h>
#include <deal.II/particles/particle_handler.h>

#include <scarp/base/rank_offset.h>
#include <scarp/postprocess/particle_vtu_writer.h>

#include <filesystem>
#include <vector>

using namespace dealii;

namespace
{
  constexpr int dim = 2;

  void
  write_both(const bool only_lower_half, const unsigned int index)
  {
    const MPI_Comm                            comm = MPI_COMM_WORLD;
    parallel::distributed::Triangulation<dim> tria(comm);
    GridGenerator::subdivided_hyper_cube(tria, 16);
    const MappingQ1<dim> mapping;

    std::vector<std::string> names = {"mass"};
    std::vector<DataComponentInterpretation::DataComponentInterpretation>
      kinds = {DataComponentInterpretation::component_is_scalar};
    for (unsigned int d = 0; d < dim; ++d)
      {
        names.push_back("velocity");
        kinds.push_back(
          DataComponentInterpretation::component_is_part_of_vector);
      }
    for (unsigned int d = 0; d < dim * dim; ++d)
      {
        names.push_back("deformation_gradient");
        kinds.push_back(
          DataComponentInterpretation::component_is_part_of_tensor);
      }

    Particles::ParticleHandler<dim> particles(tria, mapping, names.size());
    const std::vector<Point<dim>>   lattice = {Point<dim>(0.25, 0.25),
                                               Point<dim>(0.75, 0.25),
                                               Point<dim>(0.25, 0.75),
                                               Point<dim>(0.75, 0.75)};
    std::vector<
      std::pair<typename Triangulation<dim>::active_cell_iterator, Point<dim>>>
      places;
    for (const auto &cell : tria.active_cell_iterators())
      if (cell->is_locally_owned() &&
          (!only_lower_half || cell->center()[1] < 0.5))
        for (const Point<dim> &xi : lattice)
          places.emplace_back(cell, xi);
    const types::particle_index first = scarp::rank_offset(places.size(), comm);
    std::vector<double>         properties(names.size());
    for (unsigned int k = 0; k < places.size(); ++k)
      {
        const types::particle_index id = first + k;
        for (unsigned int c = 0; c < properties.size(); ++c)
          properties[c] = 0.5 * id + 0.125 * c - 3.;
        const auto      &cell = places[k].first;
        const Point<dim> x =
          mapping.transform_unit_to_real_cell(cell, places[k].second);
        particles.insert_particle(
          x, places[k].second, id, cell, make_array_view(properties));
      }
    particles.update_cached_numbers();

    DataOutBase::VtkFlags flags;
    flags.time = 1.5;
    flags.compression_level =
      DataOutBase::VtkFlags::ZlibCompressionLevel::best_speed;

    Particles::DataOut<dim> reference;
    reference.build_patches(particles, names, kinds);
    reference.set_flags(flags);
    reference.write_vtu_with_pvtu_record(
      "reference/", "particles", index, comm, 5, 0);

    const scarp::postprocess::ParticleVtuWriter<dim> writer(names, kinds, 64);
    writer.write(particles, "chunked/", "particles", index, flags, comm);
  }
} // namespace

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
    for (const char *d : {"reference", "chunked"})
      {
        std::filesystem::remove_all(d);
        std::filesystem::create_directory(d);
      }
  MPI_Barrier(MPI_COMM_WORLD);
  write_both(false, 7);
  write_both(true, 8);
  return 0;
}
