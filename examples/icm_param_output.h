// icm_param's output files, besides the mesh's format (checked with the command line,
// icm_param_arguments.cpp): where they go, checked before any work, and the pictures asked for.

#ifndef ICM_PARAM_OUTPUT_H
#define ICM_PARAM_OUTPUT_H

#include "icm_param_arguments.h"

#include <ICM/IO/write_uv_files.h>

#include <string>

namespace icm_param {

/// Why the outputs cannot be written, found before hours of work rather than after: two
/// outputs on one file, an output over an input, a read-only target, a missing directory.
std::string check_output_paths(const Arguments& args);

/// The pictures asked for, with the SVG's title.
ICM::IO::Uv_pictures pictures_of(const Arguments& args);

} // namespace icm_param

#endif // ICM_PARAM_OUTPUT_H
