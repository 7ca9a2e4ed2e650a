#pragma once
/// Observation of the keys that JsonFields readers ask for: tools that check a file
/// format's documentation against its readers (the scene schema test) install an observer
/// and parse files; every key asked for is reported, whether the file has it or not.
#include <functional>
#include <string>

namespace tightfit {

/// Called with (source, JSON pointer of the object, key) for every key asked for.
using JsonKeyObserver =
    std::function<void(const std::string& source, const std::string& path, const std::string& key)>;

/// While it lives, every JsonFields of the calling thread reports the keys it asks for to
/// `observer`; the previous observer (if any) is restored on destruction.
class ScopedJsonKeyObserver {
 public:
  explicit ScopedJsonKeyObserver(JsonKeyObserver observer);
  ~ScopedJsonKeyObserver();
  ScopedJsonKeyObserver(const ScopedJsonKeyObserver&) = delete;
  ScopedJsonKeyObserver& operator=(const ScopedJsonKeyObserver&) = delete;

 private:
  JsonKeyObserver previous_;
};

}  // namespace tightfit
