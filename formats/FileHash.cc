#include "formats/FileHash.h"

#include <fstream>
#include <memory>
#include <new>
#include <vector>

#include <xxhash.h>

#include "formats/FormatError.h"
#include "util/InputFile.h"

namespace cg::formats {

std::uint64_t fileContentHash(const std::filesystem::path& path, std::uint64_t maxBytes,
                              const std::string& what)
{
    if (const std::string problem = util::inputFileProblem(path, maxBytes); !problem.empty())
        throw FormatError(path.string(), "cannot read the " + what + ": it " + problem);
    std::ifstream in(path, std::ios::binary);
    if (!in) throw FormatError(path.string(), "cannot open the " + what);
    std::unique_ptr<XXH3_state_t, decltype(&XXH3_freeState)> state(XXH3_createState(),
                                                                   &XXH3_freeState);
    if (!state || XXH3_64bits_reset(state.get()) != XXH_OK) throw std::bad_alloc();
    std::vector<char> buffer(1 << 20);
    while (in) {
        in.read(buffer.data(), static_cast<std::streamsize>(buffer.size()));
        XXH3_64bits_update(state.get(), buffer.data(), static_cast<std::size_t>(in.gcount()));
    }
    if (in.bad()) throw FormatError(path.string(), "cannot read the " + what);
    return XXH3_64bits_digest(state.get());
}

}  // namespace cg::formats
