// Range checks of option values, each failing with `ERROR_WRONG_PARAMETER` and a sentence
// that names the option and its value ("newton.tolerance = nan: must be a finite number > 0").
// The options structs check their own fields with these (`check_options`), and every entry
// point checks its options before it reads the mesh.

#ifndef ICM_INTERNAL_OPTION_CHECKS_H
#define ICM_INTERNAL_OPTION_CHECKS_H

#include <ICM/Status.h>

#include <cmath>
#include <sstream>
#include <string>

namespace ICM {
namespace internal {

/// Collects the first failed check of a set of options; later checks are then skipped.
class Option_checks
{
public:
  /// `prefix` names the options struct inside its parent ("energy.newton."), empty at the top.
  explicit Option_checks(std::string prefix = std::string()) : prefix_(std::move(prefix)) {}

  /// A finite number, > `low` (or >= it when `low_included`) and, when `high` is finite,
  /// < `high` (or <= it when `high_included`).
  Option_checks& real(const char* name, double value, double low, bool low_included, double high = HUGE_VAL,
                      bool high_included = false)
  {
    const bool above = low_included ? value >= low : value > low;
    const bool below = !std::isfinite(high) || (high_included ? value <= high : value < high);
    if(!(std::isfinite(value) && above && below))
    {
      std::ostringstream range;
      range << "must be a finite number " << (low_included ? ">= " : "> ") << low;
      if(std::isfinite(high))
        range << " and " << (high_included ? "<= " : "< ") << high;
      fail(name, number(value), range.str());
    }
    return *this;
  }
  /// An integer >= `low`.
  Option_checks& at_least(const char* name, long long value, long long low)
  {
    if(value < low)
      fail(name, std::to_string(value), "must be >= " + std::to_string(low));
    return *this;
  }
  /// An integer <= `high`; `why`, when given, says what the bound keeps.
  Option_checks& at_most(const char* name, long long value, long long high, const std::string& why = std::string())
  {
    if(value > high)
      fail(name, std::to_string(value), "must be <= " + std::to_string(high) + (why.empty() ? "" : " " + why));
    return *this;
  }
  /// An enumerator among the `count` first values of its enumeration.
  template <class Enum>
  Option_checks& one_of(const char* name, Enum value, int count)
  {
    const int v = static_cast<int>(value);
    if(v < 0 || v >= count)
      fail(name, std::to_string(v), "is not a value of its enumeration");
    return *this;
  }
  /// The checks of a nested options struct, `name` its field.
  Option_checks& nested(const Status& status)
  {
    if(status_.ok())
      status_ = status;
    return *this;
  }
  Status status() const { return status_; }

private:
  void fail(const char* name, const std::string& value, const std::string& why)
  {
    if(status_.ok())
      status_ = Status::wrong_parameter("option " + prefix_ + name + " = " + value + ": " + why);
  }
  static std::string number(double value) { return message_number(value); }

  std::string prefix_;
  Status status_;
};

} // namespace internal
} // namespace ICM

#endif // ICM_INTERNAL_OPTION_CHECKS_H
