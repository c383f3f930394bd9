// The pairs of closed axis-aligned boxes in the plane that meet: the candidate pairs of the
// exact overlap tests (Border_overlaps.h).
//
// A bounding-volume tree (median splits of the box centres along the longer side) is
// traversed against itself: a pair of nodes whose boxes are apart is passed over with all
// the pairs below it, so a layout's border of n edges costs about O(n log n + k) for k
// meeting pairs, whether its edges are spread evenly or bunched where the map shrinks the
// surface a millionfold, and an axis-parallel side (a square border's) is no worse than a
// curved one.

#ifndef ICM_INTERNAL_BOX_PAIRS_H
#define ICM_INTERNAL_BOX_PAIRS_H

#include <ICM/internal/Vector_geometry.h>

#include <algorithm>
#include <array>
#include <utility>
#include <vector>

namespace ICM {
namespace internal {

/// A closed box [low[0], high[0]] x [low[1], high[1]].
struct Box2
{
  Uv low, high;

  static Box2 around(const Uv& p) { return {p, p}; }
  void extend(const Uv& p)
  {
    for(int k = 0; k < 2; ++k)
    {
      low[k] = std::min(low[k], p[k]);
      high[k] = std::max(high[k], p[k]);
    }
  }
  void extend(const Box2& b)
  {
    extend(b.low);
    extend(b.high);
  }
  /// Closed boxes meet when they share a point, so a flat box (an axis-parallel edge's) still
  /// meets its neighbours.
  bool meets(const Box2& b) const
  {
    return low[0] <= b.high[0] && b.low[0] <= high[0] && low[1] <= b.high[1] && b.low[1] <= high[1];
  }
};

/// The tree over a fixed array of boxes, and its traversal against itself.
class Box_tree
{
public:
  explicit Box_tree(const std::vector<Box2>& boxes) : boxes_(boxes), order_(boxes.size())
  {
    for(std::size_t i = 0; i < order_.size(); ++i)
      order_[i] = static_cast<int>(i);
    if(!boxes.empty())
    {
      nodes_.reserve(2 * boxes.size() / leaf_size + 2);
      build(0, static_cast<int>(boxes.size()));
    }
  }

  /// Calls `visit(i, j)`, i < j indices of the array, once for every pair of boxes that meet,
  /// until `visit` returns false. Returns false when it was stopped.
  template <class Visit>
  bool for_each_meeting_pair(Visit&& visit) const
  {
    if(nodes_.empty())
      return true;
    std::vector<std::pair<int, int>> stack{{0, 0}};
    while(!stack.empty())
    {
      const auto [a, b] = stack.back();
      stack.pop_back();
      const Node &na = nodes_[a], &nb = nodes_[b];
      if(a == b)
      {
        if(na.is_leaf())
        {
          if(!visit_pairs_within(na, visit))
            return false;
        }
        else
          stack.insert(stack.end(), {{na.left, na.left}, {na.right, na.right}, {na.left, na.right}});
      }
      else if(na.box.meets(nb.box))
      {
        if(na.is_leaf() && nb.is_leaf())
        {
          if(!visit_pairs_between(na, nb, visit))
            return false;
        }
        else if(nb.is_leaf() || (!na.is_leaf() && na.end - na.begin >= nb.end - nb.begin))
          stack.insert(stack.end(), {{na.left, b}, {na.right, b}});
        else
          stack.insert(stack.end(), {{a, nb.left}, {a, nb.right}});
      }
    }
    return true;
  }

private:
  static constexpr int leaf_size = 8;

  struct Node
  {
    Box2 box;
    int begin, end; // range of order_
    int left = -1, right = -1;
    bool is_leaf() const { return left < 0; }
  };

  int build(int begin, int end)
  {
    const int id = static_cast<int>(nodes_.size());
    nodes_.push_back({boxes_[order_[begin]], begin, end});
    Box2 centres = Box2::around(centre(order_[begin]));
    for(int i = begin; i < end; ++i)
    {
      nodes_[id].box.extend(boxes_[order_[i]]);
      centres.extend(centre(order_[i]));
    }
    if(end - begin <= leaf_size)
      return id;
    const int axis = (centres.high[0] - centres.low[0] >= centres.high[1] - centres.low[1]) ? 0 : 1;
    const int middle = begin + (end - begin) / 2;
    std::nth_element(order_.begin() + begin, order_.begin() + middle, order_.begin() + end,
                     [&](int i, int j) { return centre(i)[axis] < centre(j)[axis]; });
    const int left = build(begin, middle);
    const int right = build(middle, end);
    nodes_[id].left = left;
    nodes_[id].right = right;
    return id;
  }

  Uv centre(int i) const
  {
    return {boxes_[i].low[0] / 2 + boxes_[i].high[0] / 2, boxes_[i].low[1] / 2 + boxes_[i].high[1] / 2};
  }

  template <class Visit>
  bool visit_if_meeting(int i, int j, Visit& visit) const
  {
    return !boxes_[i].meets(boxes_[j]) || visit(std::min(i, j), std::max(i, j));
  }

  template <class Visit>
  bool visit_pairs_within(const Node& n, Visit& visit) const
  {
    for(int x = n.begin; x < n.end; ++x)
      for(int y = x + 1; y < n.end; ++y)
        if(!visit_if_meeting(order_[x], order_[y], visit))
          return false;
    return true;
  }

  template <class Visit>
  bool visit_pairs_between(const Node& n, const Node& m, Visit& visit) const
  {
    for(int x = n.begin; x < n.end; ++x)
      for(int y = m.begin; y < m.end; ++y)
        if(!visit_if_meeting(order_[x], order_[y], visit))
          return false;
    return true;
  }

  const std::vector<Box2>& boxes_;
  std::vector<int> order_;
  std::vector<Node> nodes_;
};

} // namespace internal
} // namespace ICM

#endif // ICM_INTERNAL_BOX_PAIRS_H
