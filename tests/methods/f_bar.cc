// F-bar (Transfer/Volumetric averaging = F-bar, transfer/f_bar.h): the
// increment of one cell against the hand-computed form, and the wiring in
// the MPM step: with F-bar all points that stayed in one cell share their
// volume ratio J, without it they do not (Q1 and GIMP, MUSL and USL, 2D and
// 3D, a mesh with cells of two sizes). The physics (the undrained footing) is
// tests/examples/; 1 rank = 2 ranks is core_parallel_fbar.

#include <scarp/transfer/f_bar.h>

#include "../core/core_tools.h"

#include <map>
#include <tuple>

using namespace scarp_test;

namespace
{
  /// Relative distance of two tensors.
  template <int dim>
  double
  relative(const Tensor<2, dim> &a, const Tensor<2, dim> &b)
  {
    return (a - b).norm() / b.norm();
  }

  /// The isochoric part dF / det(dF)^(1/dim).
  template <int dim>
  Tensor<2, dim>
  isochoric(const Tensor<2, dim> &a)
  {
    return a / std::pow(determinant(a), 1. / dim);
  }

  void
  increment()
  {
    // Two points of a 2D cell, numbers chosen by hand: dJ = 1.1 and 0.9,
    // volumes 1 and 3, so dJbar = (1 * 1.1 + 3 * 0.9) / 4 = 0.95; the
    // first point also shears (the off-diagonal does not change dJ).
    {
      Tensor<2, 2> dF[2];
      dF[0][0][0]                    = 1.1;
      dF[0][1][1]                    = 1.0;
      dF[0][0][1]                    = 0.05;
      dF[1][0][0]                    = 1.0;
      dF[1][1][1]                    = 0.9;
      const Tensor<2, 2> original[2] = {dF[0], dF[1]};
      const double       volume[2]   = {1., 3.};
      const double       dJ_bar      = transfer::apply_f_bar<2>(dF, volume, 2);
      out() << "  2D: dJbar = " << dJ_bar
            << ", det dFbar = " << determinant(dF[0]) << ", "
            << determinant(dF[1]) << std::endl;
      check(std::abs(dJ_bar - 0.95) < 1e-15, "2D: dJbar = 0.95 (by hand)");
      // By hand: dFbar = sqrt(0.95 / dJ) dF.
      Tensor<2, 2> expected0, expected1;
      expected0[0][0] = std::sqrt(0.95 / 1.1) * 1.1;
      expected0[0][1] = std::sqrt(0.95 / 1.1) * 0.05;
      expected0[1][1] = std::sqrt(0.95 / 1.1) * 1.0;
      expected1[0][0] = std::sqrt(0.95 / 0.9) * 1.0;
      expected1[1][1] = std::sqrt(0.95 / 0.9) * 0.9;
      check(relative(dF[0], expected0) < 1e-15 &&
              relative(dF[1], expected1) < 1e-15,
            "2D: dFbar = sqrt(dJbar / dJ) dF (by hand), to round-off");
      check(std::abs(determinant(dF[0]) - 0.95) < 1e-15 &&
              std::abs(determinant(dF[1]) - 0.95) < 1e-15,
            "2D: det dFbar = dJbar at both points");
      check(relative(isochoric(dF[0]), isochoric(original[0])) < 1e-15 &&
              relative(isochoric(dF[1]), isochoric(original[1])) < 1e-15,
            "2D: the isochoric part of dF is kept");
    }
    // Four points of a 3D cell with general increments (rotation, shear,
    // stretch): dJbar the volume-weighted mean of their determinants.
    {
      Tensor<2, 3> dF[4], original[4];
      double       volume[4], sum_v = 0, sum_vj = 0;
      for (unsigned int p = 0; p < 4; ++p)
        {
          for (unsigned int i = 0; i < 3; ++i)
            for (unsigned int j = 0; j < 3; ++j)
              dF[p][i][j] = (i == j ? 1. : 0.) +
                            0.01 * std::sin(1. + p + 3. * i + 7. * j) +
                            (i == j ? 0.02 * p : 0.);
          original[p] = dF[p];
          volume[p]   = 0.5 + 0.25 * p;
          sum_v += volume[p];
          sum_vj += volume[p] * determinant(dF[p]);
        }
      const double dJ_bar    = transfer::apply_f_bar<3>(dF, volume, 4);
      double       det_error = 0, iso_error = 0, ratio_error = 0;
      for (unsigned int p = 0; p < 4; ++p)
        {
          det_error =
            std::max(det_error, std::abs(determinant(dF[p]) / dJ_bar - 1));
          iso_error =
            std::max(iso_error,
                     relative(isochoric(dF[p]), isochoric(original[p])));
          // dFbar = (dJbar / dJ)^(1/3) dF, written out.
          ratio_error =
            std::max(ratio_error,
                     relative(dF[p],
                              Tensor<2, 3>(std::cbrt(sum_vj / sum_v /
                                                     determinant(original[p])) *
                                           original[p])));
        }
      out() << "  3D: dJbar = " << dJ_bar
            << ", |det dFbar / dJbar - 1| <= " << det_error
            << ", isochoric part to " << iso_error << std::endl;
      check(std::abs(dJ_bar / (sum_vj / sum_v) - 1) < 1e-15,
            "3D: dJbar = sum V dJ / sum V");
      check(det_error < 1e-14, "3D: det dFbar = dJbar at every point");
      check(iso_error < 1e-14, "3D: the isochoric part of dF is kept");
      check(ratio_error < 1e-15, "3D: dFbar = cbrt(dJbar / dJ) dF");
    }
    // A point that inverts (dJ < 0): the cell is left as it is, so that the
    // step's J check reports it (a cube root of a negative ratio would
    // hide it).
    {
      Tensor<2, 2> dF[2];
      dF[0][0][0]            = 1.0;
      dF[0][1][1]            = 1.0;
      dF[1][0][0]            = -0.1;
      dF[1][1][1]            = 1.0;
      const double volume[2] = {1., 1.};
      const double dJ_bar    = transfer::apply_f_bar<2>(dF, volume, 2);
      check(dJ_bar == 0 && dF[0][0][0] == 1.0 && dF[1][0][0] == -0.1,
            "a cell with an inverted point is left unchanged");
    }
  }

  /// A free elastic block (nu = 0.45) with a non-uniform initial velocity,
  /// run for ~10 steps without points leaving their cells; @p refined: the
  /// left half of the mesh one level finer (cells of two sizes, hanging
  /// nodes along x = 0.5 in the block).
  std::string
  block_scene(const unsigned int dim,
              const std::string &shapes,
              const std::string &scheme,
              const std::string &averaging,
              const bool         refined,
              const std::string &transfer = "FLIP")
  {
    const std::vector<double> lower(dim, 0.), upper(dim, 1.);
    std::vector<double>       corners(dim, 0.25);
    corners.resize(2 * dim, 0.75);
    std::vector<double> region(dim, 0.);
    region.resize(2 * dim, 1.);
    region[dim] = 0.5;
    const std::string velocity =
      dim == 2 ? "0.01 * x * y; -0.01 * x * x"
               : "0.01 * x * y; -0.01 * x * x; 0.01 * y * z";
    std::string mesh =
      mesh_text(lower, upper, 0.125, std::vector<std::string>(2 * dim, "free"));
    if (refined)
      mesh += "subsection Mesh\n  subsection Refinement\n    set Initial "
              "levels = 1\n    set Initial region = " +
              scarp_test::list(region) + "\n  end\nend\n";
    return scene_header(dim) + material_text("linear elastic", 1e6, 0.45, 1e3) +
           mesh + body_text("body", box_shape(corners), 2, velocity) +
           run_text(std::vector<double>(dim, 0.),
                    0.5,
                    0.01,
                    transfer,
                    scheme,
                    1e30,
                    "",
                    "  set Shape functions = " + shapes +
                      "\n  set Volumetric averaging = " + averaging + "\n");
  }

  /// Largest relative spread of J among the points of one active cell at
  /// the end; no point moves by more than 1e-2 of a cell (points start a
  /// quarter cell from its faces), so each stayed in its cell.
  template <int dim>
  double
  spread_of_J_in_cells(const std::string &text, const bool refined)
  {
    auto sim = make_scene<dim>(text, MPI_COMM_WORLD);
    check(sim->background_grid().triangulation().n_global_levels() ==
            (refined ? 2u : 1u),
          refined ? "cells of two sizes" : "cells of one size");
    sim->run_until(0.01);
    const auto &layout    = sim->property_layout();
    const auto &particles = sim->particle_handler();
    double      spread = 0, moved = 0, h_min = 1e30;
    for (const auto &cell :
         sim->background_grid().dof_handler().active_cell_iterators())
      if (cell->is_locally_owned())
        {
          h_min = std::min(h_min, cell->diameter() / std::sqrt(double(dim)));
          double J_min = 1e30, J_max = -1e30;
          for (const auto &particle : particles.particles_in_cell(cell))
            {
              const double *p = particle.get_properties().data();
              const double  J =
                determinant(layout.get_matrix(p, layout.deformation_gradient));
              J_min = std::min(J_min, J);
              J_max = std::max(J_max, J);
              Point<dim> X;
              for (unsigned int d = 0; d < dim; ++d)
                X[d] = p[layout.reference_position + d];
              moved = std::max(moved, particle.get_location().distance(X));
            }
          if (J_max >= J_min)
            spread = std::max(spread, (J_max - J_min) / J_min);
        }
    h_min = Utilities::MPI::min(h_min, MPI_COMM_WORLD);
    check(Utilities::MPI::max(moved, MPI_COMM_WORLD) < 1e-2 * h_min,
          "no point moved by 1e-2 of the smallest cell");
    return Utilities::MPI::max(spread, MPI_COMM_WORLD);
  }

  template <int dim>
  void
  cells(const std::string &shapes,
        const std::string &scheme,
        const bool         refined  = false,
        const std::string &transfer = "FLIP")
  {
    const double with = spread_of_J_in_cells<dim>(
      block_scene(dim, shapes, scheme, "F-bar", refined, transfer), refined);
    const double without = spread_of_J_in_cells<dim>(
      block_scene(dim, shapes, scheme, "none", refined, transfer), refined);
    out() << "  " << dim << "D " << shapes << "/" << scheme << "/" << transfer
          << (refined ? ", refined" : "")
          << ": spread of J within a cell, F-bar " << with << ", none "
          << without << std::endl;
    // With F-bar each step gives the points of a cell one dJbar (to a few
    // eps: det of the scaled increment); without, the velocity field
    // (gradients of ~1e-2 varying within cells) separates them by ~1e-5.
    check(with < 1e-13, "F-bar: one J per cell, to round-off");
    check(without > 1e-7, "none: the points of a cell differ in J");
  }
} // namespace

int
main(int argc, char **argv)
{
  return run_cases(
    argc,
    argv,
    {{"increment", increment},
     {"cells_q1_musl", [] { cells<2>("Q1", "MUSL"); }},
     {"cells_gimp_musl", [] { cells<2>("GIMP", "MUSL"); }},
     {"cells_gimp_musl_apic", [] { cells<2>("GIMP", "MUSL", false, "APIC"); }},
     {"cells_q1_usl_3d", [] { cells<3>("Q1", "USL"); }},
     {"cells_gimp_refined", [] { cells<2>("GIMP", "MUSL", true); }}});
}
