/// libFuzzer target: the "scene" reader (readers.hpp).
#include "fuzz_input.hpp"

TIGHTFIT_FUZZ_READER("scene")
