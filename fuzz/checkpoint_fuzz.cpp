/// libFuzzer target: the "checkpoint" reader (readers.hpp).
#include "fuzz_input.hpp"

TIGHTFIT_FUZZ_READER("checkpoint")
