#pragma once
/// All-or-nothing output folders: a command writes into a staging folder beside the
/// target and `commit()` renames it into place. If the command fails (the object is
/// destroyed without commit), the staging folder is removed and the target is untouched.
#include <filesystem>

namespace tightfit {

class OutputDirectory {
 public:
  /// `target` is the folder the results should end up in (created on commit; an
  /// existing folder of that name is replaced on commit).
  explicit OutputDirectory(std::filesystem::path target);
  ~OutputDirectory();
  OutputDirectory(const OutputDirectory&) = delete;
  OutputDirectory& operator=(const OutputDirectory&) = delete;

  /// The folder to write into until commit().
  const std::filesystem::path& staging() const { return staging_; }
  /// staging() / name.
  std::filesystem::path file(const std::string& name) const { return staging_ / name; }
  /// Moves the staging folder to the target.
  void commit();
  const std::filesystem::path& target() const { return target_; }

 private:
  std::filesystem::path target_;
  std::filesystem::path staging_;
  bool committed_ = false;
};

}  // namespace tightfit
