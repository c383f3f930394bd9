// A child's result through its pipe (child_result.h): one JSON object. A number that is not
// finite goes as the text "nan", "inf" or "-inf", so that what the parent reads back is the
// child's double, bit for bit.

#include "child_result.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdlib>

namespace compare {

namespace {

// Keys stay in the order they are set: the report's numbers keep theirs.
using Json = nlohmann::ordered_json;

const std::pair<const char*, double Measures::*> measure_fields[] = {
  {"faces", &Measures::faces},
  {"flipped", &Measures::flipped},
  {"degenerate", &Measures::degenerate},
  {"conformality", &Measures::conformality},
  {"angle_distortion", &Measures::angle_distortion},
  {"l2_shear", &Measures::l2_shear},
  {"l2_stretch", &Measures::l2_stretch},
  {"log_area_distortion", &Measures::log_area_distortion},
  {"log_area_weighted", &Measures::log_area_weighted},
  {"qc_mean", &Measures::qc_mean},
  {"qc_max", &Measures::qc_max},
  {"area_ratio_min", &Measures::area_ratio_min},
  {"area_ratio_max", &Measures::area_ratio_max}};

Json number(double x)
{
  if(std::isfinite(x))
    return x;
  return std::isnan(x) ? "nan" : x > 0 ? "inf" : "-inf";
}

double number_of(const Json& value)
{
  if(value.is_number())
    return value.get<double>();
  return value.is_string() ? std::strtod(value.get<std::string>().c_str(), nullptr) : NaN;
}

double number_at(const Json& o, const char* key)
{
  const auto it = o.find(key);
  return it == o.end() ? NaN : number_of(*it);
}

std::string text_at(const Json& o, const char* key)
{
  const auto it = o.find(key);
  return it != o.end() && it->is_string() ? it->get<std::string>() : std::string();
}

// A text on one line, as the results always travelled.
std::string one_line(std::string s)
{
  for(char& c : s)
    if(c == '\n' || c == '\r')
      c = ' ';
  return s;
}

Json measures_object(const Measures& m)
{
  Json o = Json::object();
  for(const auto& [key, field] : measure_fields)
    o[key] = number(m.*field);
  return o;
}

Measures measures_of(const Json& o)
{
  Measures m;
  for(const auto& [key, field] : measure_fields)
    m.*field = number_at(o, key);
  return m;
}

} // namespace

Measures to_measures(const ICM::Distortion_measures& d)
{
  Measures m;
  m.faces = static_cast<double>(d.faces);
  m.flipped = static_cast<double>(d.flipped_faces);
  m.degenerate = static_cast<double>(d.degenerate_uv_faces);
  m.conformality = d.conformality;
  m.angle_distortion = d.angle_distortion;
  m.l2_shear = d.l2_shear;
  m.l2_stretch = d.l2_stretch;
  m.log_area_distortion = d.log_area_distortion;
  m.log_area_weighted = d.log_area_distortion_area_weighted;
  m.qc_mean = d.qc_mean;
  m.qc_max = d.qc_max;
  m.area_ratio_min = d.area_ratio_min;
  m.area_ratio_max = d.area_ratio_max;
  return m;
}

double extra_value(const Child_result& r, const std::string& key)
{
  for(const auto& [k, v] : r.extra)
    if(k == key)
      return v;
  return NaN;
}

std::string to_pipe_text(const Child_result& r)
{
  Json o;
  o["code"] = r.code;
  o["seconds"] = number(r.seconds);
  o["rss"] = number(r.peak_rss_mb);
  if(r.newton_iterations)
    o["newton"] = *r.newton_iterations;
  o["metric"] = one_line(r.metric);
  if(r.has_measures)
    o["measures"] = measures_object(r.m);
  o["message"] = one_line(r.message);
  o["exception"] = one_line(r.exception);
  Json extra = Json::object();
  for(const auto& [key, value] : r.extra)
    extra[key] = number(value);
  o["extra"] = extra;
  o["fallback"] = one_line(r.fallback_reason);
  o["seams"] = r.seams;
  return o.dump(-1, ' ', false, Json::error_handler_t::replace);
}

Child_result from_pipe_text(const std::string& text)
{
  Child_result r;
  const Json o = Json::parse(text, nullptr, false);
  if(!o.is_object())
    return r;
  r.complete = true;
  r.code = o.value("code", 0);
  r.seconds = number_at(o, "seconds");
  r.peak_rss_mb = number_at(o, "rss");
  if(o.contains("newton"))
    r.newton_iterations = o["newton"].get<int>();
  r.metric = text_at(o, "metric");
  r.has_measures = o.contains("measures");
  if(r.has_measures)
    r.m = measures_of(o["measures"]);
  r.message = text_at(o, "message");
  r.exception = text_at(o, "exception");
  if(o.contains("extra"))
    for(auto it = o["extra"].begin(); it != o["extra"].end(); ++it)
      r.extra.emplace_back(it.key(), number_of(*it));
  r.fallback_reason = text_at(o, "fallback");
  if(o.contains("seams"))
    r.seams = o["seams"].get<std::vector<std::size_t>>();
  return r;
}

} // namespace compare
