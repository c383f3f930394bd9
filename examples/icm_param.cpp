// icm_param: parameterize any triangle mesh file with the inverse curvature map (cones and
// seams where its topology needs them, one chart per connected component) and write the UV'd
// mesh (OBJ with a vt per corner side of every seam, PLY with per-corner texcoords, or glTF
// split at the seams, by the extension of -o), optionally pictures (the layout as SVG or PNG,
// the surface with a checkerboard as PNG) and a JSON line.
//
//   icm_param INPUT -o OUTPUT.obj|.ply|.gltf|.glb [--ply-binary] [--svg FILE] [--png FILE] [--preview FILE]
//             [--picture-size PIXELS] [--json] [--triangulate] [--quiet]
//             [--metric intrinsic-delaunay|vertex-scaling|inversive-distance|circle-packing]
//             [--energy entropy|u-square|area|angle|log-area]
//             [--cones auto|N] [--cone VERTEX:DEGREES]... [--seams FILE.selection.txt]
//             [--keep-overlaps] [--atlas SIZE [--padding TEXELS]]   (icm_param --help for all)
//
// The input is untrusted: it is read by ICM's own checked readers (IO/read_polygon_soup.h),
// repaired only as users expect (isolated vertices dropped, non-manifold vertices split,
// polygons triangulated with --triangulate), and everything else refused with the reason.
// On any failure it prints one line on stderr naming the reason (and with --json a JSON error
// object on stdout), exits non-zero and changes no file: the mesh and the pictures are written to
// temporary files and renamed into place together, only when all were written. An output
// name whose extension names no format written is refused before any work.
//
// The files: the command line (icm_param_arguments.h), the run of one mesh (icm_param_run.h)
// with its output files (icm_param_output.h), its figures and JSON line (icm_param_report.h)
// and its progress line (icm_param_progress.h), a batch of meshes (icm_param_batch.h), and the
// runs of each energy and border (icm_param_energy.h).

#include "icm_param_arguments.h"
#include "icm_param_batch.h"
#include "icm_param_run.h"

#include <csignal>
#include <cstdlib>
#include <exception>
#include <fstream>
#include <new>
#include <string>

#if defined(__linux__) && defined(__GLIBC__)
#include <unistd.h>
#endif

namespace {

/// Whether the kernel gives transparent huge pages to the memory a process asks for
/// (madvise), not to all of it (always) nor to none (never).
bool huge_pages_on_request()
{
  std::ifstream setting("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string line;
  return std::getline(setting, line) && line.find("[madvise]") != std::string::npos;
}

/// glibc's malloc asks for huge pages for its large blocks only in a process started with
/// GLIBC_TUNABLES=glibc.malloc.hugetlb=1. Where the kernel gives them on request (Debian's
/// default) a large mesh then takes one page fault per 2 MB instead of one per 4 kB, which a
/// virtual machine pays dearly: on the 2-core VM, lion-head Loop x3 (1.07M faces, --cones 0)
/// takes 13.6-13.9 s instead of 16.0-16.9 s. So icm_param starts itself again, once, with it,
/// unless GLIBC_TUNABLES is set (to anything: the user's choice). If the exec fails, the run
/// goes on as it is.
void restart_with_huge_pages(char** argv)
{
#if defined(__linux__) && defined(__GLIBC__)
  if(std::getenv("GLIBC_TUNABLES") != nullptr || !huge_pages_on_request())
    return;
  if(::setenv("GLIBC_TUNABLES", "glibc.malloc.hugetlb=1", 0) == 0)
    ::execv("/proc/self/exe", argv);
#else
  (void)argv;
#endif
}

} // namespace

int main(int argc, char** argv)
{
  restart_with_huge_pages(argv);
  icm_param::Arguments args;
  icm_param::Failure_report fail;
  for(int i = 1; i < argc; ++i)
    fail.json = fail.json || std::string(argv[i]) == "--json";
  const int parsed = icm_param::parse_arguments(argc, argv, args, fail);
  if(parsed >= 0)
    return parsed;
  fail.json = fail.json || !args.batch_item.empty();
  fail.input = args.input;
  fail.output = args.output;
  try
  {
    if(!args.batch.output_dir.empty() && args.batch_item.empty())
      return icm_param::run_batch(args.batch, argc, argv);
    // Test only (test_cli_batch.cpp): a batch item that crashes, as a bug would.
    if(const char* crash = std::getenv("ICM_PARAM_TEST_CRASH"); crash != nullptr && args.batch_item == crash)
      std::raise(SIGSEGV);
    if(!args.batch_item.empty() && args.batch.max_memory_mb > 0)
      if(std::string error; !icm_param::limit_memory(args.batch.max_memory_mb, error))
        return fail(error);
    return icm_param::run(args, fail);
  }
  catch(const std::bad_alloc&)
  {
    return fail("out of memory");
  }
  catch(const std::exception& e)
  {
    return fail(std::string("internal error: ") + e.what());
  }
}
