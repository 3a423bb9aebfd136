#include "golden/GoldenCompare.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace cg::golden {

Tolerance toleranceOf(Kind kind)
{
    // Outputs are bit-identical for any thread count with one compiler; these allow for gcc
    // and clang rounding the last bits differently (docs/testing.md has the measurements).
    switch (kind) {
        case Kind::Count:
            return {0.0, 0.0};
        case Kind::Sum:
            return {1e-6, 1e-9};
        case Kind::Mean:
            return {1e-6, 1e-9};
        case Kind::Bound:
            return {1e-6, 1e-3};  // a millimetre on top: coordinates near 0
    }
    return {};
}

namespace {

std::string kindName(Kind kind)
{
    switch (kind) {
        case Kind::Count:
            return "exact";
        case Kind::Sum:
            return "sum";
        case Kind::Mean:
            return "mean";
        case Kind::Bound:
            return "bound";
    }
    return "?";
}

double rounded(double v)
{
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.9g", v);
    return std::strtod(buf, nullptr);
}

std::string format(double v)
{
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.9g", v);
    return buf;
}

/// "0080/voxelize.volume/active_voxels" -> "frame 80, node 'voxelize' output 'volume':
/// active_voxels"; "files/figure6/frame.0080.png/mean_r" -> "file 'figure6/frame.0080.png':
/// mean_r"; "files/figure6/*.png" -> "files 'figure6/*.png' written".
std::string describe(const std::string& name)
{
    const std::size_t a = name.find('/');
    const std::size_t b = name.rfind('/');
    if (a == std::string::npos || a == b) return name;
    if (name.compare(0, a, "files") == 0) {
        if (name[b + 1] == '*') return "files '" + name.substr(a + 1) + "' written";
        return "file '" + name.substr(a + 1, b - a - 1) + "': " + name.substr(b + 1);
    }
    const std::size_t dot = name.find('.', a + 1);
    if (dot == std::string::npos || dot > b) return name;
    return "frame " + std::to_string(std::atoi(name.substr(0, a).c_str())) + ", node '" +
           name.substr(a + 1, dot - a - 1) + "' output '" + name.substr(dot + 1, b - dot - 1) +
           "': " + name.substr(b + 1);
}

}  // namespace

nlohmann::json toJson(const std::string& graphFile, const std::vector<int>& frames,
                      const Stats& stats)
{
    nlohmann::json values = nlohmann::json::object();
    for (const auto& [name, stat] : stats) {
        if (stat.kind == Kind::Count)
            values[name] = static_cast<std::int64_t>(stat.value);
        else
            values[name] = rounded(stat.value);
    }
    return {{"graph", graphFile}, {"frames", frames}, {"stats", values}};
}

void writeExpected(const std::filesystem::path& file, const nlohmann::json& expected)
{
    std::filesystem::create_directories(file.parent_path());
    std::ofstream out(file, std::ios::binary | std::ios::trunc);
    out << expected.dump(4) << '\n';
    if (!out.flush()) throw std::runtime_error("cannot write " + file.string());
}

std::vector<std::string> compare(const Stats& actual, const nlohmann::json& expectedStats)
{
    std::vector<std::string> problems;
    for (const auto& [name, stat] : actual) {
        const auto it = expectedStats.find(name);
        if (it == expectedStats.end()) {
            problems.push_back(describe(name) + " is new (" + format(stat.value) +
                               "), not in the expected file");
            continue;
        }
        if (!it->is_number()) {
            problems.push_back(describe(name) + ": the expected value is not a number");
            continue;
        }
        const double want = it->get<double>();
        const Tolerance tol = toleranceOf(stat.kind);
        const double allowed = std::max(tol.relative * std::abs(want), tol.absolute);
        if (stat.kind == Kind::Count ? stat.value != want
                                     : !(std::abs(stat.value - want) <= allowed)) {
            std::ostringstream m;
            m << describe(name) << " is " << format(stat.value) << ", expected " << format(want)
              << " (" << kindName(stat.kind);
            if (stat.kind != Kind::Count)
                m << ": relative "
                  << (want != 0.0 ? (stat.value - want) / std::abs(want) : stat.value)
                  << ", allowed " << tol.relative << " or " << tol.absolute << " absolute";
            m << ")";
            problems.push_back(m.str());
        }
    }
    for (auto it = expectedStats.begin(); it != expectedStats.end(); ++it)
        if (actual.count(it.key()) == 0)
            problems.push_back(describe(it.key()) + " is expected (" + it.value().dump() +
                               ") but was not produced");
    return problems;
}

}  // namespace cg::golden
