// compare's table (output.h): Markdown with the paper's decimals, or JSON lines.

#include "output.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <iostream>
#include <sstream>
#include <thread>

namespace compare {

namespace {

// --json-file's stream, opened by open_json_file().
std::ofstream json_file;

void print_json(const Row& r, std::ostream& out = std::cout)
{
  const Measures& m = r.m;
  const bool h = r.has_measures;
  Json o;
  o["mesh"] = r.mesh;
  o["vertices"] = r.vertices;
  o["faces"] = r.faces;
  o["method"] = r.method;
  o["status"] = r.status;
  o["seconds"] = json_num(r.seconds);
  o["peak_rss_mb"] = json_num(r.peak_rss_mb);
  o["flipped"] = h ? json_count(m.flipped) : Json();
  o["degenerate"] = h ? json_count(m.degenerate) : Json();
  o["conformality"] = h ? json_num(m.conformality) : Json();
  o["angle_distortion"] = h ? json_num(m.angle_distortion) : Json();
  o["l2_shear"] = h ? json_num(m.l2_shear) : Json();
  o["l2_stretch"] = h ? json_num(m.l2_stretch) : Json();
  o["log_area_distortion"] = h ? json_num(m.log_area_distortion) : Json();
  o["log_area_distortion_area_weighted"] = h ? json_num(m.log_area_weighted) : Json();
  o["qc_mean"] = h ? json_num(m.qc_mean) : Json();
  o["qc_max"] = h ? json_num(m.qc_max) : Json();
  o["area_ratio_min"] = h ? json_num(m.area_ratio_min) : Json();
  o["area_ratio_max"] = h ? json_num(m.area_ratio_max) : Json();
  o["newton_iterations"] = r.newton_iterations ? Json(*r.newton_iterations) : Json();
  o["metric"] = r.metric.empty() ? Json() : Json(r.metric);
  for(const auto& [key, value] : r.json_extra)
    o[key] = value;
  out << o.dump(-1, ' ', false, Json::error_handler_t::replace) << "\n" << std::flush;
}

// Fixed decimals as in the paper's table, switching to scientific notation when that would
// show fewer than two significant digits (or a huge number).
std::string fmt_fixed(double x, int decimals)
{
  if(std::isnan(x))
    return "nan";
  if(std::isinf(x))
    return x > 0 ? "inf" : "-inf";
  char buf[64];
  const double ax = std::fabs(x);
  if(x != 0 && (ax < 10.0 * std::pow(10.0, -decimals) || ax >= 1e7))
    std::snprintf(buf, sizeof buf, "%.2e", x);
  else
    std::snprintf(buf, sizeof buf, "%.*f", decimals, x);
  return buf;
}

std::string md_cell(std::string s)
{
  std::string o;
  for(char c : s)
  {
    if(c == '|')
      o += "\\|";
    else
      o += c;
  }
  return o;
}

std::string model_label(const Row& r)
{
  return r.mesh + " #v: " + std::to_string(r.vertices) + " #f: " + std::to_string(r.faces) +
         (r.topology.empty() ? std::string() : " (" + r.topology + ")");
}

void print_markdown_header()
{
  std::cout << "| Model | Method | conformality | angle distortion | L2 shear | L2 stretch | "
               "log area distortion | time (s) | flipped | QC mean | QC max | peak MB | "
               "Newton its | status |\n"
               "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|\n";
}

void print_markdown_row(const Row& r, bool first)
{
  const Measures& m = r.m;
  const bool h = r.has_measures;
  auto cell = [&](double x, int decimals) { return h ? fmt_fixed(x, decimals) : std::string(); };
  std::ostringstream o;
  // An ICM row names the metric of its result: after a fallback it is not the requested one.
  std::string details = r.metric;
  if(!r.detail.empty())
    details += (details.empty() ? "" : ", ") + r.detail;
  const std::string method = details.empty() ? r.method : r.method + " (" + details + ")";
  o << "| " << (first ? md_cell(model_label(r)) : "") << " | " << md_cell(method) << " | " << cell(m.conformality, 5)
    << " | " << cell(m.angle_distortion, 5) << " | " << cell(m.l2_shear, 4) << " | " << cell(m.l2_stretch, 4) << " | "
    << cell(m.log_area_distortion, 5) << " | " << fmt_seconds(r.seconds) << " | " << (h ? count_text(m.flipped) : "")
    << " | " << cell(m.qc_mean, 4) << " | " << cell(m.qc_max, 3) << " | "
    << (std::isfinite(r.peak_rss_mb) ? fmt_fixed(r.peak_rss_mb, 1) : "") << " | "
    << (r.newton_iterations ? std::to_string(*r.newton_iterations) : "") << " | "
    << md_cell(r.note.empty() ? r.status : r.status + "; " + r.note) << " |\n";
  std::cout << o.str() << std::flush;
}

std::string machine_description()
{
  std::ifstream cpuinfo("/proc/cpuinfo");
  std::string line, model;
  int processors = 0;
  while(std::getline(cpuinfo, line))
  {
    if(line.rfind("processor", 0) == 0)
      ++processors;
    if(model.empty() && line.rfind("model name", 0) == 0)
    {
      const auto colon = line.find(':');
      if(colon != std::string::npos)
      {
        model = line.substr(colon + 1);
        model.erase(0, model.find_first_not_of(" \t"));
      }
    }
  }
  if(model.empty())
    model = "unknown CPU";
  if(processors == 0)
    processors = static_cast<int>(std::thread::hardware_concurrency());
  return model + ", " + std::to_string(processors) + " logical cores";
}

std::string date_now()
{
  const std::time_t t = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[64];
  std::strftime(buf, sizeof buf, "%Y-%m-%d %H:%M UTC", &tm);
  return buf;
}

} // namespace

Json json_num(double x)
{
  if(!std::isfinite(x))
    return nullptr;
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.10g", x);
  return std::strtod(buf, nullptr);
}

Json json_count(double x)
{
  if(!std::isfinite(x))
    return nullptr;
  return static_cast<long long>(std::llround(x));
}

std::string count_text(double x)
{
  if(!std::isfinite(x))
    return "";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.0f", x);
  return buf;
}

std::string fmt_seconds(double x)
{
  if(!std::isfinite(x))
    return "";
  char buf[64];
  if(x < 10.0)
    std::snprintf(buf, sizeof buf, "%.3g", x);
  else
    std::snprintf(buf, sizeof buf, "%.1f", x);
  return buf;
}

bool open_json_file(const std::string& path)
{
  json_file.open(path);
  return static_cast<bool>(json_file);
}

void print_markdown_preamble(const Options& opt)
{
  std::cout << "# Parameterization comparison\n\n"
            << "Machine: " << machine_description() << "  \n"
            << "Date: " << date_now() << "  \n"
            << "Runs: "
            << (opt.runs > 0 ? std::to_string(opt.runs) + " per method (median time)"
                             : std::string("3 per method if one takes < 2 s, else 1 (median time)"))
            << "; time limit " << opt.time_limit << " s per run"
            << (opt.subdivide > 0 ? "; Loop subdivision x" + std::to_string(opt.subdivide) : std::string())
            << (opt.open ? "; closed meshes opened by removing the star of their first vertex" : std::string())
            << "\n\n";
  print_markdown_header();
}

void emit(const Row& row, bool first, const Options& opt)
{
  if(opt.json)
    print_json(row);
  else
    print_markdown_row(row, first);
  if(json_file.is_open())
    print_json(row, json_file);
}

} // namespace compare
