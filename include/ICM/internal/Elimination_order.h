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

} // namespace elimination
#endif

/// A fill-reducing order of the symmetric pattern `upper` (its upper triangle, column by
/// column): `order[i]` is the unknown eliminated i-th. Nested dissection (METIS through
/// CHOLMOD) from `nested_dissection_min_vertices` unknowns
/// when CHOLMOD is present, Eigen's AMD otherwise.
inline std::vector<int> fill_reducing_order(const Eigen::SparseMatrix<double, Eigen::ColMajor, int>& upper)
{
  const int n = static_cast<int>(upper.rows());
#ifdef ICM_HAS_CHOLMOD
  if(n >= nested_dissection_min_vertices)
  {
    // One METIS call on one thread: METIS draws from one random number generator shared by
    // the whole process, so two calls at once (each half of a first separator on its own
    // thread, as ICM once did to save 40% of this time) draw in an order that changes from
    // run to run, and with it the order, the rounding and the map (armadillo's and
    // refined_elephant's output differed from run to run).
    const std::vector<int> order = elimination::metis_order(upper);
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
