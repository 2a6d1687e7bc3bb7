#ifndef scarp_scenes_polygon_shape_h
#define scarp_scenes_polygon_shape_h

#include <scarp/scenes/shape.h>

#include <string>
#include <vector>

namespace scarp
{
  namespace scenes
  {
    /**
     * @brief A simple polygon in 2D (convex or not), given by its vertices
     * in order, either orientation; the closing edge is implied.
     *
     * The constructor checks that the polygon is usable and throws an
     * ExcMessage naming the problem otherwise: fewer than three vertices,
     * repeated consecutive vertices, zero area, or edges that cross or
     * touch (self-intersection). A last vertex equal to the first is
     * accepted and dropped.
     *
     * contains() is the even-odd (crossing number) rule with a half-open
     * rule for vertices on the ray, evaluated with the sign of a cross
     * product instead of a division, so a ray through a vertex is counted
     * once and the answer does not depend on round-off in an intersection
     * point. Points exactly on an edge may go either way; two polygons that
     * share an edge never both claim such a point.
     */
    class PolygonShape : public Shape<2>
    {
    public:
      explicit PolygonShape(const std::vector<Point<2>> &vertices);

      bool
      contains(const Point<2> &point) const override;

      BoundingBox<2>
      bounding_box() const override;

      /// The vertices, as given (without a repeated closing vertex).
      const std::vector<Point<2>> &
      vertices() const;

      /// Enclosed area (shoelace formula), always positive.
      double
      area() const;

      /**
       * Parse a vertex list of the form "x0,y0; x1,y1; x2,y2" (blanks
       * allowed, a trailing ';' ignored). Throws an ExcMessage naming the
       * offending vertex when an item is not two numbers separated by a
       * comma. Does not check the polygon itself; the constructor does.
       */
      static std::vector<Point<2>>
      parse_vertices(const std::string &text);

    private:
      std::vector<Point<2>> polygon_vertices;
      BoundingBox<2>        box;
    };
  } // namespace scenes
} // namespace scarp

#endif
