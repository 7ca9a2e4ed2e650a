/// libFuzzer target: the "fabric" reader (readers.hpp): a fabric file of a scene.
#include "fuzz_input.hpp"

TIGHTFIT_FUZZ_READER("fabric")
