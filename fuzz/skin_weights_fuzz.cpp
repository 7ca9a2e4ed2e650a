/// libFuzzer target: the "skin_weights" reader (readers.hpp).
#include "fuzz_input.hpp"

TIGHTFIT_FUZZ_READER("skin_weights")
