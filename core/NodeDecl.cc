#include "core/NodeDecl.h"

#include <limits>

#include "core/Error.h"

namespace cg {

namespace {
template <class T>
const T* findByName(const std::vector<T>& items, const std::string& name)
{
    for (const T& item : items)
        if (item.name == name) return &item;
    return nullptr;
}
}  // namespace

const PortDecl* NodeDecl::findInput(const std::string& name) const
{
    return findByName(inputs, name);
}
const PortDecl* NodeDecl::findOutput(const std::string& name) const
{
    return findByName(outputs, name);
}
const ParamDecl* NodeDecl::findParam(const std::string& name) const
{
    return findByName(params, name);
}

void ParamChecker::fail(const std::string& param, const std::string& message) const
{
    throw InputError(nodePointer + "/params/" + param, message);
}

void ParamChecker::checkAllocation(const std::string& param,
                                   const std::vector<std::int64_t>& counts,
                                   std::uint64_t bytesPerItem) const
{
    std::uint64_t total = bytesPerItem;
    for (std::int64_t c : counts) {
        if (c < 0) fail(param, "size " + std::to_string(c) + " is negative");
        const auto n = static_cast<std::uint64_t>(c);
        if (n != 0 && total > std::numeric_limits<std::uint64_t>::max() / n) {
            fail(param,
                 "size overflows 64-bit arithmetic; it would exceed the allocation limit of " +
                     std::to_string(allocationLimitBytes) + " bytes");
        }
        total *= n;
    }
    if (total > allocationLimitBytes) {
        fail(param, "would allocate " + std::to_string(total) + " bytes, over the limit of " +
                        std::to_string(allocationLimitBytes) + " bytes");
    }
}

}  // namespace cg
