#pragma once
/// Typed node parameters: declaration (type, default, range, units, doc) and values.

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include <nlohmann/json_fwd.hpp>

namespace cg {

class Hasher;

using Vec3 = std::array<double, 3>;

enum class ParamType { Float, Int, Bool, String, Vector3, FloatList, IntList };

/// Index order matches ParamType.
using ParamValue = std::variant<double, std::int64_t, bool, std::string, Vec3, std::vector<double>,
                                std::vector<std::int64_t>>;

/// What a string parameter names, so the engine can check and resolve it.
enum class ParamRole {
    Plain,
    OutputPath,  ///< a file name under the run's --out directory; may hold a #### frame pattern
    InputFile,   ///< a file to read; nodes hash its content into their key themselves
    /// A program the node runs. A graph is data and may not choose what runs: a graph that
    /// sets it is refused unless the user opts in (LoadOptions::allowGraphPrograms).
    Program,
};

const char* paramTypeName(ParamType t);
/// "plain", "output_path", "input_file", "program".
const char* paramRoleName(ParamRole role);
ParamType paramTypeOf(const ParamValue& v);

struct ParamDecl {
    std::string name;
    ParamType type = ParamType::Float;
    ParamValue defaultValue = 0.0;
    std::optional<double> min;  ///< inclusive; applies to each element of a list
    std::optional<double> max;  ///< inclusive; applies to each element of a list
    std::string units;          ///< "m", "s", "degC", "1/km" ... or empty for dimensionless
    std::string doc;            ///< one line
    ParamRole role = ParamRole::Plain;
    std::vector<std::string> choices;  ///< allowed values of a String parameter, if non-empty
    std::size_t minSize = 0;           ///< lists: fewest elements
    std::size_t maxSize = 4096;        ///< lists: most elements
};

/// Converts JSON to a value of decl's type, checking type, finiteness, range and choices.
/// Throws InputError naming `pointer` (a JSON pointer such as /nodes/a/params/beta).
ParamValue paramFromJson(const nlohmann::json& j, const ParamDecl& decl,
                         const std::string& pointer);
nlohmann::json paramToJson(const ParamValue& v);
/// Human-readable value ("2.5", "[1, 2]", "\"a\"").
std::string paramToString(const ParamValue& v);
void hashParam(Hasher& h, const ParamValue& v);

/// A node's parameter values, one per declaration, in declaration order.
class ParamSet {
public:
    ParamSet() = default;
    explicit ParamSet(const std::vector<ParamDecl>* decls);

    const std::vector<ParamDecl>& decls() const { return *mDecls; }
    const ParamValue& value(const std::string& name) const;
    const ParamValue& valueAt(std::size_t i) const { return mValues[i]; }
    /// Replaces a value; the caller has validated it with paramFromJson.
    void set(const std::string& name, ParamValue v);
    std::optional<std::size_t> indexOf(const std::string& name) const;

    double getFloat(const std::string& name) const { return std::get<double>(value(name)); }
    std::int64_t getInt(const std::string& name) const
    {
        return std::get<std::int64_t>(value(name));
    }
    bool getBool(const std::string& name) const { return std::get<bool>(value(name)); }
    const std::string& getString(const std::string& name) const
    {
        return std::get<std::string>(value(name));
    }
    Vec3 getVec3(const std::string& name) const { return std::get<Vec3>(value(name)); }
    const std::vector<double>& getFloatList(const std::string& name) const
    {
        return std::get<std::vector<double>>(value(name));
    }
    const std::vector<std::int64_t>& getIntList(const std::string& name) const
    {
        return std::get<std::vector<std::int64_t>>(value(name));
    }

private:
    const std::vector<ParamDecl>* mDecls = nullptr;
    std::vector<ParamValue> mValues;
};

}  // namespace cg
