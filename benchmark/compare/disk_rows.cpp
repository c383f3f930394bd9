// The rows of a disk (rows.h), and ICM's reports in a row.

#include "output.h"
#include "rows.h"
#include "run.h"

#include <cmath>
#include <cstdio>
#include <iostream>
#include <utility>

namespace compare {

namespace {

// ICM's report on a disk: its numbers as JSON keys; the optimum's time and, for an energy
// other than the entropy, the optimizer's steps and values in the Markdown status.
void add_disk_icm_report(Row& row, const Child_result& result)
{
  auto is_count = [](const std::string& key) {
    return key == "energy_iterations" || key == "border_iterations" || key == "border_crossings";
  };
  for(const auto& [key, value] : result.extra)
    row.json_extra.emplace_back(key, is_count(key) ? json_count(value) : json_num(value));
  if(result.extra.empty() || row.status.rfind("ok", 0) != 0)
    return;
  row.note = "optimum " + fmt_seconds(extra_value(result, "seconds_optimum")) + " s";
  if(extra_value(result, "border_crossings") > 0)
    row.note += "; " + count_text(extra_value(result, "border_crossings")) + " border crossings";
  const double deviation = extra_value(result, "circle_deviation");
  if(std::isfinite(deviation))
  {
    char circles[120];
    std::snprintf(circles, sizeof circles, "; %.0f circle iterations, circle deviation %.2g",
                  extra_value(result, "border_iterations"), deviation);
    row.note += circles;
  }
  const double steps = extra_value(result, "energy_iterations");
  if(!std::isfinite(steps))
    return;
  char buf[160];
  std::snprintf(buf, sizeof buf, "; %.0f energy steps, E %.4g -> %.4g", steps, extra_value(result, "initial_energy"),
                extra_value(result, "final_energy"));
  row.note += buf;
}

// The row of `name` on a disk: a registry method, a pipeline row, or a row for closed meshes.
Row disk_row(const Mesh& mesh, const Row& base, const Options& opt, const std::string& name,
             const std::vector<Method>& registry)
{
  if(const Method* method = find_method(registry, name))
    return run_method(mesh, *method, opt, base);
  if(name == "icm" || name == "icm_keep_overlaps" || exact_cone_count(name) >= 0)
  {
    Child_result result;
    Row row = run_job(icm_pipeline_job(mesh, name), name, opt, base, &result);
    add_icm_report(row, result);
    return row;
  }
  // icm_free_boundary_opened
  Row row = base;
  row.method = name;
  row.status = "skipped: the mesh is not closed";
  return row;
}

} // namespace

void add_icm_report(Row& row, const Child_result& result)
{
  auto is_measure = [](const std::string& key) {
    return key.rfind("seconds", 0) == 0 || key == "initial_energy" || key == "final_energy" || key == "seam_length";
  };
  for(const auto& [key, value] : result.extra)
    row.json_extra.emplace_back(key, is_measure(key) ? json_num(value) : json_count(value));
  if(result.extra.empty() || row.status.rfind("ok", 0) != 0)
    return;
  auto x = [&](const char* key) { return extra_value(result, key); };
  char buf[320];
  std::snprintf(buf, sizeof buf,
                "%.0f cones, %.0f seam edges, %.0f chart%s; cones %s s, optimum %s s, cut %s s, "
                "layout %s s",
                x("cones"), x("seam_edges"), x("charts"), x("charts") == 1 ? "" : "s",
                fmt_seconds(x("seconds_cones")).c_str(), fmt_seconds(x("seconds_optimum")).c_str(),
                fmt_seconds(x("seconds_cut")).c_str(), fmt_seconds(x("seconds_layout")).c_str());
  row.note = buf;
  if(x("border_crossings") > 0)
    row.note += "; " + count_text(x("border_crossings")) + " border crossings";
  if(std::isfinite(x("energy_iterations")))
  {
    std::snprintf(buf, sizeof buf, "; %.0f energy steps, E %.4g -> %.4g", x("energy_iterations"), x("initial_energy"),
                  x("final_energy"));
    row.note += buf;
  }
}

Row run_method(const Mesh& mesh, const Method& method, const Options& opt, Row row)
{
  Child_result result;
  row = run_job(method_job(mesh, method), method.name, opt, std::move(row), &result);
  add_disk_icm_report(row, result);
  return row;
}

void run_disk(const Mesh& mesh, const Row& base, const Options& opt, const std::vector<std::string>& asked,
              const std::vector<Method>& registry)
{
  std::vector<std::string> names = asked;
  if(names.empty())
    for(const Method& m : registry)
      names.push_back(m.name);
  bool first = true;
  for(const std::string& name : names)
  {
    if(!opt.quiet)
      std::cerr << "compare: " << base.mesh << " (" << base.faces << " faces): " << name << " ..." << std::flush;
    const Row row = disk_row(mesh, base, opt, name, registry);
    if(!opt.quiet)
      std::cerr << " " << row.status << (std::isfinite(row.seconds) ? ", " + fmt_seconds(row.seconds) + " s" : "")
                << "\n";
    emit(row, first, opt);
    first = false;
  }
}

} // namespace compare
