/// libFuzzer target: the "pieces" reader (readers.hpp).
#include "fuzz_input.hpp"

TIGHTFIT_FUZZ_READER("pieces")
