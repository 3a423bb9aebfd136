#include "cli/FarmToken.h"

#include <algorithm>
#include <cstdio>
#include <random>

#include "core/Error.h"

namespace cg::cli {

namespace {

constexpr std::size_t kTokenDigits = 16;

std::string recordName(const std::string& token) { return "farm-" + token; }

}  // namespace

std::string leaveFarmToken(const DiskCache& cache)
{
    std::random_device device;
    const std::uint64_t bits = (std::uint64_t{device()} << 32) ^ device();
    char token[kTokenDigits + 1];
    std::snprintf(token, sizeof token, "%016llx", static_cast<unsigned long long>(bits));
    cache.storeRecord(recordName(token), {{"token", token}});
    if (!cache.loadRecord(recordName(token)))
        throw InputError("--cache " + cache.root().string(),
                         "cannot store the farm's token record");
    return token;
}

void checkFarmToken(const DiskCache& cache, const std::string& token)
{
    const bool wellFormed =
        token.size() == kTokenDigits && std::all_of(token.begin(), token.end(), [](char c) {
            return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f');
        });
    if (!wellFormed)
        throw InputError("--farm-token", "'" + token + "' is not 16 lowercase hex digits");
    const auto record = cache.loadRecord(recordName(token));
    if (!record || record->value("token", "") != token) {
        throw InputError("--cache " + cache.root().string(),
                         "holds no record of farm token " + token +
                             ": this machine does not see the directory the farm was set up in "
                             "(put --cache on a file system shared by every node)");
    }
}

}  // namespace cg::cli
