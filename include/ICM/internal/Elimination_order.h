// One fill-reducing elimination order of a mesh's vertices, computed once and shared by the
// sparse Cholesky factorizations of every Laplacian built on the mesh
// (curvature/Dynamic_laplacian.h).

#ifndef ICM_INTERNAL_ELIMINATION_ORDER_H
#define ICM_INTERNAL_ELIMINATION_ORDER_H

#include <ICM/internal/Mesh_index.h>

#include <Eigen/OrderingMethods>
#include <Eigen/SparseCore>
#ifdef ICM_HAS_CHOLMOD
#include <cholmod.h>
#endif

#include <algorithm>
#include <array>
#include <thread>
#include <type_traits>
#include <utility>
#include <vector>

namespace ICM {

/// Vertices from which a mesh gets one nested dissection order of its own
/// (`order_vertices_for_elimination`) and the default solver CHOLMOD's factorizations in it.
/// On lion-head refined to 66k faces (33k unknowns) one nested dissection, paid once per
/// mesh, costs 0.13 s and every factorization after it takes half as long as in AMD order;
/// at 8k vertices the two are within milliseconds (measured with CHOLMOD and OpenBLAS,
/// doc/solvers.md).
constexpr int nested_dissection_min_vertices = 25000;

namespace internal {

#ifdef ICM_HAS_CHOLMOD
namespace elimination {

/// CHOLMOD's view of the symmetric pattern `upper` (its upper triangle, column by column).
inline cholmod_sparse pattern_of(const Eigen::SparseMatrix<double, Eigen::ColMajor, int>& upper)
{
  cholmod_sparse pattern{};
  pattern.nrow = pattern.ncol = static_cast<std::size_t>(upper.rows());
  pattern.nzmax = static_cast<std::size_t>(upper.nonZeros());
  pattern.p = const_cast<int*>(upper.outerIndexPtr());
  pattern.i = const_cast<int*>(upper.innerIndexPtr());
  pattern.stype = 1;
  pattern.itype = CHOLMOD_INT;
  pattern.xtype = CHOLMOD_PATTERN;
  pattern.dtype = CHOLMOD_DOUBLE;
  pattern.sorted = 1;
  pattern.packed = 1;
  return pattern;
}

/// METIS's nested dissection of `upper` through CHOLMOD, postordered, or empty when it fails.
inline std::vector<int> metis_order(const Eigen::SparseMatrix<double, Eigen::ColMajor, int>& upper)
{
  std::vector<int> order(static_cast<std::size_t>(upper.rows()));
  cholmod_common common;
  cholmod_start(&common);
  common.print = 0;
  cholmod_sparse pattern = pattern_of(upper);
  const bool ordered = cholmod_metis(&pattern, nullptr, 0, 1, order.data(), &common) != 0;
  cholmod_finish(&common);
  return ordered ? order : std::vector<int>();
}

/// The upper triangle of `upper` restricted to the unknowns `part` (in their order).
inline Eigen::SparseMatrix<double, Eigen::ColMajor, int>
principal_submatrix(const Eigen::SparseMatrix<double, Eigen::ColMajor, int>& upper, const std::vector<int>& part,
                    std::vector<int>& position)
{
  for(std::size_t i = 0; i < part.size(); ++i)
    position[part[i]] = static_cast<int>(i);
  std::vector<Eigen::Triplet<double, int>> entries;
  for(int j : part)
    for(Eigen::SparseMatrix<double, Eigen::ColMajor, int>::InnerIterator it(upper, j); it; ++it)
      if(position[it.row()] >= 0)
        entries.emplace_back(position[it.row()], position[j], 1.0);
  Eigen::SparseMatrix<double, Eigen::ColMajor, int> sub(static_cast<int>(part.size()), static_cast<int>(part.size()));
  sub.setFromTriplets(entries.begin(), entries.end());
  for(int v : part)
    position[v] = -1;
  return sub;
}

/// Nested dissection with its two halves ordered at once: METIS's first separator
/// (`cholmod_bisect`), then each side ordered by METIS on its own thread, the separator last.
/// The levels below the first take most of METIS's time, so two cores order in about 60% of
/// the time of one (lion-head refined to 1.07M faces: 2.6 s for one call); the fill is that
/// of one dissection with the same first separator. Empty when the bisection fails.
inline std::vector<int> two_sided_metis_order(const Eigen::SparseMatrix<double, Eigen::ColMajor, int>& upper)
{
  const int n = static_cast<int>(upper.rows());
  std::vector<int> side(n);
  {
    cholmod_common common;
    cholmod_start(&common);
    common.print = 0;
    cholmod_sparse pattern = pattern_of(upper);
    const bool bisected =
      cholmod_bisect(&pattern, nullptr, 0, 1, side.data(), &common) >= 0 && common.status == CHOLMOD_OK;
    cholmod_finish(&common);
    if(!bisected)
      return {};
  }
  std::array<std::vector<int>, 3> parts; // left, right, separator
  for(int v = 0; v < n; ++v)
    parts[side[v]].push_back(v);
  if(parts[0].empty() || parts[1].empty())
    return {};
  std::vector<int> position(n, -1);
  const Eigen::SparseMatrix<double, Eigen::ColMajor, int> left = principal_submatrix(upper, parts[0], position);
  const Eigen::SparseMatrix<double, Eigen::ColMajor, int> right = principal_submatrix(upper, parts[1], position);
  std::vector<int> right_order;
  std::thread right_thread([&right, &right_order] { right_order = metis_order(right); });
  const std::vector<int> left_order = metis_order(left);
  right_thread.join();
  if(left_order.empty() || right_order.empty())
    return {};
  std::vector<int> order;
  order.reserve(n);
  for(int i : left_order)
    order.push_back(parts[0][i]);
  for(int i : right_order)
    order.push_back(parts[1][i]);
  order.insert(order.end(), parts[2].begin(), parts[2].end());
  return order;
}

} // namespace elimination
#endif

/// A fill-reducing order of the symmetric pattern `upper` (its upper triangle, column by
/// column): `order[i]` is the unknown eliminated i-th. Nested dissection (METIS through
/// CHOLMOD, its two halves on two threads) from `nested_dissection_min_vertices` unknowns
/// when CHOLMOD is present, Eigen's AMD otherwise.
inline std::vector<int> fill_reducing_order(const Eigen::SparseMatrix<double, Eigen::ColMajor, int>& upper)
{
  const int n = static_cast<int>(upper.rows());
#ifdef ICM_HAS_CHOLMOD
  if(n >= nested_dissection_min_vertices)
  {
    std::vector<int> order = elimination::two_sided_metis_order(upper);
    if(order.empty())
      order = elimination::metis_order(upper);
    if(!order.empty())
      return order;
  }
#endif
  std::vector<int> order(n);
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> inverse;
  Eigen::AMDOrdering<int>()(upper, inverse); // orders the pattern of A + A^T
  const Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> permutation = inverse.inverse();
  for(int i = 0; i < n; ++i)
    order[permutation.indices()[i]] = i;
  return order;
}

/// Gives a mesh of at least `nested_dissection_min_vertices` vertices its
/// `Mesh_index::elimination_rank`: one nested dissection of its vertex graph, joined with the
/// edges of `flipped` (the same vertices triangulated otherwise) when given, that every
/// Laplacian built on the mesh after this reuses (without CHOLMOD, or on a smaller mesh,
/// each Laplacian orders its own unknowns by AMD, which costs little there).
inline void order_vertices_for_elimination(Mesh_index& index, const Mesh_index* flipped = nullptr)
{
  index.elimination_rank.clear();
#ifdef ICM_HAS_CHOLMOD
  const int n = index.number_of_vertices();
  if(n < nested_dissection_min_vertices)
    return;
  std::vector<Eigen::Triplet<double, int>> entries;
  entries.reserve(index.edges.size() + (flipped != nullptr ? flipped->edges.size() : 0) + n);
  for(int v = 0; v < n; ++v)
    entries.emplace_back(v, v, 1.0);
  for(const Mesh_index* graph : {static_cast<const Mesh_index*>(&index), flipped})
    if(graph != nullptr)
      for(const auto& e : graph->edges)
        if(e[0] != e[1])
          entries.emplace_back(std::min(e[0], e[1]), std::max(e[0], e[1]), 1.0);
  Eigen::SparseMatrix<double, Eigen::ColMajor, int> upper(n, n);
  upper.setFromTriplets(entries.begin(), entries.end()); // an edge of both graphs sums to one entry
  const std::vector<int> order = fill_reducing_order(upper);
  index.elimination_rank.resize(n);
  for(int r = 0; r < n; ++r)
    index.elimination_rank[order[r]] = r;
#endif
}

/// `order_vertices_for_elimination` for the Laplacians of `Metric`: a metric that flips the
/// mesh to another triangulation (`Intrinsic_delaunay_metric::triangulation()`) joins
/// vertices across the mesh's separators (lion-head refined to 267k faces flips 14% of its
/// edges, and its factor in the mesh's own order had six times the entries), so the order is
/// of both graphs; Ptolemy flips during Newton and edges kept by seams then add little.
template <class Metric, class = void>
struct Flips_the_triangulation : std::false_type
{};
template <class Metric>
struct Flips_the_triangulation<Metric, std::void_t<decltype(std::declval<const Metric&>().triangulation())>>
  : std::is_constructible<Metric, const Mesh_index&>
{};

template <class Metric>
void order_vertices_for_elimination_in(Mesh_index& index)
{
  if(!Flips_the_triangulation<Metric>::value || index.number_of_vertices() < nested_dissection_min_vertices)
    return order_vertices_for_elimination(index);
  if constexpr(Flips_the_triangulation<Metric>::value)
  {
    index.elimination_rank.clear();
    const Metric metric(index);
    order_vertices_for_elimination(index, &metric.triangulation());
  }
}

} // namespace internal
} // namespace ICM

#endif // ICM_INTERNAL_ELIMINATION_ORDER_H
