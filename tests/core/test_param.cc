// Parameter conversion from JSON: types, ranges, finiteness, choices, lists; hashing; ParamSet.

#include <cmath>
#include <limits>
#include <stdexcept>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/Error.h"
#include "core/Hash.h"
#include "core/Param.h"

namespace cg {
namespace {

using Json = nlohmann::json;

ParamDecl decl(ParamType type, ParamValue def)
{
    ParamDecl d;
    d.name = "p";
    d.type = type;
    d.defaultValue = std::move(def);
    d.doc = "test";
    return d;
}

/// The what() of the InputError paramFromJson throws, or "" if it accepts the value.
std::string errorOf(const Json& j, const ParamDecl& d, const std::string& pointer = "/p")
{
    try {
        paramFromJson(j, d, pointer);
    } catch (const InputError& e) {
        EXPECT_EQ(e.where().substr(0, pointer.size()), pointer);
        return e.what();
    }
    return "";
}

TEST(Param, TypeNames)
{
    EXPECT_STREQ(paramTypeName(ParamType::Float), "float");
    EXPECT_STREQ(paramTypeName(ParamType::Int), "int");
    EXPECT_STREQ(paramTypeName(ParamType::Bool), "bool");
    EXPECT_STREQ(paramTypeName(ParamType::String), "string");
    EXPECT_STREQ(paramTypeName(ParamType::Vector3), "vec3");
    EXPECT_STREQ(paramTypeName(ParamType::FloatList), "float list");
    EXPECT_STREQ(paramTypeName(ParamType::IntList), "int list");
    EXPECT_EQ(paramTypeOf(ParamValue(std::int64_t(3))), ParamType::Int);
    EXPECT_STREQ(paramRoleName(ParamRole::Plain), "plain");
    EXPECT_STREQ(paramRoleName(ParamRole::OutputPath), "output_path");
    EXPECT_STREQ(paramRoleName(ParamRole::InputFile), "input_file");
    EXPECT_STREQ(paramRoleName(ParamRole::Program), "program");
    EXPECT_EQ(paramTypeOf(ParamValue(Vec3{1, 2, 3})), ParamType::Vector3);
    EXPECT_EQ(paramTypeOf(ParamValue(std::vector<std::int64_t>{})), ParamType::IntList);
}

TEST(Param, FloatAcceptsAnyNumber)
{
    const ParamDecl d = decl(ParamType::Float, 0.0);
    EXPECT_EQ(std::get<double>(paramFromJson(Json(2), d, "/p")), 2.0);
    EXPECT_EQ(std::get<double>(paramFromJson(Json(-2), d, "/p")), -2.0);
    EXPECT_EQ(std::get<double>(paramFromJson(Json(2.5), d, "/p")), 2.5);
    EXPECT_EQ(errorOf(Json("2"), d, "/nodes/a/params/p"),
              "/nodes/a/params/p: expected a number, got string \"2\"");
    EXPECT_EQ(errorOf(Json(true), d), "/p: expected a number, got true");
    EXPECT_EQ(errorOf(Json(nullptr), d), "/p: expected a number, got null");
}

TEST(Param, FloatMustBeFinite)
{
    const ParamDecl d = decl(ParamType::Float, 0.0);
    EXPECT_EQ(errorOf(Json(std::numeric_limits<double>::infinity()), d),
              "/p: value inf is not finite");
    EXPECT_EQ(errorOf(Json(std::nan("")), d), "/p: value nan is not finite");
}

TEST(Param, RangeIsInclusive)
{
    ParamDecl d = decl(ParamType::Int, std::int64_t(1));
    d.min = 1;
    d.max = 5;
    EXPECT_EQ(std::get<std::int64_t>(paramFromJson(Json(1), d, "/p")), 1);
    EXPECT_EQ(std::get<std::int64_t>(paramFromJson(Json(5), d, "/p")), 5);
    EXPECT_EQ(errorOf(Json(7), d, "/nodes/n/params/p"),
              "/nodes/n/params/p: value 7 is above the maximum 5");
    EXPECT_EQ(errorOf(Json(0), d), "/p: value 0 is below the minimum 1");

    ParamDecl f = decl(ParamType::Float, 1.0);
    f.min = 1e-6;
    EXPECT_EQ(errorOf(Json(0.0), f), "/p: value 0 is below the minimum 1e-06");
    f.max = 0.1;
    EXPECT_EQ(errorOf(Json(0.25), f), "/p: value 0.25 is above the maximum 0.1");
}

TEST(Param, IntRefusesFloatsAndHugeValues)
{
    const ParamDecl d = decl(ParamType::Int, std::int64_t(0));
    EXPECT_EQ(std::get<std::int64_t>(paramFromJson(Json(-3), d, "/p")), -3);
    EXPECT_EQ(errorOf(Json(2.5), d), "/p: expected an integer, got 2.5");
    EXPECT_EQ(errorOf(Json(2.0), d), "/p: expected an integer, got 2.0");
    EXPECT_EQ(errorOf(Json("3"), d), "/p: expected an integer, got string \"3\"");
    EXPECT_EQ(errorOf(Json(std::uint64_t(1) << 63), d),
              "/p: value 9223372036854775808 does not fit in a 64-bit signed integer");
}

TEST(Param, BoolAndString)
{
    const ParamDecl b = decl(ParamType::Bool, false);
    EXPECT_TRUE(std::get<bool>(paramFromJson(Json(true), b, "/p")));
    EXPECT_EQ(errorOf(Json(1), b), "/p: expected true or false, got 1");

    ParamDecl s = decl(ParamType::String, std::string("a"));
    EXPECT_EQ(std::get<std::string>(paramFromJson(Json("xyz"), s, "/p")), "xyz");
    EXPECT_EQ(errorOf(Json(1), s), "/p: expected a string, got 1");
    s.choices = {"a", "b"};
    EXPECT_EQ(std::get<std::string>(paramFromJson(Json("b"), s, "/p")), "b");
    EXPECT_EQ(errorOf(Json("c"), s), "/p: value 'c' is not one of 'a', 'b'");
    EXPECT_EQ(errorOf(Json(std::string("\xff")), s), "/p: string is not valid UTF-8");
}

TEST(Param, Vector3)
{
    ParamDecl d = decl(ParamType::Vector3, Vec3{0, 0, 0});
    d.max = 10;
    EXPECT_EQ(std::get<Vec3>(paramFromJson(Json::array({1, 2.5, 3}), d, "/p")), (Vec3{1, 2.5, 3}));
    EXPECT_EQ(errorOf(Json::array({1, 2}), d),
              "/p: expected an array of 3 numbers, got an array of 2");
    EXPECT_EQ(errorOf(Json::array({1, 2, "x"}), d), "/p/2: expected a number, got string \"x\"");
    EXPECT_EQ(errorOf(Json::array({1, 20, 3}), d), "/p/1: value 20 is above the maximum 10");
}

TEST(Param, Lists)
{
    ParamDecl d = decl(ParamType::FloatList, std::vector<double>{1.0});
    d.minSize = 1;
    d.maxSize = 3;
    d.min = 0;
    EXPECT_EQ(std::get<std::vector<double>>(paramFromJson(Json::array({1, 2.5}), d, "/p")),
              (std::vector<double>{1, 2.5}));
    EXPECT_EQ(errorOf(Json::array(), d), "/p: list has 0 elements, fewer than the 1 required");
    EXPECT_EQ(errorOf(Json::array({1, 2, 3, 4}), d),
              "/p: list has 4 elements, more than the 3 allowed");
    EXPECT_EQ(errorOf(Json::array({1, -1}), d), "/p/1: value -1 is below the minimum 0");
    EXPECT_EQ(errorOf(Json(1), d), "/p: expected an array of numbers, got 1");

    ParamDecl i = decl(ParamType::IntList, std::vector<std::int64_t>{});
    EXPECT_EQ(std::get<std::vector<std::int64_t>>(paramFromJson(Json::array({4, 5}), i, "/p")),
              (std::vector<std::int64_t>{4, 5}));
    EXPECT_EQ(errorOf(Json::array({4, 5.5}), i), "/p/1: expected an integer, got 5.5");
}

TEST(Param, JsonRoundTripAndText)
{
    const std::vector<ParamValue> values = {2.5,
                                            std::int64_t(-7),
                                            true,
                                            std::string("a\"b"),
                                            Vec3{1, 2, 3},
                                            std::vector<double>{0.5, 1},
                                            std::vector<std::int64_t>{1, 2}};
    for (const ParamValue& v : values) {
        const ParamDecl d = decl(paramTypeOf(v), v);
        EXPECT_EQ(paramFromJson(paramToJson(v), d, "/p"), v) << paramToString(v);
    }
    EXPECT_EQ(paramToString(ParamValue(2.5)), "2.5");
    EXPECT_EQ(paramToString(ParamValue(0.1)), "0.1");
    EXPECT_EQ(paramToString(ParamValue(std::int64_t(3))), "3");
    EXPECT_EQ(paramToString(ParamValue(std::string("a"))), "\"a\"");
    EXPECT_EQ(paramToString(ParamValue(std::vector<double>{1, 2})), "[1, 2]");
    EXPECT_EQ(paramToString(ParamValue(Vec3{1, 0.5, 3})), "[1, 0.5, 3]");
    EXPECT_EQ(paramToString(ParamValue(false)), "false");
}

Key keyOf(const ParamValue& v)
{
    Hasher h;
    hashParam(h, v);
    return h.finish();
}

TEST(Param, HashDistinguishesValuesAndTypes)
{
    EXPECT_EQ(keyOf(1.5), keyOf(1.5));
    EXPECT_NE(keyOf(1.5), keyOf(2.5));
    EXPECT_NE(keyOf(1.0), keyOf(std::int64_t(1)));
    EXPECT_NE(keyOf(std::int64_t(1)), keyOf(true));
    EXPECT_NE(keyOf(std::vector<double>{}), keyOf(std::vector<std::int64_t>{}));
    EXPECT_NE(keyOf(std::vector<double>{1, 2}), keyOf(std::vector<double>{1, 2, 0}));
    EXPECT_NE(keyOf(Vec3{1, 2, 3}), keyOf(std::vector<double>{1, 2, 3}));
    EXPECT_NE(keyOf(std::string("a")), keyOf(std::string("b")));
    EXPECT_EQ(keyOf(0.0), keyOf(-0.0));
}

TEST(Param, ParamSetStartsAtDefaults)
{
    std::vector<ParamDecl> decls = {decl(ParamType::Float, 2.5),
                                    decl(ParamType::String, std::string("x"))};
    decls[1].name = "s";
    ParamSet set(&decls);
    EXPECT_EQ(set.getFloat("p"), 2.5);
    EXPECT_EQ(set.getString("s"), "x");
    EXPECT_EQ(set.indexOf("s"), std::optional<std::size_t>(1));
    EXPECT_FALSE(set.indexOf("q"));
    EXPECT_THROW(set.value("q"), std::out_of_range);
    set.set("p", 4.0);
    EXPECT_EQ(set.getFloat("p"), 4.0);
    EXPECT_EQ(std::get<double>(set.valueAt(0)), 4.0);
    EXPECT_THROW(set.set("q", 1.0), std::out_of_range);
    EXPECT_THROW(set.set("p", std::int64_t(1)), std::invalid_argument);
}

}  // namespace
}  // namespace cg
