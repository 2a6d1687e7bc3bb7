#include <deal.II/base/exceptions.h>

#include <scarp/scenes/polygon_shape.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>

namespace scarp
{
  namespace scenes
  {
    namespace
    {
      // Twice the signed area of the triangle (a, b, c): positive when c lies
      // to the left of the line from a to b.
      double
      orientation(const Point<2> &a, const Point<2> &b, const Point<2> &c)
      {
        return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
      }


      int
      sign(const double x)
      {
        return (x > 0.) - (x < 0.);
      }


      // For c collinear with a and b: whether c lies on the closed segment.
      bool
      within_segment(const Point<2> &a, const Point<2> &b, const Point<2> &c)
      {
        return std::min(a[0], b[0]) <= c[0] && c[0] <= std::max(a[0], b[0]) &&
               std::min(a[1], b[1]) <= c[1] && c[1] <= std::max(a[1], b[1]);
      }


      // Whether the closed segments [p1, p2] and [p3, p4] share a point.
      bool
      segments_meet(const Point<2> &p1,
                    const Point<2> &p2,
                    const Point<2> &p3,
                    const Point<2> &p4)
      {
        const int d1 = sign(orientation(p3, p4, p1));
        const int d2 = sign(orientation(p3, p4, p2));
        const int d3 = sign(orientation(p1, p2, p3));
        const int d4 = sign(orientation(p1, p2, p4));
        if (d1 * d2 < 0 && d3 * d4 < 0)
          return true;
        return (d1 == 0 && within_segment(p3, p4, p1)) ||
               (d2 == 0 && within_segment(p3, p4, p2)) ||
               (d3 == 0 && within_segment(p1, p2, p3)) ||
               (d4 == 0 && within_segment(p1, p2, p4));
      }


      std::string
      trim(const std::string &text)
      {
        const auto begin = text.find_first_not_of(" \t\n\r");
        if (begin == std::string::npos)
          return "";
        const auto end = text.find_last_not_of(" \t\n\r");
        return text.substr(begin, end - begin + 1);
      }


      // Strict number parsing: the whole (trimmed) text must be a finite
      // number, so that "1.5x" or "" are errors rather than 1.5 or 0.
      bool
      parse_double(const std::string &text, double &value)
      {
        const std::string t = trim(text);
        if (t.empty())
          return false;
        char *end = nullptr;
        value     = std::strtod(t.c_str(), &end);
        return end == t.c_str() + t.size() && std::isfinite(value);
      }
    } // namespace


    PolygonShape::PolygonShape(const std::vector<Point<2>> &vertices)
      : polygon_vertices(vertices)
    {
      auto &v = polygon_vertices;
      if (v.size() > 1 && v.front() == v.back())
        v.pop_back();

      {
        std::ostringstream message;
        message << "Vertices: a polygon needs at least 3 vertices, got "
                << v.size() << ".";
        AssertThrow(v.size() >= 3, ExcMessage(message.str()));
      }

      const unsigned int n = v.size();
      for (unsigned int i = 0; i < n; ++i)
        {
          std::ostringstream message;
          message << "Vertices: vertex " << i << " (" << v[i]
                  << ") is not finite.";
          AssertThrow(std::isfinite(v[i][0]) && std::isfinite(v[i][1]),
                      ExcMessage(message.str()));
        }
      for (unsigned int i = 0; i < n; ++i)
        {
          std::ostringstream message;
          message << "Vertices: vertex " << (i + 1) % n << " ("
                  << v[(i + 1) % n] << ") repeats vertex " << i
                  << ": zero-length edge.";
          AssertThrow(!(v[i] == v[(i + 1) % n]), ExcMessage(message.str()));
        }

      box = BoundingBox<2>(v);

      {
        // All vertices on one line: the fan triangles from vertex 0 all have
        // zero area. Checked before self-intersection, which such a polygon
        // also is, because "zero area" is the clearer message.
        const double diameter_2 =
          (box.get_boundary_points().second - box.get_boundary_points().first)
            .norm_square();
        double fan = 0.;
        for (unsigned int i = 1; i + 1 < n; ++i)
          fan += std::abs(orientation(v[0], v[i], v[i + 1]));
        AssertThrow(fan > 1e-12 * diameter_2,
                    ExcMessage("Vertices: the polygon has zero area (its "
                               "vertices lie on a line)."));
      }

      // Self-intersection, O(n^2): scene polygons have few vertices.
      for (unsigned int i = 0; i < n; ++i)
        for (unsigned int j = i + 1; j < n; ++j)
          {
            const Point<2> &a = v[i], &b = v[(i + 1) % n];
            const Point<2> &c = v[j], &d = v[(j + 1) % n];
            const bool      adjacent_after  = (j == i + 1);
            const bool      adjacent_before = (i == 0 && j == n - 1);
            bool            bad             = false;
            if (adjacent_after || adjacent_before)
              {
                // Adjacent edges share a vertex; they are only bad when they
                // run back over each other from it.
                const Point<2> &shared = adjacent_after ? b : a;
                const Point<2> &p      = adjacent_after ? a : b;
                const Point<2> &q      = adjacent_after ? d : c;
                bad                    = orientation(shared, p, q) == 0. &&
                      (p - shared) * (q - shared) > 0.;
              }
            else
              bad = segments_meet(a, b, c, d);

            std::ostringstream message;
            message << "Vertices: the polygon is self-intersecting: edge " << i
                    << " (" << a << ") - (" << b << ") and edge " << j << " ("
                    << c << ") - (" << d << ") "
                    << ((adjacent_after || adjacent_before)
                          ? "fold back onto each other."
                          : "cross or touch.");
            AssertThrow(!bad, ExcMessage(message.str()));
          }

      // A simple polygon has a positive area; this only catches slivers
      // below round-off.
      {
        const double diameter_2 =
          (box.get_boundary_points().second - box.get_boundary_points().first)
            .norm_square();
        AssertThrow(area() > 1e-12 * diameter_2,
                    ExcMessage("Vertices: the polygon has zero area."));
      }
    }


    bool
    PolygonShape::contains(const Point<2> &point) const
    {
      if (!box.point_inside(point))
        return false;

      bool               inside = false;
      const unsigned int n      = polygon_vertices.size();
      for (unsigned int i = 0, j = n - 1; i < n; j = i++)
        {
          const Point<2> &a = polygon_vertices[j];
          const Point<2> &b = polygon_vertices[i];
          // Half-open in y: an edge counts when exactly one end lies above
          // the ray, so a ray through a vertex is counted once.
          if ((a[1] > point[1]) != (b[1] > point[1]))
            {
              // The edge crosses the ray to the right of the point when the
              // point is left of an upward edge or right of a downward one.
              const double o = orientation(a, b, point);
              if (b[1] > a[1] ? o > 0. : o < 0.)
                inside = !inside;
            }
        }
      return inside;
    }


    BoundingBox<2>
    PolygonShape::bounding_box() const
    {
      return box;
    }


    const std::vector<Point<2>> &
    PolygonShape::vertices() const
    {
      return polygon_vertices;
    }


    double
    PolygonShape::area() const
    {
      double             twice_area = 0.;
      const unsigned int n          = polygon_vertices.size();
      for (unsigned int i = 0, j = n - 1; i < n; j = i++)
        twice_area += polygon_vertices[j][0] * polygon_vertices[i][1] -
                      polygon_vertices[i][0] * polygon_vertices[j][1];
      return 0.5 * std::abs(twice_area);
    }


    std::vector<Point<2>>
    PolygonShape::parse_vertices(const std::string &text)
    {
      std::vector<std::string> items;
      {
        std::string::size_type begin = 0;
        while (true)
          {
            const auto end = text.find(';', begin);
            items.push_back(text.substr(begin, end - begin));
            if (end == std::string::npos)
              break;
            begin = end + 1;
          }
      }
      if (items.size() > 1 && trim(items.back()).empty())
        items.pop_back();

      std::vector<Point<2>> result;
      for (unsigned int k = 0; k < items.size(); ++k)
        {
          const std::string item  = trim(items[k]);
          const auto        comma = item.find(',');
          double            x = 0., y = 0.;
          const bool        ok = comma != std::string::npos &&
                          item.find(',', comma + 1) == std::string::npos &&
                          parse_double(item.substr(0, comma), x) &&
                          parse_double(item.substr(comma + 1), y);
          std::ostringstream message;
          message << "Vertices: item " << k << " ('" << item
                  << "') is not a vertex of the form 'x,y'; expected a list "
                     "like \"0,0; 1,0; 0,1\" (vertices separated by ';', "
                     "coordinates by ',').";
          AssertThrow(ok, ExcMessage(message.str()));
          result.emplace_back(x, y);
        }
      return result;
    }
  } // namespace scenes
} // namespace scarp
