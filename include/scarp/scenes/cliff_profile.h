#ifndef scarp_scenes_cliff_profile_h
#define scarp_scenes_cliff_profile_h

#include <deal.II/base/parameter_handler.h>

#include <scarp/scenes/box_shape.h>
#include <scarp/scenes/polygon_shape.h>

#include <optional>
#include <vector>

namespace scarp
{
  namespace scenes
  {
    /**
     * @brief The 2D (plane strain) section of a cliff: a body with a sloped
     * lower face, an optional steeper upper face, a wave-cut notch at the
     * toe and a vertical tension crack behind the crest.
     *
     * The sea is on the +x side: the body lies at x < toe, the face leans
     * back (towards -x) as it rises and debris runs out towards +x.
     *
     * Coordinates, with y_b = Beach level, x_t = Toe position,
     * H_u = Upper face height and H_l = Height - H_u:
     *  - toe T = (x_t, y_b): where the lower face, extended down, meets the
     *    beach. It is the reference for the run-out even when a notch
     *    removes it from the body;
     *  - knee K = (x_t - H_l cot(Lower face angle), y_b + H_l): top of the
     *    lower face (coincides with T or with the crest when H_l or H_u is
     *    zero);
     *  - crest C = (x_K - H_u cot(Upper face angle), y_b + Height);
     *  - back x_back = x_C - Back length; the body is the region between
     *    x_back, the beach, the top y_b + Height and the face;
     *  - notch: the triangle (or, when it reaches the upper face, the
     *    quadrilateral) between the innermost point N = (x_t - Notch depth,
     *    y_b), T and the point U where the line from N rising at Notch
     *    angle towards the sea meets the face. Its lower side lies on the
     *    beach level and it is cut out of the body. Its height is
     *    h_n = Notch depth / (cot(Notch angle) + cot(Lower face angle))
     *    while U lies on the lower face;
     *  - tension crack: the box [x_k - w/2, x_k + w/2) x [y_b + Height -
     *    Crack depth, y_b + Height) with x_k = x_C - Crack offset and w the
     *    Crack width (one background cell when zero);
     *  - optional pre-damage band instead of the crack box: damage
     *    d(r) = exp(-(r/w)^4) for r <= c w, else 0, with r the distance to
     *    the crack centre segment from (x_k, y_top - Crack depth) to
     *    (x_k, y_top), w = Crack band width factor * l_c and c = Crack band
     *    cut-off (the profile of the authors' code, doc/joss_bay.md);
     *  - optional base layer: a slab of the same material, Base layer
     *    thickness deep under the beach level, from the back of the body
     *    to Base layer extent seaward of the toe.
     *
     * The defaults are the Joss Bay case of the reference paper (section 4):
     * Height 15.5 m, lower face 78 degrees, no vertical upper part, notch
     * 0.5 m at 45 degrees, crack 2.2 m behind the crest, body about 2H long.
     */
    class CliffProfile
    {
    public:
      /**
       * @brief The numbers of the "Cliff" subsection; lengths in metres,
       * angles in degrees from the horizontal.
       */
      struct Parameters
      {
        double toe_position      = 31.0;
        double beach_level       = 0.0;
        double height            = 15.5;
        double lower_face_angle  = 78.0;
        double upper_face_height = 0.0;
        double upper_face_angle  = 90.0;
        /// 27.7 m + the 3.29 m wide default face = 31 m, about 2H.
        double back_length  = 27.7;
        double notch_depth  = 0.5;
        double notch_angle  = 45.0;
        double crack_offset = 2.2;
        /// Not given by the paper; a scene choice.
        double crack_depth = 5.0;
        /// 0: one background cell, see set_cell_size().
        double crack_width = 0.0;
        /// Half-width of the pre-damage band in units of the non-local
        /// length l_c; 0: no band (the crack is the fully damaged box).
        double crack_band_width_factor = 0.0;
        /// The band ends at this multiple of its half-width (authors: 1).
        double crack_band_cutoff = 1.0;
        /// Thickness of the slab under the beach level; 0: none.
        double base_layer_thickness = 0.0;
        /// How far the slab reaches seaward of the toe.
        double base_layer_extent = 25.0;
      };

      /// The default (Joss Bay) cliff.
      CliffProfile();

      /// Validates @p parameters (throws an ExcMessage that names the
      /// offending entry) and builds the geometry.
      explicit CliffProfile(const Parameters &parameters);

      /// Declares the subsection "Cliff" inside the current subsection.
      static void
      declare_parameters(ParameterHandler &prm);

      /// Reads the subsection "Cliff" of the current subsection, validates
      /// and rebuilds the geometry.
      void
      parse_parameters(ParameterHandler &prm);

      /// Background cell size, used when Crack width is zero.
      void
      set_cell_size(const double cell_size);

      /// Non-local length scale l_c of the body's material, used by the
      /// pre-damage band (Crack band width factor > 0).
      void
      set_nonlocal_length(const double length_scale);

      const Parameters &
      get_parameters() const;

      /// The cliff body, notch removed. Vertices counter-clockwise from the
      /// bottom of the back: (x_back, y_b), N, U [, K], C, (x_back, y_top);
      /// without a notch: (x_back, y_b), T [, K], C, (x_back, y_top). With
      /// a base layer of thickness t and end x_e = x_t + Base layer extent
      /// the first vertex is replaced by (x_back, y_b - t), (x_e, y_b - t),
      /// (x_e, y_b) [, T without a notch].
      const PolygonShape &
      body() const;

      /// Whether Crack depth is positive.
      bool
      has_crack() const;

      /// Whether the crack is a pre-damage band (Crack depth and Crack band
      /// width factor positive) rather than a fully damaged box.
      bool
      has_crack_band() const;

      /// Half-width w = Crack band width factor * l_c of the band [m].
      /// Throws if no positive l_c was set (set_nonlocal_length()).
      double
      crack_band_half_width() const;

      /// Initial damage of the band at @p x: exp(-(r/w)^4) for r <= cut-off
      /// w, else 0; r is the distance of @p x to the crack centre segment.
      double
      crack_band_damage(const Point<2> &x) const;

      /// The tension crack region, to be marked fully damaged. Throws if
      /// there is no crack, or if Crack width is zero and no cell size was
      /// set.
      BoxShape<2>
      crack_region() const;

      /// Toe T (lower face extended to the beach level).
      Point<2>
      toe() const;

      /// Crest C (top of the face).
      Point<2>
      crest() const;

      /// x of the back of the body.
      double
      back_position() const;

      /// y of the top of the body.
      double
      top_level() const;

      /// y of the bottom of the body: Beach level - Base layer thickness.
      double
      bottom_level() const;

      /// Whether Base layer thickness is positive.
      bool
      has_base_layer() const;

      /// x of the seaward end of the base layer (toe + Base layer extent).
      double
      base_layer_end() const;

      /// Top point U of the notch (equal to the toe without a notch).
      Point<2>
      notch_top() const;

      /// Innermost point N of the notch (equal to the toe without a notch).
      Point<2>
      notch_root() const;

      /// Analytic area of the body: Height * (Back length) + the area
      /// between the face and the crest vertical - the notch + the base
      /// layer thickness * (its end - x_back).
      double
      area() const;

      /**
       * The initial outline of the free surface as a polyline from the back
       * of the top to the toe: (x_back, y_top), C [, K], U, N, T, i.e. with
       * the notch, which makes it non-single-valued in x under the face
       * (U -> N goes back landward). Without a notch it ends K, T.
       */
      std::vector<Point<2>>
      surface_outline() const;

      /// Height of the top of the initial material at @p x, as seen from
      /// above (the notch is overhung, so it does not show): the top level
      /// up to the crest, the face, then the beach level seaward of the toe
      /// and also behind the back of the body.
      double
      surface_height(const double x) const;

    private:
      void
      build();

      Parameters parameters;
      double     cell_size       = 0.;
      double     nonlocal_length = 0.;

      Point<2> toe_point;
      Point<2> knee_point;
      Point<2> crest_point;
      Point<2> notch_root_point;
      Point<2> notch_top_point;
      double   back_x     = 0.;
      double   notch_area = 0.;
      // Optional only because a polygon has no empty state; always set
      // after build().
      std::optional<PolygonShape> body_polygon;
    };
  } // namespace scenes
} // namespace scarp

#endif
