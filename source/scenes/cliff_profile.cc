#include <deal.II/base/exceptions.h>
#include <deal.II/base/numbers.h>

#include <scarp/scenes/cliff_profile.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace scarp
{
  namespace scenes
  {
    // AssertThrow with the message prefixed by the subsection, as a macro so
    // that deal.II reports the violated condition itself.
#define SCARP_CLIFF_REQUIRE(condition, message) \
  AssertThrow(condition, ExcMessage("Cliff/" + std::string(message)))

    namespace
    {
      double
      cot_degrees(const double angle)
      {
        // Exactly zero at 90 degrees, so vertical faces are exactly vertical.
        if (angle == 90.)
          return 0.;
        return 1. / std::tan(angle * numbers::PI / 180.);
      }


      template <typename... Args>
      std::string
      format(const Args &...args)
      {
        std::ostringstream s;
        (s << ... << args);
        return s.str();
      }


      void
      check_angle(const double angle, const std::string &name)
      {
        SCARP_CLIFF_REQUIRE(
          angle > 0. && angle <= 90.,
          format(name,
                 " must lie in (0, 90] degrees from the horizontal, "
                 "got ",
                 angle,
                 "."));
      }
    } // namespace


    CliffProfile::CliffProfile()
      : CliffProfile(Parameters())
    {
    }


    CliffProfile::CliffProfile(const Parameters &p)
      : parameters(p)
    {
      build();
    }


    void
    CliffProfile::declare_parameters(ParameterHandler &prm)
    {
      const Parameters d;
      prm.enter_subsection("Cliff");
      {
        prm.declare_entry(
          "Toe position",
          format(d.toe_position),
          Patterns::Double(),
          "x [m] of the toe: where the lower face, extended down, meets the "
          "beach level. The sea is on the +x side.");
        prm.declare_entry("Beach level",
                          format(d.beach_level),
                          Patterns::Double(),
                          "y [m] of the base of the cliff body (the beach).");
        prm.declare_entry("Height",
                          format(d.height),
                          Patterns::Double(),
                          "Cliff height H [m] from the beach to the crest.");
        prm.declare_entry(
          "Lower face angle",
          format(d.lower_face_angle),
          Patterns::Double(),
          "Angle of the lower face from the horizontal, in (0, 90] degrees.");
        prm.declare_entry(
          "Upper face height",
          format(d.upper_face_height),
          Patterns::Double(),
          "Height [m] of an upper face part with its own angle, below the "
          "crest; 0 = none (the lower face reaches the crest).");
        prm.declare_entry(
          "Upper face angle",
          format(d.upper_face_angle),
          Patterns::Double(),
          "Angle of the upper face part from the horizontal, in (0, 90] "
          "degrees (90 = vertical).");
        prm.declare_entry("Back length",
                          format(d.back_length),
                          Patterns::Double(),
                          "Length [m] of the cliff body behind the crest.");
        prm.declare_entry(
          "Notch depth",
          format(d.notch_depth),
          Patterns::Double(),
          "Horizontal depth [m] of the wave-cut notch, measured along the "
          "beach level from the toe into the body; 0 = no notch.");
        prm.declare_entry(
          "Notch angle",
          format(d.notch_angle),
          Patterns::Double(),
          "Angle in (0, 90] degrees of the notch roof, which rises from the "
          "innermost point of the notch towards the sea until it meets the "
          "face. The notch floor is the beach level.");
        prm.declare_entry(
          "Crack offset",
          format(d.crack_offset),
          Patterns::Double(),
          "Horizontal distance [m] from the crest back to the centre line of "
          "the vertical tension crack.");
        prm.declare_entry(
          "Crack depth",
          format(d.crack_depth),
          Patterns::Double(),
          "Depth [m] of the tension crack from the top of the cliff down; "
          "0 = no crack.");
        prm.declare_entry(
          "Crack width",
          format(d.crack_width),
          Patterns::Double(),
          "Width [m] of the tension crack; 0 = one background cell.");
        prm.declare_entry(
          "Crack band width factor",
          format(d.crack_band_width_factor),
          Patterns::Double(),
          "Pre-damage band instead of the fully damaged crack box, with "
          "half-width w = this factor times the non-local length scale l_c "
          "of the body's material: initial damage exp(-(r/w)^4) at distance "
          "r from the crack centre line (from the top down to Crack depth), "
          "0 beyond Crack band cut-off * w. 0 = no band. The authors' code "
          "uses w = the radius of its bell weight, i.e. sqrt(7) = 2.6458 "
          "with l_c the standard deviation.");
        prm.declare_entry(
          "Crack band cut-off",
          format(d.crack_band_cutoff),
          Patterns::Double(),
          "Distance, in units of the band half-width w, beyond which the "
          "pre-damage band leaves the material undamaged; >= 1. The "
          "authors' code: 1 (damage jumps from exp(-1) to 0 at r = w); 2 "
          "makes the band smooth (exp(-16) at the cut).");
        prm.declare_entry(
          "Base layer thickness",
          format(d.base_layer_thickness),
          Patterns::Double(),
          "Thickness [m] of a slab of the body's material under the beach "
          "level, from the back of the body to Base layer extent seaward of "
          "the toe (the authors' code: 2-3 m on a fixed bottom); 0 = none. "
          "The mesh must then reach below the beach: Mesh/Lower corner.");
        prm.declare_entry(
          "Base layer extent",
          format(d.base_layer_extent),
          Patterns::Double(),
          "Distance [m] from the toe to the seaward end of the base layer; "
          ">= 0. Used only with a positive Base layer thickness.");
      }
      prm.leave_subsection();
    }


    void
    CliffProfile::parse_parameters(ParameterHandler &prm)
    {
      Parameters p;
      prm.enter_subsection("Cliff");
      {
        p.toe_position            = prm.get_double("Toe position");
        p.beach_level             = prm.get_double("Beach level");
        p.height                  = prm.get_double("Height");
        p.lower_face_angle        = prm.get_double("Lower face angle");
        p.upper_face_height       = prm.get_double("Upper face height");
        p.upper_face_angle        = prm.get_double("Upper face angle");
        p.back_length             = prm.get_double("Back length");
        p.notch_depth             = prm.get_double("Notch depth");
        p.notch_angle             = prm.get_double("Notch angle");
        p.crack_offset            = prm.get_double("Crack offset");
        p.crack_depth             = prm.get_double("Crack depth");
        p.crack_width             = prm.get_double("Crack width");
        p.crack_band_width_factor = prm.get_double("Crack band width factor");
        p.crack_band_cutoff       = prm.get_double("Crack band cut-off");
        p.base_layer_thickness    = prm.get_double("Base layer thickness");
        p.base_layer_extent       = prm.get_double("Base layer extent");
      }
      prm.leave_subsection();
      parameters = p;
      build();
    }


    void
    CliffProfile::set_cell_size(const double h)
    {
      AssertThrow(h > 0.,
                  ExcMessage(format("CliffProfile::set_cell_size: the cell "
                                    "size must be positive, got ",
                                    h,
                                    ".")));
      cell_size = h;
    }


    void
    CliffProfile::set_nonlocal_length(const double length_scale)
    {
      AssertThrow(length_scale >= 0. && std::isfinite(length_scale),
                  ExcMessage(format("CliffProfile::set_nonlocal_length: the "
                                    "length scale must be >= 0, got ",
                                    length_scale,
                                    ".")));
      nonlocal_length = length_scale;
    }


    const CliffProfile::Parameters &
    CliffProfile::get_parameters() const
    {
      return parameters;
    }


    void
    CliffProfile::build()
    {
      const Parameters &p = parameters;

      // Each check names the entry (or the pair of entries) at fault.
      for (const double value : {p.toe_position,
                                 p.beach_level,
                                 p.height,
                                 p.lower_face_angle,
                                 p.upper_face_height,
                                 p.upper_face_angle,
                                 p.back_length,
                                 p.notch_depth,
                                 p.notch_angle,
                                 p.crack_offset,
                                 p.crack_depth,
                                 p.crack_width,
                                 p.crack_band_width_factor,
                                 p.crack_band_cutoff,
                                 p.base_layer_thickness,
                                 p.base_layer_extent})
        SCARP_CLIFF_REQUIRE(std::isfinite(value),
                            "all entries must be finite numbers.");
      SCARP_CLIFF_REQUIRE(p.height > 0.,
                          format("Height must be positive, got ", p.height));
      check_angle(p.lower_face_angle, "Lower face angle");
      check_angle(p.upper_face_angle, "Upper face angle");
      check_angle(p.notch_angle, "Notch angle");
      SCARP_CLIFF_REQUIRE(p.upper_face_height >= 0.,
                          format("Upper face height must not be negative, got ",
                                 p.upper_face_height,
                                 "."));
      SCARP_CLIFF_REQUIRE(
        p.upper_face_height <= p.height,
        format("Upper face height (",
               p.upper_face_height,
               ") must not exceed Height (",
               p.height,
               "): the upper face is taller than the cliff."));
      SCARP_CLIFF_REQUIRE(p.back_length > 0.,
                          format("Back length must be positive, got ",
                                 p.back_length,
                                 "."));
      SCARP_CLIFF_REQUIRE(p.notch_depth >= 0.,
                          format("Notch depth must not be negative, got ",
                                 p.notch_depth,
                                 "."));
      SCARP_CLIFF_REQUIRE(p.crack_offset >= 0.,
                          format("Crack offset must not be negative, got ",
                                 p.crack_offset,
                                 "."));
      SCARP_CLIFF_REQUIRE(p.crack_depth >= 0.,
                          format("Crack depth must not be negative, got ",
                                 p.crack_depth,
                                 "."));
      SCARP_CLIFF_REQUIRE(
        p.crack_depth < p.height,
        format("Crack depth (",
               p.crack_depth,
               ") must be smaller than Height (",
               p.height,
               "): the crack would be deeper than the cliff."));
      SCARP_CLIFF_REQUIRE(p.crack_width >= 0.,
                          format("Crack width must not be negative, got ",
                                 p.crack_width,
                                 "."));

      SCARP_CLIFF_REQUIRE(p.crack_band_width_factor >= 0.,
                          format("Crack band width factor must not be "
                                 "negative, got ",
                                 p.crack_band_width_factor,
                                 "."));
      SCARP_CLIFF_REQUIRE(p.crack_band_cutoff >= 1.,
                          format("Crack band cut-off must be at least 1 "
                                 "(the band reaches its half-width), got ",
                                 p.crack_band_cutoff,
                                 "."));
      SCARP_CLIFF_REQUIRE(p.base_layer_thickness >= 0.,
                          format("Base layer thickness must not be negative, "
                                 "got ",
                                 p.base_layer_thickness,
                                 "."));
      SCARP_CLIFF_REQUIRE(p.base_layer_extent >= 0.,
                          format("Base layer extent must not be negative, "
                                 "got ",
                                 p.base_layer_extent,
                                 "."));

      const double y_b          = p.beach_level;
      const double lower_height = p.height - p.upper_face_height;
      const double cot_lower    = cot_degrees(p.lower_face_angle);
      const double cot_upper    = cot_degrees(p.upper_face_angle);
      const double cot_notch    = cot_degrees(p.notch_angle);
      toe_point                 = Point<2>(p.toe_position, y_b);
      knee_point =
        Point<2>(p.toe_position - lower_height * cot_lower, y_b + lower_height);
      crest_point = Point<2>(knee_point[0] - p.upper_face_height * cot_upper,
                             y_b + p.height);
      back_x      = crest_point[0] - p.back_length;

      SCARP_CLIFF_REQUIRE(
        p.toe_position - p.notch_depth > back_x,
        format("Notch depth (",
               p.notch_depth,
               ") reaches the back of the body (",
               p.toe_position - back_x,
               " m behind the toe): increase Back length or reduce "
               "Notch depth."));

      // The notch roof x = x_N + s cot(notch) (s: height above the beach)
      // meets the face once, since the face only moves landward as it rises
      // and the roof only seaward.
      notch_root_point         = toe_point;
      notch_top_point          = toe_point;
      notch_area               = 0.;
      bool notch_on_upper_face = false;
      if (p.notch_depth > 0.)
        {
          notch_root_point = Point<2>(p.toe_position - p.notch_depth, y_b);
          double       notch_height = std::numeric_limits<double>::infinity();
          const double lower_denominator = cot_notch + cot_lower;
          if (lower_height > 0. && lower_denominator > 0. &&
              p.notch_depth / lower_denominator <= lower_height)
            notch_height = p.notch_depth / lower_denominator;
          else if (cot_notch + cot_upper > 0.)
            {
              notch_on_upper_face = true;
              notch_height =
                (p.notch_depth - lower_height * (cot_lower - cot_upper)) /
                (cot_notch + cot_upper);
            }
          SCARP_CLIFF_REQUIRE(
            notch_height < p.height,
            format("Notch depth (",
                   p.notch_depth,
                   ") with Notch angle (",
                   p.notch_angle,
                   ") gives a notch that reaches the crest: the "
                   "notch would be taller than the cliff (Height ",
                   p.height,
                   ")."));
          notch_top_point =
            Point<2>(notch_root_point[0] + notch_height * cot_notch,
                     y_b + notch_height);
        }

      std::vector<Point<2>> v;
      if (p.base_layer_thickness > 0.)
        {
          // The slab under the beach: its top from its seaward end to the
          // toe is the beach level, on which the notch (if any) sits.
          v.emplace_back(back_x, y_b - p.base_layer_thickness);
          v.emplace_back(base_layer_end(), y_b - p.base_layer_thickness);
          v.emplace_back(base_layer_end(), y_b);
        }
      else
        v.emplace_back(back_x, y_b);
      if (p.notch_depth > 0.)
        {
          v.push_back(notch_root_point);
          v.push_back(notch_top_point);
        }
      else if (!(v.back() == toe_point))
        v.push_back(toe_point);
      // The knee is a vertex only when it is a real corner above the notch.
      if (lower_height > 0. && p.upper_face_height > 0. &&
          !notch_on_upper_face && !(notch_top_point == knee_point))
        v.push_back(knee_point);
      v.push_back(crest_point);
      v.emplace_back(back_x, y_b + p.height);
      body_polygon.emplace(v);

      {
        // The part of the face region between the crest vertical and the
        // face that the notch removes, by the shoelace formula.
        std::vector<Point<2>> notch{notch_root_point, toe_point};
        if (notch_on_upper_face && lower_height > 0.)
          notch.push_back(knee_point);
        notch.push_back(notch_top_point);
        double twice = 0.;
        for (unsigned int i = 0, j = notch.size() - 1; i < notch.size();
             j = i++)
          twice += notch[j][0] * notch[i][1] - notch[i][0] * notch[j][1];
        notch_area = (p.notch_depth > 0.) ? 0.5 * std::abs(twice) : 0.;
      }

      if (p.crack_depth > 0.)
        {
          const double half_width = 0.5 * p.crack_width;
          SCARP_CLIFF_REQUIRE(
            crest_point[0] - p.crack_offset - half_width > back_x,
            format("Crack offset (",
                   p.crack_offset,
                   ") puts the crack at or beyond the back of the body "
                   "(Back length ",
                   p.back_length,
                   ")."));
        }
    }


    const PolygonShape &
    CliffProfile::body() const
    {
      return *body_polygon;
    }


    bool
    CliffProfile::has_crack() const
    {
      return parameters.crack_depth > 0.;
    }


    bool
    CliffProfile::has_crack_band() const
    {
      return has_crack() && parameters.crack_band_width_factor > 0.;
    }


    double
    CliffProfile::crack_band_half_width() const
    {
      AssertThrow(has_crack_band(),
                  ExcMessage("Cliff/Crack band width factor (or Crack "
                             "depth) is zero: there is no pre-damage band."));
      AssertThrow(nonlocal_length > 0.,
                  ExcMessage("Cliff/Crack band width factor needs the "
                             "non-local length scale l_c of the body's "
                             "material, and it is zero: use a damage "
                             "material with a bell or gaussian Nonlocal "
                             "weight."));
      return parameters.crack_band_width_factor * nonlocal_length;
    }


    double
    CliffProfile::crack_band_damage(const Point<2> &x) const
    {
      const double w     = crack_band_half_width();
      const double x_k   = crest_point[0] - parameters.crack_offset;
      const double y_top = top_level();
      // Distance to the segment x = x_k, y in [y_top - depth, y_top]; above
      // the top (outside the body anyway) it is measured to the top end.
      const double y_c =
        std::clamp(x[1], y_top - parameters.crack_depth, y_top);
      const double r = std::hypot(x[0] - x_k, x[1] - y_c);
      if (r > parameters.crack_band_cutoff * w)
        return 0.;
      const double s = r / w;
      return std::exp(-(s * s) * (s * s));
    }


    BoxShape<2>
    CliffProfile::crack_region() const
    {
      AssertThrow(has_crack(),
                  ExcMessage("Cliff/Crack depth is zero: there is no tension "
                             "crack region."));
      double width = parameters.crack_width;
      if (width == 0.)
        {
          AssertThrow(cell_size > 0.,
                      ExcMessage("Cliff/Crack width is 0 (one background "
                                 "cell) but no cell size was given: call "
                                 "CliffProfile::set_cell_size() first."));
          width = cell_size;
        }
      const double x_k = crest_point[0] - parameters.crack_offset;
      // Only a Crack width of 0 can reach here unchecked (a cell wider than
      // the room behind the crack).
      AssertThrow(x_k - 0.5 * width > back_x,
                  ExcMessage(format("Cliff/Crack offset (",
                                    parameters.crack_offset,
                                    ") with a crack ",
                                    width,
                                    " m wide reaches the back of the body.")));
      const double y_top = top_level();
      return BoxShape<2>(Point<2>(x_k - 0.5 * width,
                                  y_top - parameters.crack_depth),
                         Point<2>(x_k + 0.5 * width, y_top));
    }


    Point<2>
    CliffProfile::toe() const
    {
      return toe_point;
    }


    Point<2>
    CliffProfile::crest() const
    {
      return crest_point;
    }


    double
    CliffProfile::back_position() const
    {
      return back_x;
    }


    double
    CliffProfile::top_level() const
    {
      return parameters.beach_level + parameters.height;
    }


    double
    CliffProfile::bottom_level() const
    {
      return parameters.beach_level - parameters.base_layer_thickness;
    }


    bool
    CliffProfile::has_base_layer() const
    {
      return parameters.base_layer_thickness > 0.;
    }


    double
    CliffProfile::base_layer_end() const
    {
      return parameters.toe_position + parameters.base_layer_extent;
    }


    Point<2>
    CliffProfile::notch_top() const
    {
      return notch_top_point;
    }


    Point<2>
    CliffProfile::notch_root() const
    {
      return notch_root_point;
    }


    double
    CliffProfile::area() const
    {
      const Parameters &p            = parameters;
      const double      lower_height = p.height - p.upper_face_height;
      // Face region between the crest vertical and the face: a trapezoid
      // beside the lower face plus a triangle beside the upper face.
      const double face_area =
        lower_height * (knee_point[0] - crest_point[0]) +
        0.5 * lower_height * lower_height * cot_degrees(p.lower_face_angle) +
        0.5 * p.upper_face_height * p.upper_face_height *
          cot_degrees(p.upper_face_angle);
      const double base_area =
        p.base_layer_thickness * (base_layer_end() - back_x);
      return p.height * p.back_length + face_area - notch_area + base_area;
    }


    std::vector<Point<2>>
    CliffProfile::surface_outline() const
    {
      std::vector<Point<2>> outline;
      outline.emplace_back(back_x, top_level());
      outline.push_back(crest_point);
      const bool notch = parameters.notch_depth > 0.;
      if (!(knee_point == crest_point) && !(knee_point == toe_point) &&
          knee_point[1] > notch_top_point[1])
        outline.push_back(knee_point);
      if (notch)
        {
          outline.push_back(notch_top_point);
          outline.push_back(notch_root_point);
        }
      outline.push_back(toe_point);
      return outline;
    }


    double
    CliffProfile::surface_height(const double x) const
    {
      if (x < back_x || x >= toe_point[0])
        return parameters.beach_level;
      if (x <= crest_point[0])
        return top_level();
      // On the face: interpolate on the segment that spans x.
      const Point<2> &a = (x <= knee_point[0]) ? crest_point : knee_point;
      const Point<2> &b = (x <= knee_point[0]) ? knee_point : toe_point;
      if (b[0] == a[0])
        return std::max(a[1], b[1]);
      return a[1] + (x - a[0]) * (b[1] - a[1]) / (b[0] - a[0]);
    }
  } // namespace scenes
} // namespace scarp
