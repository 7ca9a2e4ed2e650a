#!/usr/bin/env python3
"""Tests of scripts/check_sizes.py: the function finder on the C++ constructs of the code
base, and the allow-list rule (new offenders and stale entries both fail)."""
import pathlib
import sys
import tempfile
import unittest

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[2] / "scripts"))
import check_sizes  # noqa: E402

SOURCE = r'''#include "x.hpp"
namespace tightfit {
namespace {
/// A comment with a brace { that must not count.
int helper(int a) {
  const char* s = "}}}";
  const char c = '}';
  return a + 1'000;
}
const std::set<std::string> kNames = {"a", "b"};
const auto kTable = [] { return 1; }();
enum class Kind { kA, kB };
}  // namespace

Foo::Foo(int a, int b)
    : a_(a),
      b_{b} {
  auto f = [&](int x) {
    return x * 2;
  };
  if (a) {
    f(1);
  }
}

template <typename T>
std::vector<T> Foo::twice(const std::vector<T>& v) const {
  return v;
}

class Bar : public Base {
 public:
  bool operator()(int x) const { return x > 0; }
  Bar& operator=(const Bar&) = default;
  int value() const {
    return R"(raw { string )" [0];
  }

 private:
  int v_{0};
};

extern "C" void on_signal(int signal) {
  if (signal) {
    stop();
  }
}

template <int Dim>
struct Metric {
  double norm(const Vec& v, const Options& o = {}) const {
    return v.norm();
  }
};

Baz::Baz(const Garment& g)
    : regions_(g, {}, kSource) {
  init();
}

const Registration kCommand{
    "name", [](App& app) {
      app.run();
    }};

}  // namespace tightfit
'''


class FunctionFinder(unittest.TestCase):
    def test_finds_every_definition_with_its_lines(self):
        found = {name: (first, last) for name, first, last in check_sizes.functions(SOURCE)}
        self.assertEqual(found, {
            "helper": (5, 9),
            "Foo::Foo": (15, 24),
            "Foo::twice": (27, 29),
            "Bar::operator()": (33, 33),
            "Bar::value": (35, 37),
            "on_signal": (43, 47),
            "Metric::norm": (51, 53),
            "Baz::Baz": (56, 59),
            "kCommand": (61, 64),
        })

    def test_comments_and_literals_keep_their_lines(self):
        code = check_sizes.strip_code(SOURCE)
        self.assertEqual(code.count("\n"), SOURCE.count("\n"))
        self.assertNotIn("{ that", code)
        self.assertNotIn("raw {", code)


def tree(files):
    root = pathlib.Path(tempfile.mkdtemp())
    for rel, text in files.items():
        (root / rel).parent.mkdir(parents=True, exist_ok=True)
        (root / rel).write_text(text)
    return root


def long_function(name, body_lines):
    return f"void {name}() {{\n" + "  x();\n" * body_lines + "}\n"


class AllowList(unittest.TestCase):
    def test_a_new_offender_fails(self):
        root = tree({"src/a.cpp": long_function("f", 118) + long_function("g", 119)})
        _, problems = check_sizes.check(root, [])
        self.assertEqual(len(problems), 1)
        self.assertIn("src/a.cpp:g: 121 lines", problems[0])

    def test_a_listed_offender_passes_and_a_stale_entry_fails(self):
        root = tree({"src/a.cpp": long_function("g", 130), "src/b.hpp": "int x;\n" * 501})
        _, problems = check_sizes.check(root, ["src/a.cpp:g", "src/b.hpp"])
        self.assertEqual(problems, [])
        _, problems = check_sizes.check(root, ["src/a.cpp:g", "src/b.hpp", "src/a.cpp:f",
                                               "src/a.cpp"])
        self.assertEqual(len(problems), 2)
        self.assertTrue(all("delete it" in p for p in problems))

    def test_the_repository_passes(self):
        root = pathlib.Path(__file__).resolve().parents[2]
        allow = check_sizes.read_allowlist(root / "scripts" / "size_allowlist.txt")
        _, problems = check_sizes.check(root, allow)
        self.assertEqual(problems, [])


if __name__ == "__main__":
    unittest.main()
