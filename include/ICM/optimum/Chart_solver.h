// Moved to <ICM/pipeline/Chart_solver.h>: the chart solver composes the stages (optimum,
// layout, checks), so it stands with the pipeline above them (doc/design.md).

#ifndef ICM_OPTIMUM_CHART_SOLVER_H
#define ICM_OPTIMUM_CHART_SOLVER_H

#define CGAL_DEPRECATED_HEADER "<ICM/optimum/Chart_solver.h>"
#define CGAL_REPLACEMENT_HEADER "<ICM/pipeline/Chart_solver.h>"
#include <CGAL/Installation/internal/deprecation_warning.h>

#include <ICM/pipeline/Chart_solver.h>

#endif // ICM_OPTIMUM_CHART_SOLVER_H
