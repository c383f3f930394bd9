// The one clock of the stages' timings (`seconds_*` in the reports).

#ifndef ICM_INTERNAL_STOPWATCH_H
#define ICM_INTERNAL_STOPWATCH_H

#include <chrono>

namespace ICM {
namespace internal {

using Clock = std::chrono::steady_clock;

/// Seconds from `start` to now.
inline double seconds_since(Clock::time_point start)
{
  return std::chrono::duration<double>(Clock::now() - start).count();
}

/// Seconds between successive calls of `lap`, from construction on.
class Stopwatch
{
public:
  double lap()
  {
    const Clock::time_point now = Clock::now();
    const double seconds = std::chrono::duration<double>(now - last_).count();
    last_ = now;
    return seconds;
  }
  double total() const { return seconds_since(start_); }

private:
  Clock::time_point start_ = Clock::now(), last_ = start_;
};

} // namespace internal
} // namespace ICM

#endif // ICM_INTERNAL_STOPWATCH_H
