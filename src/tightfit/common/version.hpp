#pragma once
/// tightfit's version and the time stamps written into a run's outputs.
#include <string>

namespace tightfit {

/// The version of this build ("0.1.0"; CMake's project version).
const char* tightfit_version();

/// The current time in UTC as ISO 8601, e.g. "2026-12-02T03:41:07Z".
std::string utc_timestamp();

}  // namespace tightfit
