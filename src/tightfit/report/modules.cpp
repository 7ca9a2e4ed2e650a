#include "tightfit/report/modules.hpp"

#include <fstream>
#include <map>
#include <sstream>

#include "tightfit/common/error.hpp"
#include "tightfit/report/encoding.hpp"

namespace tightfit {

namespace {

std::string read_text(const std::filesystem::path& path, const std::string& needed_by) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    throw InputError(path.string(),
                     needed_by.empty()
                         ? "cannot read the JavaScript module"
                         : "cannot read the JavaScript module imported by " + needed_by);
  }
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

bool is_word_char(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
         c == '$';
}

/// True when the quote at `quote` follows the keyword `from` or `import` (with optional
/// white space between), as in `from "./x.js"` or `import"./x.js"`.
bool follows_import_keyword(const std::string& code, std::size_t quote) {
  std::size_t end = quote;
  while (end > 0 && (code[end - 1] == ' ' || code[end - 1] == '\t' || code[end - 1] == '\n' ||
                     code[end - 1] == '\r')) {
    --end;
  }
  for (const std::string keyword : {"from", "import"}) {
    if (end < keyword.size()) continue;
    const std::size_t start = end - keyword.size();
    if (code.compare(start, keyword.size(), keyword) != 0) continue;
    if (start > 0 && (is_word_char(code[start - 1]) || code[start - 1] == '.')) continue;
    return true;
  }
  return false;
}

class Inliner {
 public:
  /// The bare specifier under which `file` (canonical) is mapped, inlining it first.
  std::string add(const std::filesystem::path& file, const std::string& needed_by) {
    const auto key = std::filesystem::weakly_canonical(file);
    if (const auto it = specifiers_.find(key); it != specifiers_.end()) return it->second;
    const std::string specifier =
        "tightfit-inline/" + std::to_string(specifiers_.size()) + "/" + key.filename().string();
    specifiers_[key] = specifier;
    imports_[specifier] = data_url(key, needed_by);
    return specifier;
  }

  /// Maps `specifier` directly to the data URL of `file`.
  /// Relative imports of the same file elsewhere reuse `specifier`.
  void add_as(const std::string& specifier, const std::filesystem::path& file) {
    const auto key = std::filesystem::weakly_canonical(file);
    specifiers_[key] = specifier;
    imports_[specifier] = data_url(key, "");
  }

  nlohmann::json import_map() const { return {{"imports", imports_}}; }

 private:
  std::string data_url(const std::filesystem::path& file, const std::string& needed_by) {
    std::string code = read_text(file, needed_by);
    std::string out;
    out.reserve(code.size());
    std::size_t copied = 0;
    for (std::size_t i = 0; i + 2 < code.size(); ++i) {
      const char quote = code[i];
      if (quote != '"' && quote != '\'') continue;
      const bool relative = code.compare(i + 1, 2, "./") == 0 || code.compare(i + 1, 3, "../") == 0;
      if (!relative || !follows_import_keyword(code, i)) continue;
      const std::size_t close = code.find(quote, i + 1);
      if (close == std::string::npos) break;
      const std::string target = code.substr(i + 1, close - i - 1);
      const std::string specifier = add(file.parent_path() / target, file.string());
      out.append(code, copied, i - copied);
      out += quote + specifier + quote;
      copied = close + 1;
      i = close;
    }
    out.append(code, copied, std::string::npos);
    return "data:text/javascript;base64," + base64_encode(out);
  }

  std::map<std::filesystem::path, std::string> specifiers_;
  std::map<std::string, std::string> imports_;
};

}  // namespace

nlohmann::json inline_module_import_map(const std::vector<InlineModule>& modules) {
  Inliner inliner;
  for (const auto& module : modules) inliner.add_as(module.specifier, module.file);
  return inliner.import_map();
}

}  // namespace tightfit
