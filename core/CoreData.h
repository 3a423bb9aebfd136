#pragma once
/// The engine's own port types: Float, Int, FloatArray, Text. Domain types (maps, particles,
/// volumes, images) live with the nodes that make them.

#include <cstdint>
#include <string>
#include <vector>

#include "core/Data.h"

namespace cg {

/// A single number ("Float" ports).
class FloatData final : public Data {
public:
    explicit FloatData(double v) : value(v) {}
    const double value;
    std::string typeName() const override { return "Float"; }
    std::size_t byteSize() const override { return sizeof(*this); }
    bool serialize(ByteWriter& out) const override;
};

/// A single integer ("Int" ports).
class IntData final : public Data {
public:
    explicit IntData(std::int64_t v) : value(v) {}
    const std::int64_t value;
    std::string typeName() const override { return "Int"; }
    std::size_t byteSize() const override { return sizeof(*this); }
    bool serialize(ByteWriter& out) const override;
};

/// An array of 32-bit floats ("FloatArray" ports).
class FloatArrayData final : public Data {
public:
    explicit FloatArrayData(std::vector<float> v) : values(std::move(v)) {}
    const std::vector<float> values;
    std::string typeName() const override { return "FloatArray"; }
    std::size_t byteSize() const override { return sizeof(*this) + values.size() * sizeof(float); }
    bool serialize(ByteWriter& out) const override;
};

/// Text, e.g. a list of files a writer produced ("Text" ports).
class TextData final : public Data {
public:
    explicit TextData(std::string v) : value(std::move(v)) {}
    const std::string value;
    std::string typeName() const override { return "Text"; }
    std::size_t byteSize() const override { return sizeof(*this) + value.size(); }
    bool serialize(ByteWriter& out) const override;
};

}  // namespace cg
