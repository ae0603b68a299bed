// The one exception type of the core; the FreeFEM adapter turns it into ExecError.
#pragma once
#include <stdexcept>
#include <string>

namespace dlmfsi {

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& what) : std::runtime_error("dlmfsi: " + what) {}
};

}  // namespace dlmfsi
