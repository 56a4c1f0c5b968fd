// libFuzzer target: fuzz::mesh (see fuzz_entries.hpp for the input format).
// Built with `make fuzz` (clang, -DFIGGEN_FUZZ=ON); seeds in tests/fuzz/corpus/mesh/.
#include <cstddef>
#include <cstdint>

#include "fuzz/fuzz_entries.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    fuzz::mesh(data, size);
    return 0;
}
