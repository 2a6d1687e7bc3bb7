// CliffProfile: the default (Joss Bay) geometry against hand-computed
// points and areas, a vertical upper face, a notch reaching the upper face,
// the tension crack, the surface profile, and one error per impossible
// parameter combination, each naming the entry at fault.

#include <deal.II/base/parameter_handler.h>

#include <scarp/scenes/cliff_profile.h>

#include <map>

#include "check.h"

using namespace scarp::scenes;

namespace
{
  double
  cot(const double degrees)
  {
    return degrees == 90. ? 0. : 1. / std::tan(degrees * M_PI / 180.);
  }


  double
  lattice_area(const PolygonShape &polygon, const double h)
  {
    const auto bb    = polygon.bounding_box().get_boundary_points();
    double     count = 0;
    for (double x = bb.first[0] + h / 2; x < bb.second[0]; x += h)
      for (double y = bb.first[1] + h / 2; y < bb.second[1]; y += h)
        count += polygon.contains(Point<2>(x, y));
    return count * h * h;
  }


  double
  perimeter(const PolygonShape &polygon)
  {
    const auto &v      = polygon.vertices();
    double      result = 0.;
    for (unsigned int i = 0, j = v.size() - 1; i < v.size(); j = i++)
      result += v[i].distance(v[j]);
    return result;
  }


  CliffProfile
  parse(const std::map<std::string, std::string> &entries)
  {
    ParameterHandler prm;
    CliffProfile::declare_parameters(prm);
    prm.enter_subsection("Cliff");
    for (const auto &[name, value] : entries)
      prm.set(name, value);
    prm.leave_subsection();
    CliffProfile cliff;
    cliff.parse_parameters(prm);
    return cliff;
  }
} // namespace


int
main()
{
  // The default: Joss Bay, H = 15.5, 78 deg face, notch 0.5 m at 45 deg.
  {
    const CliffProfile cliff = parse({});
    const double       H = 15.5, cot_face = cot(78.), L_n = 0.5;
    const double       x_t = 31., x_c = x_t - H * cot_face, back = 27.7;
    CHECK_CLOSE(cliff.toe()[0], x_t, 1e-12);
    CHECK_CLOSE(cliff.toe()[1], 0., 1e-12);
    CHECK_CLOSE(cliff.crest()[0], x_c, 1e-12);
    CHECK_CLOSE(cliff.crest()[1], H, 1e-12);
    CHECK_CLOSE(cliff.back_position(), x_c - back, 1e-12);
    CHECK_CLOSE(cliff.top_level(), H, 1e-12);

    // Notch: triangle (x_t - L_n, 0), (x_t, 0) and the top at height
    // h_n = L_n / (cot 45 + cot 78) on the face.
    const double h_n = L_n / (1. + cot_face);
    CHECK_CLOSE(cliff.notch_root()[0], x_t - L_n, 1e-12);
    CHECK_CLOSE(cliff.notch_top()[1], h_n, 1e-12);
    CHECK_CLOSE(cliff.notch_top()[0], x_t - h_n * cot_face, 1e-12);
    CHECK_CLOSE(cliff.notch_top()[0], x_t - L_n + h_n, 1e-12);

    // Area: H * back + face triangle - notch wedge.
    const double area = H * back + 0.5 * H * H * cot_face - 0.5 * L_n * h_n;
    CHECK_CLOSE(cliff.area(), area, 1e-10);
    CHECK_CLOSE(cliff.body().area(), area, 1e-10);
    const double h = 0.02;
    CHECK_CLOSE(lattice_area(cliff.body(), h),
                area,
                perimeter(cliff.body()) * h / 2.);
    CHECK(cliff.body().vertices().size() == 5);

    // Points: body, notch, in front of the face, crack.
    CHECK(cliff.body().contains(Point<2>(1., 1.)));
    CHECK(cliff.body().contains(Point<2>(x_c - 0.01, H - 0.01)));
    CHECK(!cliff.body().contains(Point<2>(x_c + 0.05, H - 0.01)));
    CHECK(!cliff.body().contains(Point<2>(30.9, 0.02)));  // in the notch
    CHECK(!cliff.body().contains(Point<2>(30.55, 0.01))); // notch root
    CHECK(cliff.body().contains(Point<2>(30.45, 0.01)));  // behind it
    CHECK(cliff.body().contains(Point<2>(30.6, 0.3)));    // above the roof
    CHECK(cliff.body().contains(Point<2>(30.9, 0.45)));   // above the notch
    CHECK(!cliff.body().contains(Point<2>(30.95, 0.45))); // outside the face
    CHECK(!cliff.body().contains(Point<2>(32., 0.01)));   // beach

    // Crack: one cell wide, centred 2.2 m behind the crest, 5 m deep.
    CHECK(cliff.has_crack());
    CHECK_THROWS_WITH(cliff.crack_region(), "set_cell_size");
    CliffProfile with_cells = cliff;
    with_cells.set_cell_size(0.045);
    const BoxShape<2> crack = with_cells.crack_region();
    CHECK_CLOSE(crack.lower_corner()[0], x_c - 2.2 - 0.0225, 1e-12);
    CHECK_CLOSE(crack.upper_corner()[0], x_c - 2.2 + 0.0225, 1e-12);
    CHECK_CLOSE(crack.lower_corner()[1], H - 5., 1e-12);
    CHECK_CLOSE(crack.upper_corner()[1], H, 1e-12);
    CHECK(crack.contains(Point<2>(x_c - 2.2, H - 0.1)));
    CHECK(!crack.contains(Point<2>(x_c - 2.2, H - 5.1)));

    // Surface: top, face, beach; the notch is overhung and does not show.
    CHECK_CLOSE(cliff.surface_height(5.), H, 1e-12);
    CHECK_CLOSE(cliff.surface_height(x_c), H, 1e-12);
    CHECK_CLOSE(cliff.surface_height(x_t - 1.), 1. / cot_face, 1e-10);
    CHECK_CLOSE(cliff.surface_height(x_t - 0.1), 0.1 / cot_face, 1e-10);
    CHECK_CLOSE(cliff.surface_height(x_t + 1.), 0., 1e-12);
    CHECK_CLOSE(cliff.surface_height(cliff.back_position() - 1.), 0., 1e-12);
    const auto outline = cliff.surface_outline();
    CHECK(outline.size() == 5);
    CHECK(outline[1] == cliff.crest());
    CHECK(outline[2] == cliff.notch_top());
    CHECK(outline[3] == cliff.notch_root());
    CHECK(outline[4] == cliff.toe());
  }

  // Field survey shape: 6.6 m vertical upper face over an 80 deg face; the
  // notch stays on the lower face. Beach and toe moved.
  {
    const CliffProfile cliff = parse({{"Upper face height", "6.6"},
                                      {"Upper face angle", "90"},
                                      {"Lower face angle", "80"},
                                      {"Beach level", "2"},
                                      {"Toe position", "40"},
                                      {"Back length", "20"},
                                      {"Notch depth", "0.8"},
                                      {"Notch angle", "60"}});
    const double       H = 15.5, H_u = 6.6, H_l = H - H_u, y_b = 2.;
    const double       x_t = 40., x_k = x_t - H_l * cot(80.);
    CHECK_CLOSE(cliff.crest()[0], x_k, 1e-12);
    CHECK_CLOSE(cliff.crest()[1], y_b + H, 1e-12);
    const double h_n = 0.8 / (cot(60.) + cot(80.));
    CHECK_CLOSE(cliff.notch_top()[1], y_b + h_n, 1e-12);
    const double area = H * 20. + 0.5 * H_l * H_l * cot(80.) - 0.5 * 0.8 * h_n;
    CHECK_CLOSE(cliff.area(), area, 1e-10);
    CHECK_CLOSE(cliff.body().area(), area, 1e-10);
    CHECK(cliff.body().vertices().size() == 6); // with the knee
    CHECK(cliff.body().contains(Point<2>(x_k - 0.01, y_b + H - 0.1)));
    CHECK(!cliff.body().contains(Point<2>(x_k + 0.01, y_b + H - 0.1)));
    CHECK(!cliff.body().contains(Point<2>(x_k + 0.01, y_b + H_l + 0.1)));
    CHECK(cliff.body().contains(Point<2>(x_k + 0.01, y_b + H_l - 0.1)));
    CHECK_CLOSE(cliff.surface_height(x_k + 0.5 * (x_t - x_k)),
                y_b + 0.5 * H_l,
                1e-10);
    const double h = 0.02;
    CHECK_CLOSE(lattice_area(cliff.body(), h),
                area,
                perimeter(cliff.body()) * h / 2.);
  }

  // A low lower face (0.2 m): the notch roof meets the upper face, and the
  // notch is the quadrilateral N, T, K, U.
  {
    const CliffProfile cliff = parse({{"Upper face height", "15.3"},
                                      {"Upper face angle", "85"},
                                      {"Notch depth", "0.5"},
                                      {"Notch angle", "45"}});
    const double       H = 15.5, H_l = 0.2, x_t = 31., x_n = x_t - 0.5;
    const double       x_k = x_t - H_l * cot(78.);
    // Roof x = x_n + y meets the upper face x = x_k - (y - H_l) cot 85.
    const double h_n = (x_k - x_n + H_l * cot(85.)) / (1. + cot(85.));
    CHECK(h_n > H_l);
    CHECK_CLOSE(cliff.notch_top()[1], h_n, 1e-12);
    // Notch area = integral over y of (face - roof).
    const double notch = (x_t - x_n) * H_l - 0.5 * H_l * H_l * (cot(78.) + 1.) +
                         (x_k - x_n + H_l * cot(85.)) * (h_n - H_l) -
                         0.5 * (h_n * h_n - H_l * H_l) * (cot(85.) + 1.);
    const double x_c  = x_k - (H - H_l) * cot(85.);
    const double face = H_l * (x_k - x_c) + 0.5 * H_l * H_l * cot(78.) +
                        0.5 * (H - H_l) * (H - H_l) * cot(85.);
    const double area = H * 27.7 + face - notch;
    CHECK_CLOSE(cliff.area(), area, 1e-10);
    CHECK_CLOSE(cliff.body().area(), area, 1e-10);
    CHECK(cliff.body().vertices().size() == 5); // knee cut away
  }

  // No notch, no crack, lower face alone: a trapezoid.
  {
    const CliffProfile cliff =
      parse({{"Notch depth", "0"}, {"Crack depth", "0"}});
    CHECK(!cliff.has_crack());
    CHECK_THROWS_WITH(cliff.crack_region(), "Crack depth");
    CHECK(cliff.body().vertices().size() == 4);
    CHECK_CLOSE(cliff.area(),
                15.5 * 27.7 + 0.5 * 15.5 * 15.5 * cot(78.),
                1e-10);
    CHECK(cliff.notch_top() == cliff.toe());
  }

  // Programmatic construction and an explicit crack width.
  {
    CliffProfile::Parameters p;
    p.crack_width = 0.1;
    const CliffProfile cliff(p);
    const BoxShape<2>  crack = cliff.crack_region();
    CHECK_CLOSE(crack.upper_corner()[0] - crack.lower_corner()[0], 0.1, 1e-12);
  }

  // Base layer: a slab of thickness t under the beach from the back of the
  // body to `extent` seaward of the toe. Its area is t (x_t + extent -
  // x_back) on top of the default body; the Joss Bay body with the authors'
  // 7 m vertical upper face and a 2 m slab, with and without the notch.
  for (const bool notch : {true, false})
    {
      const CliffProfile cliff = parse({{"Upper face height", "7"},
                                        {"Base layer thickness", "2"},
                                        {"Base layer extent", "25"},
                                        {"Notch depth", notch ? "0.5" : "0"}});
      const double       H = 15.5, H_l = 8.5, t = 2., x_t = 31., back = 27.7;
      const double       x_k = x_t - H_l * cot(78.), x_back = x_k - back;
      CHECK(cliff.has_base_layer());
      CHECK_CLOSE(cliff.bottom_level(), -t, 1e-12);
      CHECK_CLOSE(cliff.base_layer_end(), x_t + 25., 1e-12);
      CHECK_CLOSE(cliff.crest()[0], x_k, 1e-12);
      const double h_n  = notch ? 0.5 / (1. + cot(78.)) : 0.;
      const double slab = t * (x_t + 25. - x_back);
      // Face region beside the lower face: rectangle + triangle (the upper
      // face is vertical and adds nothing).
      const double area =
        H * back + 0.5 * H_l * H_l * cot(78.) - 0.5 * 0.5 * h_n + slab;
      CHECK_CLOSE(cliff.area(), area, 1e-10);
      CHECK_CLOSE(cliff.body().area(), area, 1e-10);
      const double h = 0.02;
      CHECK_CLOSE(lattice_area(cliff.body(), h),
                  area,
                  perimeter(cliff.body()) * h / 2.);
      // (x_back, -t), (x_e, -t), (x_e, 0), N, U or T, K, C, (x_back, H).
      CHECK(cliff.body().vertices().size() == (notch ? 8u : 7u));
      CHECK(cliff.body().contains(Point<2>(x_t + 20., -1.))); // under beach
      CHECK(cliff.body().contains(Point<2>(x_back + 0.1, -1.9)));
      CHECK(!cliff.body().contains(Point<2>(x_t + 20., 0.1))); // on beach
      CHECK(!cliff.body().contains(Point<2>(x_t + 25.1, -1.)));
      CHECK(!cliff.body().contains(Point<2>(x_t, -2.1)));
      CHECK(cliff.body().contains(Point<2>(x_t - 0.45, -0.01))); // under N
      CHECK(notch != cliff.body().contains(Point<2>(x_t - 0.45, 0.01)));
      CHECK_CLOSE(cliff.surface_height(x_t + 1.), 0., 1e-12);
    }
  // A slab that ends at the toe (extent 0).
  {
    const CliffProfile cliff =
      parse({{"Base layer thickness", "3"}, {"Base layer extent", "0"}});
    const CliffProfile none = parse({});
    CHECK_CLOSE(cliff.area(),
                none.area() + 3. * (31. - none.back_position()),
                1e-10);
    CHECK_CLOSE(cliff.body().area(), cliff.area(), 1e-10);
  }

  // Pre-damage band: d = exp(-(r/w)^4) for r <= c w, r the distance to the
  // crack centre segment x = x_c - 2.2, y in [H - 5, H], w = factor l_c.
  {
    CliffProfile cliff =
      parse({{"Crack band width factor", "2.6457513110645906"}});
    CHECK(cliff.has_crack_band());
    CHECK_THROWS_WITH(cliff.crack_band_half_width(), "l_c");
    cliff.set_nonlocal_length(0.18);
    const double w = std::sqrt(7.) * 0.18, H = 15.5;
    const double x_k = 31. - H * cot(78.) - 2.2;
    CHECK_CLOSE(cliff.crack_band_half_width(), w, 1e-15);
    // The values are exp of a few flops of r/w: round-off ~1e-15.
    const auto profile = [&](const double r) {
      return r > w ? 0. : std::exp(-std::pow(r / w, 4));
    };
    CHECK_CLOSE(cliff.crack_band_damage(Point<2>(x_k, H - 1.)), 1., 1e-15);
    for (const double r : {0.05, 0.2, 0.3, 0.4, 0.47, 0.48, 1.})
      {
        // Beside the centre line, and below its lower end (round end).
        CHECK_CLOSE(cliff.crack_band_damage(Point<2>(x_k + r, H - 2.)),
                    profile(r),
                    1e-14);
        CHECK_CLOSE(cliff.crack_band_damage(Point<2>(x_k - r, H - 0.01)),
                    profile(r),
                    1e-14);
        CHECK_CLOSE(cliff.crack_band_damage(Point<2>(x_k, H - 5. - r)),
                    profile(r),
                    1e-13);
        const double s = r / std::sqrt(2.);
        CHECK_CLOSE(cliff.crack_band_damage(Point<2>(x_k + s, H - 5. - s)),
                    profile(r),
                    1e-13);
      }
    // Just inside the cut-off the authors' profile is exp(-1), beyond it 0.
    CHECK_CLOSE(cliff.crack_band_damage(Point<2>(x_k + 0.999999 * w, H - 2.)),
                std::exp(-1.),
                1e-5);
    CHECK_CLOSE(cliff.crack_band_damage(Point<2>(x_k + 1.000001 * w, H - 2.)),
                0.,
                0.);
    // A cut-off of 2 keeps the tail up to 2 w (exp(-16) at the end).
    CliffProfile smooth =
      parse({{"Crack band width factor", "1"}, {"Crack band cut-off", "2"}});
    smooth.set_nonlocal_length(0.18);
    CHECK_CLOSE(smooth.crack_band_damage(Point<2>(x_k + 0.27, H - 2.)),
                std::exp(-std::pow(1.5, 4)),
                1e-15);
    CHECK_CLOSE(smooth.crack_band_damage(Point<2>(x_k + 0.37, H - 2.)), 0., 0.);
    // Without crack depth there is no band.
    CHECK(!parse({{"Crack band width factor", "1"}, {"Crack depth", "0"}})
             .has_crack_band());
  }

  // Impossible combinations: each error names the entry.
  const auto error = [](const std::map<std::string, std::string> &entries) {
    return scenes_test::message_of([&]() { parse(entries); });
  };
  const std::vector<std::pair<std::map<std::string, std::string>, std::string>>
    cases = {
      {{{"Height", "0"}}, "Height must be positive"},
      {{{"Height", "-3"}}, "Height must be positive"},
      {{{"Lower face angle", "0"}}, "Lower face angle must lie in (0, 90]"},
      {{{"Lower face angle", "95"}}, "Lower face angle must lie in (0, 90]"},
      {{{"Upper face angle", "-10"}}, "Upper face angle must lie in (0, 90]"},
      {{{"Notch angle", "90.5"}}, "Notch angle must lie in (0, 90]"},
      {{{"Upper face height", "-1"}}, "Upper face height must not be"},
      {{{"Upper face height", "16"}}, "upper face is taller than the cliff"},
      {{{"Back length", "0"}}, "Back length must be positive"},
      {{{"Notch depth", "-0.1"}}, "Notch depth must not be negative"},
      {{{"Notch depth", "40"}}, "Notch depth (40) reaches the back"},
      {{{"Notch depth", "20"}, {"Back length", "50"}},
       "notch would be taller than the cliff"},
      // Vertical face and vertical notch roof never meet.
      {{{"Lower face angle", "90"}, {"Notch angle", "90"}},
       "notch would be taller than the cliff"},
      {{{"Crack offset", "-1"}}, "Crack offset must not be negative"},
      {{{"Crack offset", "28"}}, "Crack offset (28) puts the crack"},
      {{{"Crack offset", "27.7"}, {"Crack width", "0.1"}},
       "Crack offset (27.7) puts the crack"},
      {{{"Crack depth", "15.5"}}, "crack would be deeper than the cliff"},
      {{{"Crack depth", "-1"}}, "Crack depth must not be negative"},
      {{{"Crack width", "-0.1"}}, "Crack width must not be negative"},
      {{{"Crack band width factor", "-1"}},
       "Crack band width factor must not be negative"},
      {{{"Crack band cut-off", "0.5"}}, "Crack band cut-off must be at least"},
      {{{"Base layer thickness", "-2"}},
       "Base layer thickness must not be negative"},
      {{{"Base layer extent", "-1"}}, "Base layer extent must not be"}};
  for (const auto &[entries, text] : cases)
    {
      const std::string message = error(entries);
      if (message.find(text) == std::string::npos)
        {
          std::cout << "expected an error with '" << text << "' for "
                    << entries.begin()->first << " = "
                    << entries.begin()->second << ", got '" << message << "'"
                    << std::endl;
          ++scenes_test::n_failures;
        }
    }
  // A cell too wide for the room behind the crack.
  {
    CliffProfile cliff = parse({{"Crack offset", "27.69"}});
    cliff.set_cell_size(0.1);
    CHECK_THROWS_WITH(cliff.crack_region(), "Crack offset");
  }

  return scenes_test::finish();
}
