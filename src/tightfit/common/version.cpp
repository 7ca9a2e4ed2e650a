#include "tightfit/common/version.hpp"

#include <ctime>

#ifndef TIGHTFIT_VERSION
#error "TIGHTFIT_VERSION must be defined by the build (CMakeLists.txt)"
#endif

namespace tightfit {

const char* tightfit_version() { return TIGHTFIT_VERSION; }

std::string utc_timestamp() {
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &utc);
  return text;
}

}  // namespace tightfit
