#include "core/Param.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "core/Error.h"
#include "core/Hash.h"

// Strictness, decided once for every parameter:
//  - Float takes any JSON number; Int takes only JSON integers (2.0 is refused, so a typo
//    like 2.5 never truncates silently); Bool only true/false; String only strings.
//  - Every number must be finite. Files cannot hold NaN or infinity (the JSON reader
//    refuses them), but values built in code or via --set could.
//  - min/max are inclusive and apply to each element of a list or vector.

namespace cg {

namespace {

using Json = nlohmann::json;

/// Shortest text that reads back as the same double ("5", "0.1", "1e-06").
std::string formatDouble(double v)
{
    if (std::isnan(v)) return "nan";
    if (std::isinf(v)) return v < 0 ? "-inf" : "inf";
    char buf[32];
    // Whole numbers in full ("20", not "2e+01"), as long as they read back exactly.
    if (std::fabs(v) < 1e17 && std::trunc(v) == v) {
        std::snprintf(buf, sizeof(buf), "%.0f", v);
        return buf;
    }
    for (int precision = 1; precision <= 17; ++precision) {
        std::snprintf(buf, sizeof(buf), "%.*g", precision, v);
        if (std::strtod(buf, nullptr) == v) break;
    }
    return buf;
}

/// JSON text of `j`, with invalid UTF-8 replaced rather than thrown on.
std::string dumpLenient(const Json& j)
{
    return j.dump(-1, ' ', false, Json::error_handler_t::replace);
}

/// A short description of a JSON value for messages: `string "abc"`, `2.5`, `an object`.
std::string describe(const Json& j)
{
    std::string text;
    switch (j.type()) {
        case Json::value_t::object:
            return "an object";
        case Json::value_t::array:
            return "an array of " + std::to_string(j.size());
        case Json::value_t::null:
            return "null";
        case Json::value_t::string:
            text = "string " + dumpLenient(j);
            break;
        case Json::value_t::number_float:
            // "2.0", so "expected an integer, got 2.0" does not read as a contradiction.
            text = formatDouble(j.get<double>());
            if (text.find_first_of(".en") == std::string::npos) text += ".0";
            break;
        default:
            text = dumpLenient(j);
            break;
    }
    if (text.size() > 60) text = text.substr(0, 57) + "...";
    return text;
}

[[noreturn]] void fail(const std::string& pointer, const std::string& message)
{
    throw InputError(pointer, message);
}

void checkRange(double v, const std::string& text, const ParamDecl& decl,
                const std::string& pointer)
{
    if (decl.min && v < *decl.min)
        fail(pointer, "value " + text + " is below the minimum " + formatDouble(*decl.min));
    if (decl.max && v > *decl.max)
        fail(pointer, "value " + text + " is above the maximum " + formatDouble(*decl.max));
}

double readFloat(const Json& j, const ParamDecl& decl, const std::string& pointer)
{
    if (!j.is_number()) fail(pointer, "expected a number, got " + describe(j));
    const double v = j.get<double>();
    if (!std::isfinite(v)) fail(pointer, "value " + formatDouble(v) + " is not finite");
    checkRange(v, formatDouble(v), decl, pointer);
    return v;
}

std::int64_t readInt(const Json& j, const ParamDecl& decl, const std::string& pointer)
{
    if (j.is_number_float()) {
        const double d = j.get<double>();
        if (!std::isfinite(d)) fail(pointer, "value " + formatDouble(d) + " is not finite");
        fail(pointer, "expected an integer, got " + describe(j));
    }
    if (!j.is_number_integer()) fail(pointer, "expected an integer, got " + describe(j));
    if (j.is_number_unsigned() &&
        j.get<std::uint64_t>() >
            static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max()))
        fail(pointer, "value " + j.dump() + " does not fit in a 64-bit signed integer");
    const auto v = j.get<std::int64_t>();
    checkRange(static_cast<double>(v), std::to_string(v), decl, pointer);
    return v;
}

template <class T, class Read>
std::vector<T> readList(const Json& j, const ParamDecl& decl, const std::string& pointer,
                        const char* what, Read read)
{
    if (!j.is_array()) fail(pointer, std::string("expected ") + what + ", got " + describe(j));
    if (j.size() < decl.minSize)
        fail(pointer, "list has " + std::to_string(j.size()) + " elements, fewer than the " +
                          std::to_string(decl.minSize) + " required");
    if (j.size() > decl.maxSize)
        fail(pointer, "list has " + std::to_string(j.size()) + " elements, more than the " +
                          std::to_string(decl.maxSize) + " allowed");
    std::vector<T> out;
    out.reserve(j.size());
    for (std::size_t i = 0; i < j.size(); ++i)
        out.push_back(read(j[i], decl, pointer + "/" + std::to_string(i)));
    return out;
}

template <class... F>
struct Overload : F... {
    using F::operator()...;
};
template <class... F>
Overload(F...) -> Overload<F...>;

template <class T>
std::string joinList(const std::vector<T>& v)
{
    std::string s = "[";
    for (std::size_t i = 0; i < v.size(); ++i) {
        if (i) s += ", ";
        if constexpr (std::is_same_v<T, double>)
            s += formatDouble(v[i]);
        else
            s += std::to_string(v[i]);
    }
    return s + "]";
}

}  // namespace

const char* paramTypeName(ParamType t)
{
    switch (t) {
        case ParamType::Float:
            return "float";
        case ParamType::Int:
            return "int";
        case ParamType::Bool:
            return "bool";
        case ParamType::String:
            return "string";
        case ParamType::Vector3:
            return "vec3";
        case ParamType::FloatList:
            return "float list";
        case ParamType::IntList:
            return "int list";
    }
    return "unknown";
}

const char* paramRoleName(ParamRole role)
{
    switch (role) {
        case ParamRole::Plain:
            return "plain";
        case ParamRole::OutputPath:
            return "output_path";
        case ParamRole::InputFile:
            return "input_file";
        case ParamRole::Program:
            return "program";
    }
    return "unknown";
}

ParamType paramTypeOf(const ParamValue& v) { return static_cast<ParamType>(v.index()); }

ParamValue paramFromJson(const Json& j, const ParamDecl& decl, const std::string& pointer)
{
    switch (decl.type) {
        case ParamType::Float:
            return readFloat(j, decl, pointer);
        case ParamType::Int:
            return readInt(j, decl, pointer);
        case ParamType::Bool:
            if (!j.is_boolean()) fail(pointer, "expected true or false, got " + describe(j));
            return j.get<bool>();
        case ParamType::String: {
            if (!j.is_string()) fail(pointer, "expected a string, got " + describe(j));
            std::string s = j.get<std::string>();
            try {
                // Strings from the command line may be any bytes; the graph file must stay JSON.
                (void)j.dump();
            } catch (const Json::type_error&) {
                fail(pointer, "string is not valid UTF-8");
            }
            if (!decl.choices.empty()) {
                bool found = false;
                std::string list;
                for (const std::string& c : decl.choices) {
                    found = found || c == s;
                    list += (list.empty() ? "'" : ", '") + c + "'";
                }
                if (!found) fail(pointer, "value '" + s + "' is not one of " + list);
            }
            return s;
        }
        case ParamType::Vector3: {
            if (!j.is_array() || j.size() != 3)
                fail(pointer, "expected an array of 3 numbers, got " + describe(j));
            Vec3 v{};
            for (std::size_t i = 0; i < 3; ++i)
                v[i] = readFloat(j[i], decl, pointer + "/" + std::to_string(i));
            return v;
        }
        case ParamType::FloatList:
            return readList<double>(j, decl, pointer, "an array of numbers", readFloat);
        case ParamType::IntList:
            return readList<std::int64_t>(j, decl, pointer, "an array of integers", readInt);
    }
    fail(pointer, "parameter has an unknown type");
}

Json paramToJson(const ParamValue& v)
{
    return std::visit(Overload{[](const Vec3& x) {
                                   return Json::array({x[0], x[1], x[2]});
                               },
                               [](const auto& x) { return Json(x); }},
                      v);
}

std::string paramToString(const ParamValue& v)
{
    return std::visit(
        Overload{[](double x) { return formatDouble(x); },
                 [](std::int64_t x) { return std::to_string(x); },
                 [](bool x) { return std::string(x ? "true" : "false"); },
                 [](const std::string& x) { return dumpLenient(Json(x)); },
                 [](const Vec3& x) { return joinList(std::vector<double>(x.begin(), x.end())); },
                 [](const std::vector<double>& x) { return joinList(x); },
                 [](const std::vector<std::int64_t>& x) { return joinList(x); }},
        v);
}

void hashParam(Hasher& h, const ParamValue& v)
{
    // The type tag keeps int 1 and float 1.0 (and [] of either list type) apart.
    h.u64(v.index());
    std::visit(Overload{[&](double x) { h.f64(x); }, [&](std::int64_t x) { h.i64(x); },
                        [&](bool x) { h.u64(x ? 1 : 0); }, [&](const std::string& x) { h.str(x); },
                        [&](const Vec3& x) {
                            for (double c : x) h.f64(c);
                        },
                        [&](const std::vector<double>& x) {
                            h.u64(x.size());
                            for (double c : x) h.f64(c);
                        },
                        [&](const std::vector<std::int64_t>& x) {
                            h.u64(x.size());
                            for (std::int64_t c : x) h.i64(c);
                        }},
               v);
}

ParamSet::ParamSet(const std::vector<ParamDecl>* decls) : mDecls(decls)
{
    mValues.reserve(decls->size());
    for (const ParamDecl& d : *decls) mValues.push_back(d.defaultValue);
}

std::optional<std::size_t> ParamSet::indexOf(const std::string& name) const
{
    if (!mDecls) return std::nullopt;
    for (std::size_t i = 0; i < mDecls->size(); ++i)
        if ((*mDecls)[i].name == name) return i;
    return std::nullopt;
}

const ParamValue& ParamSet::value(const std::string& name) const
{
    const auto i = indexOf(name);
    if (!i) throw std::out_of_range("unknown parameter '" + name + "'");
    return mValues[*i];
}

void ParamSet::set(const std::string& name, ParamValue v)
{
    const auto i = indexOf(name);
    if (!i) throw std::out_of_range("unknown parameter '" + name + "'");
    // A wrong type here is a programming error; catching it now beats a bad_variant_access
    // in some node's cook much later.
    if (paramTypeOf(v) != (*mDecls)[*i].type)
        throw std::invalid_argument("parameter '" + name + "' set to a " +
                                    paramTypeName(paramTypeOf(v)) + ", declared " +
                                    paramTypeName((*mDecls)[*i].type));
    mValues[*i] = std::move(v);
}

}  // namespace cg
