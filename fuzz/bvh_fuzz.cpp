/// libFuzzer target: the "bvh" reader (readers.hpp).
#include "fuzz_input.hpp"

TIGHTFIT_FUZZ_READER("bvh")
