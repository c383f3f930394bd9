// compare's command line, parsed with CLI11: which words are options and which their values,
// then each value checked in the order of the usage, with the messages compare always gave.
// A wrong command line gets the reason and the usage on stderr and exit code 2.

#include "options.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <limits>

namespace compare {

namespace {

const char* usage_text = "usage: compare [--json] [--runs N] [--time-limit SECONDS] [--methods a,b,c]\n"
                         "               [--subdivide K] [--open] [--svg-panels FILE] [--json-file FILE]\n"
                         "               [--write-mesh FILE] [--quiet] MESH...\n"
                         "\n"
                         "Runs each parameterization method on each mesh (OFF/OBJ/PLY) and prints the paper's\n"
                         "Table I plus time, memory and flips as Markdown (or JSON lines). A disk gets every\n"
                         "method of the registry: ICM's free boundary in each metric (icm_free_boundary,\n"
                         "icm_vertex_scaling, icm_inversive_distance, icm_circle_packing), ICM's other energies\n"
                         "(icm_u_square, icm_area, icm_angle, icm_log_area) and CGAL's lscm, arap, dcm, dac, mvc.\n"
                         "A mesh that is not a disk gets ICM::parameterize() (row icm) and CGAL's methods on a\n"
                         "seam mesh cut along ICM's seams; a closed genus-0 mesh also icm_free_boundary_opened.\n"
                         "\n"
                         "  --json             one JSON object per (mesh, method) on stdout instead of Markdown\n"
                         "  --runs N           timed runs per method, median reported (default: 3 if one run\n"
                         "                     takes < 2 s, else 1)\n"
                         "  --time-limit S     per-run limit in seconds; slower runs are killed and shown as\n"
                         "                     'timeout' (default 600)\n"
                         "  --methods a,b      run only these methods (default: all); besides the registry's:\n"
                         "                     icm, icm_keep_overlaps, icm_free_boundary_opened, icm_cones_4,\n"
                         "                     icm_cones_8, icm_cones_16, icm_cones_32 (exactly that many\n"
                         "                     cones) and icm_u_square_cones_4, ..._32 (the same, the\n"
                         "                     angles by u-square); on a surface\n"
                         "                     that is not a disk, icm_u_square, icm_area, icm_angle and\n"
                         "                     icm_log_area run ICM::parameterize with that energy\n"
                         "  --subdivide K      apply K steps of Loop subdivision to each mesh first\n"
                         "  --open             open each closed mesh by removing the faces around its first\n"
                         "                     vertex: a nearly closed disk, like a scan with one small hole\n"
                         "  --json-file FILE   also write the JSON lines to FILE (with the Markdown on stdout)\n"
                         "  --svg-panels FILE  write the UV layouts of icm_free_boundary, lscm and arap for the\n"
                         "                     first mesh side by side to FILE (faces coloured by log area ratio)\n"
                         "  --write-mesh FILE  write the mesh as the methods get it (triangulated, after\n"
                         "                     --subdivide and --open) to FILE (.obj, .off or .ply) before\n"
                         "                     they run; one MESH only\n"
                         "  --quiet            no progress lines on stderr\n";

[[noreturn]] void usage_error(const std::string& what)
{
  std::cerr << "compare: " << what << "\n\n" << usage_text;
  std::exit(2);
}

std::vector<std::string> split_commas(const std::string& s)
{
  std::vector<std::string> out;
  std::string cur;
  for(char c : s)
  {
    if(c == ',')
    {
      if(!cur.empty())
        out.push_back(cur);
      cur.clear();
    }
    else if(c != ' ')
    {
      cur += c;
    }
  }
  if(!cur.empty())
    out.push_back(cur);
  return out;
}

bool parse_int(const std::string& s, int& v)
{
  char* end = nullptr;
  errno = 0;
  const long x = std::strtol(s.c_str(), &end, 10);
  if(s.empty() || *end != '\0' || errno != 0 || x < std::numeric_limits<int>::min() ||
     x > std::numeric_limits<int>::max())
    return false;
  v = static_cast<int>(x);
  return true;
}

bool parse_double(const std::string& s, double& v)
{
  char* end = nullptr;
  errno = 0;
  v = std::strtod(s.c_str(), &end);
  return !s.empty() && *end == '\0' && errno == 0 && std::isfinite(v);
}

// The values of the options that take one, as given; each is checked after the parse.
struct Option_texts
{
  std::string runs, time_limit, subdivide, methods;
  CLI::Option *runs_option = nullptr, *time_limit_option = nullptr, *subdivide_option = nullptr,
              *methods_option = nullptr, *write_mesh_option = nullptr;
};

void add_options(CLI::App& app, Options& o, Option_texts& texts)
{
  app.set_help_flag("-h,--help");
  app.allow_extras(); // unknown options are reported below, by name
  // An option given twice takes its last value, as the hand-written parser did.
  app.option_defaults()->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
  app.add_flag("--json", o.json);
  app.add_flag("-q,--quiet", o.quiet);
  app.add_flag("--open", o.open);
  texts.runs_option = app.add_option("--runs", texts.runs);
  texts.time_limit_option = app.add_option("--time-limit", texts.time_limit);
  texts.subdivide_option = app.add_option("--subdivide", texts.subdivide);
  texts.methods_option = app.add_option("--methods", texts.methods);
  app.add_option("--svg-panels", o.svg_panels);
  app.add_option("--json-file", o.json_file);
  texts.write_mesh_option = app.add_option("--write-mesh", o.write_mesh);
  app.add_option("MESH", o.meshes)->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
}

// CLI11 also takes --option=value and clustered short flags (-qx); compare never did, and
// refuses them as unknown options. A word after an option that takes a value is that value.
void refuse_joined_words(const CLI::App& app, int argc, char** argv)
{
  for(int i = 1; i < argc; ++i)
  {
    const std::string word = argv[i];
    if(const CLI::Option* option = app.get_option_no_throw(word); option != nullptr && option->nonpositional())
    {
      if(option->get_type_size() > 0)
        ++i;
      continue;
    }
    const bool joined_value = word.rfind("--", 0) == 0 && word.find('=') != std::string::npos;
    const bool clustered = word.size() > 2 && word[0] == '-' && word[1] != '-';
    if(joined_value || clustered)
      usage_error("unknown option " + word);
  }
}

// The words of argv CLI11 takes for options or their values; exits on a wrong command line.
void parse_words(CLI::App& app, int argc, char** argv)
{
  refuse_joined_words(app, argc, argv);
  try
  {
    app.parse(argc, argv);
  }
  catch(const CLI::CallForHelp&)
  {
    std::cout << usage_text;
    std::exit(0);
  }
  catch(const CLI::ArgumentMismatch& e)
  {
    // Only the last word can miss its value.
    const std::string last = argv[argc - 1];
    if(app.get_option_no_throw(last) != nullptr)
      usage_error("option " + last + " needs a value");
    usage_error(e.what());
  }
  catch(const CLI::ParseError& e)
  {
    usage_error(e.what());
  }
  for(const std::string& extra : app.remaining())
    usage_error("unknown option " + extra);
}

// CLI11 takes a word such as -1 for a positional argument; compare refuses it as an option.
void check_meshes(const std::vector<std::string>& meshes)
{
  for(const std::string& word : meshes)
    if(word.size() > 1 && word[0] == '-')
      usage_error("unknown option " + word);
}

// The values of --runs, --time-limit, --subdivide and --methods, checked.
void read_values(const Option_texts& texts, Options& o)
{
  if(texts.runs_option->count() > 0 && (!parse_int(texts.runs, o.runs) || o.runs < 1))
    usage_error("--runs needs a positive integer");
  if(texts.time_limit_option->count() > 0 && (!parse_double(texts.time_limit, o.time_limit) || o.time_limit <= 0))
    usage_error("--time-limit needs a positive number of seconds");
  if(texts.subdivide_option->count() > 0 &&
     (!parse_int(texts.subdivide, o.subdivide) || o.subdivide < 0 || o.subdivide > 8))
    usage_error("--subdivide needs an integer in [0, 8]");
  if(texts.methods_option->count() > 0)
  {
    o.methods = split_commas(texts.methods);
    if(o.methods.empty())
      usage_error("--methods needs at least one name");
  }
}

void check_methods(const std::vector<std::string>& methods, const std::vector<std::string>& known_methods)
{
  for(const std::string& m : methods)
  {
    if(std::find(known_methods.begin(), known_methods.end(), m) != known_methods.end())
      continue;
    std::string valid;
    for(const std::string& name : known_methods)
      valid += (valid.empty() ? "" : ", ") + name;
    std::cerr << "compare: unknown method '" << m << "'; valid methods: " << valid << "\n";
    std::exit(2);
  }
}

// --write-mesh: a file name with an extension CGAL writes, and one mesh to write.
void check_write_mesh(const Option_texts& texts, const Options& o)
{
  if(texts.write_mesh_option->count() == 0)
    return;
  const std::string& file = o.write_mesh;
  auto ends_with = [&](const std::string& ext) {
    return file.size() > ext.size() && file.compare(file.size() - ext.size(), ext.size(), ext) == 0;
  };
  if(!ends_with(".obj") && !ends_with(".off") && !ends_with(".ply"))
    usage_error("--write-mesh needs a file name ending in .obj, .off or .ply, not '" + file + "'");
  if(o.meshes.size() != 1)
    usage_error("--write-mesh writes one mesh; " + std::to_string(o.meshes.size()) + " meshes given");
}

} // namespace

Options parse_options(int argc, char** argv, const std::vector<std::string>& known_methods)
{
  Options o;
  Option_texts texts;
  CLI::App app("Runs each parameterization method on each mesh", "compare");
  add_options(app, o, texts);
  parse_words(app, argc, argv);
  check_meshes(o.meshes);
  read_values(texts, o);
  check_methods(o.methods, known_methods);
  if(o.meshes.empty())
    usage_error("no mesh given");
  check_write_mesh(texts, o);
  return o;
}

} // namespace compare
