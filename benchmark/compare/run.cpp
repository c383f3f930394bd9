// A job in a child process (run.h), through the isolation of tools/child_process.h: a method
// that hangs is killed at the time limit, one that crashes takes only its child down.

#include "run.h"

#include <ICM/parameterize.h>

#include <child_process.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <exception>
#include <iostream>
#include <map>

namespace compare {

namespace {

// The child's work: run the job, catching what it throws; the result as the pipe's text.
std::string child_work(const Job& job, bool measure)
{
  Child_result r;
  try
  {
    job(r, measure);
  }
  catch(const std::exception& e)
  {
    r.exception = e.what();
    if(r.exception.empty())
      r.exception = "std::exception";
  }
  catch(...)
  {
    r.exception = "unknown exception";
  }
  return to_pipe_text(r);
}

double median(std::vector<double> v)
{
  if(v.empty())
    return NaN;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// The named times of a result (ICM's stages), each in a list of its own.
std::map<std::string, std::vector<double>> stage_times_of(const Child_result& r)
{
  std::map<std::string, std::vector<double>> stage_times;
  for(const auto& [key, value] : r.extra)
    if(key.rfind("seconds", 0) == 0)
      stage_times[key].push_back(value);
  return stage_times;
}

} // namespace

Child_outcome run_in_child(const Job& job, bool measure, double time_limit)
{
  Child_outcome out;
  const icm_tools::Isolated_run run = icm_tools::run_isolated([&] { return child_work(job, measure); }, time_limit);
  if(run.kind == icm_tools::Isolated_run::not_started)
  {
    std::cerr << "compare: " << run.failed_call << ": " << std::strerror(errno) << "\n";
    return out;
  }
  if(run.kind == icm_tools::Isolated_run::timed_out)
  {
    out.kind = Child_outcome::timeout;
    out.peak_rss_mb = run.peak_rss_mb;
    return out;
  }
  out.result = from_pipe_text(run.output);
  if(run.exit.signaled)
  {
    out.kind = Child_outcome::crashed;
    out.signal = run.exit.signal;
  }
  else if(run.exit.code != 0)
  {
    out.kind = Child_outcome::crashed;
    out.exit_code = run.exit.code;
  }
  else
  {
    out.kind = out.result.complete ? Child_outcome::finished : Child_outcome::lost;
  }
  return out;
}

std::string status_of(const Child_outcome& o)
{
  switch(o.kind)
  {
  case Child_outcome::timeout:
    return "timeout";
  case Child_outcome::crashed:
    if(o.signal != 0)
      return "crashed (signal " + std::to_string(o.signal) + ")";
    return "crashed (exit code " + std::to_string(o.exit_code) + ")";
  case Child_outcome::lost:
    return "crashed (no result)";
  case Child_outcome::finished:
    break;
  }
  const Child_result& r = o.result;
  if(!r.exception.empty())
    return "failed: exception: " + r.exception;
  if(r.code != SMP::OK)
  {
    std::string s = std::string("failed: ") + ICM::error_message(static_cast<SMP::Error_code>(r.code));
    if(!r.message.empty())
      s += "; " + r.message;
    return s;
  }
  return "ok";
}

Row run_job(const Job& job, const std::string& name, const Options& opt, Row row, Child_result* first_result)
{
  row.method = name;
  const Child_outcome first = run_in_child(job, /*measure=*/true, opt.time_limit);
  row.status = status_of(first);
  if(first_result)
    *first_result = first.result;
  if(first.kind == Child_outcome::timeout)
    row.peak_rss_mb = first.peak_rss_mb;
  if(first.kind != Child_outcome::finished)
    return row;
  const Child_result& r = first.result;
  row.has_measures = r.has_measures;
  row.m = r.m;
  row.newton_iterations = r.newton_iterations;
  row.metric = r.metric;
  row.peak_rss_mb = r.peak_rss_mb;
  std::vector<double> times{r.seconds};
  // Named times of the report (ICM's stages): the median over the runs, like the time.
  std::map<std::string, std::vector<double>> stage_times = stage_times_of(r);
  const int runs = row.status != "ok" ? 1 : opt.runs > 0 ? opt.runs : (r.seconds < 2.0 ? 3 : 1);
  for(int k = 1; k < runs; ++k)
  {
    const Child_outcome more = run_in_child(job, /*measure=*/false, opt.time_limit);
    const std::string st = status_of(more);
    if(st != "ok")
    { // a method that is not deterministic in its outcome: show it
      row.status = st + " (run " + std::to_string(k + 1) + ")";
      break;
    }
    times.push_back(more.result.seconds);
    for(const auto& [key, value] : more.result.extra)
      if(stage_times.count(key))
        stage_times[key].push_back(value);
    row.peak_rss_mb = std::max(row.peak_rss_mb, more.result.peak_rss_mb);
  }
  row.seconds = median(times);
  if(first_result)
    for(auto& [key, value] : first_result->extra)
      if(stage_times.count(key))
        value = median(stage_times[key]);
  return row;
}

} // namespace compare
