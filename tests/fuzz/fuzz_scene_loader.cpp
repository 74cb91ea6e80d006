// libFuzzer entry point: every input must load or be rejected with an
// InputError; a crash, a sanitizer report, a hang or any other exception is
// a bug. Run with scripts/fuzz.sh.
#include <cstdint>

#include "fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    pt::fuzz::load_fuzz_input(data, size, "/tmp");
    return 0;
}
