// cloudgraph nodes [TYPE] [--markdown]: the node reference, generated from the registry.

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <set>
#include <sstream>
#include <string>

#include "cli/Commands.h"
#include "cli/Common.h"
#include "core/Error.h"
#include "core/Registry.h"

namespace cg::cli {

namespace {

std::string rangeText(const ParamDecl& p)
{
    if (p.type == ParamType::String) {
        if (p.choices.empty()) return p.role == ParamRole::OutputPath ? "path under --out" : "";
        std::string s = "one of";
        for (const auto& c : p.choices) s += " `" + c + "`";
        return s;
    }
    if (p.type == ParamType::Bool) return "";
    auto num = [](double v) {
        std::ostringstream o;
        o << v;
        return o.str();
    };
    std::string s = p.min ? num(*p.min) : "-inf";
    s += " .. ";
    s += p.max ? num(*p.max) : "inf";
    return s;
}

std::string flags(const NodeDecl& d)
{
    std::string s;
    if (d.simulation)
        s += " simulation (steps from its previous frame);";
    else if (d.frameDependentIf)
        s += " frame-dependent as its parameters say;";
    else if (d.frameDependent)
        s += " frame-dependent;";
    else
        s += " changes with the frame only through its inputs;";
    if (d.writesFiles) s += " writes files;";
    if (!d.cacheOnDisk) s += " memory cache only;";
    if (!s.empty()) s.pop_back();
    return s;
}

void printMarkdown(const NodeDecl& d)
{
    std::printf("## %s\n\n*%s, version %d;%s*\n\n%s\n\n", d.type.c_str(), d.category.c_str(),
                d.version, flags(d).c_str(), d.doc.c_str());
    auto ports = [](const char* title, const std::vector<PortDecl>& list, bool inputs) {
        if (list.empty()) return;
        std::printf("**%s**\n\n| port | type | description |\n|---|---|---|\n", title);
        for (const auto& p : list)
            std::printf("| `%s` | %s | %s%s |\n", p.name.c_str(), p.type.c_str(), p.doc.c_str(),
                        inputs && p.optional ? " (optional)" : "");
        std::printf("\n");
    };
    ports("Inputs", d.inputs, true);
    ports("Outputs", d.outputs, false);
    if (!d.params.empty()) {
        std::printf(
            "**Parameters**\n\n| name | type | default | range | units | description |\n"
            "|---|---|---|---|---|---|\n");
        for (const auto& p : d.params)
            std::printf("| `%s` | %s | `%s` | %s | %s | %s |\n", p.name.c_str(),
                        paramTypeName(p.type), paramToString(p.defaultValue).c_str(),
                        rangeText(p).c_str(), p.units.c_str(), p.doc.c_str());
        std::printf("\n");
    }
}

void printText(const NodeDecl& d)
{
    std::printf("%s (%s, version %d;%s)\n  %s\n", d.type.c_str(), d.category.c_str(), d.version,
                flags(d).c_str(), d.doc.c_str());
    for (const auto& p : d.inputs)
        std::printf("  in  %-14s %-10s %s%s\n", p.name.c_str(), p.type.c_str(), p.doc.c_str(),
                    p.optional ? " (optional)" : "");
    for (const auto& p : d.outputs)
        std::printf("  out %-14s %-10s %s\n", p.name.c_str(), p.type.c_str(), p.doc.c_str());
    for (const auto& p : d.params) {
        const std::string range = rangeText(p);
        std::printf("  param %-12s %-10s = %s%s%s%s  %s\n", p.name.c_str(), paramTypeName(p.type),
                    paramToString(p.defaultValue).c_str(), p.units.empty() ? "" : " ",
                    p.units.c_str(), range.empty() ? "" : ("  [" + range + "]").c_str(),
                    p.doc.c_str());
    }
}

/// True when the word that ends just before `dot` is an abbreviation whose '.' ends no sentence.
bool isAbbreviation(const std::string& doc, std::size_t dot)
{
    static const std::set<std::string> known = {"al",  "approx", "cf",  "ch",   "e.g",
                                                "eq",  "eqs",    "fig", "figs", "i.e",
                                                "ref", "refs",   "sec", "secs", "vs"};
    auto inWord = [&](std::size_t i) {
        return std::isalpha(static_cast<unsigned char>(doc[i])) || doc[i] == '.';
    };
    std::size_t begin = dot;
    while (begin > 0 && inWord(begin - 1)) --begin;
    std::string word = doc.substr(begin, dot - begin);
    for (char& c : word) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return known.count(word) > 0;
}

/// The doc's first sentence: it ends at '.', '!' or '?' outside parentheses that is followed by
/// the end or by a space and no lower-case letter or digit ("Sec. 5.1", "e.g. the", "2k, ...
/// in" go on), and not after a known abbreviation. Never empty, always ends a sentence.
std::string summary(const std::string& doc)
{
    int depth = 0;  // unbalanced ')' (as in "[low, high)") must not make it negative
    for (std::size_t i = 0; i < doc.size(); ++i) {
        const char c = doc[i];
        if (c == '(') ++depth;
        if (c == ')') depth = std::max(0, depth - 1);
        if ((c != '.' && c != '!' && c != '?') || depth > 0) continue;
        if (i + 1 < doc.size() && !std::isspace(static_cast<unsigned char>(doc[i + 1]))) continue;
        const std::size_t next = doc.find_first_not_of(" \t\n", i + 1);
        if (next != std::string::npos && (std::islower(static_cast<unsigned char>(doc[next])) ||
                                          std::isdigit(static_cast<unsigned char>(doc[next]))))
            continue;
        if (c == '.' && (isAbbreviation(doc, i) || (i >= 2 && doc.compare(i - 2, 2, "..") == 0)))
            continue;
        return doc.substr(0, i + 1);
    }
    std::string all = doc.substr(0, doc.find_last_not_of(" \t\n") + 1);
    if (all.empty()) return "(undocumented).";
    if (all.back() != '.' && all.back() != '!' && all.back() != '?') all += '.';
    return all;
}

}  // namespace

int nodesCommand(const Args& args)
{
    OptionParser opts(args, "nodes");
    return guarded([&] {
        opts.parse();
        Registry registry;
        buildRegistry(registry, opts);
        const bool markdown = opts.has("--markdown");
        if (opts.positionals().size() > 1)
            throw InputError("command line", "nodes takes at most one TYPE");
        if (opts.positionals().size() == 1) {
            const NodeDecl* d = registry.findNode(opts.positionals()[0]);
            if (!d)
                throw InputError("command line",
                                 "unknown node type '" + opts.positionals()[0] + "'");
            markdown ? printMarkdown(*d) : printText(*d);
            return kExitOk;
        }
        if (markdown) {
            std::printf(
                "# Node reference\n\nGenerated by `cloudgraph nodes --markdown`; do not edit by "
                "hand.\n\n");
            std::printf("Port types:");
            for (const DataTypeInfo* t : registry.dataTypes())
                std::printf(" `%s` (%s);", t->name.c_str(), t->doc.c_str());
            std::printf("\n\n");
            for (const NodeDecl* d : registry.nodes()) printMarkdown(*d);
        } else {
            int width = 0;
            for (const NodeDecl* d : registry.nodes())
                width = std::max(width, static_cast<int>(d->type.size()));
            for (const NodeDecl* d : registry.nodes())
                std::printf("%-*s  %s\n", width, d->type.c_str(), summary(d->doc).c_str());
        }
        return kExitOk;
    });
}

}  // namespace cg::cli
