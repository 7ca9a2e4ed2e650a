#include "tightfit/report/modules.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "report/support/fit_test_tools.hpp"
#include "tightfit/common/error.hpp"

namespace tightfit::report_modules_test {

void write(const std::filesystem::path& path, const std::string& text) {
  std::filesystem::create_directories(path.parent_path());
  std::ofstream(path) << text;
}

std::string base64_decode(const std::string& text) {
  static const std::string alphabet =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  unsigned buffer = 0;
  int bits = 0;
  for (const char c : text) {
    if (c == '=') break;
    buffer = (buffer << 6) | static_cast<unsigned>(alphabet.find(c));
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      out.push_back(static_cast<char>((buffer >> bits) & 0xFFu));
    }
  }
  return out;
}

std::string module_text(const nlohmann::json& map, const std::string& specifier) {
  const std::string url = map["imports"][specifier];
  const std::string prefix = "data:text/javascript;base64,";
  EXPECT_EQ(url.substr(0, prefix.size()), prefix);
  return base64_decode(url.substr(prefix.size()));
}

TEST(ReportModules, RelativeImportsBecomeMappedDataUrls) {
  test::TempDir dir("modules");
  write(dir / "lib/main.js",
        "import {a} from './a.js';\nexport * from\"../shared/b.js\";\n"
        "const s = 'from ./not-an-import.js';\nexport {x} from 'three';\n");
  write(dir / "lib/a.js", "import {b} from '../shared/b.js'; export const a = b;\n");
  write(dir / "shared/b.js", "export const b = 1;\n");
  write(dir / "addon.js", "import {a} from 'three'; import './lib/main.js';\n");

  const auto map =
      inline_module_import_map({{"three", dir / "lib/main.js"}, {"addon", dir / "addon.js"}});
  const auto& imports = map["imports"];
  // main, a, b and the addon: b is included once although two files import it, and the
  // addon's relative import of main.js reuses the "three" entry.
  EXPECT_EQ(imports.size(), 4u) << map.dump(2);
  const std::string main = module_text(map, "three");
  EXPECT_EQ(main.find("./a.js"), std::string::npos) << main;
  EXPECT_NE(main.find("'tightfit-inline/"), std::string::npos) << main;
  EXPECT_NE(main.find("from\"tightfit-inline/"), std::string::npos) << main;
  EXPECT_NE(main.find("'from ./not-an-import.js'"), std::string::npos) << main;
  EXPECT_NE(main.find("from 'three'"), std::string::npos) << main;
  EXPECT_NE(module_text(map, "addon").find("import 'three';"), std::string::npos);
  for (const auto& [specifier, url] : imports.items()) {
    if (specifier.rfind("tightfit-inline/", 0) == 0 && specifier.ends_with("/b.js")) {
      EXPECT_EQ(module_text(map, specifier), "export const b = 1;\n");
    }
  }
}

TEST(ReportModules, MissingFilesAreInputErrors) {
  test::TempDir dir("modules_missing");
  write(dir / "main.js", "import './gone.js';\n");
  try {
    inline_module_import_map({{"three", dir / "main.js"}});
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("gone.js"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("imported by"), std::string::npos) << e.what();
  }
  EXPECT_THROW(inline_module_import_map({{"three", dir / "nothing.js"}}), InputError);
}

}  // namespace tightfit::report_modules_test
