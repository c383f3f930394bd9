// The linear algebra of every Newton step: the dynamic Laplacian restricted to the vertices
// whose u is free, with a sparse Cholesky whose pattern is analysed once.
//
// Restricting to a free set covers every use: Algorithm 1 pins one vertex (the kernel of
// Delta is the constant vector), the free-boundary optimum frees the non-singular vertices,
// and the harmonic layout frees the interior. Only the upper triangle is stored: Eigen's
// SimplicialLDLT factorizes it in place (from a lower triangle it would copy and transpose
// the matrix at every factorization and analysis) and CHOLMOD reads either.
//
// The unknowns are numbered in a fill-reducing order once: a large mesh's one nested
// dissection of its vertices (`order_vertices_for_elimination`), shared by every Laplacian
// of the run whatever its free set (the cones' solves, Newton's, the layout's; restricting
// an order to a subset of the unknowns never adds fill), else an AMD order of the first
// pattern. A metric that flips its triangulation changes a few entries per Newton step; the
// order stays good for them, so re-analysing after flips costs only the elimination tree. A
// fresh ordering at each analysis was a large share of the run (on a million faces four
// nested dissections took longer than Newton's factorizations; doc/benchmarks.md, Scaling).

#ifndef ICM_CURVATURE_DYNAMIC_LAPLACIAN_H
#define ICM_CURVATURE_DYNAMIC_LAPLACIAN_H

#include <ICM/internal/Elimination_order.h>
#include <ICM/internal/Mesh_index.h>

#include <Eigen/Core>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#ifdef ICM_HAS_CHOLMOD
#include <Eigen/CholmodSupport>
#endif

#include <algorithm>
#include <cmath>
#include <memory>
#include <type_traits>
#include <utility>
#include <vector>

namespace ICM {

using Sparse_matrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

/// Eigen's simplicial LDL^T, in the order `Dynamic_laplacian` numbers its unknowns in:
/// always available, and the fastest choice for small meshes (ahead of CHOLMOD's supernodal
/// LL^T; benchmark/kernels times both) because their Laplacians have small supernodes.
///
/// The analysis reads the matrix in place: Eigen 3.4 recognises "no ordering" only as
/// `NaturalOrdering<Eigen::Index>`, which does not compile with int indices, and otherwise
/// copies the matrix twice per analysis (together about as long as a factorization).
///
/// \cgalModels{\ref SparseSolver}
class Simplicial_solver : public Eigen::SimplicialLDLT<Sparse_matrix, Eigen::Upper, Eigen::NaturalOrdering<int>>
{
public:
  void analyzePattern(const Sparse_matrix& matrix)
  {
    m_P.resize(0);
    m_Pinv.resize(0);
    analyzePattern_preordered(matrix, true);
  }
  /// Entries of the factor the last analysis predicts.
  Eigen::Index factor_nonzeros() const { return m_nonZerosPerCol.sum(); }
};

#ifdef ICM_HAS_CHOLMOD
/// CHOLMOD's supernodal LL^T with its default ordering (SuiteSparse).
///
/// \cgalModels{\ref SparseSolver}
using Cholmod_solver = Eigen::CholmodSupernodalLLT<Sparse_matrix, Eigen::Upper>;

/// CHOLMOD's simplicial LDL^T after a nested dissection ordering of its own (NESDIS),
/// computed at every analysis.
///
/// \cgalModels{\ref SparseSolver}
class Nested_dissection_solver : public Eigen::CholmodDecomposition<Sparse_matrix, Eigen::Upper>
{
public:
  Nested_dissection_solver()
  {
    cholmod().nmethods = 1;
    cholmod().method[0].ordering = CHOLMOD_NESDIS;
    setMode(Eigen::CholmodLDLt);
  }
};

/// CHOLMOD on a matrix already numbered in a fill-reducing order (the analysis keeps it: it
/// is only the elimination tree, the column counts and the supernodes, a fraction of a
/// factorization). CHOLMOD picks supernodal LL^T, which does its work in BLAS, or simplicial
/// LDL^T by the factor's flops per entry: supernodal from 100, where it overtook the
/// simplicial factorization on OpenBLAS (lion-head refined, 33k to 533k unknowns: 77 flops
/// per entry simplicial 0.036 s against 0.044 s; 128 per entry 0.27 s against 0.22 s; 222 per
/// entry 2.2 s against 0.9 s; CHOLMOD's own switch is at 40). A Laplacian with a negative
/// weight (a metric that is not Delaunay) may be indefinite, which CHOLMOD refuses in LL^T and
/// in LDL^T alike: Eigen's LDL^T (`Simplicial_solver`, in the same order) then takes over
/// until the next analysis.
///
/// \cgalModels{\ref SparseSolver}
class Preordered_cholmod_solver
{
public:
  Preordered_cholmod_solver()
  {
    cholmod_.setMode(Eigen::CholmodAuto);
    cholmod_.cholmod().nmethods = 1;
    cholmod_.cholmod().method[0].ordering = CHOLMOD_NATURAL;
    cholmod_.cholmod().supernodal_switch = 100;
    cholmod_.cholmod().print = 0; // an indefinite matrix is handled here, not printed
  }
  void analyzePattern(const Sparse_matrix& matrix)
  {
    cholmod_.analyzePattern(matrix);
    use_ldlt_ = false;
    ldlt_analysed_ = false;
  }
  void factorize(const Sparse_matrix& matrix)
  {
    if(!use_ldlt_)
    {
      cholmod_.factorize(matrix);
      if(cholmod_.info() == Eigen::Success)
        return;
      use_ldlt_ = true;
    }
    if(!ldlt_analysed_)
    {
      ldlt_.analyzePattern(matrix);
      ldlt_analysed_ = true;
    }
    ldlt_.factorize(matrix);
  }
  Eigen::ComputationInfo info() const { return use_ldlt_ ? ldlt_.info() : cholmod_.info(); }
  template <class Rhs>
  typename Rhs::PlainObject solve(const Eigen::MatrixBase<Rhs>& b) const
  {
    if(use_ldlt_)
      return ldlt_.solve(b);
    return cholmod_.solve(b);
  }

private:
  Eigen::CholmodDecomposition<Sparse_matrix, Eigen::Upper> cholmod_;
  Simplicial_solver ldlt_;
  bool use_ldlt_ = false, ldlt_analysed_ = false;
};

/// The default when SuiteSparse is present: Eigen's `Simplicial_solver` below
/// `nested_dissection_min_vertices` unknowns, `Preordered_cholmod_solver` from there on,
/// where `Dynamic_laplacian` numbers the unknowns by nested dissection.
///
/// \cgalModels{\ref SparseSolver (the default with CHOLMOD)}
class Size_adaptive_solver
{
public:
  void analyzePattern(const Sparse_matrix& matrix)
  {
    large_ = matrix.rows() >= nested_dissection_min_vertices;
    if(large_)
      large_solver_.analyzePattern(matrix);
    else
      simplicial_.analyzePattern(matrix);
  }
  void factorize(const Sparse_matrix& matrix)
  {
    if(large_)
      large_solver_.factorize(matrix);
    else
      simplicial_.factorize(matrix);
  }
  Eigen::ComputationInfo info() const { return large_ ? large_solver_.info() : simplicial_.info(); }
  template <class Rhs>
  typename Rhs::PlainObject solve(const Eigen::MatrixBase<Rhs>& b) const
  {
    if(large_)
      return large_solver_.solve(b);
    return simplicial_.solve(b);
  }
  /// Whether the last `analyzePattern` chose CHOLMOD.
  bool uses_cholmod() const { return large_; }
  /// Entries of the simplicial factor the last analysis predicts; 0 for CHOLMOD, whose
  /// nested dissection order does not go stale the way AMD's does.
  Eigen::Index factor_nonzeros() const { return large_ ? 0 : simplicial_.factor_nonzeros(); }

private:
  bool large_ = false;
  Simplicial_solver simplicial_;
  Preordered_cholmod_solver large_solver_;
};
/// The \ref SparseSolver that `CGAL::Default` picks: `Size_adaptive_solver` with CHOLMOD,
/// `Simplicial_solver` without.
using Default_sparse_solver = Size_adaptive_solver;
#else
/// The \ref SparseSolver that `CGAL::Default` picks: `Size_adaptive_solver` with CHOLMOD,
/// `Simplicial_solver` without.
using Default_sparse_solver = Simplicial_solver;
#endif

/// Whether a solver reports the fill of its factor (`factor_nonzeros()`).
template <class Solver, class = void>
struct Reports_fill : std::false_type
{};
template <class Solver>
struct Reports_fill<Solver, std::void_t<decltype(std::declval<const Solver&>().factor_nonzeros())>> : std::true_type
{};

/// Delta(u) restricted to a free vertex set: Delta_ii = sum_j w_ij over all neighbours,
/// Delta_ij = -w_ij between free neighbours. Two edges between the same vertices (possible
/// in an intrinsic triangulation) share one entry. `SparseSolver` is an Eigen sparse Cholesky
/// (analyzePattern / factorize / solve / info).
///
/// \tparam SparseSolver a model of \ref ::SparseSolver "SparseSolver"
template <class SparseSolver = Default_sparse_solver>
class Dynamic_laplacian
{
public:
  Dynamic_laplacian(const internal::Mesh_index& index, const std::vector<char>& is_free)
    : index_(index), free_of_(index.number_of_vertices(), -1)
  {
    for(int v = 0; v < index.number_of_vertices(); ++v)
      if(is_free[v])
      {
        free_of_[v] = static_cast<int>(vertex_of_.size());
        vertex_of_.push_back(v);
      }
    diagonal_slot_.resize(size());
    order_and_analyze(true);
  }

  /// Rebuilds the pattern from the edges of the index (after edge flips) and analyses it
  /// again; the next solve needs a new factorization. Flips can make the fill-reducing order
  /// stale: a first Newton step's flips of a small fraction of the edges can grow the factor
  /// by a sixth. When the solver reports its fill (`factor_nonzeros()`) and it grew by more
  /// than `max_fill_growth` since the unknowns were numbered, they are numbered again: AMD
  /// costs a fraction of a factorization there, and a factor 10% larger costs more than that
  /// over the remaining Newton steps. Returns whether the unknowns were renumbered.
  bool rebuild_pattern(double max_fill_growth = 0.1)
  {
    build_pattern();
    analyze();
    if(!(factor_nonzeros() > (1.0 + max_fill_growth) * ordered_fill_))
      return false;
    order_and_analyze(false);
    return true;
  }

  int size() const { return static_cast<int>(vertex_of_.size()); }
  /// Position of vertex `v` among the unknowns, or -1 when it is fixed.
  int free_index(int v) const { return free_of_[v]; }
  int vertex(int i) const { return vertex_of_[i]; }
  const Sparse_matrix& matrix() const { return matrix_; }

  /// Writes the values of Delta for the per-edge weights `w` into the fixed pattern.
  void assemble(const std::vector<double>& w)
  {
    double* values = matrix_.valuePtr();
    std::fill(values, values + matrix_.nonZeros(), 0.0);
    for(int e = 0; e < index_.number_of_edges(); ++e)
    {
      if(index_.edges[e][0] == index_.edges[e][1])
        continue; // a loop of an intrinsic triangulation: w (u_i - u_i)^2 adds nothing
      const int i = free_of_[index_.edges[e][0]], j = free_of_[index_.edges[e][1]];
      if(i >= 0)
        values[diagonal_slot_[i]] += w[e];
      if(j >= 0)
        values[diagonal_slot_[j]] += w[e];
      if(edge_slot_[e] >= 0)
        values[edge_slot_[e]] -= w[e];
    }
  }

  /// Numeric factorization only; the symbolic analysis was done once in the constructor.
  bool factorize()
  {
    if(size() == 0)
      return true;
    solver_->factorize(matrix_);
    factorized_ = solver_->info() == Eigen::Success;
    previous_ = std::make_unique<SparseSolver>(); // outdated now: its memory goes
    previous_factorized_ = false;
    return factorized_;
  }

  /// Whether `other` has the same unknowns in the same order, so that its factorization
  /// preconditions this Laplacian's solves.
  bool numbers_unknowns_as(const Dynamic_laplacian& other) const { return vertex_of_ == other.vertex_of_; }

  /// Whether a numeric factorization of some earlier assembly is available: of this pattern,
  /// or of the one before the last `rebuild_pattern()` when that kept the unknowns' numbers.
  bool has_factorization() const { return factorized_ || previous_factorized_; }

  /// Solves Delta_FF x = b for right-hand sides given per free unknown, with the last
  /// factorization.
  template <class Rhs>
  typename Rhs::PlainObject solve(const Eigen::MatrixBase<Rhs>& b) const
  {
    if(size() == 0)
      return b; // no unknown (every vertex fixed): nothing was factorized
    return solver_->solve(b);
  }

  /// Solves with the matrix as assembled now, using the last factorization — of a nearby
  /// assembly, also of the pattern before a few edge flips — as preconditioner of an
  /// iterative refinement. When every weight changed by a relative epsilon since that
  /// factorization, the error contracts by epsilon per refinement (a Laplacian with
  /// non-negative weights is then within (1 +- epsilon) of the factorized one in the Loewner
  /// order). Succeeds when a correction is below `tolerance` relative to x, or when the
  /// corrections stop halving below `rounding_floor` of it: there the refinement has reached
  /// the solve's own rounding (condition number times epsilon, some 1e-10 at 4M unknowns),
  /// which a new factorization would not lower. Returns false otherwise, after at most
  /// `max_refinements` corrections.
  template <class Rhs>
  bool solve_refined(const Eigen::MatrixBase<Rhs>& b, typename Rhs::PlainObject& x, double tolerance = 1e-13,
                     int max_refinements = 6) const
  {
    constexpr double rounding_floor = 1e-8;
    if(size() == 0)
    {
      x = b;
      return true;
    }
    const SparseSolver& factor = factorized_ ? *solver_ : *previous_;
    x = factor.solve(b);
    double last = HUGE_VAL;
    for(int refinement = 0; refinement < max_refinements; ++refinement)
    {
      const typename Rhs::PlainObject correction =
        factor.solve(b - matrix_.template selfadjointView<Eigen::Upper>() * x);
      x += correction;
      const double size = correction.norm(), scale = x.norm();
      if(size <= tolerance * scale || (size > 0.5 * last && size <= rounding_floor * scale))
        return x.allFinite();
      last = size;
    }
    return false;
  }

  /// Solves with the matrix as assembled now by conjugate gradients, preconditioned by the
  /// last factorization (of a nearby assembly, also of the pattern before a few edge flips).
  /// Where every weight changed by a relative epsilon since that factorization, the
  /// preconditioned matrix has its spectrum in [1 - epsilon, 1 + epsilon] and each iteration
  /// shrinks the error by about epsilon / 2: a Newton step's weights, which move by a few
  /// percent, are solved to a Newton step's accuracy in a few triangular solves, where
  /// `solve_refined`, a fixed-point iteration, contracts by epsilon only and diverges past
  /// epsilon = 1. Succeeds when |b - A x| <= `tolerance` |b| in every column of b; returns
  /// false after `max_iterations` solves, or on a direction of non-positive curvature (a
  /// Laplacian with negative weights may be indefinite). `iterations` counts the solves.
  /// `factorized`, when given, lends its last factorization instead
  /// (`numbers_unknowns_as(*factorized)`).
  template <class Rhs>
  bool solve_preconditioned(const Eigen::MatrixBase<Rhs>& b, typename Rhs::PlainObject& x, double tolerance,
                            int max_iterations, int& iterations, const Dynamic_laplacian* factorized = nullptr) const
  {
    // Each column of b is its own CG run; the columns share every triangular solve, which
    // costs little more for two columns than for one (the factor is read once).
    using Plain = typename Rhs::PlainObject;
    using Row = Eigen::Matrix<double, 1, Rhs::ColsAtCompileTime>;
    iterations = 0;
    x = Plain::Zero(b.rows(), b.cols());
    if(size() == 0)
      return true;
    const Dynamic_laplacian& lender = factorized != nullptr ? *factorized : *this;
    const SparseSolver& factor = lender.factorized_ ? *lender.solver_ : *lender.previous_;
    const Row target = tolerance * b.colwise().norm();
    Plain r = b, z = factor.solve(r), p = z, q(b.rows(), b.cols());
    Row rz = r.cwiseProduct(z).colwise().sum();
    Eigen::Array<bool, 1, Rhs::ColsAtCompileTime> done = (r.colwise().norm().array() <= target.array());
    for(iterations = 1; iterations <= max_iterations; ++iterations)
    {
      q.noalias() = matrix_.template selfadjointView<Eigen::Upper>() * p;
      const Row curvature = p.cwiseProduct(q).colwise().sum();
      for(Eigen::Index c = 0; c < b.cols(); ++c)
      {
        if(done(c))
          continue;
        if(!(curvature(c) > 0.0))
          return false;
        const double step = rz(c) / curvature(c);
        x.col(c) += step * p.col(c);
        r.col(c) -= step * q.col(c);
        done(c) = r.col(c).norm() <= target(c);
      }
      if(done.all())
        return x.allFinite();
      if(iterations == max_iterations)
        break;
      z = factor.solve(r);
      const Row rz_next = r.cwiseProduct(z).colwise().sum();
      for(Eigen::Index c = 0; c < b.cols(); ++c)
        if(!done(c))
          p.col(c) = z.col(c) + (rz_next(c) / rz(c)) * p.col(c);
      rz = rz_next;
    }
    return false;
  }

private:
  /// Numbers the unknowns in a fill-reducing order (the mesh's, when it has one and
  /// `use_mesh_order`, else of the current edges), then analyses.
  void order_and_analyze(bool use_mesh_order)
  {
    if(!use_mesh_order || index_.elimination_rank.empty())
      build_pattern();
    number_unknowns_in_fill_reducing_order(use_mesh_order);
    build_pattern();
    analyze();
    previous_factorized_ = false; // of other numbers
    ordered_fill_ = factor_nonzeros();
  }

  /// The fill the solver predicts, or 0 when it does not say.
  double factor_nonzeros() const
  {
    if constexpr(Reports_fill<SparseSolver>::value)
      return size() > 0 ? static_cast<double>(solver_->factor_nonzeros()) : 0.0;
    else
      return 0.0;
  }

  /// A new analysis ends the current factorization; it is kept aside for `solve_refined` and
  /// `solve_preconditioned` (until the next factorization or renumbering, over any number of
  /// analyses), since a Newton step near the solution flips a few edges (lion-head Loop x3:
  /// 2 of 1.6M) and leaves a factorization that still solves the new system in a few solves.
  void analyze()
  {
    if(factorized_)
    {
      std::swap(solver_, previous_);
      previous_factorized_ = true;
    }
    factorized_ = false;
    if(size() > 0)
      solver_->analyzePattern(matrix_);
  }

  /// Renumbers the unknowns in the mesh's elimination order when it has one and
  /// `use_mesh_order`, else in a fill-reducing order of the current pattern.
  void number_unknowns_in_fill_reducing_order(bool use_mesh_order)
  {
    if(size() == 0)
      return;
    if(use_mesh_order && !index_.elimination_rank.empty())
    {
      const std::vector<int>& rank = index_.elimination_rank;
      std::sort(vertex_of_.begin(), vertex_of_.end(), [&rank](int a, int b) { return rank[a] < rank[b]; });
    }
    else
    {
      const std::vector<int> order = internal::fill_reducing_order(matrix_);
      std::vector<int> vertex_in_order(size());
      for(int i = 0; i < size(); ++i)
        vertex_in_order[i] = vertex_of_[order[i]];
      vertex_of_.swap(vertex_in_order);
    }
    for(int i = 0; i < size(); ++i)
      free_of_[vertex_of_[i]] = i;
  }

  /// The upper triangle of the free vertices' adjacency, column by column, and the slot of
  /// every edge in it, in two passes over the edges and no search: this runs again after
  /// every Newton step whose edge flips changed the triangulation.
  void build_pattern()
  {
    const int n = size();
    const int ne = index_.number_of_edges();
    // Entries of column j: (row i <= j, edge e), the diagonal with e = -1.
    std::vector<int>& start = column_start_;
    start.assign(n + 1, 0);
    for(int i = 0; i < n; ++i)
      start[i + 1] = 1;
    for(int e = 0; e < ne; ++e)
    {
      const int i = free_of_[index_.edges[e][0]], j = free_of_[index_.edges[e][1]];
      if(i >= 0 && j >= 0 && i != j)
        ++start[std::max(i, j) + 1];
    }
    for(int i = 0; i < n; ++i)
      start[i + 1] += start[i];
    entries_.resize(start[n]);
    next_.assign(start.begin(), start.end() - 1);
    for(int i = 0; i < n; ++i)
      entries_[next_[i]++] = {i, -1};
    edge_slot_.assign(ne, -1);
    for(int e = 0; e < ne; ++e)
    {
      const int i = free_of_[index_.edges[e][0]], j = free_of_[index_.edges[e][1]];
      if(i >= 0 && j >= 0 && i != j)
        entries_[next_[std::max(i, j)]++] = {std::min(i, j), e};
    }

    // Sort each column by row (a handful of entries: insertion sort) and merge the entries
    // of two edges that join the same vertices, possible in an intrinsic triangulation.
    matrix_.resize(n, n);
    matrix_.resizeNonZeros(start[n]);
    int* outer = matrix_.outerIndexPtr();
    int* inner = matrix_.innerIndexPtr();
    int nonzeros = 0;
    for(int j = 0; j < n; ++j)
    {
      std::pair<int, int>* first = entries_.data() + start[j];
      std::pair<int, int>* last = entries_.data() + start[j + 1];
      for(std::pair<int, int>* x = first + 1; x < last; ++x)
        for(std::pair<int, int>* y = x; y > first && y[-1].first > y[0].first; --y)
          std::swap(y[-1], y[0]);
      outer[j] = nonzeros;
      for(std::pair<int, int>* x = first; x < last; ++x)
      {
        if(x == first || x->first != x[-1].first)
          inner[nonzeros++] = x->first;
        if(x->second >= 0)
          edge_slot_[x->second] = nonzeros - 1;
        else
          diagonal_slot_[j] = nonzeros - 1;
      }
    }
    outer[n] = nonzeros;
    matrix_.resizeNonZeros(nonzeros);
    std::fill(matrix_.valuePtr(), matrix_.valuePtr() + nonzeros, 0.0);
  }

  const internal::Mesh_index& index_;
  std::vector<int> free_of_;
  std::vector<int> vertex_of_;
  double ordered_fill_ = 0; ///< factor_nonzeros() when the unknowns were numbered
  Sparse_matrix matrix_;
  std::vector<int> diagonal_slot_;
  std::vector<int> edge_slot_;
  std::vector<int> column_start_, next_; // build_pattern's scratch, kept between rebuilds
  std::vector<std::pair<int, int>> entries_;
  std::unique_ptr<SparseSolver> solver_ = std::make_unique<SparseSolver>();
  std::unique_ptr<SparseSolver> previous_ = std::make_unique<SparseSolver>(); // see analyze()
  bool factorized_ = false, previous_factorized_ = false;
};

} // namespace ICM

#endif // ICM_CURVATURE_DYNAMIC_LAPLACIAN_H
