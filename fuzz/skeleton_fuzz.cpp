/// libFuzzer target: the "skeleton" reader (readers.hpp).
#include "fuzz_input.hpp"

TIGHTFIT_FUZZ_READER("skeleton")
