// Checks of an atlas computed from its UV triangles alone, shared by test_layout.cpp (the
// packer) and test_cli.cpp (icm_param --atlas): the charts as the triangles connect them, the
// exact distance between two charts' triangles, the covered area.

#ifndef ICM_TEST_ATLAS_CHECKS_H
#define ICM_TEST_ATLAS_CHECKS_H

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <vector>

namespace icm_test {

using Uv2 = std::array<double, 2>;
using Uv_triangle = std::array<Uv2, 3>;

inline double cross2(const Uv2& o, const Uv2& a, const Uv2& b)
{
  return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
}

inline double point_segment_distance(const Uv2& p, const Uv2& a, const Uv2& b)
{
  const double dx = b[0] - a[0], dy = b[1] - a[1], length2 = dx * dx + dy * dy;
  const double t = length2 > 0 ? std::clamp(((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / length2, 0.0, 1.0) : 0.0;
  return std::hypot(p[0] - a[0] - t * dx, p[1] - a[1] - t * dy);
}

inline bool segments_cross(const Uv2& a, const Uv2& b, const Uv2& c, const Uv2& d)
{
  const double d1 = cross2(a, b, c), d2 = cross2(a, b, d), d3 = cross2(c, d, a), d4 = cross2(c, d, b);
  return ((d1 > 0) != (d2 > 0)) && ((d3 > 0) != (d4 > 0)) && d1 != 0 && d2 != 0 && d3 != 0 && d4 != 0;
}

inline bool inside_triangle(const Uv2& p, const Uv_triangle& t)
{
  const double a = cross2(t[0], t[1], p), b = cross2(t[1], t[2], p), c = cross2(t[2], t[0], p);
  return (a >= 0 && b >= 0 && c >= 0) || (a <= 0 && b <= 0 && c <= 0);
}

/// The distance between two closed triangles (0 when they meet).
inline double triangle_distance(const Uv_triangle& s, const Uv_triangle& t)
{
  if(inside_triangle(s[0], t) || inside_triangle(t[0], s))
    return 0;
  double d = HUGE_VAL;
  for(int i = 0; i < 3; ++i)
    for(int j = 0; j < 3; ++j)
    {
      if(segments_cross(s[i], s[(i + 1) % 3], t[j], t[(j + 1) % 3]))
        return 0;
      d = std::min(
        {d, point_segment_distance(s[i], t[j], t[(j + 1) % 3]), point_segment_distance(t[j], s[i], s[(i + 1) % 3])});
    }
  return d;
}

/// The bounding box {xmin, ymin, xmax, ymax} of triangles.
inline std::array<double, 4> box_of(const std::vector<Uv_triangle>& triangles)
{
  std::array<double, 4> box{HUGE_VAL, HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  for(const Uv_triangle& t : triangles)
    for(const Uv2& p : t)
      box = {std::min(box[0], p[0]), std::min(box[1], p[1]), std::max(box[2], p[0]), std::max(box[3], p[1])};
  return box;
}

/// The Euclidean distance between two boxes (0 when they meet).
inline double box_distance(const std::array<double, 4>& a, const std::array<double, 4>& b)
{
  const double dx = std::max({0.0, b[0] - a[2], a[0] - b[2]}), dy = std::max({0.0, b[1] - a[3], a[1] - b[3]});
  return std::hypot(dx, dy);
}

/// The least distance between a triangle of `a` and one of `b`; triangles farther from the
/// other chart's box than `beyond` are skipped (the result is then min(distance, >= beyond)).
inline double chart_distance(const std::vector<Uv_triangle>& a, const std::vector<Uv_triangle>& b, double beyond)
{
  const std::array<double, 4> box_a = box_of(a), box_b = box_of(b);
  std::vector<const Uv_triangle*> near_a, near_b;
  for(const Uv_triangle& t : a)
    if(box_distance(box_of({t}), box_b) < beyond)
      near_a.push_back(&t);
  for(const Uv_triangle& t : b)
    if(box_distance(box_of({t}), box_a) < beyond)
      near_b.push_back(&t);
  double d = HUGE_VAL;
  for(const Uv_triangle* s : near_a)
    for(const Uv_triangle* t : near_b)
      d = std::min(d, triangle_distance(*s, *t));
  return std::min(d, std::max(beyond, box_distance(box_a, box_b)));
}

/// The charts of a triangle soup whose corners are indices into UV points: triangles that
/// share a UV index are in one chart.
inline std::vector<std::vector<Uv_triangle>> charts_of(const std::vector<Uv2>& uv,
                                                       const std::vector<std::array<int, 3>>& corners)
{
  std::vector<int> parent(uv.size());
  std::iota(parent.begin(), parent.end(), 0);
  auto root = [&parent](int v) {
    while(parent[v] != v)
      v = parent[v] = parent[parent[v]];
    return v;
  };
  for(const auto& f : corners)
    for(int c = 1; c < 3; ++c)
      parent[root(f[c])] = root(f[0]);
  std::vector<int> chart_of_root(uv.size(), -1);
  std::vector<std::vector<Uv_triangle>> charts;
  for(const auto& f : corners)
  {
    int& chart = chart_of_root[root(f[0])];
    if(chart < 0)
    {
      chart = static_cast<int>(charts.size());
      charts.emplace_back();
    }
    charts[chart].push_back({uv[f[0]], uv[f[1]], uv[f[2]]});
  }
  return charts;
}

inline double signed_area_of(const Uv_triangle& t)
{
  return 0.5 * cross2(t[0], t[1], t[2]);
}

} // namespace icm_test

#endif // ICM_TEST_ATLAS_CHECKS_H
