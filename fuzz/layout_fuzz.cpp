/// libFuzzer target: the "layout" reader (readers.hpp).
#include "fuzz_input.hpp"

TIGHTFIT_FUZZ_READER("layout")
