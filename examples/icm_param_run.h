// icm_param's run of one mesh (INPUT -o OUTPUT, or a batch's child): read it, parameterize
// it, write the outputs, tell the figures (icm_param_run.cpp).

#ifndef ICM_PARAM_RUN_H
#define ICM_PARAM_RUN_H

#include "icm_param_arguments.h"

namespace icm_param {

/// Runs the mesh `args` names and returns the exit code: 0 once every output is written and
/// the figures told, 1 after `fail` has told why nothing is written.
int run(const Arguments& args, const Failure_report& fail);

} // namespace icm_param

#endif // ICM_PARAM_RUN_H
