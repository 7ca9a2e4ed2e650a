#pragma once
/// Inlining of JavaScript ES modules (three.js and its addons) into one HTML file that
/// opens offline from file://, where module scripts cannot load other files.
///
/// Every module becomes a base64 `data:text/javascript` URL listed in an import map.
/// Relative imports ("./x.js", "../y.js" after `from` or `import`) are followed
/// recursively: the imported file gets its own map entry under the bare specifier
/// "tightfit-inline/N/FILE" and the import is rewritten to that specifier, so each
/// file is included once and module identity is kept. Bare imports (e.g. 'three' in
/// the addons) are resolved by the map itself. Dynamic import() is not followed.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace tightfit {

/// A module to make importable under a bare `specifier` (e.g. "three").
struct InlineModule {
  std::string specifier;
  std::filesystem::path file;
};

/// The import map {"imports": {specifier: data URL, ...}}. InputError naming the file
/// when a module or a file it imports cannot be read.
nlohmann::json inline_module_import_map(const std::vector<InlineModule>& modules);

}  // namespace tightfit
