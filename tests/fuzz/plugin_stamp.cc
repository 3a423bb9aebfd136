// Fuzz target: the plugin ABI stamp reader (core/PluginStamp.h), which parses a library's ELF
// section headers before anything of it is loaded. The input is the whole file. A stamp must
// be found or reported missing, or the file refused with std::runtime_error; nothing else.
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <stdexcept>

#include "core/PluginStamp.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    const cg::ByteSource read = [data, size](std::uint64_t offset, void* out, std::size_t n) {
        if (offset > size || n > size - offset) return false;
        std::memcpy(out, data + offset, n);
        return true;
    };
    try {
        (void)cg::readPluginStamp(read, size);
    } catch (const std::runtime_error&) {
    }
    return 0;
}
