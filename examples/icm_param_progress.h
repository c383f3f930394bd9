// icm_param's progress line on stderr, for the meshes that take seconds (icm_param_run.cpp).

#ifndef ICM_PARAM_PROGRESS_H
#define ICM_PARAM_PROGRESS_H

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <string>

#ifndef _WIN32
#include <unistd.h>
#endif

namespace icm_param {

/// "icm_param: cones 12%, 9 s, about 70 s left" on stderr, rewritten in place on a terminal:
/// the stage, the share of the run done, the seconds since it began and, once enough of it
/// is done to extrapolate from, the time left at the pace so far (a rough guess: the shares
/// are fixed per stage, not measured). Shown whenever the stage changes, otherwise at most
/// four times a second on a terminal and every few seconds in a log, whatever the rate of
/// the library's callbacks (one per greedy cone round).
class Progress_line
{
public:
  explicit Progress_line(bool shown) : shown_(shown), start_(Clock::now())
  {
#ifndef _WIN32
    terminal_ = ::isatty(2) != 0;
#endif
  }
  void operator()(const std::string& stage, double fraction)
  {
    if(!shown_)
      return;
    const double elapsed = std::chrono::duration<double>(Clock::now() - start_).count();
    if(stage == stage_ && elapsed - shown_at_ < (terminal_ ? 0.25 : 5.0))
      return;
    stage_ = stage;
    shown_at_ = elapsed;
    fraction = std::clamp(fraction, 0.0, 1.0);
    std::cerr << (terminal_ ? "\r" : "") << "icm_param: " << stage << " "
              << static_cast<int>(std::floor(100 * fraction)) << "%, " << duration_text(elapsed);
    if(fraction >= least_fraction_for_an_estimate && fraction < 1)
      std::cerr << ", about " << duration_text(elapsed * (1 - fraction) / fraction) << " left";
    std::cerr << (terminal_ ? "\x1b[K" : "\n") << std::flush;
    open_ = terminal_;
  }
  /// Ends the line on a terminal, so that what follows starts on its own.
  void finish()
  {
    if(open_)
      std::cerr << "\n";
    open_ = false;
  }

private:
  using Clock = std::chrono::steady_clock;
  /// Below this share done, the pace so far says too little of the rest.
  static constexpr double least_fraction_for_an_estimate = 0.03;

  static std::string duration_text(double seconds)
  {
    return seconds < 120 ? std::to_string(static_cast<long>(seconds)) + " s"
                         : std::to_string(static_cast<long>(std::lround(seconds / 60))) + " min";
  }

  bool shown_, terminal_ = false, open_ = false;
  Clock::time_point start_;
  std::string stage_;
  double shown_at_ = 0;
};

} // namespace icm_param

#endif // ICM_PARAM_PROGRESS_H
