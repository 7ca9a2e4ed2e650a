// LeakSanitizer suppressions for the io test executable (this file holds no tests; its
// name only makes the test glob pick it up). cairo's toy text API goes through
// fontconfig, which keeps its configuration and the patterns cairo duplicates in
// process-lifetime caches that LeakSanitizer reports as leaks at exit (make test-asan
// runs with detect_leaks=1). Only allocations made inside libfontconfig are suppressed.
extern "C" const char* __lsan_default_suppressions();
extern "C" const char* __lsan_default_suppressions() { return "leak:libfontconfig.so\n"; }
