// CGAL's parameterizers take <TriangleMesh, BorderParameterizer_, SolverTraits_>; ICM's takes
// <TriangleMesh, Metric, SparseSolver, Energy, BorderCondition>. So that a CGAL program ports by
// changing the parameterizer's name, the second and third arguments may also be CGAL's:
//  - a CGAL border parameterizer becomes the border condition: a fixed-border one (circle,
//    square, a user's) the shape of its polygon (`Border_shape`), `Two_vertices_parameterizer_3`
//    (LSCM's and ARAP's, which pins two vertices of a free border) the free border, which
//    needs no pinned vertex;
//  - a CGAL solver traits (`CGAL::Eigen_solver_traits<S>`) becomes its Eigen solver when that
//    is a simplicial Cholesky (on the upper triangle, which the dynamic Laplacian fills), else
//    ICM's default: the Laplacian is symmetric positive definite and Newton needs it solved
//    exactly, which CGAL's default BiCGSTAB does not do.
// Anything else stops the compilation with one sentence naming the argument.

#ifndef ICM_PIPELINE_CGAL_ARGUMENTS_H
#define ICM_PIPELINE_CGAL_ARGUMENTS_H

#include <ICM/border/Border_conditions.h>
#include <ICM/border/Border_shape.h>
#include <ICM/curvature/Dynamic_laplacian.h>
#include <ICM/metrics/Intrinsic_delaunay_metric.h>

#include <CGAL/Default.h>

#include <Eigen/SparseCholesky>

#include <type_traits>
#include <utility>

namespace ICM {
namespace internal {

/// Whether `T` is a CGAL border parameterizer (it names its `Triangle_mesh` and says whether
/// its border is convex).
template <class T, class = void>
struct Is_border_parameterizer : std::false_type
{};
template <class T>
struct Is_border_parameterizer<
  T, std::void_t<typename T::Triangle_mesh, decltype(std::declval<const T&>().is_border_convex())>> : std::true_type
{};

/// Whether `T` is a CGAL sparse linear algebra traits (`SparseLinearAlgebraTraits_d`).
template <class T, class = void>
struct Is_solver_traits : std::false_type
{};
template <class T>
struct Is_solver_traits<T, std::void_t<typename T::Matrix, typename T::Vector, typename T::NT>> : std::true_type
{};

/// Whether `T` models ICM's `Metric` (doc/concepts.md): a name, u0, a summary.
template <class T, class = void>
struct Is_metric : std::false_type
{};
template <class T>
struct Is_metric<T, std::void_t<decltype(T::name), decltype(std::declval<const T&>().u0),
                                decltype(std::declval<const T&>().summary())>> : std::true_type
{};

/// Whether `T` can factorize and solve a sparse symmetric system as the dynamic Laplacian
/// asks (an Eigen sparse Cholesky, `Size_adaptive_solver`).
template <class T, class = void>
struct Is_sparse_solver : std::false_type
{};
template <class T>
struct Is_sparse_solver<
  T, std::void_t<decltype(std::declval<T&>().analyzePattern(std::declval<const Eigen::SparseMatrix<double>&>())),
                 decltype(std::declval<T&>().factorize(std::declval<const Eigen::SparseMatrix<double>&>())),
                 decltype(std::declval<const T&>().info())>> : std::true_type
{};

/// One of Eigen's simplicial Cholesky factorizations, in the form the dynamic Laplacian takes:
/// ICM's sparse matrix, whose upper triangle it fills (`type`); else not one (`void`).
template <class T>
struct Simplicial_cholesky_form
{
  using type = void;
};
template <class Matrix, int UpLo, class Ordering>
struct Simplicial_cholesky_form<Eigen::SimplicialLDLT<Matrix, UpLo, Ordering>>
{
  using type = Eigen::SimplicialLDLT<Sparse_matrix, Eigen::Upper, Ordering>;
};
template <class Matrix, int UpLo, class Ordering>
struct Simplicial_cholesky_form<Eigen::SimplicialCholesky<Matrix, UpLo, Ordering>>
{
  using type = Eigen::SimplicialLDLT<Sparse_matrix, Eigen::Upper, Ordering>; // its default mode
};
template <class Matrix, int UpLo, class Ordering>
struct Simplicial_cholesky_form<Eigen::SimplicialLLT<Matrix, UpLo, Ordering>>
{
  using type = Eigen::SimplicialLLT<Sparse_matrix, Eigen::Upper, Ordering>;
};

/// The metric of the second argument: ICM's default when it is a border parameterizer.
template <class Argument>
using Metric_argument = std::conditional_t<Is_border_parameterizer<Argument>::value, Default_metric,
                                           typename CGAL::Default::Get<Argument, Default_metric>::type>;

/// The solver of the third argument (see the file comment).
template <class Argument, class = void>
struct Solver_argument
{
  using type = typename CGAL::Default::Get<Argument, Default_sparse_solver>::type;
};
template <class Argument>
struct Solver_argument<Argument, std::enable_if_t<Is_solver_traits<Argument>::value>>
{
  using Cholesky = typename Simplicial_cholesky_form<typename Argument::Solver>::type;
  using type = std::conditional_t<std::is_void<Cholesky>::value, Default_sparse_solver, Cholesky>;
};

/// The border condition: the fifth argument, or the border parameterizer's (second), or free.
template <class BorderCondition, class Second, class = void>
struct Border_condition_argument
{
  using type = typename CGAL::Default::Get<BorderCondition, Free_border>::type;
};
template <class Second>
struct Border_condition_argument<CGAL::Default, Second, std::enable_if_t<Is_border_parameterizer<Second>::value>>
{
  using type =
    std::conditional_t<std::is_same<Second, CGAL::Surface_mesh_parameterization::Two_vertices_parameterizer_3<
                                              typename Second::Triangle_mesh>>::value,
                       Free_border, Border_shape<Second>>;
};

/// The border condition made from a CGAL border parameterizer object.
template <class Condition, class BorderParameterizer>
Condition border_condition_of(const BorderParameterizer& border)
{
  if constexpr(std::is_constructible<Condition, const BorderParameterizer&>::value)
    return Condition(border);
  else
    return Condition(); // the free border pins nothing
}

} // namespace internal
} // namespace ICM

#endif // ICM_PIPELINE_CGAL_ARGUMENTS_H
