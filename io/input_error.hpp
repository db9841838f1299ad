#pragma once
/// The one exception type for bad user input (files, keys, arguments). Its message names the
/// file and the line, column or key at fault; the command-line program prints it on one line
/// and exits non-zero. Numerical failures are not InputErrors.
#include <stdexcept>
#include <string>

namespace cushion {

class InputError : public std::runtime_error {
 public:
  explicit InputError(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace cushion
