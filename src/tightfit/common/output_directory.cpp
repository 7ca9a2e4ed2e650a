#include "tightfit/common/output_directory.hpp"

#include "tightfit/common/atomic_file.hpp"
#include "tightfit/common/error.hpp"

namespace tightfit {

OutputDirectory::OutputDirectory(std::filesystem::path target) : target_(std::move(target)) {
  if (target_.empty()) throw InputError("--out", "no output folder given");
  if (!target_.has_filename()) target_ = target_.parent_path();
  const auto parent = target_.has_parent_path() ? target_.parent_path() : std::filesystem::path(".");
  std::error_code ec;
  std::filesystem::create_directories(parent, ec);
  if (ec) throw InputError(target_.string(), "cannot create the parent folder: " + ec.message());
  staging_ = temporary_path_for(target_);
  std::filesystem::create_directory(staging_, ec);
  if (ec) throw InputError(target_.string(), "cannot create a staging folder: " + ec.message());
}

OutputDirectory::~OutputDirectory() {
  if (!committed_) {
    std::error_code ec;
    std::filesystem::remove_all(staging_, ec);
  }
}

void OutputDirectory::commit() {
  std::error_code ec;
  std::filesystem::path old;
  if (std::filesystem::exists(target_)) {
    old = temporary_path_for(target_);
    std::filesystem::rename(target_, old, ec);
    if (ec) throw InputError(target_.string(), "cannot replace the existing folder: " + ec.message());
  }
  std::filesystem::rename(staging_, target_, ec);
  if (ec) {
    if (!old.empty()) std::filesystem::rename(old, target_, ec);
    throw InputError(target_.string(), "cannot move the results into place");
  }
  committed_ = true;
  if (!old.empty()) std::filesystem::remove_all(old, ec);
}

}  // namespace tightfit
