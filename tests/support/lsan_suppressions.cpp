// LeakSanitizer suppressions, linked into every test executable (tests/CMakeLists.txt).
// cairo's toy text API goes through fontconfig, which keeps its configuration and the
// patterns cairo duplicates in process-lifetime caches that LeakSanitizer reports as
// leaks at exit (make test-asan runs with detect_leaks=1). Only allocations made inside
// libfontconfig are suppressed.
extern "C" const char* __lsan_default_suppressions();
extern "C" const char* __lsan_default_suppressions() { return "leak:libfontconfig.so\n"; }
