/// libFuzzer target: the "vtu" reader (readers.hpp).
#include "fuzz_input.hpp"

TIGHTFIT_FUZZ_READER("vtu")
