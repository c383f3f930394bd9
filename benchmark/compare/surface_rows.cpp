// The rows of a mesh that is not a disk (rows.h): ICM's one call first (its row, and its
// seams for CGAL's methods), then each row in the order asked.

#include "output.h"
#include "rows.h"
#include "run.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <map>
#include <utility>

namespace compare {

namespace {

// Default rows of a mesh that is not a disk: ICM's one call, CGAL's methods on its cut and,
// for a closed genus-0 mesh, the free-boundary parameterizer on the mesh opened at one vertex.
std::vector<std::string> surface_names(const Topology& t)
{
  std::vector<std::string> names = {"icm", "lscm", "arap", "dcm", "dac", "mvc"};
  if(t.components == 1 && t.closed() && t.two_g() == 0)
    names.push_back("icm_free_boundary_opened");
  if(t.components == 1 && t.loops > 1 && t.two_g() == 0)
    names.push_back("icm_circle_domain");
  return names;
}

// The row every row of the mesh starts from: its topology, also as JSON keys.
Row surface_base(Row base, const Topology& topology)
{
  base.topology = topology.description();
  const std::string genus = topology.genus(); // "?" when 2g is odd (a non-orientable cut)
  base.json_extra = {{"components", topology.components},
                     {"genus", topology.components != 1 ? Json()
                               : genus == "?"           ? Json(genus)
                                                        : Json(std::stol(genus))},
                     {"loops", topology.loops}};
  return base;
}

// The opened mesh's sizes, the parameterizer's stage times and why it fell back, if it did.
void add_opened_report(Row& row, const Child_result& result, const Mesh& opened)
{
  row.json_extra.emplace_back("opened_vertices", num_vertices(opened));
  row.json_extra.emplace_back("opened_faces", num_faces(opened));
  for(const auto& [key, value] : result.extra)
    row.json_extra.emplace_back(key, json_num(value));
  row.json_extra.emplace_back("fallback_reason",
                              result.fallback_reason.empty() ? Json() : Json(result.fallback_reason));
  row.note = "opened: " + std::to_string(num_faces(opened)) + " faces";
  if(!result.extra.empty() && row.status == "ok")
  {
    auto x = [&](const char* key) { return fmt_seconds(extra_value(result, key)); };
    row.note += "; index " + x("seconds_index") + " s, metric " + x("seconds_metric") + " s, optimum " +
                x("seconds_optimum") + " s, layout " + x("seconds_layout") + " s";
  }
  if(!result.fallback_reason.empty())
    row.note += "; fell back: " + result.fallback_reason;
}

class Surface_rows
{
public:
  Surface_rows(const Mesh& mesh, const Topology& topology, const Row& base, const Options& opt,
               const std::vector<Method>& registry, const std::vector<Seam_method>& seam_registry)
    : mesh_(mesh), topology_(topology), base_(base), opt_(opt), registry_(registry), seam_registry_(seam_registry),
      connected_(topology.components == 1)
  {}

  void run(std::vector<std::string> names)
  {
    find_cut(names);
    bool first = true;
    for(const std::string& name : names)
    {
      emit(row_of(name), first, opt_);
      first = false;
    }
  }

private:
  const Mesh& mesh_;
  const Topology& topology_;
  const Row& base_;
  const Options& opt_;
  const std::vector<Method>& registry_;
  const std::vector<Seam_method>& seam_registry_;
  const bool connected_;
  std::map<std::string, Row> done_; // the rows run by find_cut()
  std::vector<std::size_t> cut_;    // the seams CGAL's methods cut along
  std::string cut_name_;            // the row whose seams they are
  std::string no_cut_;              // why there is no cut, when there is none

  const Seam_method* seam_method(const std::string& name) const
  {
    for(const Seam_method& m : seam_registry_)
      if(m.name == name)
        return &m;
    return nullptr;
  }

  void progress(const std::string& name) const
  {
    if(!opt_.quiet)
      std::cerr << "compare: " << base_.mesh << " (" << base_.faces << " faces, " << base_.topology << "): " << name
                << " ..." << std::flush;
  }

  void progress_done(const Row& row) const
  {
    if(!opt_.quiet)
      std::cerr << " " << row.status << (std::isfinite(row.seconds) ? ", " + fmt_seconds(row.seconds) + " s" : "")
                << "\n";
  }

  Row skipped(const std::string& name, const std::string& status) const
  {
    Row row = base_;
    row.method = name;
    row.status = status;
    return row;
  }

  // A row run in child processes with ICM's report of `job`.
  Row icm_row(const Job& job, const std::string& name)
  {
    progress(name);
    Child_result result;
    Row row = run_job(job, name, opt_, base_, &result);
    add_icm_report(row, result);
    progress_done(row);
    return row;
  }

  // ICM's one call, shown as a row (kept in done_) or only run for its seams; its status.
  std::string icm_run(bool remove_overlaps, bool shown, Child_result& result)
  {
    const std::string name = remove_overlaps ? "icm" : "icm_keep_overlaps";
    if(shown)
    {
      progress(name);
      Row row = run_job(icm_pipeline_job(mesh_, name), name, opt_, base_, &result);
      add_icm_report(row, result);
      progress_done(row);
      done_[name] = row;
      return row.status;
    }
    if(!opt_.quiet)
      std::cerr << "compare: " << base_.mesh << ": " << name << " for the cut ...";
    const Child_outcome o = run_in_child(icm_pipeline_job(mesh_, name), false, opt_.time_limit);
    result = o.result;
    const std::string status = status_of(o);
    if(!opt_.quiet)
      std::cerr << " " << status << "\n";
    return status;
  }

  // ICM first: its row, and its seams for CGAL's methods. When overlap removal cut the chart
  // into pieces, the seams do not make one disk: CGAL's methods get the raw cut, ICM's with
  // remove_overlaps = false (shown as icm_keep_overlaps when icm is shown).
  void find_cut(std::vector<std::string>& names)
  {
    auto asks = [&](const std::string& name) { return std::find(names.begin(), names.end(), name) != names.end(); };
    const bool wants_cgal =
      std::any_of(names.begin(), names.end(), [&](const std::string& n) { return seam_method(n) != nullptr; });
    if(!asks("icm") && !(connected_ && wants_cgal))
      return;
    Child_result icm;
    const std::string status = icm_run(true, asks("icm"), icm);
    if(!connected_ || !wants_cgal)
      return;
    if(status != "ok")
    {
      no_cut_ = "skipped: no cut (icm " + status + ")";
    }
    else if(extra_value(icm, "charts") > 1)
    {
      Child_result raw;
      const bool show = asks("icm") || asks("icm_keep_overlaps");
      const std::string raw_status = icm_run(false, show, raw);
      if(show && !asks("icm_keep_overlaps"))
        names.insert(std::find(names.begin(), names.end(), "icm") + 1, "icm_keep_overlaps");
      if(raw_status == "ok")
      {
        cut_ = raw.seams;
        cut_name_ = "icm_keep_overlaps";
      }
      else
      {
        no_cut_ = "skipped: no cut (icm_keep_overlaps " + raw_status + ")";
      }
    }
    else
    {
      cut_ = icm.seams;
      cut_name_ = "icm";
    }
  }

  Row row_of(const std::string& name)
  {
    if(done_.count(name))
      return done_[name];
    if(name == "icm" || name == "icm_keep_overlaps" || exact_cone_count(name) >= 0)
      return icm_row(icm_pipeline_job(mesh_, name), name);
    if(const Seam_method* m = seam_method(name))
      return seam_row(name, *m);
    if(Job job = icm_energy_job(mesh_, name))
      return icm_row(job, name);
    if(name == "icm_circle_domain")
      return circle_domain_row(name);
    if(name == "icm_free_boundary_opened")
      return opened_row(name);
    // a registry method for disks only
    Mesh copy = mesh_;
    return skipped(name, disk_check(copy));
  }

  // A CGAL method on the mesh cut along ICM's seams.
  Row seam_row(const std::string& name, const Seam_method& method)
  {
    if(!connected_)
      return skipped(name, "skipped: " + std::to_string(topology_.components) +
                             " components (CGAL's parameterizers take one connected mesh)");
    if(!no_cut_.empty())
      return skipped(name, no_cut_);
    progress(name);
    Row row = run_job(seam_job(mesh_, cut_, method), name, opt_, base_);
    row.detail = "cut: " + cut_name_;
    row.json_extra.emplace_back("cut", cut_name_);
    row.json_extra.emplace_back("cut_seam_edges", cut_.size());
    progress_done(row);
    return row;
  }

  Row circle_domain_row(const std::string& name)
  {
    if(!connected_ || topology_.loops < 2 || topology_.two_g() != 0)
      return skipped(name, "skipped: a circle domain needs one component of genus 0 with several loops");
    progress(name);
    Row row = run_method(mesh_, *find_method(registry_, name), opt_, base_);
    progress_done(row);
    return row;
  }

  // icm_free_boundary on the closed mesh opened at its first vertex.
  Row opened_row(const std::string& name)
  {
    if(!connected_ || !topology_.closed())
      return skipped(name, connected_ ? "skipped: the mesh is not closed"
                                      : "skipped: " + std::to_string(topology_.components) + " components");
    Mesh opened = mesh_;
    open_at_first_vertex(opened);
    opened.collect_garbage();
    const std::string skip = disk_check(opened);
    if(!skip.empty())
      return skipped(name, "skipped: the opened mesh is " + skip.substr(std::string("skipped: ").size()));
    progress(name);
    Child_result result;
    Row row = run_job(method_job(opened, *find_method(registry_, "icm_free_boundary")), name, opt_, base_, &result);
    add_opened_report(row, result, opened);
    progress_done(row);
    return row;
  }
};

} // namespace

void run_surface(const Mesh& mesh, const Topology& topology, Row base, const Options& opt,
                 const std::vector<std::string>& asked, const std::vector<Method>& registry,
                 const std::vector<Seam_method>& seam_registry)
{
  const Row surface = surface_base(std::move(base), topology);
  Surface_rows rows(mesh, topology, surface, opt, registry, seam_registry);
  rows.run(asked.empty() ? surface_names(topology) : asked);
}

} // namespace compare
