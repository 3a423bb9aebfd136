#include "core/CoreData.h"

#include <stdexcept>

#include "core/Registry.h"
#include "util/LittleEndian.h"

namespace cg {

void ByteReader::bytes(void* out, std::size_t size)
{
    if (size > remaining()) overrun();
    if (size) std::memcpy(out, mData + mPos, size);
    mPos += size;
}

std::uint64_t ByteReader::u64()
{
    unsigned char b[8];
    bytes(b, 8);
    return util::getU64(b);
}

double ByteReader::f64()
{
    const std::uint64_t bits = u64();
    double v;
    std::memcpy(&v, &bits, 8);
    return v;
}

std::string ByteReader::str()
{
    const std::uint64_t n = u64();
    if (n > remaining()) overrun();
    std::string s(static_cast<std::size_t>(n), '\0');
    bytes(s.data(), s.size());
    return s;
}

void ByteReader::overrun() const
{
    throw std::runtime_error("stored value ends early at byte " + std::to_string(mPos) + " of " +
                             std::to_string(mSize));
}

bool FloatData::serialize(ByteWriter& out) const
{
    out.f64(value);
    return true;
}
bool IntData::serialize(ByteWriter& out) const
{
    out.u64(static_cast<std::uint64_t>(value));
    return true;
}
bool FloatArrayData::serialize(ByteWriter& out) const
{
    out.podVector(values);
    return true;
}
bool TextData::serialize(ByteWriter& out) const
{
    out.str(value);
    return true;
}

// Every bit pattern is a valid Float, Int, FloatArray or Text (NaN included: Statistics of no
// values makes it), so a stored one is checked only for its length, which ByteReader bounds
// by the bytes left before anything is allocated.
void registerCoreDataTypes(Registry& registry)
{
    registry.addDataType({"Float", "a number", [](ByteReader& in) -> DataPtr {
                              return std::make_shared<FloatData>(in.f64());
                          }});
    registry.addDataType({"Int", "an integer", [](ByteReader& in) -> DataPtr {
                              return std::make_shared<IntData>(static_cast<std::int64_t>(in.u64()));
                          }});
    registry.addDataType({"FloatArray", "an array of 32-bit floats", [](ByteReader& in) -> DataPtr {
                              return std::make_shared<FloatArrayData>(in.podVector<float>());
                          }});
    registry.addDataType({"Text", "a string", [](ByteReader& in) -> DataPtr {
                              return std::make_shared<TextData>(in.str());
                          }});
}

}  // namespace cg
