/// libFuzzer target: the "strip_csv" reader (readers.hpp): strip tests read and fitted.
#include "fuzz_input.hpp"

TIGHTFIT_FUZZ_READER("strip_csv")
