// The outcome of every stage: CGAL's error code and the human reason, passed up the stack.
//
// Each stage (indexing, the border condition, cones, the cut, the optimum, the layout)
// returns a `Status`; its caller either passes it on, with context prepended to the message,
// or acts on its code. No code is ever recovered from a message's text.

#ifndef ICM_STATUS_H
#define ICM_STATUS_H

#include <CGAL/Surface_mesh_parameterization/Error_code.h>

#include <sstream>
#include <string>
#include <utility>

namespace ICM {

using Error_code = CGAL::Surface_mesh_parameterization::Error_code;

/// The status of a report before its first run. CGAL's `Error_code` has no such value: this
/// one lies after its last code and inside the range the enumeration can hold (its values
/// take 4 bits, so 0 to 15 are valid), so no CGAL code is ever mistaken for it.
constexpr Error_code NOT_RUN = static_cast<Error_code>(15);

/// The text of an `Error_code` (and "not run" for `NOT_RUN`). CGAL 5.5.1's
/// `get_error_message()` skips `ERROR_NO_TOPOLOGICAL_BALL`, so from there on it returns the
/// next code's text and a null pointer for `ERROR_WRONG_PARAMETER`.
inline const char* error_message(Error_code code)
{
  using namespace CGAL::Surface_mesh_parameterization;
  switch(code)
  {
  case OK:
    return "Success";
  case ERROR_EMPTY_MESH:
    return "Input mesh is empty";
  case ERROR_NON_TRIANGULAR_MESH:
    return "Input mesh is not triangular";
  case ERROR_NO_TOPOLOGICAL_DISC:
    return "Input mesh is not a topological disc";
  case ERROR_NO_TOPOLOGICAL_BALL:
    return "Input mesh is not a topological ball";
  case ERROR_BORDER_TOO_SHORT:
    return "This border parameterization requires a longer border";
  case ERROR_NON_CONVEX_BORDER:
    return "This parameterization method requires a convex border";
  case ERROR_CANNOT_SOLVE_LINEAR_SYSTEM:
    return "Cannot solve linear system";
  case ERROR_NO_1_TO_1_MAPPING:
    return "Parameterization failed: no one-to-one mapping";
  case ERROR_WRONG_PARAMETER:
    return "Invalid input";
  }
  if(code == NOT_RUN)
    return "not run";
  return "Unknown error";
}

/// What a stage did: `OK`, or the code that fits the cause and the reason in words.
struct Status
{
  Error_code code = CGAL::Surface_mesh_parameterization::OK;
  std::string message;

  bool ok() const { return code == CGAL::Surface_mesh_parameterization::OK; }

  static Status success() { return Status(); }
  static Status failure(Error_code code, std::string why) { return Status{code, std::move(why)}; }
  /// A bad argument: `ERROR_WRONG_PARAMETER` with the reason (which names the argument).
  static Status wrong_parameter(std::string why)
  {
    return failure(CGAL::Surface_mesh_parameterization::ERROR_WRONG_PARAMETER, std::move(why));
  }
  /// The same status, its message behind `context` ("component 0: ...").
  Status within(const std::string& context) const { return ok() ? *this : failure(code, context + message); }
};

namespace internal {

/// A number for a message, to `digits` significant digits ("1e+308", "-2.5"), in the C
/// locale whatever the program's global one.
inline std::string message_number(double x, int digits = 6)
{
  std::ostringstream text;
  text.imbue(std::locale::classic());
  text.precision(digits);
  text << x;
  return text.str();
}

} // namespace internal
} // namespace ICM

#endif // ICM_STATUS_H
