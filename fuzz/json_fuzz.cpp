/// libFuzzer target: the JSON text reader every JSON reader starts with (nesting depth,
/// repeated keys, syntax; common/json_fields.hpp).
#include "fuzz_input.hpp"

TIGHTFIT_FUZZ_READER("json")
